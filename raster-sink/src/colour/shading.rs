//! Flat Lambert shading: the light, the factor of a drawn piece or a whole face, and the
//! shaded colour.

use face_sort::glam::DVec3;
use face_sort::{DrawItem, DrawList, Projection, View};

/// A directional light for flat Lambert shading: each face's colour is multiplied by
/// `ambient + (1 − ambient) · max(0, n · l)`, `n` its unit normal turned toward the viewer,
/// `l` the unit direction toward the light, both in view space (x right, y up, z toward the
/// viewer).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Direction toward the light, view space (need not be unit length).
    pub direction: DVec3,
    /// Light every face receives, 0..=1.
    pub ambient: f64,
}

impl Light {
    /// The Lambert factor `ambient + (1 − ambient) · max(0, n · l)` of a surface whose unit
    /// normal (view space, turned toward the viewer) is `normal`.
    #[must_use]
    pub fn factor(&self, normal: DVec3) -> f64 {
        let l = self.direction.normalize_or_zero();
        let ambient = self.ambient.clamp(0.0, 1.0);
        ambient + (1.0 - ambient) * normal.dot(l).max(0.0)
    }

    /// Light from the upper left front, ambient 0.3.
    pub const DEFAULT: Light = Light {
        direction: DVec3::new(-0.4, 0.6, 1.0),
        ambient: 0.3,
    };

    /// The [`factor`](Self::factor) of a face seen in `view` whose model-space normal (any
    /// length) is `normal`, turned toward the viewer along the view axis. Used for whole
    /// faces (sprite brushes); the raster shades each drawn piece by its own plane.
    #[must_use]
    pub fn facing_factor(&self, view: &View, normal: DVec3) -> f64 {
        let mut n = view.direction_to_view(normal.normalize_or_zero());
        if n.z < 0.0 {
            n = -n;
        }
        self.factor(n)
    }
}

/// Multiplies the colour channels of a straight-alpha colour by a shading factor (alpha
/// unchanged), rounding to bytes.
#[must_use]
pub fn shade_colour(colour: [u8; 4], factor: f64) -> [u8; 4] {
    let m = |c: u8| (f64::from(c) * factor).round().clamp(0.0, 255.0) as u8;
    [m(colour[0]), m(colour[1]), m(colour[2]), colour[3]]
}

/// Lambert factor of a drawn item under a light (its own plane, turned toward the viewer
/// by the CONVENTIONS.md facing test of the view's projection).
pub(super) fn lambert(view: &View, list: &DrawList, item: DrawItem, light: &Light) -> f64 {
    let mut n = view.direction_to_view(list.plane(item).normal());
    let toward_viewer = match view.projection() {
        Projection::Orthographic => n.z,
        Projection::Perspective { .. } => {
            let eye = view.eye_in_view().unwrap_or(DVec3::Z);
            let v0 = list
                .corners(item)
                .first()
                .map_or(DVec3::ZERO, |&c| view.to_view(c));
            n.dot(eye - v0)
        }
    };
    if toward_viewer < 0.0 {
        n = -n;
    }
    light.factor(n)
}
