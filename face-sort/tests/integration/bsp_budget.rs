//! The BSP fragment budget: a scene whose tree needs about `n²` fragments is refused with a
//! typed error under a tight budget, built under the default one, and the Newell fallback
//! is exact where the BSP was refused.

use face_sort::glam::DVec3;
use face_sort::{
    Bsp, BspError, BspFallback, BspOptions, BspTree, CullMode, DrawList, Geometry, PolygonMesh,
    View, oracle,
};

/// `n` horizontal slabs crossed by `n` vertical walls: every wall's plane cuts every slab
/// (and every slab's plane every wall), so any BSP tree needs about `n²` fragments.
fn grid_of_crossing_quads(n: usize) -> PolygonMesh {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    let mut quad = |corners: [DVec3; 4]| {
        let start = positions.len() as u32;
        positions.extend(corners);
        faces.push([start, start + 1, start + 2, start + 3]);
    };
    for k in 0..n {
        let t = -1.0 + 2.0 * (k as f64 + 0.5) / n as f64;
        // A slab at height y = t, slightly tilted so that no plane is axis-aligned.
        let y = |x: f64, z: f64| t + 0.01 * x + 0.007 * z;
        quad([
            DVec3::new(-1.0, y(-1.0, -1.0), -1.0),
            DVec3::new(-1.0, y(-1.0, 1.0), 1.0),
            DVec3::new(1.0, y(1.0, 1.0), 1.0),
            DVec3::new(1.0, y(1.0, -1.0), -1.0),
        ]);
        // A wall at x = t.
        quad([
            DVec3::new(t, -1.2, -1.1),
            DVec3::new(t, 1.2, -1.1),
            DVec3::new(t, 1.2, 1.1),
            DVec3::new(t, -1.2, 1.1),
        ]);
    }
    PolygonMesh::new(positions, faces).unwrap()
}

fn tight() -> BspOptions {
    let mut options = BspOptions::DEFAULT;
    options.max_fragments_per_piece = 2.0;
    options.min_fragment_budget = 0;
    options
}

#[test]
fn the_budget_scales_with_pieces_and_has_a_floor() {
    let options = BspOptions::DEFAULT;
    assert_eq!(options.fragment_budget(10), 4096);
    assert_eq!(options.fragment_budget(10_000), 160_000);
    assert_eq!(tight().fragment_budget(7), 14);
    let mut zero = tight();
    zero.max_fragments_per_piece = 0.0;
    // Never below the pieces: an unsplit tree always fits.
    assert_eq!(zero.fragment_budget(7), 7);
}

#[test]
fn a_quadratic_scene_exceeds_a_tight_budget_with_a_typed_error() {
    let geometry = Geometry::new(&grid_of_crossing_quads(24)).unwrap();
    let pieces = geometry.pieces().len();
    assert_eq!(pieces, 48);
    // Unbounded, the tree needs far more than 2 fragments per piece.
    let unbounded = BspTree::build(&geometry, &BspOptions::DEFAULT);
    assert!(
        unbounded.fragment_count() > 2 * pieces,
        "{} fragments",
        unbounded.fragment_count()
    );
    let error = BspTree::try_build(&geometry, &tight()).unwrap_err();
    assert_eq!(
        error,
        BspError::FragmentBudget {
            pieces,
            budget: 2 * pieces
        }
    );
    assert!(
        error.to_string().contains("budget of 96 fragments"),
        "{error}"
    );
    assert!(matches!(
        Bsp::try_new(&geometry, &tight()),
        Err(BspError::FragmentBudget { .. })
    ));
    assert!(matches!(
        Bsp::new_or_fallback(&geometry, &tight(), BspFallback::Error),
        Err(BspError::FragmentBudget { .. })
    ));
}

#[test]
fn within_the_default_budget_the_tree_is_the_unbounded_one() {
    let geometry = Geometry::new(&grid_of_crossing_quads(24)).unwrap();
    let bounded = BspTree::try_build(&geometry, &BspOptions::DEFAULT).unwrap();
    let unbounded = BspTree::build(&geometry, &BspOptions::DEFAULT);
    assert_eq!(bounded.fragment_count(), unbounded.fragment_count());
    assert!(bounded.fragment_count() <= BspOptions::DEFAULT.fragment_budget(48));
}

#[test]
fn the_fallbacks_are_exact() {
    let geometry = Geometry::new(&grid_of_crossing_quads(24)).unwrap();
    let mut list = DrawList::new();
    for (yaw, pitch) in [(30.0, 20.0), (200.0, -50.0), (95.0, 5.0)] {
        let view = View::fit(&geometry.bounds(), 128, 128)
            .with_yaw_pitch_roll(yaw, pitch, 0.0)
            .with_cull(CullMode::None);
        let mut fallback = Bsp::new_or_fallback(&geometry, &tight(), BspFallback::Newell).unwrap();
        assert_eq!(fallback.name(), "newell");
        fallback.sort(&view, &mut list);
        assert!(!list.is_empty());
        assert_eq!(oracle::count_violations(&view, &list), 0);
        let mut bsp =
            Bsp::new_or_fallback(&geometry, &BspOptions::DEFAULT, BspFallback::Newell).unwrap();
        assert_eq!(bsp.name(), "bsp");
        bsp.sort(&view, &mut list);
        assert_eq!(oracle::count_violations(&view, &list), 0);
    }
}
