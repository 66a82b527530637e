//! Runs the built `xtask` binary: render the demo, a bad model, `--json`, and a smoke bench.

use std::path::PathBuf;
use std::process::{Command, Output};

fn xtask(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .output()
        .expect("run xtask")
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("xtask-test-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn render_demo_writes_a_png() {
    let dir = temp_dir("demo");
    let out = dir.join("demo.png");
    let result = xtask(&["render", "--size", "128x128", "-o", out.to_str().unwrap()]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    let stdout = text(&result.stdout);
    assert!(
        stdout.contains("faces") && stdout.contains("drawn"),
        "{stdout}"
    );
    let bytes = std::fs::read(&out).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
}

#[test]
fn render_bad_obj_fails_with_a_message() {
    let dir = temp_dir("bad");
    let model = dir.join("bad.obj");
    std::fs::write(&model, "v 0 0 0\nv 1 0 0\nf 1 2 7\n").unwrap();
    let out = dir.join("bad.png");
    let result = xtask(&[
        "render",
        model.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(!result.status.success());
    let stderr = text(&result.stderr);
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!out.exists());
}

#[test]
fn render_json_has_the_keys() {
    let dir = temp_dir("json");
    let out = dir.join("box.png");
    let model = test_support::model_path("assimp-obj/box.obj");
    let model = model.to_str().unwrap();
    let result = xtask(&[
        "render",
        model,
        "--json",
        "--size",
        "64x64",
        "--yaw",
        "30",
        "--pitch",
        "-20",
        "--check",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    let value: serde_json::Value = serde_json::from_slice(&result.stdout).expect("one JSON object");
    for key in [
        "faces",
        "drawn",
        "fragments",
        "sorter",
        "load_ms",
        "sort_ms",
        "raster_ms",
        "plan",
    ] {
        assert!(value.get(key).is_some(), "missing {key}: {value}");
    }
    assert_eq!(value["faces"], 6);
    assert_eq!(value["violations"], 0);
}

#[test]
fn render_ids_writes_an_id_image() {
    let dir = temp_dir("ids");
    let out = dir.join("ids.png");
    let model = test_support::model_path("assimp-obj/box.obj");
    let model = model.to_str().unwrap();
    let result = xtask(&[
        "render",
        model,
        "--ids",
        "--size",
        "32x32",
        "--yaw",
        "30",
        "--pitch",
        "20",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    assert!(out.exists());
}

#[test]
fn bench_smoke_writes_the_reports() {
    let dir = temp_dir("bench");
    let result = xtask(&["bench", "--smoke", "--out", dir.to_str().unwrap()]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    let rows: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    let rows = rows.as_array().expect("an array of rows");
    for sorter in ["centroid", "topological", "newell", "bsp", "plane-split"] {
        assert!(
            rows.iter().any(|r| r["sorter"] == sorter),
            "no {sorter} row"
        );
    }
    for key in [
        "sorter",
        "scene",
        "projection",
        "faces",
        "frame_us",
        "build_ms",
        "fragments",
        "pixel_error",
        "violations",
        "frame_ratio_vs_centroid",
        "same_view_us",
        "same_view_ratio_vs_centroid",
    ] {
        assert!(rows[0].get(key).is_some(), "missing {key}");
    }
    for row in rows
        .iter()
        .filter(|r| r["sorter"] == "bsp" || r["sorter"] == "newell")
    {
        assert_eq!(row["violations"], 0, "{row}");
    }
    assert!(dir.join("report.md").exists() && dir.join("chart.svg").exists());
}

/// `bench --presort-scaling` writes a row per size with build time, memory, certificate
/// bytes and per-frame ratios against the centroid sort, and a certificate that covers the
/// frames it measured (no fallback frame).
#[test]
fn bench_presort_scaling_writes_its_table() {
    let dir = temp_dir("bench-presort");
    let result = xtask(&[
        "bench",
        "--smoke",
        "--presort-scaling",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    let table = std::fs::read_to_string(dir.join("presort-scaling.md")).unwrap();
    let row = table
        .lines()
        .find(|l| l.starts_with("| 200 |"))
        .unwrap_or_else(|| panic!("no row for 200 faces in {table}"));
    let cells: Vec<&str> = row.split('|').map(str::trim).collect();
    assert!(
        cells[3].ends_with(" s") && cells[5].ends_with(" KB"),
        "{row}"
    );
    assert!(cells[8].contains('×') && cells[9].contains('×'), "{row}");
    assert_eq!(cells[11], "0", "fallback frames: {row}");
}

/// `bench --presort-cache DIR` builds each scene's certificate once and loads it on the next
/// run, and the presorted rows say which, with no violation either way.
#[test]
fn bench_reuses_its_presort_cache() {
    let dir = temp_dir("bench-cache");
    let cache = dir.join("certificates");
    let _ = std::fs::remove_dir_all(&cache);
    for (run, had) in [(1, "built and saved"), (2, "loaded from")] {
        let out = dir.join(format!("run{run}"));
        let result = xtask(&[
            "bench",
            "--smoke",
            "--out",
            out.to_str().unwrap(),
            "--presort-cache",
            cache.to_str().unwrap(),
        ]);
        assert!(result.status.success(), "{}", text(&result.stderr));
        let rows: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap())
                .unwrap();
        let presorted: Vec<&serde_json::Value> = rows
            .as_array()
            .expect("an array of rows")
            .iter()
            .filter(|r| r["sorter"] == "presorted")
            .collect();
        assert!(!presorted.is_empty());
        for row in presorted {
            assert!(
                row["note"]
                    .as_str()
                    .is_some_and(|n| n.contains(&format!("certificate {had}"))),
                "run {run}: {row}"
            );
            assert_eq!(row["violations"], 0, "{row}");
        }
    }
}

#[test]
fn fuzz_few_cases_passes() {
    let dir = temp_dir("fuzz");
    let result = xtask(&["fuzz", "--cases", "20", "--out", dir.to_str().unwrap()]);
    assert!(
        result.status.success(),
        "{}{}",
        text(&result.stdout),
        text(&result.stderr)
    );
}

/// Runs `render MODEL --json --check` with extra flags and returns the summary.
fn render_summary(model: &str, extra: &[&str], name: &str) -> serde_json::Value {
    let out = temp_dir(name).join("out.png");
    let mut args = vec!["render", model, "--json", "--check", "--size", "96x96"];
    args.extend_from_slice(extra);
    args.extend_from_slice(&["-o", out.to_str().unwrap()]);
    let result = xtask(&args);
    assert!(result.status.success(), "{}", text(&result.stderr));
    serde_json::from_slice(&result.stdout).expect("one JSON object")
}

#[test]
fn auto_culls_a_convex_box_only_and_stays_exact() {
    let model = test_support::model_path("assimp-obj/box.obj");
    let model = model.to_str().unwrap();
    for (i, extra) in [
        &["--yaw", "30", "--pitch", "-20"][..],
        &["--yaw", "200", "--pitch", "50", "--persp", "150"][..],
        &["--yaw", "10", "--cull", "none"][..],
    ]
    .into_iter()
    .enumerate()
    {
        let value = render_summary(model, extra, &format!("convex-{i}"));
        assert_eq!(value["sorter"], "cull-only", "{value}");
        assert!(
            value["plan"].as_str().unwrap().contains("cull only"),
            "{value}"
        );
        // No fragments: one item per drawn face.
        assert_eq!(value["fragments"], value["drawn"], "{value}");
        assert_eq!(value["violations"], 0, "{value}");
        assert_eq!(value["pixel_error"], 0.0, "{value}");
    }
}

#[test]
fn auto_takes_newell_for_one_picture_of_a_curved_model() {
    let model = test_support::model_path("keenan-crane/spot/spot_quadrangulated.obj");
    let model = model.to_str().unwrap();
    let value = render_summary(model, &["--yaw", "120", "--pitch", "15"], "spot-auto");
    assert_eq!(value["sorter"], "newell", "{value}");
    assert!(
        value["plan"].as_str().unwrap().contains("one frame"),
        "{value}"
    );
    assert_eq!(value["violations"], 0, "{value}");
    assert_eq!(value["pixel_error"], 0.0, "{value}");
}

#[test]
fn presorted_renders_exactly_at_any_rotation() {
    // Models outside the bench, at views of every kind: the pixels against the z-buffer
    // truth, and the oracle. (A sweep of more models and views is in docs/bench.md.)
    for model in [
        "keenan-crane/spot/spot_control_mesh.obj",
        "opensubdiv-torus/catmark_torus_creases0.obj",
        "compas/tubemesh.obj",
    ] {
        let path = test_support::model_path(model);
        for (i, extra) in [
            &["--yaw", "137", "--pitch", "-32", "--roll", "71"][..],
            &[
                "--yaw", "274", "--pitch", "21", "--roll", "142", "--persp", "180",
            ][..],
            &[
                "--yaw", "51", "--pitch", "74", "--roll", "213", "--persp", "300",
            ][..],
        ]
        .into_iter()
        .enumerate()
        {
            let value = render_summary(
                path.to_str().unwrap(),
                &[extra, &["--sorter", "presorted"][..]].concat(),
                &format!("presorted-{i}"),
            );
            assert_eq!(value["sorter"], "presorted", "{value}");
            assert_eq!(value["violations"], 0, "{model}: {value}");
            assert_eq!(value["pixel_error"], 0.0, "{model}: {value}");
        }
    }
}

/// `--sorter presorted` never falls back silently: a near eye says that this view was drawn by
/// the BSP and why, in `--json` and in the summary line; a certificate saved with
/// `--presort-cache` is loaded on the next run and orders as exactly.
#[test]
fn presorted_says_when_it_falls_back_and_reuses_its_cache() {
    let model = test_support::model_path("keenan-crane/spot/spot_control_mesh.obj");
    let model = model.to_str().unwrap();
    // The eye 60 px from the centre at 96 px: nearer than 1.5 bounding radii.
    let near = ["--sorter", "presorted", "--yaw", "30", "--persp", "60"];
    let value = render_summary(model, &near, "presorted-near");
    assert_eq!(value["presorted"]["drawn_by"], "bsp", "{value}");
    assert!(
        value["presorted"]["fell_back"]
            .as_str()
            .is_some_and(|why| why.contains("nearer than min_eye_distance")),
        "{value}"
    );
    assert_eq!(value["presorted"]["fallback_frames"], 1, "{value}");
    assert_eq!(value["violations"], 0, "{value}");
    let out = temp_dir("presorted-near-line").join("out.png");
    let line = xtask(
        &[
            &["render", model][..],
            &near,
            &["-o", out.to_str().unwrap()],
        ]
        .concat(),
    );
    assert!(
        text(&line.stdout).contains("this view fell back to the BSP"),
        "{}",
        text(&line.stdout)
    );

    let cache = temp_dir("presorted-cache").join("spot.presort");
    let _ = std::fs::remove_file(&cache);
    let cached = [
        "--sorter",
        "presorted",
        "--yaw",
        "30",
        "--presort-cache",
        cache.to_str().unwrap(),
    ];
    let first = render_summary(model, &cached, "presorted-cache-1");
    assert!(
        first["presorted"]["certificate"]
            .as_str()
            .is_some_and(|c| c.starts_with("built and saved")),
        "{first}"
    );
    let second = render_summary(model, &cached, "presorted-cache-2");
    assert!(
        second["presorted"]["certificate"]
            .as_str()
            .is_some_and(|c| c.starts_with("loaded from")),
        "{second}"
    );
    for value in [&first, &second] {
        assert_eq!(value["presorted"]["drawn_by"], "presorted", "{value}");
        assert_eq!(value["violations"], 0, "{value}");
        assert_eq!(value["pixel_error"], 0.0, "{value}");
    }
    assert_eq!(first["fragments"], second["fragments"]);
}

#[test]
fn bench_docs_check_accepts_the_committed_report() {
    let result = xtask(&["bench", "--docs", "--check"]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    assert!(
        text(&result.stdout).contains("in the current report format"),
        "{}",
        text(&result.stdout)
    );
}

#[test]
fn svg_leaves_hidden_parts_out_unless_asked() {
    let model = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/models/keenan-crane/spot/spot_control_mesh.obj"
    );
    let dir = temp_dir("svg-hidden");
    let mut shapes = Vec::new();
    for keep in [false, true] {
        let svg = dir.join(format!("spot-{keep}.svg"));
        let mut extra = vec!["--cull", "none", "--svg", svg.to_str().unwrap()];
        if keep {
            extra.push("--keep-hidden");
        }
        let value = render_summary(model, &extra, &format!("svg-hidden-{keep}"));
        assert_eq!(value["svg"]["keep_hidden"], keep, "{value}");
        let written = std::fs::read_to_string(&svg).unwrap();
        assert_eq!(value["svg"]["bytes"], written.len(), "{value}");
        shapes.push(value["svg"]["shapes"].as_u64().unwrap());
    }
    // With no culling about half of the polygons face away and lie behind the others.
    assert!(shapes[0] * 10 <= shapes[1] * 6, "{shapes:?}");
}

#[test]
fn pdf_is_written_beside_the_png() {
    let model = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/models/suzanne/suzanne.obj"
    );
    let pdf = temp_dir("pdf").join("suzanne.pdf");
    let value = render_summary(model, &["--ids", "--pdf", pdf.to_str().unwrap()], "pdf");
    let bytes = std::fs::read(&pdf).unwrap();
    assert!(bytes.starts_with(b"%PDF-"), "not a PDF");
    assert_eq!(value["pdf"]["bytes"], bytes.len(), "{value}");
    assert_eq!(value["pdf"]["keep_hidden"], false, "{value}");
}

#[test]
fn render_refuses_files_outside_the_model_folder_unless_allowed() {
    let dir = temp_dir("outside");
    std::fs::create_dir_all(dir.join("model")).unwrap();
    std::fs::write(dir.join("secret.mtl"), "newmtl m\nKd 1 0 0\n").unwrap();
    let model = dir.join("model/m.obj");
    std::fs::write(
        &model,
        "mtllib ../secret.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl m\nf 1 2 3 4\n",
    )
    .unwrap();
    let out = dir.join("m.png");
    let args = [
        "render",
        model.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    let result = xtask(&args);
    assert!(!result.status.success());
    let stderr = text(&result.stderr);
    assert!(
        stderr.contains("../secret.mtl") && stderr.contains("outside the model's folder"),
        "{stderr}"
    );
    assert!(!out.exists());
    let result = xtask(&[&args[..], &["--allow-outside"]].concat());
    assert!(result.status.success(), "{}", text(&result.stderr));
    assert!(out.exists());
}

#[test]
fn render_survives_a_texture_declaring_30000_squared_pixels() {
    let dir = temp_dir("bomb");
    // PNG signature and an IHDR declaring 30000 × 30000 RGBA (CRC left zero: the size is
    // refused before the chunk is checked), then nothing.
    let mut png = b"\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR".to_vec();
    png.extend(30_000u32.to_be_bytes());
    png.extend(30_000u32.to_be_bytes());
    png.extend([8, 6, 0, 0, 0, 0, 0, 0, 0]);
    std::fs::write(dir.join("bomb.png"), png).unwrap();
    std::fs::write(dir.join("m.mtl"), "newmtl m\nKd 1 0 0\nmap_Kd bomb.png\n").unwrap();
    let model = dir.join("m.obj");
    std::fs::write(
        &model,
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
         vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3 4/4\n",
    )
    .unwrap();
    let out = dir.join("m.png");
    let result = xtask(&[
        "render",
        model.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    let stderr = text(&result.stderr);
    assert!(
        stderr.contains("bomb.png") && stderr.contains("texture width in pixels is 30000"),
        "{stderr}"
    );
    assert!(out.exists());
}

#[test]
fn plot_writes_strokes_and_hpgl() {
    let model = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/models/fandisk-quads/fandisk_quads.converted.obj"
    );
    let dir = temp_dir("plot");
    let (svg, hpgl) = (dir.join("fandisk.svg"), dir.join("fandisk.hpgl"));
    let mut counts = Vec::new();
    for crease in ["30", "89"] {
        let value = render_summary(
            model,
            &[
                "--plot",
                svg.to_str().unwrap(),
                "--hpgl",
                hpgl.to_str().unwrap(),
                "--crease",
                crease,
            ],
            &format!("plot-{crease}"),
        );
        let plot = &value["plot"];
        let written = std::fs::read_to_string(&svg).unwrap();
        assert_eq!(plot["bytes"], written.len(), "{value}");
        assert_eq!(
            written.matches("<path").count() as u64,
            plot["polylines"].as_u64().unwrap(),
            "{value}"
        );
        assert!(written.contains("fill=\"none\"") && !written.contains("<polygon"));
        let hpgl = std::fs::read_to_string(&hpgl).unwrap();
        assert!(hpgl.starts_with("IN;SP1;"), "{hpgl}");
        assert!(plot["pen_down_px"].as_f64().unwrap() > 100.0, "{value}");
        assert!(plot["pen_up_px"].as_f64().is_some(), "{value}");
        counts.push(plot["edges"].as_u64().unwrap());
    }
    // A larger crease angle draws fewer creases.
    assert!(counts[1] < counts[0], "{counts:?}");
}

#[test]
fn wire_and_points_are_drawn_in_png_svg_and_pdf() {
    let model = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/models/fandisk-quads/fandisk_quads.converted.obj"
    );
    let dir = temp_dir("wire");
    let (svg, pdf) = (dir.join("fandisk.svg"), dir.join("fandisk.pdf"));
    let mut sizes = Vec::new();
    for extra in [&[][..], &["--wire", "--points"][..]] {
        let mut args = vec![
            "--svg",
            svg.to_str().unwrap(),
            "--pdf",
            pdf.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        render_summary(model, &args, &format!("wire-{}", extra.len()));
        let written = std::fs::read_to_string(&svg).unwrap();
        sizes.push((
            written.matches("<line").count(),
            written.matches("<circle").count(),
            std::fs::metadata(&pdf).unwrap().len(),
        ));
    }
    assert_eq!((sizes[0].0, sizes[0].1), (0, 0), "{sizes:?}");
    // Fandisk's 764 faces: hundreds of visible edge parts and vertices.
    assert!(sizes[1].0 > 300 && sizes[1].1 > 100, "{sizes:?}");
    assert!(sizes[1].2 > sizes[0].2, "{sizes:?}");
}

#[test]
fn embedded_gltf_textures_reach_every_writer() {
    use test_support::textured_box::{ImageSource, textured_box};
    let dir = temp_dir("glb");
    let glb = dir.join("box.glb");
    std::fs::write(
        &glb,
        textured_box(ImageSource::Glb, Some([0.5, 1.0, 0.25, 1.0])),
    )
    .unwrap();
    let (svg, html) = (dir.join("box.svg"), dir.join("box.html"));
    let out = xtask(&[
        "render",
        glb.to_str().unwrap(),
        "--yaw",
        "30",
        "--pitch",
        "25",
        "--svg",
        svg.to_str().unwrap(),
        "--html",
        html.to_str().unwrap(),
        "-o",
        dir.join("box.png").to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    // No warning about the texture: it is drawn, not replaced by the fallback colour.
    assert!(
        !text(&out.stderr).contains("texture"),
        "{}",
        text(&out.stderr)
    );
    for page in [&svg, &html] {
        let written = std::fs::read_to_string(page).unwrap();
        assert!(
            written.contains("data:image/png;base64,"),
            "{}: the embedded, tinted texture is written as a data URI",
            page.display()
        );
    }
}

#[test]
fn gltf_renders_through_the_scene_path_exactly() {
    let dir = temp_dir("gltf-scene");
    let model = dir.join("cubes.gltf");
    std::fs::write(&model, test_support::gltf_scene::cube_scene_gltf()).unwrap();
    let svg = dir.join("cubes.svg");
    for view in [
        &["--yaw", "30", "--pitch", "25"][..],
        &["--yaw", "250", "--pitch", "50", "--persp", "700"][..],
    ] {
        let mut args = vec!["--svg", svg.to_str().unwrap()];
        args.extend_from_slice(view);
        let value = render_summary(model.to_str().unwrap(), &args, "gltf-scene");
        assert!(
            value["plan"]
                .as_str()
                .unwrap()
                .starts_with("glTF scene: 5 instances of 1 meshes"),
            "{value}"
        );
        assert_eq!(value["violations"], 0, "{value}");
        assert_eq!(value["pixel_error"], 0.0, "{value}");
        assert!(std::fs::read_to_string(&svg).unwrap().contains("<polygon"));
    }
}

#[test]
fn the_demo_scene_is_exact_through_the_scene_path() {
    let out = temp_dir("scene").join("scene.png");
    let result = xtask(&[
        "render",
        "--scene",
        "--check",
        "--json",
        "--size",
        "160x160",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    let value: serde_json::Value = serde_json::from_slice(&result.stdout).unwrap();
    assert_eq!(value["instances"], 56, "{value}");
    assert_eq!(value["violations"], 0, "{value}");
    assert_eq!(value["composite_wrong"], 0, "{value}");
    assert!(out.exists());
}

/// `render --plot` writes exactly the library's plot of the same view (`plot_edges`, whose
/// visible parts sprite-compose's plot tests judge against the truth for lines): on the
/// nested and interpenetrating boxes of those tests.
#[test]
fn render_plot_is_the_librarys_plot() {
    use face_sort::glam::DVec3;
    let v = DVec3::new;
    let mesh = test_support::models::boxes(&[
        (v(-1.0, -1.0, -1.0), v(1.0, 1.0, 1.0)),
        (v(0.2, -0.4, -0.4), v(1.6, 0.3, 0.5)),
        (v(-0.5, -0.5, -0.5), v(0.0, 0.0, 0.0)),
        (v(-0.8, 1.0, -0.6), v(-0.1, 1.5, 0.2)),
    ]);
    let dir = temp_dir("plot-boxes");
    let obj = dir.join("boxes.obj");
    std::fs::write(&obj, test_support::to_obj(&mesh, &[])).unwrap();
    let svg = dir.join("boxes.svg");
    let out = xtask(&[
        "render",
        obj.to_str().unwrap(),
        "--yaw",
        "30",
        "--pitch",
        "20",
        "--size",
        "256x256",
        "--plot",
        svg.to_str().unwrap(),
        "-o",
        dir.join("boxes.png").to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let loaded = test_support::polygon_mesh(&test_support::load_model_at(&obj));
    let geometry = face_sort::Geometry::new(&loaded).unwrap();
    let view =
        face_sort::View::fit(&geometry.bounds(), 256, 256).with_yaw_pitch_roll(30.0, 20.0, 0.0);
    let plot = sprite_compose::plot_edges(
        &loaded,
        &geometry,
        &view,
        &sprite_compose::PlotOptions::DEFAULT,
    );
    assert!(
        plot.edges
            .iter()
            .any(|e| e.kind == sprite_compose::EdgeKind::Silhouette)
    );
    assert_eq!(
        std::fs::read_to_string(&svg).unwrap(),
        vector_sink::plot_svg(&plot, 1.0)
    );
}

/// The file's camera, projected independently: glam's own matrices from the glTF values
/// (node pose, `yfov`, `aspectRatio`, `znear`; `xmag`, `ymag`), a ray per pixel centre
/// unprojected through their inverse, the nearest triangle by Möller–Trumbore in f64. The
/// ID image `render --camera N` writes must agree on every pixel that is not ambiguous
/// (0.75 px from a projected edge, or two nearest depths within 1e-6 of each other).
#[test]
fn render_camera_draws_what_the_files_camera_sees() {
    use glam::{DMat4, DQuat, DVec2, DVec3};
    let dir = temp_dir("gltf-camera");
    let model = dir.join("cubes.gltf");
    std::fs::write(&model, test_support::gltf_scene::cube_scene_gltf()).unwrap();
    let (mesh, _) = obj_quads::load_gltf(&model, &obj_quads::LoadOptions::default()).unwrap();
    let triangles: Vec<[DVec3; 3]> = (0..mesh.face_count())
        .map(|f| {
            let c = mesh.face(f).unwrap();
            assert_eq!(c.len(), 3, "the scene is triangles");
            [0, 1, 2].map(|k| mesh.positions()[c[k] as usize])
        })
        .collect();
    let root = DMat4::from_quat(DQuat::from_xyzw(0.0, 0.2588190451, 0.0, 0.9659258263));
    let cameras = [
        (
            DMat4::from_rotation_translation(
                DQuat::from_xyzw(-0.1300295007, 0.0864101133, 0.0113761072, 0.9876721144)
                    .normalize(),
                DVec3::new(2.0, 3.0, 9.0),
            ),
            glam::dcamera::rh::proj::directx::perspective(0.7, 1.5, 0.1, 100.0),
        ),
        (
            root * DMat4::from_translation(DVec3::new(0.0, 1.0, 10.0)),
            glam::dcamera::rh::proj::directx::orthographic(-4.5, 4.5, -3.0, 3.0, 0.1, 100.0),
        ),
    ];
    let (w, h) = (240u32, 160u32);
    for (n, (pose, projection)) in cameras.iter().enumerate() {
        let clip_from_model = *projection * pose.inverse();
        let model_from_clip = clip_from_model.inverse();
        let unproject = |ndc: DVec3| {
            let p = model_from_clip * ndc.extend(1.0);
            p.truncate() / p.w
        };
        let pixel_of = |p: DVec3| {
            let c = clip_from_model * p.extend(1.0);
            DVec2::new(
                f64::from(w) * 0.5 * (1.0 + c.x / c.w),
                f64::from(h) * 0.5 * (1.0 - c.y / c.w),
            )
        };
        let projected: Vec<[DVec2; 3]> = triangles.iter().map(|t| t.map(pixel_of)).collect();
        for sorter in ["bsp", "newell"] {
            let out = dir.join(format!("camera{n}-{sorter}.png"));
            let result = xtask(&[
                "render",
                model.to_str().unwrap(),
                "--camera",
                &n.to_string(),
                "--size",
                "240x240",
                "--sorter",
                sorter,
                "--ids",
                "-o",
                out.to_str().unwrap(),
            ]);
            assert!(result.status.success(), "{}", text(&result.stderr));
            let image = obj_quads::decode_texture(
                &std::fs::read(&out).unwrap(),
                "ids.png",
                &obj_quads::LoadOptions::default(),
            )
            .unwrap();
            assert_eq!(
                (image.width, image.height),
                (w, h),
                "the height follows the aspect"
            );
            let (mut compared, mut wrong) = (0usize, 0usize);
            for y in 0..h {
                for x in 0..w {
                    let centre = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
                    let ndc = DVec2::new(
                        centre.x / f64::from(w) * 2.0 - 1.0,
                        1.0 - centre.y / f64::from(h) * 2.0,
                    );
                    let (a, b) = (unproject(ndc.extend(0.0)), unproject(ndc.extend(1.0)));
                    let d = (b - a).normalize();
                    let mut hits: Vec<(f64, usize)> = triangles
                        .iter()
                        .enumerate()
                        .filter_map(|(f, t)| ray_triangle(a, d, t).map(|s| (s, f)))
                        .collect();
                    hits.sort_by(|p, q| p.0.total_cmp(&q.0));
                    let near_edge = projected.iter().any(|t| {
                        (0..3).any(|k| segment_distance(centre, t[k], t[(k + 1) % 3]) < 0.75)
                    });
                    let close = hits.len() > 1 && hits[1].0 - hits[0].0 < 1e-6 * 10.0;
                    if near_edge || close {
                        continue;
                    }
                    let want = hits.first().map_or(0, |&(_, f)| f as u32 + 1);
                    let at = 4 * (y * w + x) as usize;
                    let px = &image.rgba[at..at + 3];
                    let got = u32::from(px[0]) << 16 | u32::from(px[1]) << 8 | u32::from(px[2]);
                    if want != 0 {
                        compared += 1;
                    }
                    if got != want {
                        wrong += 1;
                    }
                }
            }
            assert_eq!(
                wrong, 0,
                "camera {n}, {sorter}: {wrong} of {compared} pixels differ"
            );
            assert!(
                compared > 1000,
                "camera {n}: only {compared} covered pixels compared"
            );
        }
    }
}

/// Distance along a unit ray to a triangle (Möller–Trumbore), either side facing.
fn ray_triangle(o: glam::DVec3, d: glam::DVec3, t: &[glam::DVec3; 3]) -> Option<f64> {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-15 {
        return None;
    }
    let s = o - t[0];
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = d.dot(q) / det;
    if u < 0.0 || v < 0.0 || u + v > 1.0 {
        return None;
    }
    let along = e2.dot(q) / det;
    (along > 0.0).then_some(along)
}

/// Distance from `p` to the segment `a`–`b`.
fn segment_distance(p: glam::DVec2, a: glam::DVec2, b: glam::DVec2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared().max(1e-300)).clamp(0.0, 1.0);
    (a + ab * t).distance(p)
}

#[test]
fn turn_writes_a_page_or_says_why_not() {
    let dir = temp_dir("turn");
    let page = dir.join("book.html");
    let book = test_support::model_path("combobulate-samples/book.obj");
    let result = xtask(&[
        "turn",
        book.to_str().unwrap(),
        "--html",
        page.to_str().unwrap(),
        "--yaw",
        "30",
        "--pitch",
        "-20",
    ]);
    assert!(result.status.success(), "{}", text(&result.stderr));
    let stdout = text(&result.stdout);
    assert!(
        stdout.contains("1 orders") && stdout.contains("one order serves every view"),
        "{stdout}"
    );
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.contains("const S=[[30,-20]]") && html.contains("backface-visibility:hidden"));
    // boxes: near eyes are left uncertified, so there is no page for them.
    let boxes = test_support::model_path("compas/boxes.obj");
    let result = xtask(&[
        "turn",
        boxes.to_str().unwrap(),
        "--html",
        dir.join("boxes.html").to_str().unwrap(),
        "--persp",
        "600",
    ]);
    assert!(!result.status.success());
    let stderr = text(&result.stderr);
    assert!(stderr.contains("no certified order"), "{stderr}");
}
