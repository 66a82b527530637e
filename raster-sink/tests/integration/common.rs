//! Shared scenes and helpers.

#![allow(dead_code, reason = "each test module uses a different subset")]

use face_sort::sorter_api::DrawListWriter;
use std::sync::Arc;

use raster_sink::face_sort::glam::{DVec2, DVec3};
use raster_sink::face_sort::{DrawList, Geometry, PolygonMesh, PolygonSet};

pub use test_support::Rng;

/// Spot's control mesh (quads), as face-sort's mesh.
pub fn spot_control() -> PolygonMesh {
    test_support::load_polygon_mesh("keenan-crane/spot/spot_control_mesh.obj")
}

/// Spot quadrangulated, as loaded (with uvs).
pub fn spot() -> obj_quads::Mesh {
    test_support::load_model("keenan-crane/spot/spot_quadrangulated.obj")
}

/// Axis-aligned square in the plane z = `z`, counter-clockwise seen from +Z.
pub fn square(centre: DVec2, half: f64, z: f64) -> [DVec3; 4] {
    [
        DVec3::new(centre.x - half, centre.y - half, z),
        DVec3::new(centre.x + half, centre.y - half, z),
        DVec3::new(centre.x + half, centre.y + half, z),
        DVec3::new(centre.x - half, centre.y + half, z),
    ]
}

/// A mesh of separate quads.
pub fn quads_mesh(quads: &[[DVec3; 4]]) -> PolygonMesh {
    let positions: Vec<DVec3> = quads.iter().flatten().copied().collect();
    let faces: Vec<[u32; 4]> = (0..quads.len() as u32)
        .map(|i| [4 * i, 4 * i + 1, 4 * i + 2, 4 * i + 3])
        .collect();
    PolygonMesh::new(positions, faces).expect("valid mesh")
}

/// A draw list with the geometry's pieces in the given order (piece indices).
pub fn list_in_order(geometry: &Geometry, order: &[usize]) -> DrawList {
    let pieces: &Arc<PolygonSet> = geometry.pieces();
    let mut list = DrawList::new();
    list.begin(pieces);
    for &i in order {
        list.push(i as u32, pieces.face(i));
    }
    list
}

/// A closed cube subdivided into `n × n` quads per side, centred at the origin, edge 2.
pub fn subdivided_cube(n: u32) -> PolygonMesh {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    // Each side: origin, u, v axes with u × v pointing outward.
    let sides = [
        (DVec3::new(-1.0, -1.0, 1.0), DVec3::X, DVec3::Y),
        (DVec3::new(1.0, -1.0, -1.0), DVec3::NEG_X, DVec3::Y),
        (DVec3::new(1.0, -1.0, 1.0), DVec3::NEG_Z, DVec3::Y),
        (DVec3::new(-1.0, -1.0, -1.0), DVec3::Z, DVec3::Y),
        (DVec3::new(-1.0, 1.0, 1.0), DVec3::X, DVec3::NEG_Z),
        (DVec3::new(-1.0, -1.0, -1.0), DVec3::X, DVec3::Z),
    ];
    let step = 2.0 / f64::from(n);
    for (origin, u, v) in sides {
        let base = positions.len() as u32;
        for j in 0..=n {
            for i in 0..=n {
                positions.push(origin + u * (f64::from(i) * step) + v * (f64::from(j) * step));
            }
        }
        for j in 0..n {
            for i in 0..n {
                let k = base + j * (n + 1) + i;
                faces.push([k, k + 1, k + n + 2, k + n + 1]);
            }
        }
    }
    PolygonMesh::new(positions, faces).expect("valid cube")
}
