//! Resource budgets of the picture bake: a large scan stops with a typed error at its pair
//! budget, within the memory that budget states.

use aspect_bake::face_sort::{Geometry, View};
use aspect_bake::{Axis, BakeError, PictureOptions, Spin, bake_picture};

#[global_allocator]
static ALLOCATOR: test_support::memory::PeakAllocator = test_support::memory::PeakAllocator;

/// A 70,000-face closed surface with a pair budget of 20,000 stops with
/// `BakeError::PairBudget` before it builds the pairs: at most 64 MB of heap beyond the
/// geometry.
#[test]
fn a_seventy_thousand_face_scan_stops_at_its_pair_budget() {
    let mesh = test_support::models::bumpy_torus(70_000);
    let geometry = Geometry::new(&mesh).unwrap();
    let view = View::fit(&geometry.bounds(), 512, 512);
    let spin = Spin::new(
        view,
        Axis::Yaw {
            pitch: 20.0,
            roll: 0.0,
        },
    )
    .unwrap();
    let options = PictureOptions {
        max_pairs: 20_000,
        ..PictureOptions::DEFAULT
    };
    let (result, peak) = test_support::memory::peak(|| bake_picture(&geometry, &spin, &options));
    let error = result.expect_err("over the pair budget");
    assert!(matches!(error, BakeError::PairBudget { .. }), "{error}");
    println!(
        "{} pieces: {error}; peak heap {} MB",
        geometry.pieces().len(),
        peak >> 20
    );
    assert!(peak <= 64 << 20, "peak heap {peak} bytes");
}
