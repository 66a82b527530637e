//! Scenes for the bench and the fuzzer: the repository's models and generated hard cases.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use face_sort::glam::DVec3;
use face_sort::{CullMode, PolygonMesh};

use crate::workspace_root;

pub use test_support::Rng;

/// A scene to measure: a mesh, and the cull mode it is meant to be seen with (open sheets
/// of quads are seen from both sides).
pub struct Scene {
    /// Short name for tables.
    pub name: String,
    /// The mesh.
    pub mesh: PolygonMesh,
    /// Cull mode to use.
    pub cull: CullMode,
}

/// Collects faces and positions for a generated mesh.
#[derive(Default)]
struct Builder {
    positions: Vec<DVec3>,
    faces: Vec<Vec<u32>>,
}

impl Builder {
    fn face(&mut self, corners: &[DVec3]) {
        let start = self.positions.len() as u32;
        self.positions.extend_from_slice(corners);
        self.faces
            .push((start..start + corners.len() as u32).collect());
    }

    /// An axis-aligned box with outward counter-clockwise faces; `open` skips faces by
    /// index (0 −x, 1 +x, 2 −y, 3 +y, 4 −z, 5 +z).
    fn cuboid(&mut self, min: DVec3, max: DVec3, open: &[usize]) {
        let c = |x: usize, y: usize, z: usize| {
            DVec3::new(
                if x == 0 { min.x } else { max.x },
                if y == 0 { min.y } else { max.y },
                if z == 0 { min.z } else { max.z },
            )
        };
        let faces = [
            [c(0, 0, 0), c(0, 0, 1), c(0, 1, 1), c(0, 1, 0)],
            [c(1, 0, 0), c(1, 1, 0), c(1, 1, 1), c(1, 0, 1)],
            [c(0, 0, 0), c(1, 0, 0), c(1, 0, 1), c(0, 0, 1)],
            [c(0, 1, 0), c(0, 1, 1), c(1, 1, 1), c(1, 1, 0)],
            [c(0, 0, 0), c(0, 1, 0), c(1, 1, 0), c(1, 0, 0)],
            [c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1)],
        ];
        for (i, f) in faces.iter().enumerate() {
            if !open.contains(&i) {
                self.face(f);
            }
        }
    }

    fn build(self, name: &str, cull: CullMode) -> Result<Scene> {
        let mesh = PolygonMesh::new(self.positions, &self.faces)
            .with_context(|| format!("generated scene {name}"))?;
        Ok(Scene {
            name: name.to_owned(),
            mesh,
            cull,
        })
    }
}

/// Three long quads, each over the next at one end and under it at the other: a cycle no
/// face order can draw; exact sorters must split.
pub fn cycle() -> Result<Scene> {
    let mut b = Builder::default();
    let vertices: Vec<DVec3> = (0..3)
        .map(|k| {
            let a = f64::from(k) * std::f64::consts::TAU / 3.0 + 0.3;
            DVec3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    let (extend, half_width, rise) = (0.6, 0.18, 0.25);
    for k in 0..3 {
        let (a, c) = (vertices[k], vertices[(k + 1) % 3]);
        let u = (c - a).normalize();
        let p = DVec3::new(-u.y, u.x, 0.0) * half_width;
        let len = (c - a).length();
        // z rises linearly along the strip: −rise at `a`, +rise at `c`.
        let z_at = |t: f64| -rise + 2.0 * rise * t / len;
        let start = a - u * extend;
        let end = c + u * extend;
        let (zs, ze) = (z_at(-extend), z_at(len + extend));
        let s = DVec3::new(start.x, start.y, zs);
        let e = DVec3::new(end.x, end.y, ze);
        b.face(&[s - p, e - p, e + p, s + p]);
    }
    b.build("cycle", CullMode::None)
}

/// Pairs of quads crossing each other along a line (interpenetration), in a row.
pub fn interpenetrating() -> Result<Scene> {
    let mut b = Builder::default();
    for k in 0..4 {
        let x = f64::from(k) * 1.2;
        let a = 0.35 + 0.25 * f64::from(k);
        let (ca, sa) = (a.cos(), a.sin());
        // Quad 1 in the plane z = 0 tilted about x; quad 2 tilted the other way.
        let q = |sign: f64| {
            let t = DVec3::new(0.0, ca, sign * sa);
            let w = DVec3::X * 0.5;
            let c = DVec3::new(x, 0.0, 0.0);
            [c - w - t, c + w - t, c + w + t, c - w + t]
        };
        b.face(&q(1.0));
        b.face(&q(-1.0));
        // A third quad standing across both.
        let c = DVec3::new(x, 0.0, 0.0);
        b.face(&[
            c + DVec3::new(0.0, -0.8, -0.5),
            c + DVec3::new(0.0, 0.8, -0.5),
            c + DVec3::new(0.0, 0.8, 0.5),
            c + DVec3::new(0.0, -0.8, 0.5),
        ]);
    }
    b.build("interpenetrating", CullMode::None)
}

/// Three open boxes, one inside the other, seen from both sides.
pub fn nested_boxes() -> Result<Scene> {
    let mut b = Builder::default();
    for (k, size) in [1.0, 0.65, 0.35].into_iter().enumerate() {
        let h = DVec3::splat(size);
        let offset = DVec3::new(0.05, -0.04, 0.03) * k as f64;
        b.cuboid(-h + offset, h + offset, &[3 - (k % 2), 5]);
    }
    b.build("nested-boxes", CullMode::None)
}

/// Random quads in a cube, crossing each other freely.
pub fn random_quads(count: usize, seed: u64) -> Result<Scene> {
    let mut rng = Rng::new(seed);
    let mut b = Builder::default();
    for _ in 0..count {
        let centre = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let n = rng.direction();
        let u = n.any_orthonormal_vector();
        let v = n.cross(u);
        let (a, c) = (rng.range(0.1, 0.6), rng.range(0.1, 0.6));
        b.face(&[
            centre - u * a - v * c,
            centre + u * a - v * c,
            centre + u * a + v * c,
            centre - u * a + v * c,
        ]);
    }
    b.build(&format!("random-quads-{count}"), CullMode::None)
}

/// The planar torus of about `faces` quads ([`test_support::models::planar_torus`]).
pub fn planar_torus(faces: usize) -> Scene {
    let mesh = test_support::models::planar_torus(faces);
    Scene {
        name: test_support::models::model_name("planar-torus", mesh.face_count()),
        mesh,
        cull: CullMode::Back,
    }
}

/// The scan-like blob (`face_sort::generate::scan_blob(264, 132)`: 69,168 triangles, a laser
/// scan's size and kind), seen from outside.
pub fn scan() -> Scene {
    Scene {
        name: "scan".to_owned(),
        mesh: face_sort::generate::scan_blob(264, 132),
        cull: CullMode::Back,
    }
}

/// The repository's test models used by the bench: (name, path relative to the root).
pub const MODELS: [(&str, &str); 7] = [
    (
        "spot",
        "assets/models/keenan-crane/spot/spot_quadrangulated.obj",
    ),
    (
        "blub",
        "assets/models/keenan-crane/blub/blub_quadrangulated.obj",
    ),
    ("suzanne", "assets/models/suzanne/suzanne.obj"),
    (
        "fandisk",
        "assets/models/fandisk-quads/fandisk_quads.converted.obj",
    ),
    ("cornell-box", "assets/models/cornell-box/cornell_box.obj"),
    ("boxes", "assets/models/compas/boxes.obj"),
    ("book", "assets/models/combobulate-samples/book.obj"),
];

/// Path of a repository file.
pub fn asset(relative: &str) -> PathBuf {
    workspace_root().join(relative)
}

/// Loads a model file as an `obj_quads` mesh with a policy.
pub fn load_model(
    path: &Path,
    policy: obj_quads::FacePolicy,
) -> Result<(obj_quads::Mesh, obj_quads::LoadReport)> {
    let options = obj_quads::LoadOptions::DEFAULT.with_face_policy(policy);
    obj_quads::load(path, &options).map_err(|e| anyhow::anyhow!("{e}"))
}

/// Converts a loaded mesh to the sorters' input.
pub fn to_polygon_mesh(mesh: &obj_quads::Mesh) -> Result<PolygonMesh> {
    test_support::try_polygon_mesh(mesh).map_err(|e| anyhow::anyhow!("{e}"))
}

/// A repository model as a bench scene (culled per its own winding; the cornell box, the
/// boxes and the book are open or single-sided, so they are seen without culling).
pub fn model_scene(name: &str, relative: &str) -> Result<Scene> {
    let (mesh, _) = load_model(&asset(relative), obj_quads::FacePolicy::Polygons)
        .with_context(|| format!("loading {relative}"))?;
    let cull = match name {
        "cornell-box" | "book" | "boxes" => CullMode::None,
        _ => CullMode::Back,
    };
    Ok(Scene {
        name: name.to_owned(),
        mesh: to_polygon_mesh(&mesh)?,
        cull,
    })
}

pub use test_support::to_obj;
