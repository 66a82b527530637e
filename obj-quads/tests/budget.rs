//! Resource budgets: a hostile but valid file stops with a typed error before it costs more
//! than its stated budget ([`obj_quads::limits`]).

use obj_quads::{LoadError, LoadOptions, load_obj_str};

#[global_allocator]
static ALLOCATOR: test_base::memory::PeakAllocator = test_base::memory::PeakAllocator;

/// A 10-million-face OBJ is refused by the first pass over its text: the face cap
/// (`DEFAULT_MAX_FACES`, 2²²) ends the load before any face is built, with at most 128 MB
/// of heap beyond the text itself.
#[test]
fn a_ten_million_face_obj_stops_within_its_budget() {
    let faces = 10_000_000;
    let mut text = String::with_capacity(24 + faces * 8);
    text.push_str("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for _ in 0..faces {
        text.push_str("f 1 2 3\n");
    }
    let (result, peak) = test_base::memory::peak(|| load_obj_str(&text, &LoadOptions::DEFAULT));
    let error = result.expect_err("10 million faces are over the default cap");
    assert!(
        matches!(
            error,
            LoadError::TooLarge {
                what: "face count",
                ..
            }
        ),
        "{error}"
    );
    println!(
        "{error}; peak heap beyond the {} MB text: {} MB",
        text.len() >> 20,
        peak >> 20
    );
    assert!(peak <= 128 << 20, "peak heap {peak} bytes");
}
