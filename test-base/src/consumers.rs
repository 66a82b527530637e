//! The real consumers tests show pages and files to: headless Chromium (HTML, SVG) and
//! poppler's `pdftoppm` (PDF), with the flags of docs/CHROMIUM.md. Missing consumers skip a
//! test with a notice, except under `CI`, where `.ci/run` installs them.

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

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
    /// Which compositor draws the layers.
    pub compositor: Compositor,
}

/// The two ways Chromium composites a page's layers (docs/CHROMIUM.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compositor {
    /// The software compositor of a machine without a GPU (`--disable-gpu`).
    Software,
    /// GPU rasterisation and compositing, as on a machine with a GPU, run on the CPU by
    /// SwiftShader (`--use-angle=swiftshader --enable-unsafe-swiftshader`).
    SwiftShader,
}

/// How long one screenshot may take (a large page takes seconds) before Chromium is killed
/// and the screenshot tried again, instead of waiting for ever.
pub const SCREENSHOT_DEADLINE: Duration = Duration::from_secs(180);

/// How many times a screenshot that does not finish within [`SCREENSHOT_DEADLINE`] is
/// tried before the test fails.
pub const SCREENSHOT_ATTEMPTS: u32 = 3;

/// Headless Chromium's screenshot of `page` (an HTML or SVG file) written to `shot`.
/// Panics, with Chromium's messages, when no screenshot appears, or none within
/// [`SCREENSHOT_DEADLINE`] in [`SCREENSHOT_ATTEMPTS`] tries.
pub fn chromium_screenshot(browser: &Path, page: &Path, shot: &Path, screen: Screen) {
    let profile = shot.with_extension("profile");
    let log = shot.with_extension("log");
    let mut args = vec![
        "--headless".to_owned(),
        "--no-sandbox".into(),
        "--disable-quic".into(),
        "--no-first-run".into(),
        "--disable-background-networking".into(),
        "--disable-component-update".into(),
        "--disable-sync".into(),
        format!("--user-data-dir={}", profile.display()),
        "--hide-scrollbars".into(),
        format!("--force-device-scale-factor={}", screen.zoom),
        "--force-color-profile=srgb".into(),
        format!("--screenshot={}", shot.display()),
        format!("--window-size={0},{0}", screen.size),
        format!("file://{}", page.display()),
    ];
    match screen.compositor {
        Compositor::Software => args.extend([
            "--disable-gpu".into(),
            // Every layer rastered before the capture: without it, a large page's
            // screenshot sometimes misses an element.
            "--run-all-compositor-stages-before-draw".into(),
        ]),
        // Without that flag: with it, about one screenshot in six never finishes here.
        Compositor::SwiftShader => args.extend([
            "--use-angle=swiftshader".into(),
            "--enable-unsafe-swiftshader".into(),
        ]),
    }
    if !screen.composited_antialiasing {
        args.push("--disable-composited-antialiasing".into());
    }
    let mut said = String::new();
    for attempt in 1..=SCREENSHOT_ATTEMPTS {
        let _ = std::fs::remove_file(shot);
        let finished = run_until_deadline(browser, &args, &log, SCREENSHOT_DEADLINE);
        said = std::fs::read_to_string(&log).unwrap_or_default();
        let _ = std::fs::remove_dir_all(&profile);
        let _ = std::fs::remove_file(&log);
        if finished {
            break;
        }
        // A screenshot that never finishes is Chromium's flake (docs/CHROMIUM.md), not a
        // result: the same page is shown again, from a fresh profile.
        assert!(
            attempt < SCREENSHOT_ATTEMPTS,
            "chromium did not finish within {SCREENSHOT_DEADLINE:?} ({:?}), {SCREENSHOT_ATTEMPTS} times; it said: {said}",
            screen.compositor
        );
        eprintln!(
            "notice: chromium did not finish within {SCREENSHOT_DEADLINE:?} ({:?}); showing {} again (attempt {} of {SCREENSHOT_ATTEMPTS})",
            screen.compositor,
            page.display(),
            attempt + 1
        );
    }
    assert!(shot.exists(), "no screenshot; chromium said: {said}");
}

/// Runs Chromium with `args`, its messages to `log`, until it exits (true) or
/// `deadline` passes (false: the browser and every process it started are
/// killed).
fn run_until_deadline(browser: &Path, args: &[String], log: &Path, deadline: Duration) -> bool {
    let messages = std::fs::File::create(log).expect("chromium's log file");
    let mut child = Command::new(browser)
        .args(args)
        .process_group(0)
        .stdout(Stdio::null())
        .stderr(messages)
        .spawn()
        .expect("run chromium");
    let started = Instant::now();
    loop {
        if child.try_wait().expect("wait for chromium").is_some() {
            return true;
        }
        if started.elapsed() > deadline {
            // The whole process group (`kill -KILL -PGID` without `--` leaves it running:
            // procps reads the group as an option), then the browser itself.
            let _ = Command::new("kill")
                .args(["-s", "KILL", "--", &format!("-{}", child.id())])
                .status();
            let _ = child.kill();
            let _ = child.wait();
            return false;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_browser_past_its_deadline_is_killed_with_every_process_it_started() {
        let dir = std::env::temp_dir().join(format!("consumers-deadline-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let pid_file = dir.join("pid");
        // A "browser" that starts a helper and never exits.
        let script = format!("sleep 100 & echo $! > {}; wait", pid_file.display());
        let args = ["-c".to_owned(), script];
        let started = Instant::now();
        let finished = run_until_deadline(
            Path::new("/bin/sh"),
            &args,
            &dir.join("log"),
            Duration::from_millis(300),
        );
        assert!(!finished);
        assert!(started.elapsed() < Duration::from_secs(10));
        let helper = std::fs::read_to_string(&pid_file).unwrap();
        let helper = Path::new("/proc").join(helper.trim());
        // Killed processes leave /proc once their parent (init, for an orphan) reaps them.
        let gone = (0..100).any(|_| {
            std::thread::sleep(Duration::from_millis(20));
            std::fs::read_to_string(helper.join("stat")).map_or(true, |stat| stat.contains(") Z "))
        });
        assert!(gone, "{} survived", helper.display());
        // A browser that exits in time is not killed.
        assert!(run_until_deadline(
            Path::new("/bin/sh"),
            &["-c".to_owned(), "exit 0".to_owned()],
            &dir.join("log"),
            Duration::from_secs(60),
        ));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
