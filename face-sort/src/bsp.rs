//! Placeholder: delegates to the centroid order until implemented.

use crate::{Centroid, DrawList, FaceSorter, Geometry, View};

/// Placeholder.
#[derive(Debug)]
pub struct Bsp(Centroid);

impl Bsp {
    /// Placeholder.
    #[must_use]
    pub fn new(geometry: &Geometry) -> Self {
        Bsp(Centroid::new(geometry))
    }
}

impl FaceSorter for Bsp {
    fn name(&self) -> &'static str {
        "bsp"
    }
    fn sort(&mut self, view: &View, out: &mut DrawList) {
        self.0.sort(view, out);
    }
}
