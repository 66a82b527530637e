//! Replays the committed sorter cases of `tests/data/sorters/` (README there): every exact
//! sorter must order each case's view with zero oracle violations. Each file also names the
//! sorter it once broke; a case saved for a sorter that is not exact (the centroid sort) must
//! still break it, so that the file keeps testing something hard.

use crate::common;
use face_sort::strategies::ViewSpec;
use face_sort::{DrawList, Geometry, SorterKind, oracle};

/// A saved case: the OBJ, its view and the sorter it was saved for.
struct Case {
    name: String,
    geometry: Geometry,
    spec: ViewSpec,
    saved_for: SorterKind,
}

fn cases() -> Vec<Case> {
    let dir = test_base::test_data_dir().join("sorters");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "obj"))
        .collect();
    paths.sort();
    paths
        .into_iter()
        .map(|path| {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            let text = std::fs::read_to_string(&path).expect("case file");
            let comment = |prefix: &str| {
                text.lines()
                    .find_map(|l| l.strip_prefix("# ")?.strip_prefix(prefix))
                    .unwrap_or_else(|| panic!("{name}: no `# {prefix}` line"))
                    .to_owned()
            };
            let spec: ViewSpec = comment("view-spec: ")
                .parse()
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            let sorter = name.split('-').next().unwrap_or_default();
            let saved_for = SorterKind::ALL
                .into_iter()
                .find(|k| k.name() == sorter)
                .unwrap_or_else(|| panic!("{name}: no sorter named `{sorter}`"));
            let mesh = common::read_obj(&path);
            let geometry = Geometry::new(&mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
            Case {
                name,
                geometry,
                spec,
                saved_for,
            }
        })
        .collect()
}

fn violations(kind: SorterKind, case: &Case, list: &mut DrawList) -> usize {
    let view = case.spec.view(&case.geometry);
    kind.build(&case.geometry).sort(&view, list);
    oracle::count_violations(&view, list)
}

#[test]
fn committed_sorter_cases_replay() {
    let cases = cases();
    assert!(!cases.is_empty(), "tests/data/sorters/ holds no case");
    let mut list = DrawList::new();
    for case in &cases {
        for kind in SorterKind::EXACT {
            assert_eq!(
                violations(kind, case, &mut list),
                0,
                "{}: {} ({})",
                case.name,
                kind.name(),
                case.spec
            );
        }
        if !SorterKind::EXACT.contains(&case.saved_for) {
            assert!(
                violations(case.saved_for, case, &mut list) > 0,
                "{}: no longer breaks {}, so it tests nothing hard",
                case.name,
                case.saved_for.name()
            );
        }
    }
}

#[test]
fn view_spec_text_round_trips() {
    for text in [
        "yaw=30.0 pitch=-20.5 roll=0.0 eye=ortho cull=back",
        "yaw=1e-300 pitch=0.1 roll=359.9 eye=0.6000000000000001 cull=none",
        "yaw=0.0 pitch=0.0 roll=0.0 eye=2.0 cull=front",
    ] {
        let spec: ViewSpec = text.parse().expect(text);
        assert_eq!(spec.to_string(), text);
        assert_eq!(spec.to_string().parse::<ViewSpec>().unwrap(), spec);
    }
    for bad in ["yaw", "yaw=x", "eye=inf", "cull=sideways", "zoom=2"] {
        assert!(bad.parse::<ViewSpec>().is_err(), "{bad}");
    }
}
