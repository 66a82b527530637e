//! Scenes shared by the golden and grid tests.

use face_sort::sorter_api::DrawListWriter;
use std::sync::Arc;

use raster_sink::face_sort::glam::DVec3;
use raster_sink::face_sort::{Centroid, DrawList, FaceSorter, Geometry, PolygonMesh, View};
use raster_sink::{GroundGrid, MaterialOptions, Style};

/// Centroid order (deterministic, independent of the exact sorters' progress).
pub fn centroid_list(view: &View, geometry: &Geometry) -> DrawList {
    let mut list = DrawList::new();
    Centroid::new(geometry).sort(view, &mut list);
    list
}

/// Spot's faces textured with its texture (raster-sink's own material path: uvs fitted per
/// face, v flipped).
pub fn textured_spot_style(spot: &obj_quads::Mesh, geometry: &Geometry) -> Style {
    let options = MaterialOptions::DEFAULT.with_texture(test_support::model_path(
        "keenan-crane/spot/spot_texture.png",
    ));
    Style::from_materials(spot, geometry.bounds().centre(), &options)
        .expect("spot's texture")
        .style
}

/// A mesh plus a ground grid quad as the last face. Returns the mesh, the grid and
/// the grid's face index.
pub fn with_grid(base: &PolygonMesh, grid_size_factor: f64) -> (PolygonMesh, Arc<GroundGrid>, u32) {
    let bounds = base.bounds().expect("bounds");
    let size = grid_size_factor * bounds.diagonal();
    let grid = GroundGrid::new(&bounds, size).with_cell(size / 40.0);
    let mut positions = base.positions().to_vec();
    let mut faces: Vec<Vec<u32>> = base.faces().map(<[u32]>::to_vec).collect();
    let first = positions.len() as u32;
    positions.extend(grid.quad());
    faces.push(vec![first, first + 1, first + 2, first + 3]);
    let face = (faces.len() - 1) as u32;
    let mesh = PolygonMesh::new(positions, faces).expect("mesh");
    (mesh, Arc::new(grid), face)
}

/// A draw list with the grid's items first, then the model in centroid order (right for
/// views from above, where the ground is behind everything).
pub fn grid_first_list(view: &View, geometry: &Geometry, grid_face: u32) -> DrawList {
    let sorted = centroid_list(view, geometry);
    let mut list = DrawList::new();
    list.begin(geometry.pieces());
    for pass in [true, false] {
        for item in sorted.items() {
            if (item.face == grid_face) == pass {
                list.push(item.polygon, item.face);
            }
        }
    }
    list
}

/// A mesh that is only a grid quad, the grid centred at the origin on y = 0.
pub fn grid_only(size: f64, cell: f64) -> (Geometry, Arc<GroundGrid>) {
    let half = size / 2.0;
    let bounds = raster_sink::face_sort::Bounds {
        min: DVec3::new(-half, 0.0, -half),
        max: DVec3::new(half, 0.0, half),
    };
    let grid = GroundGrid::new(&bounds, size).with_cell(cell);
    let mesh = PolygonMesh::new(grid.quad().to_vec(), [[0u32, 1, 2, 3]]).expect("quad");
    (Geometry::new(&mesh).expect("geometry"), Arc::new(grid))
}
