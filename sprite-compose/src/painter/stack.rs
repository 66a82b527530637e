//! Stack diffing: which sprites a frame shows, in which order, and the operations that take
//! the compositor's stack there (visibility flips for changes only, few moves).

use super::pool::SpriteState;
use crate::order::StackMirror;
use crate::{Compositor, SpriteId};

/// The painter's view of the compositor's stack, and the sequences of the last and the
/// current frame.
#[derive(Default)]
pub(super) struct StackDiff {
    /// The compositor's stack as the painter left it.
    pub mirror: StackMirror,
    /// Sprites shown this frame, bottom first.
    pub sequence: Vec<SpriteId>,
    /// Sprites shown last frame.
    pub previous: Vec<SpriteId>,
    /// `shown[id] == stamp`: sprite `id` is in this frame's sequence.
    pub shown: Vec<u32>,
    /// This frame's mark in `shown`.
    pub stamp: u32,
}

impl StackDiff {
    /// Room for `n` sprites (so that steady-state frames do not allocate).
    pub fn reserve(&mut self, n: usize) {
        self.mirror.reserve(n);
        self.sequence.reserve(n);
        self.previous.reserve(n);
        self.shown.resize(n, 0);
    }

    /// Starts a frame's sequence.
    pub fn begin(&mut self) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.shown.iter_mut().for_each(|s| *s = 0);
            self.stamp = 1;
        }
        self.sequence.clear();
    }

    /// Appends sprite `id` to this frame's sequence unless it is already in it (a sprite
    /// drawn for several items is stacked at its first). `pool_len` sizes the marks.
    pub fn push(&mut self, id: u32, pool_len: usize) {
        if self.shown.len() <= id as usize {
            self.shown.resize(pool_len.max(id as usize + 1), 0);
        }
        if self.shown[id as usize] == self.stamp {
            return;
        }
        self.shown[id as usize] = self.stamp;
        self.sequence.push(SpriteId(id));
    }

    /// Sends the frame: shows sprites that became visible, hides those that left, reorders
    /// the stack to the sequence, and keeps the sequence as the previous one.
    pub fn finish(&mut self, sprites: &mut [SpriteState], out: &mut dyn Compositor) {
        for &id in &self.sequence {
            let sprite = &mut sprites[id.index()];
            if !sprite.visible {
                sprite.visible = true;
                out.set_visible(id, true);
            }
        }
        for &id in &self.previous {
            let sprite = &mut sprites[id.index()];
            if sprite.visible && self.shown.get(id.index()) != Some(&self.stamp) {
                sprite.visible = false;
                out.set_visible(id, false);
            }
        }
        self.mirror.reorder(&self.sequence, out);
        std::mem::swap(&mut self.sequence, &mut self.previous);
    }

    /// Sprites shown by the last frame.
    pub fn drawn(&self) -> usize {
        self.previous.len()
    }
}
