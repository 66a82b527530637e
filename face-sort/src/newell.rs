//! Placeholder: delegates to the centroid order until implemented.

use crate::{Centroid, DrawList, FaceSorter, Geometry, View};

/// Placeholder.
#[derive(Debug)]
pub struct Newell(Centroid);

impl Newell {
    /// Placeholder.
    #[must_use]
    pub fn new(geometry: &Geometry) -> Self {
        Newell(Centroid::new(geometry))
    }
}

impl FaceSorter for Newell {
    fn name(&self) -> &'static str {
        "newell"
    }
    fn sort(&mut self, view: &View, out: &mut DrawList) {
        self.0.sort(view, out);
    }
}
