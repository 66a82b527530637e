//! The BSP build's growth: a large smooth surface gets a shallow tree. Face planes of a
//! smooth surface mostly peel a few polygons off at a time; large sets also split at a median
//! plane across their widest axis, which keeps the tree shallow and the build near
//! `n log n` (the figures from before that split are in docs/bench.md's notes). This test's
//! own figures are printed by its assertions' messages when they fail.

use face_sort::{BspOptions, BspTree, Geometry};

#[test]
fn a_large_smooth_surface_gets_a_shallow_tree() {
    let geometry = Geometry::new(&face_sort::generate::planar_torus(20_000)).unwrap();
    let tree = BspTree::build(&geometry, &BspOptions::DEFAULT);
    let pieces = geometry.pieces().len();
    assert!(tree.depth() <= 400, "depth {}", tree.depth());
    let per_piece = tree.fragment_count() as f64 / pieces as f64;
    assert!(per_piece <= 2.3, "{per_piece:.3} fragments per piece");
}
