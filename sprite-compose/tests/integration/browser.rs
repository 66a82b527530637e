//! HTML/CSS 3D pages screenshot in headless Chromium, compared with raster-sink.
//!
//! Needs `/usr/bin/chromium` (Debian package `chromium`). Without it the tests print a notice
//! and pass, unless the environment variable `CI` is set: then they fail.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use raster_sink::{pixel_error, render_ids, truth};
use sprite_compose::face_sort::SorterKind;
use sprite_compose::{HtmlMode, HtmlOptions, write_html};

use crate::writers::{SIZE, differing, ids_of_rgba, spot_painter};

const CHROMIUM: &str = "/usr/bin/chromium";

fn chromium() -> Option<&'static Path> {
    let path = Path::new(CHROMIUM);
    if path.exists() {
        return Some(path);
    }
    if std::env::var_os("CI").is_some() {
        panic!(
            "{CHROMIUM} is missing and CI is set: install the Debian package `chromium` \
             (apt-get install -y chromium) to run the HTML/CSS 3D tests"
        );
    }
    eprintln!(
        "notice: {CHROMIUM} not found; skipping the headless Chromium test (set CI to make this fail)"
    );
    None
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sprite-compose-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Screenshots `html` at `SIZE × SIZE` with the flags of docs/CHROMIUM.md; returns RGBA bytes.
fn screenshot(browser: &Path, html: &str, name: &str) -> Vec<u8> {
    let dir = temp_dir(name);
    let page = dir.join("page.html");
    let shot = dir.join("shot.png");
    std::fs::write(&page, html).expect("write page");
    let profile = dir.join("profile");
    let output = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            &format!("--user-data-dir={}", profile.display()),
            "--hide-scrollbars",
            "--force-device-scale-factor=1",
            "--disable-composited-antialiasing",
            "--force-color-profile=srgb",
            &format!("--screenshot={}", shot.display()),
            &format!("--window-size={SIZE},{SIZE}"),
            &format!("file://{}", page.display()),
        ])
        .output()
        .expect("run chromium");
    let pixmap = resvg::tiny_skia::Pixmap::load_png(&shot).unwrap_or_else(|e| {
        panic!(
            "no screenshot ({e}); chromium said: {}",
            String::from_utf8_lossy(&output.stderr)
        )
    });
    assert_eq!((pixmap.width(), pixmap.height()), (SIZE, SIZE));
    let _ = std::fs::remove_dir_all(&dir);
    pixmap.data().to_vec()
}

#[test]
fn html_pages_in_chromium_match_raster_sink() {
    let Some(browser) = chromium() else {
        return;
    };
    // spot's control mesh: 180 faces, non-planar quads → fan triangles (border triangles).
    for (perspective, mode) in [
        (false, HtmlMode::Flat),
        (true, HtmlMode::Flat),
        (true, HtmlMode::Preserve3d),
    ] {
        let (g, p) = spot_painter(SorterKind::Newell, 35.0, perspective);
        let html = write_html(
            p.compositor().scene(),
            &HtmlOptions::DEFAULT
                .with_size(SIZE, SIZE)
                .with_mode(mode)
                .with_ids(true),
        );
        let started = Instant::now();
        let rgba = screenshot(browser, &html, &format!("{mode:?}-{perspective}"));
        let seconds = started.elapsed().as_secs_f64();
        let shot = ids_of_rgba(SIZE, SIZE, &rgba);
        let t = truth(p.view(), &g);
        let e = pixel_error(&shot, &t);
        let (wrong, n) = differing(&shot, &render_ids(p.view(), p.draw_list()), &t);
        println!(
            "chromium {mode:?} persp={perspective}: vs truth {}/{} = {:.4} %, vs our ID image {wrong}/{n} ({seconds:.1} s)",
            e.wrong,
            e.pixels,
            e.error * 100.0
        );
        match mode {
            // Our order, the browser only composites: near 0.
            HtmlMode::Flat => assert!(e.error <= 2e-3, "flat page: {e:?}"),
            // The browser's own 3D ordering: reported, loosely bounded.
            HtmlMode::Preserve3d => assert!(e.error <= 0.05, "preserve-3d page: {e:?}"),
        }
    }
}
