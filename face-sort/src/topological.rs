//! Placeholder: delegates to the centroid order until implemented.

use crate::{Centroid, DrawList, FaceSorter, Geometry, View};

/// Placeholder.
#[derive(Debug)]
pub struct Topological(Centroid);

impl Topological {
    /// Placeholder.
    #[must_use]
    pub fn new(geometry: &Geometry) -> Self {
        Topological(Centroid::new(geometry))
    }
}

impl FaceSorter for Topological {
    fn name(&self) -> &'static str {
        "topological"
    }
    fn sort(&mut self, view: &View, out: &mut DrawList) {
        self.0.sort(view, out);
    }
}
