//! Rotations from other threads and from time: a coalescing request slot and a sampled
//! source, applied by [`SpritePainter::tick`](super::SpritePainter::tick).

use std::sync::{Arc, Mutex};
use std::time::Duration;

use glam::DMat3;

/// A thread-safe handle that requests a rotation for the painter's next
/// [`tick`](super::SpritePainter::tick). Requests coalesce: only the latest one is applied.
#[derive(Clone, Debug, Default)]
pub struct RotationHandle {
    pending: Arc<Mutex<Option<DMat3>>>,
}

impl RotationHandle {
    /// Requests `rotation` (CONVENTIONS.md's `R`) for the next tick, replacing any request not
    /// yet applied. Callable from any thread.
    pub fn request_rotation(&self, rotation: DMat3) {
        match self.pending.lock() {
            Ok(mut slot) => *slot = Some(rotation),
            Err(poisoned) => *poisoned.into_inner() = Some(rotation),
        }
    }

    fn take(&self) -> Option<DMat3> {
        match self.pending.lock() {
            Ok(mut slot) => slot.take(),
            Err(poisoned) => poisoned.into_inner().take(),
        }
    }
}

/// A rotation as a function of time, sampled on every [`tick`](super::SpritePainter::tick).
pub type RotationSource = Box<dyn FnMut(Duration) -> DMat3 + Send>;

/// Where a painter's rotations come from besides direct calls: the handle other threads
/// write to, and an optional source sampled per tick.
#[derive(Default)]
pub(super) struct RotationInputs {
    /// The request slot shared with every [`RotationHandle`].
    pub requests: RotationHandle,
    /// Sampled on every tick.
    pub source: Option<RotationSource>,
}

impl RotationInputs {
    /// The rotations to apply at `time`, in order: the source's sample, then the latest
    /// pending request (which therefore wins for this tick).
    pub fn at(&mut self, time: Duration) -> [Option<DMat3>; 2] {
        let sampled = self.source.as_mut().map(|source| source(time));
        [sampled, self.requests.take()]
    }
}
