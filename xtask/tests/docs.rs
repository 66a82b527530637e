//! Docs that cannot drift: docs/ROBUSTNESS.md's tolerance table names every constant of every
//! crate's `tolerance` module exactly once (the values are read by people, not checked).

use std::collections::BTreeMap;
use std::path::Path;

const CRATES: [&str; 5] = [
    "obj-quads",
    "face-sort",
    "aspect-bake",
    "raster-sink",
    "sprite-compose",
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
