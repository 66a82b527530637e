//! Pieces that pass through each other are cut once, before baking, so that every remaining
//! pair has one occlusion relation wherever their projections overlap.

use face_sort::PolygonSet;

use crate::BakeError;
use crate::tolerance::PICTURE_SIDE;

/// [`face_sort::split_crossing`] at the picture bake's plane tolerance, with its error.
///
/// # Errors
/// [`BakeError::Pieces`] beyond `max_pieces`.
pub(crate) fn split_crossing(
    set: &PolygonSet,
    diagonal: f64,
    max_pieces: usize,
) -> Result<(PolygonSet, usize), BakeError> {
    face_sort::split_crossing(set, PICTURE_SIDE * diagonal, max_pieces).map_err(|e| {
        BakeError::Pieces {
            pieces: e.pieces,
            budget: e.budget,
        }
    })
}
