//! What the bake tests share: a unit cube, two nearly parallel squares, the property-test
//! configuration.

#![allow(dead_code)] // each test file uses its part

use aspect_bake::{BspSource, CentroidSource, EventSource};
use face_sort::glam::DVec3;
use face_sort::{Geometry, PolygonMesh};
use proptest::test_runner::Config;

/// A unit cube at the origin.
pub fn cube() -> Geometry {
    let mesh = test_support::models::boxes(&[(DVec3::ZERO, DVec3::ONE)]);
    Geometry::new(&mesh).unwrap()
}

/// Two small squares facing almost the same way, their normals 0.1° apart: their facing
/// events lie 0.1° apart, closer than the 0.5° step of 720 samples.
pub fn close_pair() -> Geometry {
    let square = |centre: DVec3, normal: DVec3| {
        let (u, v) = normal.any_orthonormal_pair();
        [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .map(|(a, b)| centre + (u * a + v * b) * 0.2)
            .to_vec()
    };
    let tilt = |deg: f64| {
        let t = f64::to_radians(deg);
        DVec3::new(t.sin(), 0.0, t.cos())
    };
    // Facing n·(−sin θ, 0, cos θ) = cos(θ + a) for n = (sin a, 0, cos a): zero at 90° − a.
    let quads = [
        square(DVec3::new(-1.0, 0.0, 0.0), tilt(-0.2)),
        square(DVec3::new(1.0, 0.0, 0.0), tilt(-0.3)),
    ];
    let positions: Vec<DVec3> = quads.iter().flatten().copied().collect();
    let faces = vec![vec![0, 1, 2, 3], vec![4, 5, 6, 7]];
    Geometry::new(&PolygonMesh::new(positions, faces).unwrap()).unwrap()
}

/// The centroid's event source when `centroid`, else the BSP's.
pub fn source(geometry: &Geometry, centroid: bool) -> Box<dyn EventSource> {
    if centroid {
        Box::new(CentroidSource::of(geometry))
    } else {
        Box::new(BspSource::of(geometry))
    }
}

/// `PROPTEST_CASES` cases (`default` when unset), with a reject allowance that grows with
/// them: the scene strategies reject generated polygons whose corners are too close, so that
/// the case count can be raised at will.
pub fn proptest_config(default: u32) -> Config {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default);
    Config {
        cases,
        max_local_rejects: 65_536.max(cases.saturating_mul(16)),
        max_global_rejects: 1_024.max(cases.saturating_mul(4)),
        ..Config::default()
    }
}
