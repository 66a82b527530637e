//! Test support: models read with `obj-quads`, and generated meshes.

#![allow(dead_code, reason = "each test binary uses part of the support module")]

use std::path::PathBuf;

use sprite_compose::face_sort::{Geometry, PolygonMesh};
use sprite_compose::glam::DVec3;

/// Path of a model under `assets/models`.
pub fn model_path(relative: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/models")
        .join(relative)
}

/// Reads an OBJ model under `assets/models` with `obj-quads`.
pub fn load_obj(relative: &str) -> PolygonMesh {
    let path = model_path(relative);
    let (mesh, _) = obj_quads::load(&path, &obj_quads::LoadOptions::default())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    PolygonMesh::new(mesh.positions().to_vec(), mesh.faces()).expect("valid mesh")
}

/// A UV sphere of planar quads (isosceles trapezoids: projective maps) with triangle caps.
pub fn uv_sphere(rings: u32, segments: u32) -> PolygonMesh {
    let mut positions = vec![DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, -1.0, 0.0)];
    for r in 1..rings {
        let theta = std::f64::consts::PI * f64::from(r) / f64::from(rings);
        for s in 0..segments {
            let phi = std::f64::consts::TAU * f64::from(s) / f64::from(segments);
            positions.push(DVec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            ));
        }
    }
    let at = |r: u32, s: u32| 2 + (r - 1) * segments + (s % segments);
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for s in 0..segments {
        faces.push(vec![0, at(1, s), at(1, s + 1)]);
    }
    for r in 1..rings - 1 {
        for s in 0..segments {
            faces.push(vec![at(r, s), at(r + 1, s), at(r + 1, s + 1), at(r, s + 1)]);
        }
    }
    for s in 0..segments {
        faces.push(vec![1, at(rings - 1, s + 1), at(rings - 1, s)]);
    }
    PolygonMesh::new(positions, faces).expect("valid sphere")
}

/// Axis-aligned boxes (6 quads each, counter-clockwise from outside).
pub fn boxes(boxes: &[(DVec3, DVec3)]) -> PolygonMesh {
    let mut positions = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
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
            faces.push(f.iter().map(|&i| b + i).collect());
        }
    }
    PolygonMesh::new(positions, faces).expect("valid boxes")
}

/// A geometry.
pub fn geometry(mesh: &PolygonMesh) -> Geometry {
    Geometry::new(mesh).expect("geometry")
}

/// Deterministic xorshift numbers.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}
