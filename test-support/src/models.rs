//! Named generated models. One name, one model: the two tori of the workspace are
//! [`bumpy_torus`] (non-planar quads, like scanned models) and [`planar_torus`] (planar
//! grid quads), and tables and READMEs call them by these names; there is one
//! [`uv_sphere`] and one [`boxes`].

use face_sort::PolygonMesh;
use face_sort::glam::DVec3;

/// The name of a generated model in tables: `"{kind}-{faces}"` with `k` for thousands,
/// e.g. `model_name("bumpy-torus", 10_000) == "bumpy-torus-10k"`.
#[must_use]
pub fn model_name(kind: &str, faces: usize) -> String {
    if faces >= 1000 && faces.is_multiple_of(1000) {
        format!("{kind}-{}k", faces / 1000)
    } else {
        format!("{kind}-{faces}")
    }
}

/// `"bumpy-torus"`: [`face_sort::generate::torus`], about `faces` quads (an `n × 2n` grid)
/// with a gentle deterministic bump, so most quads are not planar.
#[must_use]
pub fn bumpy_torus(faces: usize) -> PolygonMesh {
    face_sort::generate::torus(faces)
}

/// `"uv-sphere"`: [`face_sort::generate::uv_sphere`], radius 1, `segments` around the Y
/// axis and `rings` latitude bands (triangle caps, planar trapezoids between); convex.
#[must_use]
pub fn uv_sphere(segments: usize, rings: usize) -> PolygonMesh {
    face_sort::generate::uv_sphere(segments, rings)
}

/// `"boxes"`: axis-aligned boxes given by (min, max) corners, 6 quads each, counter-clockwise
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

/// `"planar-torus"`: a torus of about `faces` planar quads (surface-of-revolution grid
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

/// `"instanced"`: a scene of `count` instances of three meshes (a unit box, a UV sphere and
/// suzanne), laid out on a grid about 2.2 units apart, each rotated at random, scaled by
/// 0.6–1.4 independently per axis (non-uniform), one in five mirrored in x; one in four is
/// pushed into its neighbour so that their boxes interlock (and the meshes interpenetrate).
/// Deterministic for a seed.
#[must_use]
pub fn instanced_scene(count: usize, seed: u64) -> (Vec<PolygonMesh>, Vec<face_sort::Instance>) {
    let meshes = vec![
        boxes(&[(DVec3::splat(-0.5), DVec3::splat(0.5))]),
        uv_sphere(12, 8),
        crate::load_polygon_mesh("suzanne/suzanne.obj"),
    ];
    let instances = instance_layout(meshes.len(), count, seed, 2.2);
    (meshes, instances)
}

/// `"suzanne-scene"`: `count` instances of suzanne (500 faces, a real model, 2.7 units wide)
/// in the layout of [`instanced_scene`], 5 units apart (one in four pushed into its
/// neighbour).
#[must_use]
pub fn suzanne_scene(count: usize, seed: u64) -> (Vec<PolygonMesh>, Vec<face_sort::Instance>) {
    let meshes = vec![crate::load_polygon_mesh("suzanne/suzanne.obj")];
    (meshes, instance_layout(1, count, seed, 5.0))
}

/// The layout of [`instanced_scene`], `spacing` apart: instance `k` carries mesh
/// `k % meshes`.
fn instance_layout(
    meshes: usize,
    count: usize,
    seed: u64,
    spacing: f64,
) -> Vec<face_sort::Instance> {
    use face_sort::glam::{DAffine3, DMat3, DQuat};
    let mut rng = crate::Rng::new(seed);
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
            face_sort::Instance::new(k % meshes, DAffine3::from_mat3_translation(linear, at))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_sizes() {
        assert_eq!(model_name("bumpy-torus", 10_000), "bumpy-torus-10k");
        assert_eq!(model_name("planar-torus", 1_014), "planar-torus-1014");
        let planar = planar_torus(1_000);
        let bumpy = bumpy_torus(1_000);
        assert!(
            (900..=1100).contains(&planar.face_count()),
            "{}",
            planar.face_count()
        );
        assert!(
            (900..=1100).contains(&bumpy.face_count()),
            "{}",
            bumpy.face_count()
        );
        // The two tori are different models.
        assert_ne!(planar.positions(), bumpy.positions());
    }
}
