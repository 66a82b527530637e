//! The real consumers tests show pages and files to: headless Chromium (HTML, SVG) and
//! poppler's `pdftoppm` (PDF), with the flags of docs/CHROMIUM.md. Missing consumers skip a
//! test with a notice, except under `CI`, where `.ci/run` installs them.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Where Debian's `chromium` package puts the browser.
pub const CHROMIUM: &str = "/usr/bin/chromium";

/// The browser, or `None` (with a notice) when it is missing outside CI; panics in CI.
#[must_use]
pub fn chromium() -> Option<&'static Path> {
    let path = Path::new(CHROMIUM);
    if path.exists() {
        return Some(path);
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "{CHROMIUM} is missing and CI is set: install the Debian package `chromium` \
         (apt-get install -y chromium) to run the HTML/CSS 3D tests"
    );
    eprintln!(
        "notice: {CHROMIUM} not found; skipping the headless Chromium test (set CI to make this fail)"
    );
    None
}

/// How Chromium shows a page.
#[derive(Clone, Copy, Debug)]
pub struct Screen {
    /// Window width and height in CSS pixels.
    pub size: u32,
    /// Device pixels per CSS pixel (the screenshot is `size · zoom` square).
    pub zoom: u32,
    /// Anti-alias layer edges as a default browser does; off for ID pictures
    /// (`--disable-composited-antialiasing`).
    pub composited_antialiasing: bool,
}

/// Headless Chromium's screenshot of `page` (an HTML or SVG file) written to `shot`.
/// Panics, with Chromium's messages, when no screenshot appears.
pub fn chromium_screenshot(browser: &Path, page: &Path, shot: &Path, screen: Screen) {
    let profile = shot.with_extension("profile");
    let mut args = vec![
        "--headless".to_owned(),
        "--no-sandbox".into(),
        "--disable-gpu".into(),
        "--disable-quic".into(),
        "--no-first-run".into(),
        "--disable-background-networking".into(),
        "--disable-component-update".into(),
        "--disable-sync".into(),
        format!("--user-data-dir={}", profile.display()),
        "--hide-scrollbars".into(),
        format!("--force-device-scale-factor={}", screen.zoom),
        "--force-color-profile=srgb".into(),
        // Every layer rastered before the capture: without it, a large page's screenshot
        // sometimes misses an element.
        "--run-all-compositor-stages-before-draw".into(),
        format!("--screenshot={}", shot.display()),
        format!("--window-size={0},{0}", screen.size),
        format!("file://{}", page.display()),
    ];
    if !screen.composited_antialiasing {
        args.push("--disable-composited-antialiasing".into());
    }
    let _ = std::fs::remove_file(shot);
    let output = Command::new(browser)
        .args(&args)
        .output()
        .expect("run chromium");
    let _ = std::fs::remove_dir_all(&profile);
    assert!(
        shot.exists(),
        "no screenshot; chromium said: {}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Whether `pdftoppm` runs (a notice when it does not, outside CI; panics in CI).
#[must_use]
pub fn pdftoppm_available() -> bool {
    let found = Command::new("pdftoppm").arg("-v").output().is_ok();
    if !found {
        assert!(
            std::env::var_os("CI").is_none(),
            "pdftoppm is missing and CI is set: install the Debian package `poppler-utils`"
        );
        eprintln!("notice: pdftoppm not found; skipping the PDF tests (set CI to make this fail)");
    }
    found
}

/// Rasterises page 1 of `pdf` at `72 · zoom` dpi (one point to `zoom` pixels) into
/// `stem.png`, anti-aliased as a default viewer does or not; returns the PNG's path.
pub fn pdftoppm(pdf: &Path, stem: &Path, zoom: u32, antialias: bool) -> PathBuf {
    let mut command = Command::new("pdftoppm");
    command.args(["-r", &(72 * zoom).to_string()]);
    if !antialias {
        command.args(["-aa", "no", "-aaVector", "no"]);
    }
    let output = command
        .args(["-png", "-singlefile"])
        .arg(pdf)
        .arg(stem)
        .output()
        .expect("run pdftoppm");
    assert!(
        output.status.success(),
        "pdftoppm: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    stem.with_extension("png")
}
