//! What a sorter's sign conditions are made of ([`Row`]), and each one's event circle on the
//! sphere of view directions ([`EventCircle`]): the leaf that the event sources, the
//! two-axis bake and the verification share.

use face_sort::{Plane, Projection, View};
use glam::DVec3;

/// The event set `{d : normal·d = offset}` of one sign condition, `d` the unit vector toward
/// the viewer in centred model space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventCircle {
    /// The condition's normal (any length).
    pub normal: DVec3,
    /// The constant.
    pub offset: f64,
}

/// What a sorter's sign conditions are made of, for [`EventSource::rows`](crate::EventSource::rows).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Row {
    /// A plane whose sign against the viewer decides a facing or a BSP side: `n·d`
    /// orthographic, `n·eye − offset` perspective.
    Facing(Plane),
    /// A depth difference `n·d` (both projections).
    Depth(DVec3),
}

impl Row {
    /// The row's event circle under `template`'s projection and scale.
    #[must_use]
    pub fn circle(&self, template: &View) -> EventCircle {
        match *self {
            Row::Depth(n) => EventCircle {
                normal: n,
                offset: 0.0,
            },
            Row::Facing(plane) => EventCircle {
                normal: plane.normal(),
                offset: match template.projection() {
                    Projection::Orthographic => 0.0,
                    Projection::Perspective { distance } => {
                        plane.offset() * template.scale() / distance
                    }
                },
            },
        }
    }
}
