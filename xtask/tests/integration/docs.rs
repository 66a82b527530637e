//! Docs that cannot drift: docs/ROBUSTNESS.md's tolerance table names every constant of every
//! crate's `tolerance` module exactly once (the values are read by people, not checked), and
//! rustdoc states contracts: no doc comment quotes a timing or a commit (figures live in
//! docs/bench.md and the READMEs, with their commands).

use std::collections::BTreeMap;
use std::path::Path;

const CRATES: [&str; 6] = [
    "obj-quads",
    "face-sort",
    "aspect-bake",
    "raster-sink",
    "sprite-compose",
    "vector-sink",
];

/// `pub const NAME` of a tolerance module.
fn constants(source: &str) -> Vec<String> {
    source
        .lines()
        .filter_map(|l| l.trim().strip_prefix("pub const "))
        .map(|rest| rest.split(':').next().unwrap_or_default().trim().to_owned())
        .collect()
}

/// (crate path, constant) → how many table rows name it. A row names one crate's
/// `tolerance` module in its first cell, then one or more constants: as
/// `` `krate::tolerance::NAME` `` or as backticked `` `NAME` `` after the link.
fn table_names(doc: &str) -> BTreeMap<(String, String), usize> {
    let section = doc
        .split("\n## Tolerances")
        .nth(1)
        .expect("docs/ROBUSTNESS.md has a `## Tolerances` section");
    let mut names = BTreeMap::new();
    for row in section.lines().filter(|l| l.starts_with("| [`")) {
        let first = row.split(" | ").next().unwrap_or_default();
        let krate = first
            .trim_start_matches("| [`")
            .split("::tolerance")
            .next()
            .unwrap_or_default()
            .to_owned();
        for word in first.split('`').skip(1).step_by(2) {
            let name = word.rsplit("::").next().unwrap_or_default();
            for name in name.split(", ") {
                if !name.is_empty()
                    && name
                        .chars()
                        .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
                {
                    *names.entry((krate.clone(), name.to_owned())).or_default() += 1;
                }
            }
        }
    }
    names
}

#[test]
fn robustness_tolerance_table_lists_every_constant_once() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let doc = std::fs::read_to_string(root.join("docs/ROBUSTNESS.md")).expect("ROBUSTNESS.md");
    let table = table_names(&doc);
    let mut expected = BTreeMap::new();
    for krate in CRATES {
        let source = std::fs::read_to_string(root.join(krate).join("src/tolerance.rs"))
            .unwrap_or_else(|e| panic!("{krate}/src/tolerance.rs: {e}"));
        let names = constants(&source);
        assert!(!names.is_empty(), "{krate}: no constants read");
        for name in names {
            expected.insert((krate.replace('-', "_"), name), 1usize);
        }
    }
    let missing: Vec<_> = expected
        .keys()
        .filter(|k| !table.contains_key(*k))
        .collect();
    let twice: Vec<_> = table.iter().filter(|(_, n)| **n > 1).collect();
    let unknown: Vec<_> = table
        .keys()
        .filter(|k| !expected.contains_key(*k))
        .collect();
    assert!(
        missing.is_empty() && twice.is_empty() && unknown.is_empty(),
        "docs/ROBUSTNESS.md's tolerance table: missing {missing:?}, listed more than once \
         {twice:?}, not in the source {unknown:?}"
    );
}

/// Every `.rs` file under `dir`, recursively.
fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Whether a doc comment's text quotes a timing (a number with a time unit) or a commit (a
/// 7 to 40 digit hex word with both digits and letters).
fn quotes_timing_or_commit(text: &str) -> Option<String> {
    let words: Vec<&str> = text
        .split(|c: char| c.is_whitespace() || "(),;:`[]".contains(c))
        .map(|w| w.trim_end_matches(['.', '!', '?']))
        .filter(|w| !w.is_empty())
        .collect();
    for (k, w) in words.iter().enumerate() {
        let number = |w: &str| {
            let w = w.trim_start_matches(['~', '≈']);
            !w.is_empty()
                && w.chars().next().is_some_and(|c| c.is_ascii_digit())
                && w.chars().all(|c| c.is_ascii_digit() || ".,–-".contains(c))
        };
        let unit = |u: &str| matches!(u, "ms" | "µs" | "us" | "ns" | "s");
        // "132 s", "2.1 ms", and glued forms "805µs", "3.4s".
        if number(w) && words.get(k + 1).is_some_and(|u| unit(u)) {
            return Some(format!("{w} {}", words[k + 1]));
        }
        if let Some(split) = w.find(|c: char| c.is_alphabetic() || c == 'µ')
            && split > 0
            && number(&w[..split])
            && unit(&w[split..])
        {
            return Some((*w).to_owned());
        }
        let hex = w.len() >= 7
            && w.len() <= 40
            && w.chars()
                .all(|c| c.is_ascii_hexdigit() && !c.is_ascii_uppercase())
            && w.chars().any(|c| c.is_ascii_digit())
            && w.chars().any(|c| c.is_ascii_alphabetic());
        if hex {
            return Some((*w).to_owned());
        }
    }
    None
}

#[test]
fn rustdoc_quotes_no_timing_or_commit() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for krate in CRATES
        .iter()
        .chain(&["xtask", "test-support", "sink-checks"])
    {
        for dir in ["src", "examples", "benches", "tests"] {
            rust_files(&root.join(krate).join(dir), &mut files);
        }
    }
    assert!(files.len() > 100, "only {} files found", files.len());
    let mut found = Vec::new();
    for path in &files {
        let source = std::fs::read_to_string(path).expect("readable source");
        for (n, line) in source.lines().enumerate() {
            let trimmed = line.trim_start();
            let Some(text) = trimmed
                .strip_prefix("///")
                .or_else(|| trimmed.strip_prefix("//!"))
            else {
                continue;
            };
            if let Some(what) = quotes_timing_or_commit(text) {
                found.push(format!("{}:{}: {what}", path.display(), n + 1));
            }
        }
    }
    assert!(
        found.is_empty(),
        "doc comments quoting timings or commits:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_timing_and_commit_check_can_fail() {
    assert!(quotes_timing_or_commit(" took 132 s at 1M faces").is_some());
    assert!(quotes_timing_or_commit(" 805µs per frame").is_some());
    assert!(quotes_timing_or_commit(" see docs/bench.md on 7ec9817.").is_some());
    assert!(quotes_timing_or_commit(" a 3×3 system of 4 corners, 1e-12").is_none());
    assert!(quotes_timing_or_commit(" Milliseconds the bake took.").is_none());
}
