//! Exact back-to-front ordering of polygon mesh faces, for surfaces without a depth buffer.
//!
//! Given a mesh and a [`View`] (the camera of CONVENTIONS.md), a [`FaceSorter`] culls the
//! faces and writes the drawn ones into a [`DrawList`] back to front, so that painting them in
//! that order shows what a depth buffer would. [`Bsp`] and [`Newell`] are exact (zero order
//! violations, split fragments where needed); [`Topological`] and [`Centroid`] are cheaper
//! and measured, not promised. The [`oracle`] counts order violations of any draw list.
//!
//! ```
//! use face_sort::{Bsp, DrawList, FaceSorter, Geometry, PolygonMesh, View, oracle};
//! use glam::DVec3;
//!
//! // Two overlapping squares, one behind the other.
//! let positions = vec![
//!     DVec3::new(0.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0),
//!     DVec3::new(2.0, 2.0, 0.0), DVec3::new(0.0, 2.0, 0.0),
//!     DVec3::new(1.0, 1.0, 1.0), DVec3::new(3.0, 1.0, 1.0),
//!     DVec3::new(3.0, 3.0, 1.0), DVec3::new(1.0, 3.0, 1.0),
//! ];
//! let mesh = PolygonMesh::new(positions, [[4, 5, 6, 7], [0, 1, 2, 3]]).unwrap();
//! let geometry = Geometry::new(&mesh).unwrap();
//! let view = View::fit(&geometry.bounds(), 256, 256);
//! let mut sorter = Bsp::new(&geometry);
//! let mut list = DrawList::new();
//! sorter.sort(&view, &mut list);
//! let faces: Vec<u32> = list.items().iter().map(|item| item.face).collect();
//! assert_eq!(faces, [1, 0]); // the far square first
//! assert_eq!(oracle::count_violations(&view, &list), 0);
//! ```
//!
//! # Feature flags
//! - `proptest`: public `strategies` (random convex polygons, scenes and views) for fuzzing
//!   any sorter against the oracle.

mod bsp;
mod bsp_builder;
mod camera;
mod centroid;
pub mod colours;
mod convert;
mod coverage;
mod crossing;
mod draw_list;
mod error;
mod fragment_merge;
pub mod generate;
mod geometry;
mod ids;
mod mesh;
mod newell;
pub mod oracle;
mod plan;
mod plane;
mod polygon;
mod polygon_set;
mod presorted;
mod scene;
mod screen_grid;
mod small;
mod sorter;
pub mod sorter_api;
#[cfg(any(test, feature = "proptest"))]
pub mod strategies;
mod t_junctions;
pub mod tolerance;
mod topological;
mod view;
mod workers;

pub use bsp::{Bsp, BspFallback, BspOptions, BspTree};
pub use camera::{Camera, CameraError, ClipSpace, Lens};
pub use centroid::Centroid;
pub use convert::{Matrix4, Point3};
pub use crossing::{TooManyPieces, split_crossing};
pub use draw_list::{DrawItem, DrawList};
pub use error::{BspError, MeshError};
pub use geometry::Geometry;
pub use ids::{FaceId, PieceId};
pub use mesh::{Bounds, MAX_FACE_CORNERS, PolygonMesh};
pub use newell::Newell;
pub use plan::{Auto, ConvexParts, CostModel, CullOnly, Plan, PlanHint, Strategy};
pub use plane::{Plane, Side, newell_normal};
pub use polygon::{Box2, clip_convex_2d, signed_area_2d, split_polygon};
pub use polygon_set::PolygonSet;
pub use presorted::{
    CertifiedOrders, CertifiedOrdersError, CertifiedRegion, CoreOrders, FallbackReason,
    MAX_CORE_PLANES, OrderStep, PRESORT_FORMAT_VERSION, PresortError, PresortLoadError,
    PresortOptions, PresortProgress, Presorted,
};
pub use scene::{Instance, Layer, MAX_LODS, SceneError, SceneSorter, SceneStats};
pub use small::SmallPieceFilter;
pub use sorter::{FaceSorter, SorterStats};
pub use topological::Topological;
pub use view::{
    CullMode, CullTest, FrontFace, PixelRays, Projection, ProjectionScratch, View, Viewer,
};

pub use glam;

/// Every sorter by name, for command lines and benches.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SorterKind {
    /// [`Centroid`].
    Centroid,
    /// [`Topological`].
    Topological,
    /// [`Newell`].
    Newell,
    /// [`Bsp`].
    Bsp,
    /// [`Bsp`] drawing split pieces whole where nothing between their fragments overlaps
    /// them ([`Bsp::with_fragment_merge`]).
    BspMerged,
    /// [`Presorted`]: orders certified over regions of views, looked up per frame.
    Presorted,
}

impl SorterKind {
    /// All sorters, baseline first.
    pub const ALL: [SorterKind; 6] = [
        SorterKind::Centroid,
        SorterKind::Topological,
        SorterKind::Newell,
        SorterKind::Bsp,
        SorterKind::BspMerged,
        SorterKind::Presorted,
    ];

    /// The exact ones.
    pub const EXACT: [SorterKind; 4] = [
        SorterKind::Newell,
        SorterKind::Bsp,
        SorterKind::BspMerged,
        SorterKind::Presorted,
    ];

    /// Lower-case name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            SorterKind::Centroid => "centroid",
            SorterKind::Topological => "topological",
            SorterKind::Newell => "newell",
            SorterKind::Bsp => "bsp",
            SorterKind::BspMerged => "bsp-merged",
            SorterKind::Presorted => "presorted",
        }
    }

    /// Parses a lower-case name.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The geometry this sorter is best built from: [`Geometry::with_exact_corners`] for
    /// [`Presorted`] (its certificates need neighbours that share corners bit for bit),
    /// [`Geometry::new`] for the others.
    ///
    /// # Errors
    /// As [`Geometry::new`].
    pub fn geometry_for(self, mesh: &PolygonMesh) -> Result<Geometry, MeshError> {
        match self {
            SorterKind::Presorted => Geometry::with_exact_corners(mesh),
            _ => Geometry::new(mesh),
        }
    }

    /// Builds this sorter for a geometry.
    #[must_use]
    pub fn build(self, geometry: &Geometry) -> Box<dyn FaceSorter> {
        match self {
            SorterKind::Centroid => Box::new(Centroid::new(geometry)),
            SorterKind::Topological => Box::new(Topological::new(geometry)),
            SorterKind::Newell => Box::new(Newell::new(geometry)),
            SorterKind::Bsp => Box::new(Bsp::new(geometry)),
            SorterKind::BspMerged => Box::new(Bsp::new(geometry).with_fragment_merge(true)),
            SorterKind::Presorted => Box::new(Presorted::new(geometry)),
        }
    }
}

/// The crate's README: its examples are compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
