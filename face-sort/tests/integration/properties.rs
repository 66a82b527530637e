//! Every sorter against the oracle on generated scenes. Exact sorters must leave zero
//! violations; the others are measured and must stay within bounds (a valid permutation of the
//! drawn pieces). Each property runs [`DEFAULT_CASES`] cases, or `PROPTEST_CASES` when that
//! variable is set (e.g. `PROPTEST_CASES=1000 cargo test -p face-sort --release --test
//! properties`); `cargo xtask fuzz` runs many more.

use face_sort::strategies::{
    any_scene, crossing_scene, cyclic_scene, interpenetrating_scene, non_intersecting_scene,
    view_spec,
};
use face_sort::{DrawList, Geometry, PolygonMesh, SorterKind, oracle};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::Config;

/// Cases per property when `PROPTEST_CASES` is not set: modest, for CI.
const DEFAULT_CASES: u32 = 48;

/// [`DEFAULT_CASES`], unless `PROPTEST_CASES` is set: then proptest's own reading of it
/// (`Config::default()` parses the variable). The scene strategies filter their polygons
/// (about 35 rejects per accepted crossing scene), so the reject limit grows with the
/// cases; proptest's fixed default (65,536) stopped 10,000 crossing cases after 1,901.
fn config() -> Config {
    let base = if std::env::var_os("PROPTEST_CASES").is_some() {
        Config::default()
    } else {
        Config::with_cases(DEFAULT_CASES)
    };
    Config {
        max_local_rejects: base.max_local_rejects.max(base.cases.saturating_mul(256)),
        ..base
    }
}

fn exact_sorters_leave_no_violation(
    scene: &PolygonMesh,
    spec: &face_sort::strategies::ViewSpec,
) -> Result<(), TestCaseError> {
    let geometry = Geometry::new(scene).unwrap();
    let view = spec.view(&geometry);
    let mut list = DrawList::new();
    for kind in SorterKind::EXACT {
        let mut sorter = kind.build(&geometry);
        sorter.sort(&view, &mut list);
        let found = oracle::find_violations(&view, &list, 3);
        prop_assert!(
            found.is_empty(),
            "{} left violations {:?}",
            kind.name(),
            found
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn exact_on_non_intersecting_scenes(scene in non_intersecting_scene(), spec in view_spec()) {
        exact_sorters_leave_no_violation(&scene, &spec)?;
    }

    #[test]
    fn exact_on_interpenetrating_scenes(scene in interpenetrating_scene(), spec in view_spec()) {
        exact_sorters_leave_no_violation(&scene, &spec)?;
    }

    #[test]
    fn exact_on_cyclic_scenes(scene in cyclic_scene(), spec in view_spec()) {
        exact_sorters_leave_no_violation(&scene, &spec)?;
    }

    #[test]
    fn exact_on_crossing_scenes(scene in crossing_scene(), spec in view_spec()) {
        exact_sorters_leave_no_violation(&scene, &spec)?;
    }

    #[test]
    fn every_sorter_draws_each_drawn_piece_area_once(scene in any_scene(), spec in view_spec()) {
        // Each sorter draws exactly the pieces the cull keeps: as many items as that for the
        // unsplit sorters, and every drawn face at least once for the splitting ones.
        let geometry = Geometry::new(&scene).unwrap();
        let view = spec.view(&geometry);
        let pieces = geometry.pieces();
        let cull = view.cull_test();
        let mut drawn_faces: Vec<u32> = (0..pieces.len())
            .filter(|&i| cull.is_drawn(pieces.plane(i), pieces.corners(i)[0]))
            .map(|i| pieces.face(i))
            .collect();
        drawn_faces.sort_unstable();
        drawn_faces.dedup();
        let mut list = DrawList::new();
        for kind in SorterKind::ALL {
            let mut sorter = kind.build(&geometry);
            sorter.sort(&view, &mut list);
            let mut faces: Vec<u32> = list.items().iter().map(|i| i.face).collect();
            faces.sort_unstable();
            faces.dedup();
            prop_assert_eq!(&faces, &drawn_faces, "{}", kind.name());
        }
    }
}

#[test]
fn the_cyclic_scene_defeats_the_centroid_order() {
    // The strategies must produce cases where a non-exact order fails, or the property
    // tests above would prove nothing.
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let mut failures = 0;
    for _ in 0..64 {
        let scene = cyclic_scene().new_tree(&mut runner).unwrap().current();
        let geometry = Geometry::new(&scene).unwrap();
        let view =
            face_sort::View::fit(&geometry.bounds(), 256, 256).with_cull(face_sort::CullMode::None);
        let mut sorter = SorterKind::Centroid.build(&geometry);
        let mut list = DrawList::new();
        sorter.sort(&view, &mut list);
        failures += usize::from(oracle::count_violations(&view, &list) > 0);
    }
    assert!(
        failures > 0,
        "no generated cycle fooled the centroid sorter"
    );
}
