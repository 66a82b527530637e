//! Replays every committed loader regression case in `tests/data/loaders/` (see its
//! README): no panic, and a valid mesh or a typed error.

use test_support::loaders::{Verdict, check_loader_input, loader_cases, loader_cases_dir};

#[test]
fn every_committed_loader_case_loads_or_is_refused() {
    let cases = loader_cases();
    assert!(
        !cases.is_empty(),
        "no cases in {}",
        loader_cases_dir().display()
    );
    let scratch = std::env::temp_dir().join(format!("obj-quads-cases-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).expect("scratch folder");
    let mut failures = Vec::new();
    for (path, format) in &cases {
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("?");
        let bytes = std::fs::read(path).expect("read case");
        match check_loader_input(*format, &bytes, &scratch) {
            Err(bug) => failures.push(format!("{name}: {bug}")),
            Ok(verdict) => {
                println!("{name}: {verdict:?}");
                let wrong = match verdict {
                    Verdict::Loaded(_) => name.starts_with("hand-refused-"),
                    Verdict::Refused(_) => name.starts_with("hand-loads-"),
                };
                if wrong {
                    failures.push(format!("{name}: unexpected verdict {verdict:?}"));
                }
            }
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
