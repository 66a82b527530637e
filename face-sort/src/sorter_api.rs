//! For sorter authors: how a [`FaceSorter`](crate::FaceSorter) writes its [`DrawList`].
//!
//! Users of sorters read draw lists; only a sorter fills one. The writing methods live on
//! [`DrawListWriter`], which a sorter imports:
//!
//! ```
//! use face_sort::sorter_api::DrawListWriter;
//! use face_sort::{DrawList, FaceSorter, Geometry, PolygonSet, View};
//! use std::sync::Arc;
//!
//! /// Draws every piece in file order (exact only for scenes that need no order).
//! struct FileOrder(Arc<PolygonSet>);
//!
//! impl FaceSorter for FileOrder {
//!     fn name(&self) -> &'static str {
//!         "file-order"
//!     }
//!     fn sort(&mut self, view: &View, out: &mut DrawList) {
//!         let cull = view.cull_test();
//!         out.begin(&self.0);
//!         for i in 0..self.0.len() {
//!             if cull.is_drawn(self.0.plane(i), self.0.corners(i)[0]) {
//!                 out.push(i as u32, self.0.face(i));
//!             }
//!         }
//!     }
//! }
//! # let mesh = face_sort::PolygonMesh::new([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0u32, 1, 2]]).unwrap();
//! # let geometry = Geometry::new(&mesh).unwrap();
//! # let mut list = DrawList::new();
//! # FileOrder(Arc::clone(geometry.pieces())).sort(&View::fit(&geometry.bounds(), 8, 8), &mut list);
//! # assert_eq!(list.len(), 1);
//! ```

use std::sync::Arc;

use glam::DVec3;

use crate::{DrawItem, DrawList, Plane, PolygonSet};

/// The writing side of a [`DrawList`], for sorters.
pub trait DrawListWriter {
    /// Starts a frame over `shared` polygons: clears the items and the per-frame set.
    /// Costs no allocation when the same `Arc` (or any, once capacity is reached) is passed.
    fn begin(&mut self, shared: &Arc<PolygonSet>);
    /// Appends an item: polygon `polygon` (an index into the shared set, or one that
    /// [`add_frame_polygon`](Self::add_frame_polygon) returned) drawn for face `face`.
    fn push(&mut self, polygon: u32, face: u32);
    /// Adds a per-frame polygon (a fragment cut this frame) and returns its polygon index
    /// (not yet an item: [`push`](Self::push) it to draw it).
    fn add_frame_polygon(&mut self, corners: &[DVec3], face: u32, plane: Plane) -> u32;
    /// The items, mutable, for sorters that fill them in place.
    fn items_mut(&mut self) -> &mut Vec<DrawItem>;
}

impl DrawListWriter for DrawList {
    fn begin(&mut self, shared: &Arc<PolygonSet>) {
        DrawList::begin(self, shared);
    }
    fn push(&mut self, polygon: u32, face: u32) {
        DrawList::push(self, polygon, face);
    }
    fn add_frame_polygon(&mut self, corners: &[DVec3], face: u32, plane: Plane) -> u32 {
        DrawList::add_frame_polygon(self, corners, face, plane)
    }
    fn items_mut(&mut self) -> &mut Vec<DrawItem> {
        DrawList::items_mut(self)
    }
}
