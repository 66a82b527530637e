//! Playing a picture bake on a retained compositor: sprites made once, back faces hidden by
//! the compositor, and per turn only the visibility switches at cell boundaries.

use aspect_bake::{Bake, Spin};
use face_sort::Geometry;

use crate::culled_copies;
use crate::{BakedSpriteTree, Brush, Compositor, SpriteId, root_transform};

/// A picture bake ([`aspect_bake::bake_picture`]) realised on a [`Compositor`]: one sprite
/// per piece and place (the elements of
/// vector-sink's `write_culled_spin_html`, [`culled_copies`](crate::culled_copies)), created once in paint order
/// with their backs hidden; [`play`](Self::play) sets the root transform of an angle and,
/// when the angle enters another cell, switches only the sprites whose visibility differs.
pub struct BakePlayer<C: Compositor> {
    compositor: C,
    bake: Bake,
    spin: Spin,
    /// Per sprite, per cell: shown.
    shown: Vec<Vec<bool>>,
    /// Per sprite, the bake polygon it shows.
    pieces: Vec<u32>,
    /// The cell last played, if any.
    cell: Option<usize>,
}

impl<C: Compositor> BakePlayer<C> {
    /// Creates the sprites of `bake` (its cells' drawn lists `lists`, from
    /// [`aspect_bake::drawn_lists`]) on `compositor`, each piece's sprite with
    /// `brush(face)`. Nothing is shown until the first [`play`](Self::play).
    pub fn new(
        bake: Bake,
        lists: &[Vec<u32>],
        spin: Spin,
        geometry: &Geometry,
        brush: impl Fn(u32) -> Brush,
        mut compositor: C,
    ) -> Self {
        let graph = BakedSpriteTree::realise(&bake, geometry, &spin.view_at(0.0));
        let copies = culled_copies(lists, bake.polygons().len());
        let shown = copies.visibility(lists);
        for (e, &p) in copies.pieces().iter().enumerate() {
            let id = SpriteId(e as u32);
            let face = bake.polygons().face(p as usize);
            compositor.create_sprite(id, face);
            if let Some((transform, clip)) = graph.polygon_map(p) {
                compositor.set_transform(id, transform);
                compositor.set_clip(id, clip);
            }
            compositor.set_brush(id, &brush(face));
            compositor.set_back_visible(id, false);
        }
        BakePlayer {
            compositor,
            bake,
            spin,
            shown,
            pieces: copies.pieces().to_vec(),
            cell: None,
        }
    }

    /// Shows the bake at `degrees` of the animated parameter: the root transform of that
    /// view, and, on entering a cell, the visibility switches that differ from the last
    /// cell's. Returns the cell.
    pub fn play(&mut self, degrees: f64) -> Option<usize> {
        let cell = self.bake.cell_at(degrees)?;
        if self.cell != Some(cell) {
            for (e, shown) in self.shown.iter().enumerate() {
                if self.cell.is_none_or(|c| shown[c] != shown[cell]) {
                    self.compositor.set_visible(SpriteId(e as u32), shown[cell]);
                }
            }
            self.cell = Some(cell);
        }
        let view = self.spin.view_at(degrees);
        self.compositor.set_root_transform(&root_transform(&view));
        Some(cell)
    }

    /// The bake polygon a sprite shows.
    #[must_use]
    pub fn polygon_of(&self, id: SpriteId) -> Option<u32> {
        self.pieces.get(id.index()).copied()
    }

    /// Sprites made (one per piece and place).
    #[must_use]
    pub fn sprite_count(&self) -> usize {
        self.shown.len()
    }

    /// The compositor.
    #[must_use]
    pub fn compositor(&self) -> &C {
        &self.compositor
    }

    /// The compositor, mutable (e.g. to take a recorder's counts).
    pub fn compositor_mut(&mut self) -> &mut C {
        &mut self.compositor
    }
}
