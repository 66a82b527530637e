//! Steady-state frames of SpritePainter allocate nothing (a counting global allocator).
// A global allocator must implement the unsafe `GlobalAlloc` trait; this test binary is the
// only place in the crate that needs `unsafe`, and it only forwards to the system allocator.
#![allow(unsafe_code)]

#[path = "support/mod.rs"]
mod support;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use sprite_compose::face_sort::{SorterKind, View};
use sprite_compose::{RecordingCompositor, SpritePainter, rotation_from_yaw_pitch_roll};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);
static COUNTING: AtomicBool = AtomicBool::new(false);

// SAFETY: forwards every call unchanged to `System`, only counting calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.load(Ordering::Relaxed) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn count<T>(f: impl FnOnce() -> T) -> (T, usize) {
    ALLOCATIONS.store(0, Ordering::SeqCst);
    COUNTING.store(true, Ordering::SeqCst);
    let out = f();
    COUNTING.store(false, Ordering::SeqCst);
    (out, ALLOCATIONS.load(Ordering::SeqCst))
}

#[test]
fn steady_state_frames_allocate_nothing() {
    // One test function: the counter is global, so tests in this binary must not overlap.
    let mesh = support::load_obj("keenan-crane/spot/spot_control_mesh.obj");
    let geometry = support::geometry(&mesh);
    for kind in [SorterKind::Centroid, SorterKind::Bsp] {
        let view = View::fit(&geometry.bounds(), 256, 256)
            .with_yaw_pitch_roll(0.0, 20.0, 0.0)
            .with_cull_margin(2.0);
        let mut painter = SpritePainter::new(
            &geometry,
            kind.build(&geometry),
            view,
            RecordingCompositor::new(),
        );
        painter.frame();
        let handle = painter.rotation_handle();
        let mut ops = 0;
        let ((), allocations) = count(|| {
            for k in 1..=360u32 {
                handle.request_rotation(rotation_from_yaw_pitch_roll(f64::from(k), 20.0, 0.0));
                ops += painter
                    .tick(Duration::from_millis(u64::from(k) * 16))
                    .ops
                    .total();
                // An unchanged frame in between.
                assert_eq!(painter.frame().ops.total(), 0);
            }
        });
        assert!(
            ops > 360,
            "{}: the spin did change things ({ops} ops)",
            kind.name()
        );
        assert_eq!(allocations, 0, "{}: frames 2..=721 allocated", kind.name());
    }
}
