//! The outside peer: the `plane-split` crate (the BSP splitter WebRender uses to order
//! CSS 3D layers), rebuilt every frame from the same pieces the sorters see.
//!
//! WebRender feeds it polygons already transformed to screen space; so does this adaptor:
//! each drawn piece goes to pixel space, and under perspective through the projective map
//! `(q.x, q.y, q.z) ↦ (q.x, q.y, q.z) / w` (after near-plane clipping), which keeps planes
//! planar and turns the rays through the eye into lines parallel to z. Depth order along a
//! ray is kept, so the splitter's orthographic back-to-front order along +z is the painter
//! order. plane-split takes 4-point polygons: triangles repeat their last corner, larger
//! polygons are cut into a fan of quads.

use face_sort::sorter_api::DrawListWriter;
use std::sync::Arc;

use euclid::default::{Point3D, Vector3D};
use face_sort::glam::DVec3;
use face_sort::tolerance::NEAR_W;
use face_sort::{DrawList, Geometry, Plane, PolygonSet, Projection, View, split_polygon};
use plane_split::{BspSplitter, Polygon};

/// plane-split rebuilt per frame over a geometry's pieces.
pub struct PlaneSplitPeer {
    pieces: Arc<PolygonSet>,
    splitter: BspSplitter<usize>,
    view: Vec<DVec3>,
    kept: Vec<DVec3>,
    dropped: Vec<DVec3>,
    last_len: usize,
}

impl PlaneSplitPeer {
    /// A peer over `geometry`'s pieces.
    pub fn new(geometry: &Geometry) -> Self {
        PlaneSplitPeer {
            pieces: Arc::clone(geometry.pieces()),
            splitter: BspSplitter::new(),
            view: Vec::new(),
            kept: Vec::new(),
            dropped: Vec::new(),
            last_len: 0,
        }
    }

    /// One frame: cull, transform, rebuild the splitter's tree, order. Returns the number
    /// of polygons in the order (fragments included).
    pub fn frame(&mut self, view: &View) -> usize {
        let cull = view.cull_test();
        let scale = view.scale();
        self.splitter.reset();
        for i in 0..self.pieces.len() {
            let corners = self.pieces.corners(i);
            if !cull.is_drawn(self.pieces.plane(i), corners[0]) {
                continue;
            }
            self.view.clear();
            self.view.extend(corners.iter().map(|&c| view.to_view(c)));
            let points = match view.projection() {
                Projection::Orthographic => {
                    for v in self.view.iter_mut() {
                        *v *= scale;
                    }
                    &self.view
                }
                Projection::Perspective { distance } => {
                    let z_max = (1.0 - NEAR_W) * distance / scale;
                    if self.view.iter().any(|v| v.z > z_max) {
                        let near =
                            Plane::try_from_point_normal(DVec3::new(0.0, 0.0, z_max), -DVec3::Z)
                                .expect("unit normal");
                        self.kept.clear();
                        self.dropped.clear();
                        split_polygon(&self.view, &near, 0.0, &mut self.kept, &mut self.dropped);
                        std::mem::swap(&mut self.view, &mut self.kept);
                    }
                    for v in self.view.iter_mut() {
                        let q = *v * scale;
                        let w = (1.0 - q.z / distance).max(NEAR_W);
                        *v = q / w;
                    }
                    &self.view
                }
            };
            if points.len() < 3 {
                continue;
            }
            let p = |v: DVec3| Point3D::new(v.x, v.y, v.z);
            let mut k = 1;
            while k + 1 < points.len() {
                let quad = if k + 2 < points.len() {
                    [
                        p(points[0]),
                        p(points[k]),
                        p(points[k + 1]),
                        p(points[k + 2]),
                    ]
                } else {
                    [
                        p(points[0]),
                        p(points[k]),
                        p(points[k + 1]),
                        p(points[k + 1]),
                    ]
                };
                if let Some(polygon) = Polygon::from_points(quad, i) {
                    self.splitter.add(polygon);
                }
                k += 2;
            }
        }
        self.last_len = self.splitter.sort(Vector3D::new(0.0, 0.0, 1.0)).len();
        self.last_len
    }

    /// The last frame's order as a draw list (every output polygon a per-frame polygon,
    /// mapped back to centred model space), for the oracle and the pixel error.
    pub fn write_draw_list(&mut self, view: &View, list: &mut DrawList) {
        let order: Vec<Polygon<usize>> = self.splitter.sort(Vector3D::new(0.0, 0.0, 1.0)).to_vec();
        let scale = view.scale();
        list.begin(&self.pieces);
        let mut corners: Vec<DVec3> = Vec::with_capacity(4);
        for polygon in &order {
            corners.clear();
            for point in &polygon.points {
                let s = DVec3::new(point.x, point.y, point.z);
                let q = match view.projection() {
                    Projection::Orthographic => s,
                    Projection::Perspective { distance } => s / (1.0 + s.z / distance),
                };
                let c = view.to_centred(q / scale);
                if corners
                    .last()
                    .is_none_or(|&last: &DVec3| last.distance_squared(c) > 0.0)
                    && corners
                        .first()
                        .is_none_or(|&first| first.distance_squared(c) > 0.0)
                {
                    corners.push(c);
                }
            }
            if corners.len() < 3 {
                continue;
            }
            let piece = polygon.anchor;
            let plane = *self.pieces.plane(piece);
            let face = self.pieces.face(piece);
            let index = list.add_frame_polygon(&corners, face, plane);
            list.push(index, face);
        }
    }
}
