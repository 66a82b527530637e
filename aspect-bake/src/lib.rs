//! Exact aspect-graph bakes: every painter order of a sorter along an animation axis.
//!
//! A model turns about a known axis; [`bake`] precomputes every draw list once, as cells
//! `[lo, hi)` of the animated parameter over which the list is constant, so that a
//! compositor animates with zero per-frame CPU (`sprite-compose` realises a bake as one
//! container per cell). Breakpoints are exact: they are the closed-form roots of the event
//! functions below, not the result of sampling ([`bake_sampled`] is the seed's sampling
//! baseline, kept for comparison).
//!
//! # Why every event is `a·cos θ + b·sin θ + c`
//! The view is `R(θ) = A·Rot(k, θ)·B` ([`Spin`]): yaw, pitch or roll of CONVENTIONS.md's
//! `Ry(yaw)·Rx(pitch)·Rz(roll)` turning with the other two fixed, or a turn about any
//! view-space direction after a base rotation. Rodrigues' formula gives
//! `Rot(k, θ) = k kᵀ + cos θ·(I − k kᵀ) + sin θ·[k]×`, so `R(θ) = C₀ + cos θ·C₁ + sin θ·C₂`
//! with constant matrices. A sorter sees the view only through
//! - the unit vector toward the viewer (orthographic) `Rᵀ·ẑ`, or the eye
//!   `Rᵀ·(0, 0, d/s)` (perspective: the eye orbits with the model's rotation), both
//!   `p₀ + cos θ·p₁ + sin θ·p₂` in centred model space;
//! - a piece's facing value and a BSP node's eye side, `n·e − w·offset` with `w = 1`
//!   (perspective) or `n·d` (orthographic): a fixed linear function of that vector, so
//!   `(n·p₁)·cos θ + (n·p₂)·sin θ + (n·p₀ − w·offset)`;
//! - a centroid's depth `(Rᵀ·ẑ)·g`, likewise; a pair's depth test is the difference of two.
//!
//! Writing `r = hypot(a, b)`, `φ = atan2(b, a)`: `f(θ) = r·cos(θ − φ) + c`, zero where
//! `cos(θ − φ) = −c/r`. So ([`EventFn::roots`], in f64):
//! - `|c| < r`: two roots `φ ± acos(−c/r)`, where the sign changes (at `φ + α` downwards);
//! - `|c| = r`: one double root `φ` or `φ + π`, a tangency: zero there, no sign change;
//! - `|c| > r`: no root;
//! - `r = c = 0`: identically zero (a face edge-on all the way round, e.g. a cube's top under
//!   a yaw spin at pitch 0): never front-facing, never a change.
//!
//! "Equal" is judged relative to the magnitudes that formed the coefficients, in the one
//! [`tolerance`] module.
//!
//! # Event sources and cells
//! An [`EventSource`] lists a sorter's event functions along a spin: [`BspSource`] the node
//! planes and the piece planes (a coplanar piece's facing is its node's side, so those events
//! coincide); [`CentroidSource`] the piece facings and a kinetic sorted list of centroid depths
//! that watches only adjacent pairs. Between consecutive roots the draw list is constant; the
//! bake runs the live sorter once inside each interval (on all cores), merges neighbours with
//! equal lists, and [`verify()`] checks the result against the live sorter at random interior
//! angles and on both sides of every breakpoint.
//!
//! # Two axes
//! [`bake_two_axes`] bakes cells over yaw × pitch: every sign condition is a circle
//! `n·d = c` on the sphere of view directions, and the cells are a slab decomposition of the
//! arrangement of their curves in the `(yaw, pitch)` chart, with every critical pitch in
//! closed form (the derivation is in [`bake_two_axes`]'s module, `two_axes.rs`).
//! [`verify_two_axes`] checks such a bake like [`verify()`].
//!
//! # Feature flags
//! - `serde`: [`Bake`] (and its parts) serialise and deserialise, so a bake saves and
//!   reloads; the polygon set is written as polygons and rebuilt on load.
//!
//! # Example
//! ```
//! use aspect_bake::{Axis, BakeOptions, BspSource, Spin, bake, verify};
//! use face_sort::{Geometry, PolygonMesh, View};
//! use face_sort::glam::DVec3;
//!
//! // A unit cube.
//! let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
//! let positions = vec![
//!     p(0., 0., 0.), p(1., 0., 0.), p(1., 1., 0.), p(0., 1., 0.),
//!     p(0., 0., 1.), p(1., 0., 1.), p(1., 1., 1.), p(0., 1., 1.),
//! ];
//! let faces: Vec<Vec<u32>> = vec![
//!     vec![0, 3, 2, 1], vec![4, 5, 6, 7], vec![0, 1, 5, 4],
//!     vec![2, 3, 7, 6], vec![1, 2, 6, 5], vec![0, 4, 7, 3],
//! ];
//! let mesh = PolygonMesh::new(positions, faces).unwrap();
//! let geometry = Geometry::new(&mesh).unwrap();
//! let spin = Spin::new(
//!     View::fit(&geometry.bounds(), 256, 256),
//!     Axis::Yaw { pitch: 0.0, roll: 0.0 },
//! )
//! .unwrap();
//! let source = BspSource::of(&geometry);
//! let baked = bake(&source, &spin, &BakeOptions::DEFAULT).unwrap();
//! let at: Vec<f64> = baked.breakpoints().iter().map(|b| b.degrees).collect();
//! assert_eq!(at.len(), 4); // 0°, 90°, 180°, 270°
//! assert!(verify(&baked, &source, &spin, 4, 1).is_ok());
//! ```

mod arcs;
mod axis;
mod build;
mod cells;
mod event;
mod picture;
mod rows;
#[cfg(feature = "serde")]
mod serde_impl;
mod source;
pub mod tolerance;
mod two_axes;
mod verify;

pub use axis::{Axis, Spin};
pub use build::{BakeOptions, Progress, bake, bake_sampled};
pub use cells::{
    AngleRange, Bake, BakeCell, Breakpoint, Delta, Method, Sizes, cell_bytes, cell_list,
};
pub use event::{EventFn, Roots, reduce};
pub use picture::{PictureOptions, PictureStats, bake_picture, drawn_lists, verify_picture};
pub use rows::{EventCircle, Row};
pub use source::{BspSource, CentroidSource, Event, EventSource};
pub use two_axes::{
    Curve, Slab, TwoAxisBake, TwoAxisOptions, YawPitch, bake_two_axes, verify_two_axes,
};
pub use verify::{VerifyError, VerifyReport, verify};

pub use face_sort;

/// Why a bake stopped.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BakeError {
    /// The view has a cull margin: its facing test is then not of the form
    /// `a·cos θ + b·sin θ + c`, and the bake would not be exact.
    #[error("the view has a cull margin of {degrees}°; bakes are exact only without one")]
    CullMargin {
        /// The margin, degrees.
        degrees: f64,
    },
    /// A range that is not finite, empty, or longer than a period.
    #[error("range [{lo}°, {hi}°] is not a finite, non-empty range of at most 360°")]
    Range {
        /// Start, degrees.
        lo: f64,
        /// End, degrees.
        hi: f64,
    },
    /// More sign changes than the caller allows.
    #[error("{events} events so far, over the budget of {budget}")]
    EventBudget {
        /// Events found when stopping.
        events: usize,
        /// The budget.
        budget: usize,
    },
    /// The full per-cell lists would exceed the caller's byte budget.
    #[error(
        "the bake would take about {estimated_bytes} bytes of per-cell lists (budget {budget}): \
         {bytes_so_far} bytes in {cells_so_far} cells after {done} of {total} intervals"
    )]
    SizeBudget {
        /// Bytes of the cells kept so far.
        bytes_so_far: usize,
        /// Cells kept so far.
        cells_so_far: usize,
        /// Intervals evaluated.
        done: usize,
        /// Intervals in all.
        total: usize,
        /// The whole bake's size, extrapolated.
        estimated_bytes: usize,
        /// The budget.
        budget: usize,
    },
    /// The sorter does not list its sign conditions as rows (two-axis bakes need them).
    #[error("the {sorter} sorter cannot be baked over two axes")]
    Unsupported {
        /// The sorter's name.
        sorter: &'static str,
    },
    /// Cutting the pieces that pass through each other would make more pieces than allowed.
    #[error("cutting crossing pieces would make {pieces} pieces (budget {budget})")]
    Pieces {
        /// Pieces when stopping.
        pieces: usize,
        /// The budget.
        budget: usize,
    },
    /// More candidate pairs than allowed.
    #[error("at least {pairs} candidate pairs of pieces, over the budget of {budget}")]
    PairBudget {
        /// Pairs (or pair-and-bin keys) found when the search stopped.
        pairs: usize,
        /// The budget.
        budget: usize,
    },
    /// Pieces overlap cyclically at one view: no order of whole pieces is exact there.
    #[error("pieces overlap cyclically at {degrees}°: no order of whole pieces is exact there")]
    Cycle {
        /// Where, degrees.
        degrees: f64,
    },
    /// In perspective, the eye's orbit comes within the model (picture bakes need every
    /// point in front of the eye at every angle).
    #[error(
        "the eye orbits at {eye} model units from the centre, inside the model's reach of {reach}"
    )]
    EyeInside {
        /// Eye distance from the centre, model units.
        eye: f64,
        /// Farthest corner from the centre, model units.
        reach: f64,
    },
    /// The spin cannot be made: an angle, the base matrix, or the template's scale or eye
    /// distance is not finite, or a direction axis has no length.
    #[error("the spin's {what} is not finite or has no length")]
    Spin {
        /// Which input.
        what: &'static str,
    },
    /// The template view places the model off its centre (a camera's view offset or a moved
    /// principal point): a spin turns the model about its centre in front of a centred eye.
    #[error(
        "the spin's view has a view offset or an off-centre principal point; aim the camera at \
         the model's centre"
    )]
    ViewOffset,
    /// A sampled bake with fewer than 2 samples or a tolerance that is not positive.
    #[error(
        "sampling needs at least 2 samples and a positive tolerance ({samples}, {tolerance_deg}°)"
    )]
    Samples {
        /// Samples asked for.
        samples: usize,
        /// Tolerance asked for, degrees.
        tolerance_deg: f64,
    },
}
