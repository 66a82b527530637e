//! Vector files that ship: for BoxTextured (embedded-in-folder texture, MIRRORED_REPEAT and
//! CLAMP_TO_EDGE samplers, u from 0 to 6) and the demo's textured spot at three views, and
//! for spot in its flat palette colours, `render --svg --html --pdf` writes files that, each
//! copied alone into an empty folder, show the model in its own materials through the real
//! consumers: Chromium (SVG, HTML) and poppler's `pdftoppm` (PDF). At most 1 % of covered
//! pixels may be off raster-sink's PNG of the same view by more than 48 in a channel, and
//! no hole may be wider than 2 px (a covered pixel whose whole 3 × 3 neighbourhood is that
//! far off). The HTML page is also shown in Chromium's GPU compositor (SwiftShader) and at
//! device scale factor 2. "Covered" is a pixel whose 3 × 3 neighbourhood the ID image
//! covers: along the silhouette each consumer blends with the background.

use std::path::{Path, PathBuf};
use std::process::Command;

fn xtask(args: &[&str]) {
    let out = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .output()
        .expect("run xtask");
    assert!(
        out.status.success(),
        "xtask {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn fresh_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("xtask-ship-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn rgba(path: &Path) -> (u32, u32, Vec<u8>) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let t = obj_quads::decode_texture(&bytes, "png", &obj_quads::LoadOptions::DEFAULT)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (t.width, t.height, t.rgba)
}

use test_support::consumers::{
    Screen, chromium, chromium_screenshot, pdftoppm, pdftoppm_available,
};

/// Chromium's screenshot of `file`, beside it.
fn chromium_shot(browser: &Path, file: &Path, screen: Screen) -> PathBuf {
    let shot = file.with_file_name(format!("shot-{}x.png", screen.zoom));
    chromium_screenshot(browser, file, &shot, screen);
    shot
}

/// Covered pixels whose whole 3 × 3 neighbourhood is off the PNG by more than 48 in a
/// channel: a hole (or a crack) at least 3 px across, where a page shows something else than
/// the model. `off` flags each pixel; `covered` lists the pixels judged.
fn holes(off: &[bool], covered: &[usize], w: usize) -> Vec<(usize, usize)> {
    covered
        .iter()
        .filter(|&&k| {
            let (x, y) = (k % w, k / w);
            x > 0
                && y > 0
                && x + 1 < w
                && k + w < off.len()
                && (0..3).all(|dy| (0..3).all(|dx| off[(y + dy - 1) * w + x + dx - 1]))
        })
        .map(|&k| (k % w, k / w))
        .collect()
}

/// The files of one model at one view, and how each consumer shows them.
struct ShipCase {
    name: &'static str,
    model: PathBuf,
    extra: Vec<String>,
    yaw: &'static str,
    pitch: &'static str,
    /// (file kind, screen) pairs to check: "pdf" ignores the screen.
    shows: Vec<(&'static str, Screen)>,
}

#[test]
fn rendered_files_travel_alone_and_match_the_png() {
    use test_support::consumers::Compositor;
    let (Some(browser), true) = (chromium(), pdftoppm_available()) else {
        return;
    };
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/models");
    let spot = assets.join("keenan-crane/spot/spot_quadrangulated.obj");
    let spot_texture = vec![
        "--texture".to_owned(),
        assets
            .join("keenan-crane/spot/spot_texture.png")
            .display()
            .to_string(),
    ];
    let boxtextured = assets.join("gltf/BoxTextured/BoxTextured.gltf");
    let size = 512u32;
    let screen = |zoom, compositor| Screen {
        size,
        zoom,
        composited_antialiasing: true,
        compositor,
    };
    let one = screen(1, Compositor::Software);
    // The HTML page in both compositors and at device scale factor 2 at the first view; SVG
    // and PDF at three views.
    let html_everywhere = vec![
        ("html", one),
        ("html", screen(2, Compositor::Software)),
        ("html", screen(1, Compositor::SwiftShader)),
        ("svg", one),
        ("pdf", one),
    ];
    let files = vec![("html", one), ("svg", one), ("pdf", one)];
    let mut cases = Vec::new();
    for (name, model, extra) in [
        ("boxtextured", &boxtextured, vec![]),
        ("spot", &spot, spot_texture.clone()),
    ] {
        for (k, (yaw, pitch)) in [("145", "-25"), ("30", "20"), ("-100", "10")]
            .into_iter()
            .enumerate()
        {
            cases.push(ShipCase {
                name,
                model: model.clone(),
                extra: extra.clone(),
                yaw,
                pitch,
                shows: if k == 0 {
                    html_everywhere.clone()
                } else {
                    files.clone()
                },
            });
        }
    }
    // Spot in its own flat colours (every face its palette colour: edges of strong
    // contrast, where cracks show most).
    cases.push(ShipCase {
        name: "spot-flat",
        model: spot.clone(),
        extra: vec![],
        yaw: "145",
        pitch: "-25",
        shows: html_everywhere.clone(),
    });
    for case in cases {
        check_against_the_png(browser, &case);
    }
}

/// Renders `case`'s files, IDs and PNG with `render`, shows each file alone to its consumer,
/// and asserts the bars of this file's docs.
fn check_against_the_png(browser: &Path, case: &ShipCase) {
    use test_support::consumers::Compositor;
    let size = 512u32;
    let name = format!("{}-{}-{}", case.name, case.yaw, case.pitch);
    let work = fresh_dir(&name);
    let file = |ext: &str| work.join(format!("{}.{ext}", case.name));
    let mut args: Vec<String> = vec!["render".into(), case.model.display().to_string()];
    for arg in [
        "--yaw", case.yaw, "--pitch", case.pitch, "--size", "512x512",
    ] {
        args.push(arg.to_owned());
    }
    args.extend(case.extra.iter().cloned());
    let ids_args: Vec<String> = args
        .iter()
        .cloned()
        .chain([
            "--ids".into(),
            "-o".into(),
            file("ids.png").display().to_string(),
        ])
        .collect();
    xtask(&ids_args.iter().map(String::as_str).collect::<Vec<_>>());
    let mut colour_args = args.clone();
    for (flag, ext) in [
        ("--svg", "svg"),
        ("--html", "html"),
        ("--pdf", "pdf"),
        ("-o", "png"),
    ] {
        colour_args.push(flag.into());
        colour_args.push(file(ext).display().to_string());
    }
    xtask(&colour_args.iter().map(String::as_str).collect::<Vec<_>>());
    let (w, h, ids) = rgba(&file("ids.png"));
    let (_, _, reference) = rgba(&file("png"));
    assert_eq!((w, h), (size, size));
    let id_at = |x: i64, y: i64| {
        if x < 0 || y < 0 || x >= i64::from(w) || y >= i64::from(h) {
            return false;
        }
        let k = 4 * (y as usize * w as usize + x as usize);
        ids[k..k + 3] != [0, 0, 0]
    };
    let covered: Vec<usize> = (0..i64::from(h))
        .flat_map(|y| (0..i64::from(w)).map(move |x| (x, y)))
        .filter(|&(x, y)| (-1..=1).all(|dy| (-1..=1).all(|dx| id_at(x + dx, y + dy))))
        .map(|(x, y)| y as usize * w as usize + x as usize)
        .collect();
    assert!(
        covered.len() > 5_000,
        "{name}: {} covered pixels",
        covered.len()
    );
    for (ext, screen) in &case.shows {
        // The file alone, in an empty folder far from the model's.
        let alone = fresh_dir(&format!("{name}-{ext}-alone"));
        let copy = alone.join(format!("{}.{ext}", case.name));
        std::fs::copy(file(ext), &copy).expect("copy");
        let text = String::from_utf8_lossy(&std::fs::read(&copy).expect("read")).into_owned();
        assert!(
            !text.contains("/assets/") && !text.contains("file://"),
            "{name}.{ext} names a file outside itself"
        );
        // As a default viewer shows them: anti-aliased, one point or pixel to a pixel
        // (at device scale factor 2, each pixel the mean of its 2 × 2 device pixels).
        let shot = match *ext {
            "pdf" => pdftoppm(&copy, &copy.with_extension(""), 1, true),
            _ => chromium_shot(browser, &copy, *screen),
        };
        let zoom = if *ext == "pdf" {
            1
        } else {
            screen.zoom as usize
        };
        let (sw, sh, pixels) = rgba(&shot);
        assert_eq!(
            (sw as usize, sh as usize),
            (size as usize * zoom, size as usize * zoom),
            "{name}.{ext}: screenshot size"
        );
        let at = |k: usize, c: usize| -> i32 {
            let (x, y) = (k % w as usize, k / w as usize);
            let mut sum = 0;
            for dy in 0..zoom {
                for dx in 0..zoom {
                    let j = (y * zoom + dy) * sw as usize + x * zoom + dx;
                    sum += i32::from(pixels[4 * j + c]);
                }
            }
            sum / (zoom * zoom) as i32
        };
        let mut off = vec![false; (w * h) as usize];
        for &k in &covered {
            off[k] = (0..3).any(|c| (at(k, c) - i32::from(reference[4 * k + c])).abs() > 48);
        }
        let off_count = off.iter().filter(|&&o| o).count();
        let share = off_count as f64 / covered.len() as f64;
        let holes = holes(&off, &covered, w as usize);
        let how = match (*ext, screen.compositor) {
            ("pdf", _) => "poppler".to_owned(),
            (_, Compositor::Software) => format!("chromium software {}x", screen.zoom),
            (_, Compositor::SwiftShader) => format!("chromium gpu {}x", screen.zoom),
        };
        println!(
            "{name}.{ext} ({how}): {} bytes, {off_count} of {} covered pixels off by > 48 ({:.3} %), {} hole pixels",
            text.len(),
            covered.len(),
            share * 100.0,
            holes.len()
        );
        assert!(
            share <= 0.01,
            "{name}.{ext} ({how}): {:.3} % off",
            share * 100.0
        );
        assert!(
            holes.is_empty(),
            "{name}.{ext} ({how}): holes wider than 2 px at {:?}",
            &holes[..holes.len().min(5)]
        );
        let _ = std::fs::remove_dir_all(&alone);
    }
    let _ = std::fs::remove_dir_all(&work);
}

/// Spot with the default options: the static HTML page is at most 1.5 MB and the SVG at most
/// 400 KB, and in ID mode both are exact in Chromium at 1× and zoomed 4× (device scale
/// factor 4 against the truth of the same view at 4× the resolution): not one unambiguous
/// pixel shows another face.
#[test]
fn spot_pages_are_small_and_exact_in_id_mode_at_one_and_four_times() {
    let Some(browser) = chromium() else {
        return;
    };
    let model = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/models/keenan-crane/spot/spot_quadrangulated.obj");
    let work = fresh_dir("spot-ids");
    let view = ["--yaw", "145", "--pitch", "-25"];
    let run = |extra: &[&str]| {
        let model = model.display().to_string();
        let mut args = vec!["render", model.as_str()];
        args.extend_from_slice(&view);
        args.extend_from_slice(extra);
        xtask(&args);
    };
    let path = |name: &str| work.join(name).display().to_string();
    run(&[
        "--svg",
        &path("spot.svg"),
        "--html",
        &path("spot.html"),
        "-o",
        &path("spot.png"),
    ]);
    let (svg, html) = (
        std::fs::metadata(work.join("spot.svg")).expect("svg").len(),
        std::fs::metadata(work.join("spot.html"))
            .expect("html")
            .len(),
    );
    println!("spot, default options: SVG {svg} bytes, HTML {html} bytes");
    assert!(svg <= 400_000, "SVG {svg} bytes");
    assert!(html <= 1_500_000, "HTML {html} bytes");
    run(&[
        "--ids",
        "--svg",
        &path("ids.svg"),
        "--html",
        &path("ids.html"),
        "-o",
        &path("ids.png"),
    ]);

    let (mesh, _) = obj_quads::load(&model, &obj_quads::LoadOptions::DEFAULT).expect("spot");
    let polygons = face_sort::PolygonMesh::new(mesh.positions(), mesh.faces()).expect("mesh");
    let geometry = face_sort::Geometry::new(&polygons).expect("geometry");
    let base =
        face_sort::View::fit(&geometry.bounds(), 512, 512).with_yaw_pitch_roll(145.0, -25.0, 0.0);
    for zoom in [1u32, 4] {
        let view = base
            .with_size(512 * zoom, 512 * zoom)
            .with_scale(base.scale() * f64::from(zoom));
        let truth = raster_sink::truth(&view, &geometry);
        for file in ["ids.svg", "ids.html"] {
            let shot = chromium_shot(
                browser,
                &work.join(file),
                Screen {
                    size: 512,
                    zoom,
                    composited_antialiasing: false,
                    compositor: test_support::consumers::Compositor::Software,
                },
            );
            let (w, h, pixels) = rgba(&shot);
            assert_eq!((w, h), (512 * zoom, 512 * zoom), "{file} at {zoom}x");
            let ids = raster_sink::IdImage {
                width: w,
                height: h,
                ids: pixels
                    .chunks_exact(4)
                    .map(|p| u32::from(p[0]) << 16 | u32::from(p[1]) << 8 | u32::from(p[2]))
                    .collect(),
            };
            let error = raster_sink::pixel_error(&ids, &truth);
            println!(
                "{file} at {zoom}x: {} wrong of {} unambiguous pixels",
                error.wrong, error.pixels
            );
            assert!(
                error.pixels > 10_000 * (zoom * zoom) as usize,
                "{file}: {}",
                error.pixels
            );
            assert_eq!(error.wrong, 0, "{file} at {zoom}x");
        }
    }
    let _ = std::fs::remove_dir_all(&work);
}
