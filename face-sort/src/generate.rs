//! Generated meshes of any size, for benches and scaling series.

use glam::DVec3;

use crate::PolygonMesh;

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
