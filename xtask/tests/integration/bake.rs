//! Runs `cargo xtask bake` on a unit cube: the "done when" figures through the CLI,
//! the JSON format, the sampled baseline's `missed`, the spinning page.

use std::path::PathBuf;
use std::process::{Command, Output};

use serde_json::Value;

fn xtask(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .output()
        .expect("run xtask")
}

fn cube(dir: &str) -> (PathBuf, PathBuf) {
    let dir = std::env::temp_dir().join(format!("xtask-bake-{}-{dir}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("cube.obj");
    std::fs::write(
        &model,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
         f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 2 3 7 6\nf 1 5 8 4\n",
    )
    .unwrap();
    (dir, model)
}

/// Runs `bake` on the cube with `--json` (and `--verify` unless sampled: the baseline's cells
/// are only as good as its samples, which is the point of comparing it).
fn bake_json(args: &[&str], name: &str) -> Value {
    let (dir, model) = cube(name);
    let json = dir.join("bake.json");
    let mut all = vec!["bake", model.to_str().unwrap()];
    all.extend_from_slice(args);
    let sampled = args.contains(&"sampled");
    if !sampled {
        all.push("--verify");
    }
    all.extend_from_slice(&["--json", json.to_str().unwrap()]);
    let out = xtask(&all);
    assert!(
        out.status.success(),
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(sampled || String::from_utf8_lossy(&out.stdout).contains("verified"));
    serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap()
}

fn breakpoints(v: &Value) -> Vec<f64> {
    v["breakpoints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b.as_f64().unwrap())
        .collect()
}

#[test]
fn cube_yaw_centroid_has_eight_cells_at_multiples_of_45() {
    let v = bake_json(&["--axis", "yaw", "--sorter", "centroid"], "centroid");
    assert_eq!(v["axis"], "yaw");
    assert_eq!(v["sorter"], "centroid");
    assert_eq!(v["method"], "exact");
    assert!(v["missed"].is_null());
    assert!(v["bake_ms"].as_f64().unwrap() >= 0.0);
    let at = breakpoints(&v);
    assert_eq!(at.len(), 8, "{at:?}");
    for (k, d) in at.iter().enumerate() {
        assert!((d - 45.0 * k as f64).abs() < 1e-9, "{at:?}");
    }
    let cells = v["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 8);
    for cell in cells {
        let list = cell["draw_list"].as_array().unwrap();
        // Two side faces in view, each a whole face: plain face indices.
        assert_eq!(list.len(), 2, "{cell}");
        assert!(list.iter().all(|i| i.as_u64().is_some_and(|f| f < 6)));
        assert!(cell["hi"].as_f64().unwrap() > cell["lo"].as_f64().unwrap());
    }
}

#[test]
fn cube_yaw_bsp_breaks_at_quarter_turns_and_writes_a_page() {
    let (dir, model) = cube("bsp");
    let json = dir.join("bake.json");
    let html = dir.join("spin.html");
    let out = xtask(&[
        "bake",
        model.to_str().unwrap(),
        "--axis",
        "yaw",
        "--sorter",
        "bsp",
        "--json",
        json.to_str().unwrap(),
        "--html",
        html.to_str().unwrap(),
        "--period",
        "4",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap();
    assert_eq!(v["sorter"], "bsp");
    let at = breakpoints(&v);
    assert_eq!(at.len(), 4, "{at:?}");
    for (k, d) in at.iter().enumerate() {
        assert!((d - 90.0 * k as f64).abs() < 1e-9, "{at:?}");
    }
    let page = std::fs::read_to_string(html).unwrap();
    assert!(page.contains("@keyframes turn") && page.contains("4s linear"));
    assert_eq!(page.matches("class=\"cell\"").count(), 4);
    assert!(!page.contains("<script"));
}

#[test]
fn sampled_baseline_reports_missed_events_and_perspective_pitch_bakes_verify() {
    let v = bake_json(
        &[
            "--axis",
            "yaw",
            "--sorter",
            "bsp",
            "--method",
            "sampled",
            "--samples",
            "720",
        ],
        "sampled",
    );
    assert_eq!(v["method"], "sampled");
    assert!(v["missed"].as_u64().is_some());
    let v = bake_json(
        &[
            "--axis", "pitch", "--yaw", "30", "--persp", "600", "--sorter", "centroid",
        ],
        "pitch",
    );
    assert_eq!(v["axis"], "pitch");
    assert!(!breakpoints(&v).is_empty());
}

#[test]
fn pitch_range_bakes_two_axes_and_writes_their_cells() {
    let v = bake_json(
        &[
            "--axis",
            "yaw",
            "--sorter",
            "bsp",
            "--pitch-range",
            "-40,40",
        ],
        "two-axes",
    );
    assert_eq!(v["axes"], serde_json::json!(["yaw", "pitch"]));
    let cells = v["cells"].as_array().unwrap().len();
    let slabs = v["slabs"].as_array().unwrap();
    assert!(cells > 4 && !slabs.is_empty());
    // Every slab names a cell per gap between its curves, and the slabs tile the range.
    for s in slabs {
        let gaps = s["cells"].as_array().unwrap();
        assert_eq!(gaps.len(), s["curves"].as_array().unwrap().len() + 1);
        assert!(gaps.iter().all(|c| (c.as_u64().unwrap() as usize) < cells));
    }
    assert_eq!(slabs[0]["lo"].as_f64().unwrap(), -40.0);
    assert!((slabs[slabs.len() - 1]["hi"].as_f64().unwrap() - 40.0).abs() < 1e-9);
    // A cube's draw lists hold at most three faces, named by index (whole faces).
    for c in v["cells"].as_array().unwrap() {
        let list = c["draw_list"].as_array().unwrap();
        assert!(!list.is_empty() && list.len() <= 3);
        assert!(list.iter().all(Value::is_u64));
    }
    let (_, model) = cube("two-axes-pitch");
    let model = model.to_str().unwrap();
    let out = xtask(&["bake", model, "--axis", "pitch", "--pitch-range", "0,10"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--axis yaw"));
}

#[test]
fn cube_yaw_picture_is_one_cell_that_the_sink_culls() {
    let v = bake_json(&["--axis", "yaw", "--pitch", "20"], "picture");
    assert_eq!(v["sorter"], "picture");
    assert_eq!(v["method"], "picture");
    assert_eq!(v["culling"], "sink");
    assert_eq!(v["draw_list_items"], "piece indices");
    let pieces = v["pieces"].as_array().unwrap().len();
    // A convex cube needs no order at all: one cell for the whole turn, every piece in it.
    let cells = v["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 1);
    assert_eq!(cells[0]["draw_list"].as_array().unwrap().len(), pieces);
    assert!(breakpoints(&v).is_empty());
}

/// The finding that a full-spot `bake --json` was killed by the operating system for lack of
/// memory: the picture bake writes spot's JSON well under 5 MB, and a BSP-signature bake
/// over its byte budget stops with a clear error instead of growing.
#[test]
fn full_spot_bakes_to_json_within_its_budgets() {
    let model = test_support::model_path("keenan-crane/spot/spot_triangulated.obj");
    let dir = std::env::temp_dir().join(format!("xtask-bake-{}-spot", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let json = dir.join("spot.json");
    let (model, json_arg) = (model.to_str().unwrap(), json.to_str().unwrap());
    let out = xtask(&[
        "bake", model, "--axis", "yaw", "--pitch", "20", "--json", json_arg,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::metadata(&json).unwrap().len();
    println!("spot picture bake: {bytes} B of JSON");
    assert!(bytes < 5 << 20, "{bytes} B");
    let value: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(value["culling"], "sink");

    let out = xtask(&[
        "bake",
        model,
        "--axis",
        "yaw",
        "--pitch",
        "20",
        "--sorter",
        "bsp",
        "--budget-mib",
        "16",
        "--json",
        json_arg,
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("budget"), "{stderr}");
}
