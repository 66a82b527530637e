//! Replays every committed fuzz input through its target's check: the minimised corpora
//! (`fuzz/corpus/TARGET/`) and the regressions, each a crash or hang that libFuzzer found
//! and that is fixed (`fuzz/regressions/TARGET/`). The findings not fixed yet wait under
//! `fuzz/open/TARGET/`; an ignored test lists which of them still fail
//! (`cargo test -p fuzz-checks --test integration replay -- --ignored --nocapture`).

use std::path::Path;

fn inputs(dir: &Path) -> Vec<std::path::PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut files: Vec<_> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    files
}

fn replay(folder: &str, at_least: usize) {
    let mut total = 0;
    for target in fuzz_checks::TARGETS {
        let dir = fuzz_checks::fuzz_dir().join(folder).join(target.name);
        let files = inputs(&dir);
        for file in &files {
            let data = std::fs::read(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            let result = std::panic::catch_unwind(|| (target.check)(&data));
            assert!(result.is_ok(), "{} fails its check", file.display());
        }
        println!("{}: {} {folder} inputs pass", target.name, files.len());
        total += files.len();
    }
    assert!(
        total >= at_least,
        "{total} {folder} inputs, expected at least {at_least}"
    );
}

#[test]
fn the_regressions_stay_fixed() {
    replay("regressions", 1);
}

#[test]
fn the_corpora_pass() {
    replay("corpus", fuzz_checks::TARGETS.len());
}

/// The open findings, each still failing (move one to `fuzz/regressions/` once it passes).
#[test]
#[ignore = "open findings fail until fixed; run to see which still do"]
fn open_findings_still_fail() {
    let mut passing = Vec::new();
    for target in fuzz_checks::TARGETS {
        let dir = fuzz_checks::fuzz_dir().join("open").join(target.name);
        for file in inputs(&dir) {
            let data = std::fs::read(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            let failed = std::panic::catch_unwind(|| (target.check)(&data)).is_err();
            println!(
                "{}: {}",
                file.display(),
                if failed { "fails" } else { "PASSES" }
            );
            if !failed {
                passing.push(file);
            }
        }
    }
    assert!(
        passing.is_empty(),
        "fixed, move to fuzz/regressions/: {passing:?}"
    );
}

/// The `certificate` corpus's seed is the fixture's own certificate (the build and the format
/// unchanged), so that libFuzzer starts from bytes that load. `WRITE_CERTIFICATE_SEED=1`
/// writes it again after a deliberate change of either.
#[test]
fn the_certificate_seed_is_the_fixtures_certificate() {
    let (geometry, bytes) = fuzz_checks::certificate::fixture();
    let seed = fuzz_checks::fuzz_dir().join("corpus/certificate/valid");
    if std::env::var_os("WRITE_CERTIFICATE_SEED").is_some() {
        std::fs::create_dir_all(seed.parent().unwrap()).unwrap();
        std::fs::write(&seed, bytes).unwrap();
    }
    let committed = std::fs::read(&seed).unwrap_or_else(|e| panic!("{}: {e}", seed.display()));
    assert!(
        &committed == bytes,
        "{} is not the fixture's certificate",
        seed.display()
    );
    assert!(face_sort::Presorted::from_bytes(&committed, geometry).is_ok());
}
