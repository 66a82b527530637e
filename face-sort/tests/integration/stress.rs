//! Regression cases found by `cargo xtask stress` (docs/ROBUSTNESS.md).

use face_sort::glam::DVec3;
use face_sort::{
    Auto, CullMode, DrawList, FaceSorter, Geometry, PlanHint, PolygonMesh, SorterKind, View, oracle,
};

/// `mesh` with every position moved by `offset` (stored rounded, as a file far from the
/// origin would hold them).
fn moved(mesh: &PolygonMesh, offset: DVec3) -> PolygonMesh {
    let positions: Vec<DVec3> = mesh.positions().iter().map(|&p| p + offset).collect();
    PolygonMesh::new(positions, mesh.faces()).unwrap()
}

/// The general views of the stress suite: three orthographic, two perspective.
fn views(geometry: &Geometry) -> Vec<View> {
    let base = View::fit(&geometry.bounds(), 256, 256).with_cull(CullMode::Back);
    let ld = base.diagonal() * base.scale();
    vec![
        base.with_yaw_pitch_roll(30.0, 20.0, 0.0),
        base.with_yaw_pitch_roll(213.0, -37.0, 11.0),
        base.with_yaw_pitch_roll(301.0, 63.0, -27.0),
        base.with_yaw_pitch_roll(121.0, 14.0, 0.0)
            .with_perspective(1.5 * ld),
        base.with_yaw_pitch_roll(47.0, -22.0, 0.0)
            .with_perspective(0.7 * ld),
    ]
}

/// A UV sphere moved by 1e6 and 1e7 units: the stored positions are rounded to about
/// `5e-10 · L`, so neighbouring faces, each snapped onto its own plane, no longer share
/// corners exactly. With the plane tolerance at `1e-11 · L`, the BSP left 3 violations of
/// about `3e-9 · L` at 1e7 (faces seen at grazing angles turn a within-tolerance
/// misclassification into a depth error `1 / sin θ` times larger), and the planner's
/// convexity proof passed at 1e6, so culling alone left 2. With `PLANE_SIDE = 1e-12` there
/// are none, and the proof no longer accepts the rounded sphere.
#[test]
fn a_sphere_far_from_the_origin_is_ordered_exactly() {
    let sphere = face_sort::generate::uv_sphere(32, 16);
    let direction = DVec3::new(1.0, -0.6, 0.35);
    for offset in [1e6, 1e7] {
        let geometry = Geometry::new(&moved(&sphere, direction * offset)).unwrap();
        let mut list = DrawList::new();
        let mut sorters: Vec<Box<dyn FaceSorter>> = vec![
            SorterKind::Bsp.build(&geometry),
            SorterKind::Newell.build(&geometry),
            Box::new(Auto::new(&geometry, PlanHint::ANIMATION)),
        ];
        for view in views(&geometry) {
            for sorter in &mut sorters {
                sorter.sort(&view, &mut list);
                assert!(list.len() > 100, "{} drew {}", sorter.name(), list.len());
                let found = oracle::find_violations(&view, &list, 3);
                assert!(
                    found.is_empty(),
                    "moved {offset:e}: {} left {found:?}",
                    sorter.name()
                );
            }
        }
    }
}

/// The same sphere near the origin is still proven convex: the tighter tolerance does not
/// cost the planner its cheapest strategy on clean input.
#[test]
fn the_sphere_at_the_origin_is_still_ordered_by_culling_alone() {
    let geometry = Geometry::new(&face_sort::generate::uv_sphere(32, 16)).unwrap();
    let auto = Auto::new(&geometry, PlanHint::ANIMATION);
    assert_eq!(auto.name(), "cull-only", "{}", auto.plan().reason);
}

/// Models scaled far beyond f64's comfortable range are refused with a typed error naming
/// their size (they were refused as "no face with positive area"); up to `1e±60` they are
/// accepted.
#[test]
fn out_of_range_sizes_are_a_typed_error() {
    let sphere = face_sort::generate::uv_sphere(16, 8);
    let scaled = |s: f64| {
        let positions: Vec<DVec3> = sphere.positions().iter().map(|&p| p * s).collect();
        PolygonMesh::new(positions, sphere.faces()).unwrap()
    };
    for (scale, exponent) in [(1e100, 100), (1e-100, -100), (1e300, 300)] {
        let error = Geometry::new(&scaled(scale)).unwrap_err();
        assert_eq!(error, face_sort::MeshError::ExtentOutOfRange { exponent });
        assert!(
            error.to_string().contains(&format!("1e{exponent}")),
            "{error}"
        );
    }
    for scale in [1e-59, 1e59] {
        let geometry = Geometry::new(&scaled(scale)).unwrap();
        assert_eq!(geometry.pieces().len(), 128);
    }
}

/// A planar face that is not convex, or whose corners go round twice, is refused: the
/// sorters order convex pieces (found by `cargo xtask fuzz --libfuzzer sorters`: a face
/// `[c, d, c, e, d]` made Newell's order wrong). Straight corners and repeated neighbours
/// stay allowed, and a non-planar face is still fanned.
#[test]
fn non_convex_planar_faces_are_refused() {
    use face_sort::{MeshError, PolygonMesh};
    let positions = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 2.0, 0.0],
        [0.0, 2.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [2.0, 2.0, 0.5],
    ];
    let geometry = |faces: &[&[u32]]| Geometry::new(&PolygonMesh::new(positions, faces).unwrap());
    // An L-shaped hexagon, a bow tie of repeated corners, and a triangle with a spike back
    // along one edge (its turns add up to one full turn: found by the sorters target).
    for face in [
        &[0u32, 1, 2, 3, 4, 5][..],
        &[1, 2, 1, 5, 2],
        &[0, 1, 5, 0, 1],
    ] {
        assert_eq!(
            geometry(&[face]).unwrap_err(),
            MeshError::NonConvex { face: 0 }
        );
    }
    // A straight corner (6 on the edge 0–1), a repeated neighbour, a star-free triangle.
    for face in [&[0u32, 6, 1, 2, 5][..], &[0, 1, 1, 2, 5], &[0, 1, 5]] {
        assert!(geometry(&[face]).is_ok(), "{face:?}");
    }
    // A non-planar quad is fanned; a non-planar face that repeats a corner out of turn is
    // refused (its fan would hold a triangle and its reverse: found by the bake target).
    assert!(geometry(&[&[0, 1, 8, 5]]).is_ok());
    // A face folded onto itself (a triangle and its reverse, no net area) is refused too,
    // and a face of collinear corners is dropped as before.
    for face in [&[0u32, 1, 8, 1, 5][..], &[0, 1, 5, 1]] {
        assert_eq!(
            geometry(&[face]).unwrap_err(),
            MeshError::NonConvex { face: 0 }
        );
    }
    assert!(geometry(&[&[0, 6, 1, 6], &[0, 1, 5]]).is_ok());
}
