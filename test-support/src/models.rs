//! Named generated models. One name, one model: the two tori of the workspace are
//! [`bumpy_torus`] (non-planar quads, like scanned models) and [`planar_torus`] (planar
//! grid quads), and tables and READMEs call them by these names; there is one
//! [`uv_sphere`] and one [`boxes`].

use face_sort::PolygonMesh;
use face_sort::glam::DVec3;

/// `"boxes"`: [`face_sort::generate::boxes`], 6 quads per box.
pub use face_sort::generate::boxes;
/// `"planar-torus"`: [`face_sort::generate::planar_torus`], planar grid quads.
pub use face_sort::generate::planar_torus;
pub use test_base::model_name;

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
    let instances = face_sort::generate::scattered_instances(meshes.len(), count, seed, 2.2);
    (meshes, instances)
}

/// `"suzanne-scene"`: `count` instances of suzanne (500 faces, a real model, 2.7 units wide)
/// in the layout of [`instanced_scene`], 5 units apart (one in four pushed into its
/// neighbour).
#[must_use]
pub fn suzanne_scene(count: usize, seed: u64) -> (Vec<PolygonMesh>, Vec<face_sort::Instance>) {
    let meshes = vec![crate::load_polygon_mesh("suzanne/suzanne.obj")];
    (
        meshes,
        face_sort::generate::scattered_instances(1, count, seed, 5.0),
    )
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
