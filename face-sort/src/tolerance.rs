//! Every tolerance the crate uses, in one place.
//!
//! Names follow one rule in every crate of the workspace: a bare name is *relative* (multiply
//! by the model's bounding-box diagonal `L`, see [`Bounds::diagonal`](crate::Bounds::diagonal),
//! or by the size its doc names); `_PX` is in pixels; `_ABS` is an absolute guard against
//! underflow. The same idea has the same name in every crate (`PLANARITY`, `DEGENERATE_AREA`,
//! `UNDERFLOW_ABS`, …). docs/ROBUSTNESS.md says what these tolerances mean for exactness.

/// A face is planar when every corner lies within `PLANARITY · D` of its fitted plane,
/// `D` being the face's largest corner-to-corner distance (CONVENTIONS.md).
pub const PLANARITY: f64 = 1e-6;

/// A piece whose Newell normal is shorter than `DEGENERATE_AREA · D²` has no area and is dropped.
pub const DEGENERATE_AREA: f64 = 1e-12;

/// A piece narrower than `SLIVER · D` across (its Newell normal, twice its area, shorter
/// than `SLIVER · D²`, `D` its largest corner-to-corner distance) is dropped like one without
/// area. Rounding tilts the plane computed for a piece of width `w` by about `ε · D / w` rad,
/// which a point `L` away reads as up to `ε / SLIVER · L` of depth (about `2e-10 · L`), below
/// the oracle's [`ORACLE_DEPTH`]. Slivers a hundred million times longer than wide, which
/// the `sorters` fuzz target makes from one corner `5e8` units out, were misordered by `1e-9`
/// to `1e-8 · L`. What is dropped is a strip at most `SLIVER · L` wide: a pixel's width only
/// in images a million pixels across.
pub const SLIVER: f64 = 1e-6;

/// A planar face is convex when no corner turns the wrong way by more than
/// `CONVEXITY · D²` (the cross product of its two edges along the face's normal) and its
/// corners go round once. Ten times obj-quads' loader tolerance of the same name, so that
/// every face the loader keeps as convex passes here after snapping onto its plane.
pub const CONVEXITY: f64 = 1e-8;

/// Plane-side classification (BSP build, Newell tests, splits, the planner's convexity
/// proof): a point within `PLANE_SIDE · L` of a plane is on it. Far above f64 round-off of
/// centred coordinates (about `1e-16 · L`), and far below the oracle's depth tolerance
/// [`ORACLE_DEPTH`] even where it matters most: a point misclassified by `PLANE_SIDE · L`
/// shows, along a view ray meeting the plane at a grazing angle θ, as a depth error of
/// `PLANE_SIDE · L / sin θ`. At `1e-11` (the earlier value) `cargo xtask stress` found
/// violations of `3e-9 · L` on a UV sphere moved by 1e6 and 1e7 units (faces seen at
/// `sin θ ≈ 3e-3`, pieces one rounding apart); `1e-12` keeps such errors inside
/// [`ORACLE_DEPTH`] down to `sin θ = 1e-3` (face-sort/tests/stress.rs). Tighter costs
/// fragments on CAD models with near-coplanar neighbours, such as fandisk moved by 1e3
/// (`cargo xtask stress --only fandisk`; counts in docs/bench.md).
pub const PLANE_SIDE: f64 = 1e-12;

/// A corner within `ON_PLANE · L` of its planar face's plane is on it already and keeps its
/// bits (f64 round-off of centred coordinates is about `1e-16 · L`: typically every corner
/// of a triangle), so that neighbouring pieces keep sharing it, which the coverage test of
/// [`Newell`](crate::Newell) and `bsp-merged` needs; corners farther off are moved onto the
/// plane. Far below [`PLANE_SIDE`]: at `PLANE_SIDE` itself the UV sphere moved by 1e6 units
/// (`face-sort/tests/stress.rs`) left a BSP violation of `9e-9 · L` (faces at grazing angles
/// magnify an off-plane corner `1 / sin θ` times); at `1e-14` it leaves none.
pub const ON_PLANE: f64 = 1e-14;

/// Relative to `L`: neighbouring corners of a face this close are one corner. An edge this
/// short has a direction that only rounding decides, so every test on edges (separating
/// lines, clipping) would read noise from it.
pub const SAME_CORNER_ROUNDING: f64 = 1e-12;

/// Order-violation depth tolerance: a later polygon must lie behind an earlier one by
/// more than `ORACLE_DEPTH · L` in view depth to count (CONVENTIONS.md).
pub const ORACLE_DEPTH: f64 = 1e-9;

/// Two projections overlap "with positive area" when their intersection is larger than
/// `OVERLAP_AREA · L²` (in view units, resolution-free).
pub const OVERLAP_AREA: f64 = 1e-14;

/// Relative to the largest coordinate of each of two projected polygons (`r_a`, `r_b`): their
/// corners are known to within a few ulps of it, so an intersection with less area than a
/// band `AREA_ROUNDING · (r_a + r_b)` wide along its boundary is rounding, not an overlap.
pub const AREA_ROUNDING: f64 = 64.0 * f64::EPSILON;

/// Relative: how far a camera's matrices may be from exact before they are refused
/// ([`Camera`](crate::Camera)): a view matrix's 3 × 3 part from orthonormal (`|MᵀM − I|`),
/// the entries a projection must have zero (relative to its focal terms), and its last row
/// from `(0, 0, −1, 0)` or `(0, 0, 0, 1)`. f32 matrices carry about `1e-7` of rounding;
/// anything beyond `1e-4` is a scale, a shear or a different kind of matrix. Rotations that
/// pass are orthonormalised, so this bounds what is accepted, not the accuracy of the view.
pub const CAMERA_MATRIX: f64 = 1e-4;

/// Absolute: a rotation whose `|RᵀR − I|` is at most this (a few f64 roundings) is taken as
/// orthonormal and kept as given; one further from it (an f32 look-at is about `1e-7` off)
/// is orthonormalised ([`View::with_rotation`](crate::View::with_rotation)).
pub const ORTHONORMAL_ROUNDING: f64 = 16.0 * f64::EPSILON;

/// The smallest and largest image a view may give the model, in pixels across its diagonal
/// (`scale · L`), checked by [`Geometry::check_view`](crate::Geometry::check_view). Below a
/// millionth of a pixel the sorters' pixel-space tests lose the overlaps that the oracle
/// still sees (Newell orders wrongly at `1e-10` px, found by fuzzing); above `1e12` px a
/// view is a close-up a pixel grid cannot hold.
pub const MIN_IMAGE_EXTENT_PX: f64 = 1e-6;

/// See [`MIN_IMAGE_EXTENT_PX`].
pub const MAX_IMAGE_EXTENT_PX: f64 = 1e12;

/// Perspective near plane: geometry is clipped to `w ≥ NEAR_W` (CONVENTIONS.md).
pub const NEAR_W: f64 = 1e-3;

/// The oracle samples depths at points moved `ORACLE_INTERIOR` of the way from each corner of
/// an overlap toward its centroid, so that every sample lies inside both polygons.
pub const ORACLE_INTERIOR: f64 = 1e-9;

/// Corners closer than `SAME_CORNER · L` are one corner when `Topological` finds pieces that
/// share an edge: planar faces more than [`ON_PLANE`]` · L` off their fitted plane are snapped
/// onto it (by up to [`PLANARITY`]` · D`), so corners that a file shares move apart.
pub const SAME_CORNER: f64 = 1e-5;

/// Absolute: the smallest and largest bounding-box diagonal `L` a [`Geometry`](crate::Geometry)
/// accepts (`MeshError::ExtentOutOfRange` outside). Newell normals grow with the fourth power
/// of a face's size in their squared length, so faces much smaller than `1e-75` or larger
/// than `1e75` under- or overflow f64; the margin leaves room for faces `1e-15 · L` small.
/// `cargo xtask stress` orders models scaled by `1e-70` and `1e70` exactly; scaled by
/// `1e±100` they were refused as "no face with positive area".
pub const MIN_EXTENT_ABS: f64 = 1e-60;

/// See [`MIN_EXTENT_ABS`].
pub const MAX_EXTENT_ABS: f64 = 1e60;

/// Absolute: lengths are clamped to at least this before dividing by them (a zero-size
/// screen box or median radius), far below any length a model can have.
pub const UNDERFLOW_ABS: f64 = 1e-300;

/// Relative rounding of a ray-plane depth in f64 ([`crate::PixelRays::depth_error`]): a few
/// operations on the view-space normal (itself rotated, so off by a few ulps) and the pixel
/// point, each rounding by `2⁻⁵³`; generous, since the bound only matters where a plane is
/// nearly parallel to the rays and it then multiplies a huge `1 / |n·ray|`.
pub const DEPTH_ROUNDING: f64 = 64.0 * f64::EPSILON;

/// Relative (angle, radians): [`Presorted`](crate::Presorted) grows every region of views
/// by this before certifying it (corners pushed away from its centre, eye distances widened),
/// so that a viewer that rounding places just outside a region's boundary is still covered.
/// Far above the rounding of a unit direction (about `1e-16`).
pub const PRESORT_GROWTH: f64 = 1e-9;

/// Relative (angle, radians): when certifying a region, the half-spaces "the viewer is in
/// front of this plane" are grown by this, so that a direction on a plane's edge is never
/// lost to rounding (a kept pair more is safe; a lost one is not).
pub const PRESORT_CLIP: f64 = 1e-12;

/// Relative (angle, radians): two cones of directions whose rays fall on either side of a
/// plane through the origin to within this are taken as apart. They may then share a wedge
/// of directions this narrow, where two pieces overlap in a sliver about `PRESORT_SEPARATION
/// · L` wide next to where they touch, at depths that differ by no more than that: far inside
/// [`ORACLE_DEPTH`]. Exact zero would keep the pairs of neighbours that touch along a line
/// (their cones touch along a plane) as hiding each other, and their cycles would never
/// resolve.
pub const PRESORT_SEPARATION: f64 = 1e-12;
