//! proptest strategies for fuzzing sorters against the [`oracle`](crate::oracle): random
//! convex planar polygons, non-intersecting, interpenetrating and cyclic scenes, and views
//! (orthographic and perspective), at tiny and huge scales.
//!
//! ```
//! use face_sort::{DrawList, Geometry, SorterKind, oracle, strategies};
//! use proptest::prelude::*;
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::deterministic();
//! runner
//!     .run(&(strategies::any_scene(), strategies::view_spec()), |(scene, spec)| {
//!         let geometry = Geometry::new(&scene).unwrap();
//!         let view = spec.view(&geometry);
//!         let mut sorter = SorterKind::Bsp.build(&geometry);
//!         let mut list = DrawList::new();
//!         sorter.sort(&view, &mut list);
//!         prop_assert_eq!(oracle::count_violations(&view, &list), 0);
//!         Ok(())
//!     })
//!     .unwrap();
//! ```

use glam::{DMat3, DVec3, EulerRot};
use proptest::prelude::*;

use crate::{CullMode, Geometry, PolygonMesh, View};

/// A view described by its parameters, turned into a [`View`] for a given geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewSpec {
    /// Yaw in degrees.
    pub yaw: f64,
    /// Pitch in degrees.
    pub pitch: f64,
    /// Roll in degrees.
    pub roll: f64,
    /// Perspective eye distance from the centre in units of the model's diagonal `L`;
    /// `None` for orthographic.
    pub eye_distance: Option<f64>,
    /// Cull mode.
    pub cull: CullMode,
}

impl ViewSpec {
    /// The view of `geometry` at 256 × 256 with these parameters.
    #[must_use]
    pub fn view(&self, geometry: &Geometry) -> View {
        let mut view = View::fit(&geometry.bounds(), 256, 256)
            .with_yaw_pitch_roll(self.yaw, self.pitch, self.roll)
            .with_cull(self.cull);
        if let Some(k) = self.eye_distance {
            let d = k * view.diagonal() * view.scale();
            view = view.with_perspective(d);
        }
        view
    }
}

/// The text form of a [`ViewSpec`], one line: `yaw=30 pitch=-20 roll=0 eye=ortho cull=back`
/// (`eye=2.5` for perspective, in diagonals). `Display` writes it (`{:?}` precision, so it
/// reads back to the same bits) and `FromStr` reads it back: a failing case saved by a fuzzer
/// (e.g. `cargo xtask fuzz`, beside its OBJ) replays exactly.
impl std::fmt::Display for ViewSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "yaw={:?} pitch={:?} roll={:?} eye=",
            self.yaw, self.pitch, self.roll
        )?;
        match self.eye_distance {
            Some(k) => write!(f, "{k:?}")?,
            None => f.write_str("ortho")?,
        }
        let cull = match self.cull {
            CullMode::Back => "back",
            CullMode::Front => "front",
            CullMode::None => "none",
        };
        write!(f, " cull={cull}")
    }
}

/// Why a [`ViewSpec`]'s text form did not parse: the offending `key=value` word.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("bad view spec word `{0}` (expected yaw=, pitch=, roll=, eye=, cull=)")]
pub struct ViewSpecError(pub String);

impl std::str::FromStr for ViewSpec {
    type Err = ViewSpecError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let mut spec = ViewSpec {
            yaw: 0.0,
            pitch: 0.0,
            roll: 0.0,
            eye_distance: None,
            cull: CullMode::Back,
        };
        for word in s.split_whitespace() {
            let bad = || ViewSpecError(word.to_owned());
            let (key, value) = word.split_once('=').ok_or_else(bad)?;
            let number = || {
                value
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(bad)
            };
            match key {
                "yaw" => spec.yaw = number()?,
                "pitch" => spec.pitch = number()?,
                "roll" => spec.roll = number()?,
                "eye" if value == "ortho" => spec.eye_distance = None,
                "eye" => spec.eye_distance = Some(number()?),
                "cull" => spec.cull = CullMode::from_name(value).ok_or_else(bad)?,
                _ => return Err(bad()),
            }
        }
        Ok(spec)
    }
}

/// Random views: any rotation, orthographic or perspective with the eye 0.6 to 6 diagonals
/// from the centre (so sometimes inside the model: the near plane clips), any cull mode.
pub fn view_spec() -> impl Strategy<Value = ViewSpec> {
    (
        0.0..360.0f64,
        -90.0..90.0f64,
        -180.0..180.0f64,
        prop_oneof![Just(None), (0.6..6.0f64).prop_map(Some)],
        prop_oneof![
            Just(CullMode::None),
            Just(CullMode::Back),
            Just(CullMode::Front)
        ],
    )
        .prop_map(|(yaw, pitch, roll, eye_distance, cull)| ViewSpec {
            yaw,
            pitch,
            roll,
            eye_distance,
            cull,
        })
}

fn unit_vector() -> impl Strategy<Value = DVec3> {
    (0.0..std::f64::consts::TAU, -1.0..1.0f64).prop_map(|(phi, z)| {
        let r = (1.0 - z * z).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    })
}

/// Corners of a random convex planar polygon: `corners` points on an ellipse in the plane
/// through `centre` with normal `normal`, counter-clockwise seen from the normal's tip.
fn polygon_corners(centre: DVec3, normal: DVec3, radii: (f64, f64), angles: &[f64]) -> Vec<DVec3> {
    let (u, v) = normal.any_orthonormal_pair();
    angles
        .iter()
        .map(|a| centre + u * (radii.0 * a.cos()) + v * (radii.1 * a.sin()))
        .collect()
}

fn sorted_angles() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(0.0..std::f64::consts::TAU, 3..7).prop_filter_map(
        "corners too close",
        |mut a| {
            a.sort_by(f64::total_cmp);
            a.dedup_by(|x, y| (*x - *y).abs() < 0.2);
            let wrap = a.first().copied().unwrap_or(0.0) + std::f64::consts::TAU
                - a.last().copied().unwrap_or(0.0);
            // Convex with positive area: at least 3 corners, no gap of π or more.
            let max_gap = a.windows(2).map(|w| w[1] - w[0]).fold(wrap, f64::max);
            (a.len() >= 3 && max_gap < 3.0).then_some(a)
        },
    )
}

/// One random convex planar polygon in the cube `[-1, 1]³`.
pub fn convex_polygon() -> impl Strategy<Value = Vec<DVec3>> {
    (
        prop::array::uniform3(-1.0..1.0f64),
        unit_vector(),
        (0.1..1.0f64, 0.1..1.0f64),
        sorted_angles(),
    )
        .prop_map(|(c, n, radii, angles)| polygon_corners(DVec3::from(c), n, radii, &angles))
}

fn mesh_of(polygons: Vec<Vec<DVec3>>) -> PolygonMesh {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for p in polygons {
        let start = positions.len() as u32;
        faces.push((start..start + p.len() as u32).collect::<Vec<u32>>());
        positions.extend(p);
    }
    PolygonMesh::new(positions, faces).expect("generated polygons are valid")
}

/// Scales and moves a scene: `10^exponent` times, then offset by `offset` (tiny and huge
/// coordinates, far from the origin).
fn rescale(polygons: Vec<Vec<DVec3>>, exponent: i32, offset: DVec3) -> Vec<Vec<DVec3>> {
    let k = 10f64.powi(exponent);
    polygons
        .into_iter()
        .map(|p| p.into_iter().map(|c| c * k + offset * k).collect())
        .collect()
}

fn scale_and_offset() -> impl Strategy<Value = (i32, DVec3)> {
    prop_oneof![
        3 => Just((0, DVec3::ZERO)),
        1 => (-6..7i32, prop::array::uniform3(-1000.0..1000.0f64)).prop_map(|(e, o)| (e, DVec3::from(o))),
    ]
}

/// Polygons that do not intersect: each lies in its own slab along a random axis, tilted
/// less than the slab allows. Their projections overlap freely.
pub fn non_intersecting_scene() -> impl Strategy<Value = PolygonMesh> {
    (
        prop::collection::vec(
            (
                prop::array::uniform2(-0.6..0.6f64),
                (-0.6..0.6f64, -0.6..0.6f64),
                (0.2..0.9f64, 0.2..0.9f64),
                sorted_angles(),
            ),
            2..10,
        ),
        unit_vector(),
        scale_and_offset(),
    )
        .prop_map(|(items, axis, (exponent, offset))| {
            let (u, v) = axis.any_orthonormal_pair();
            let gap = 0.25;
            let polygons = items
                .into_iter()
                .enumerate()
                .map(|(i, (xy, tilt, radii, angles))| {
                    let centre = u * xy[0] + v * xy[1] + axis * (i as f64 * gap);
                    // Tilt keeps the polygon inside its slab: |tilt| · radius < gap / 2.
                    let normal = (axis + u * tilt.0 * 0.1 + v * tilt.1 * 0.1).normalize();
                    polygon_corners(centre, normal, radii, &angles)
                })
                .collect();
            mesh_of(rescale(polygons, exponent, offset))
        })
}

/// Random polygons in a cube, free to cut through each other.
pub fn interpenetrating_scene() -> impl Strategy<Value = PolygonMesh> {
    (
        prop::collection::vec(convex_polygon(), 2..8),
        scale_and_offset(),
    )
        .prop_map(|(polygons, (e, o))| mesh_of(rescale(polygons, e, o)))
}

/// Many random polygons (10 to 60) crossing each other in a cube: long cycles through
/// several polygons, the case where splitting one pair by its own planes is not enough.
pub fn crossing_scene() -> impl Strategy<Value = PolygonMesh> {
    (
        prop::collection::vec(convex_polygon(), 10..60),
        scale_and_offset(),
    )
        .prop_map(|(polygons, (e, o))| mesh_of(rescale(polygons, e, o)))
}

/// Three to five long quads each lying over the next and under the previous one: a cyclic
/// overlap no order of whole faces can paint, randomly perturbed and rotated.
pub fn cyclic_scene() -> impl Strategy<Value = PolygonMesh> {
    (
        3..6usize,
        0.05..0.3f64,
        -0.05..0.05f64,
        prop::array::uniform3(-3.0..3.0f64),
        scale_and_offset(),
    )
        .prop_map(|(count, width, jitter, euler, (e, o))| {
            let rotation = DMat3::from_euler(EulerRot::YXZ, euler[0], euler[1], euler[2]);
            let polygons = (0..count)
                .map(|i| {
                    let angle = std::f64::consts::TAU * i as f64 / count as f64;
                    let dir = DVec3::new(angle.cos(), angle.sin(), 0.0);
                    let side = DVec3::new(-dir.y, dir.x, 0.0) * width;
                    // Rises from z = -0.1 at its start to z = +0.1 at its end, so its end lies
                    // over the next stick's start.
                    let start = -dir * 0.2 + DVec3::new(0.0, 0.0, -0.1 + jitter);
                    let end = dir * 1.0 + DVec3::new(0.0, 0.0, 0.1 - jitter);
                    [start - side, end - side, end + side, start + side]
                        .map(|p| rotation * p)
                        .to_vec()
                })
                .collect();
            mesh_of(rescale(polygons, e, o))
        })
}

/// Any of the scenes above.
pub fn any_scene() -> impl Strategy<Value = PolygonMesh> {
    prop_oneof![
        non_intersecting_scene(),
        interpenetrating_scene(),
        cyclic_scene()
    ]
}
