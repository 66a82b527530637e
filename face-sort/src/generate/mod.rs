//! Generated meshes and scenes of any size, for tests, benches and scaling series, with the
//! seeded generator ([`Rng`]) they draw from and an OBJ writer ([`to_obj`]).

mod obj;
mod rng;

use glam::DVec3;

use crate::PolygonMesh;

pub use obj::to_obj;
pub use rng::Rng;

/// A closed torus of about `faces` quads (an `n × 2n` grid), tube radius 0.35, ring radius 1,
/// with a gentle deterministic bump so that quads are not planar (like real scanned models).
#[must_use]
pub fn torus(faces: usize) -> PolygonMesh {
    let nv = ((faces as f64 / 2.0).sqrt().round() as usize).max(3);
    let nu = (2 * nv).max(3);
    let mut positions = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let u = std::f64::consts::TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = std::f64::consts::TAU * j as f64 / nv as f64;
            let r = 0.35 * (1.0 + 0.08 * (5.0 * u).sin() * (3.0 * v).cos());
            let ring = 1.0 + r * v.cos();
            positions.push(DVec3::new(ring * u.cos(), r * v.sin(), ring * u.sin()));
        }
    }
    let index = |i: usize, j: usize| ((i % nu) * nv + (j % nv)) as u32;
    let faces = (0..nu).flat_map(|i| {
        (0..nv).map(move |j| {
            [
                index(i, j),
                index(i, j + 1),
                index(i + 1, j + 1),
                index(i + 1, j),
            ]
        })
    });
    PolygonMesh::new(positions, faces).expect("a torus is a valid mesh")
}

/// A closed UV sphere of radius 1: `segments` around the Y axis, `rings` latitude bands
/// (triangles at the poles, planar trapezoid quads between), wound counter-clockwise seen from
/// outside. Every face lies on the boundary of its convex hull: the convex test model.
#[must_use]
pub fn uv_sphere(segments: usize, rings: usize) -> PolygonMesh {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let mut positions = vec![DVec3::Y];
    for k in 1..rings {
        let theta = std::f64::consts::PI * k as f64 / rings as f64;
        for j in 0..segments {
            let phi = std::f64::consts::TAU * j as f64 / segments as f64;
            positions.push(DVec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ));
        }
    }
    positions.push(-DVec3::Y);
    let south = (positions.len() - 1) as u32;
    // Ring `k` (1 ≤ k < rings) counts from the north; `j` wraps around.
    let at = |k: usize, j: usize| (1 + (k - 1) * segments + j % segments) as u32;
    let mut faces: Vec<Vec<u32>> = Vec::with_capacity(segments * rings);
    for j in 0..segments {
        faces.push(vec![at(1, j), 0, at(1, j + 1)]);
        for k in 1..rings - 1 {
            faces.push(vec![at(k + 1, j), at(k, j), at(k, j + 1), at(k + 1, j + 1)]);
        }
        faces.push(vec![south, at(rings - 1, j), at(rings - 1, j + 1)]);
    }
    PolygonMesh::new(positions, faces).expect("a sphere is a valid mesh")
}

/// A scan-like closed blob: a UV sphere of `segments` × `rings` displaced radially by a few
/// waves, so that it has bumps, dents and folds that hide each other, each quad cut into two
/// triangles sharing its first corner, as scanners write them. `scan_blob(264, 132)` has
/// 69,168 triangles, the size of the laser scan that issue 12 measured.
#[must_use]
pub fn scan_blob(segments: usize, rings: usize) -> PolygonMesh {
    let radius = |d: DVec3| {
        1.0 + 0.18 * (3.0 * d.x).sin() * (4.0 * d.y).sin() * (5.0 * d.z).sin()
            + 0.06 * (13.0 * d.x + 7.0 * d.y).sin()
            + 0.04 * (17.0 * d.z - 11.0 * d.y).sin()
    };
    let sphere = uv_sphere(segments, rings);
    let positions: Vec<DVec3> = sphere.positions().iter().map(|&d| d * radius(d)).collect();
    let mut faces: Vec<Vec<u32>> = Vec::with_capacity(2 * sphere.face_count());
    for face in sphere.faces() {
        match face {
            &[a, b, c, d] => faces.extend([vec![a, b, c], vec![a, c, d]]),
            triangle => faces.push(triangle.to_vec()),
        }
    }
    PolygonMesh::new(positions, faces).expect("a displaced sphere is a valid mesh")
}

/// Axis-aligned boxes given by (min, max) corners, 6 quads each, counter-clockwise
/// seen from outside, in the order −z, +z, −x, +x, −y, +y.
#[must_use]
pub fn boxes(boxes: &[(DVec3, DVec3)]) -> PolygonMesh {
    let mut positions = Vec::new();
    let mut faces: Vec<[u32; 4]> = Vec::new();
    for &(lo, hi) in boxes {
        let b = positions.len() as u32;
        for k in 0..8u32 {
            positions.push(DVec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            ));
        }
        for f in [
            [0, 2, 3, 1], // -z
            [4, 5, 7, 6], // +z
            [0, 4, 6, 2], // -x
            [1, 3, 7, 5], // +x
            [0, 1, 5, 4], // -y
            [2, 6, 7, 3], // +y
        ] {
            faces.push(f.map(|i| b + i));
        }
    }
    match PolygonMesh::new(positions, faces) {
        Ok(mesh) => mesh,
        Err(e) => panic!("boxes are a valid mesh: {e}"),
    }
}

/// A torus of about `faces` planar quads (surface-of-revolution grid
/// quads are planar), ring radius 1, tube radius 0.35, about three times as many rings as
/// tube segments.
#[must_use]
pub fn planar_torus(faces: usize) -> PolygonMesh {
    let minor = ((faces as f64 / 3.0).sqrt().round() as usize).max(3);
    let major = (faces / minor).max(3);
    let (big, small) = (1.0, 0.35);
    let mut positions = Vec::with_capacity(major * minor);
    for i in 0..major {
        let u = i as f64 / major as f64 * std::f64::consts::TAU;
        for j in 0..minor {
            let v = j as f64 / minor as f64 * std::f64::consts::TAU;
            let r = big + small * v.cos();
            positions.push(DVec3::new(r * u.cos(), small * v.sin(), r * u.sin()));
        }
    }
    let idx = |i: usize, j: usize| ((i % major) * minor + (j % minor)) as u32;
    let faces = (0..major).flat_map(|i| {
        (0..minor).map(move |j| [idx(i, j), idx(i, j + 1), idx(i + 1, j + 1), idx(i + 1, j)])
    });
    match PolygonMesh::new(positions, faces) {
        Ok(mesh) => mesh,
        Err(e) => panic!("a torus is a valid mesh: {e}"),
    }
}

/// `count` instances of `meshes` meshes on a grid `spacing` apart (instance `k` carries mesh
/// `k % meshes`), each rotated at random, scaled by 0.6–1.4 independently per axis
/// (non-uniform), one in five mirrored in x; one in four is pushed into its neighbour so
/// that their boxes interlock. Deterministic for a seed.
#[must_use]
pub fn scattered_instances(
    meshes: usize,
    count: usize,
    seed: u64,
    spacing: f64,
) -> Vec<crate::Instance> {
    use glam::{DAffine3, DMat3, DQuat};
    let mut rng = Rng::new(seed);
    let side = (count as f64).sqrt().ceil() as usize;
    (0..count)
        .map(|k| {
            let (col, row) = ((k % side) as f64, (k / side) as f64);
            let mut at = DVec3::new(col * spacing, (k % 3) as f64 * 0.3, row * spacing);
            if k % 4 == 1 {
                at.x -= 0.5 * spacing; // into the previous instance's box
            }
            let rotation = DQuat::from_axis_angle(rng.direction(), rng.range(0.0, 6.3));
            let mut scale = DVec3::new(
                rng.range(0.6, 1.4),
                rng.range(0.6, 1.4),
                rng.range(0.6, 1.4),
            );
            if k % 5 == 2 {
                scale.x = -scale.x;
            }
            let linear = DMat3::from_quat(rotation) * DMat3::from_diagonal(scale);
            crate::Instance::new(k % meshes, DAffine3::from_mat3_translation(linear, at))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{DrawList, FaceSorter, Geometry, View, oracle};

    #[test]
    fn torus_is_closed_and_outward() {
        let mesh = torus(200);
        assert_eq!(mesh.face_count(), 200);
        let geometry = Geometry::new(&mesh).unwrap();
        // Outward winding: about half of the pieces face a viewer from any side.
        let view = View::fit(&geometry.bounds(), 128, 128).with_yaw_pitch_roll(0.0, 30.0, 0.0);
        let mut list = DrawList::new();
        let mut bsp = crate::Bsp::new(&geometry);
        bsp.sort(&view, &mut list);
        let share = list.len() as f64 / bsp.stats().polygons as f64;
        assert!((0.3..0.7).contains(&share), "{share}");
        assert_eq!(oracle::count_violations(&view, &list), 0);
    }

    #[test]
    fn uv_sphere_is_closed_planar_and_outward() {
        let mesh = uv_sphere(12, 6);
        assert_eq!(mesh.face_count(), 12 * 6);
        let geometry = Geometry::new(&mesh).unwrap();
        assert_eq!(geometry.non_planar_faces(), 0);
        let pieces = geometry.pieces();
        for i in 0..pieces.len() {
            let c = pieces.corners(i);
            let centroid = c.iter().copied().sum::<DVec3>() / c.len() as f64;
            assert!(
                pieces.plane(i).normal().dot(centroid) > 0.0,
                "piece {i} faces inward"
            );
        }
    }
}
