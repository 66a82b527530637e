//! Checks across the sinks (unpublished, tests only): vector-sink's files and
//! sprite-compose's visible lines judged by raster-sink's references (`tests/`), and the
//! root README's examples, compiled and run as doctests of this crate.
//!
//! It sits above every sink, so that no library crate dev-depends on a crate that depends on
//! it.

/// The repository's root README: its examples are compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct RootReadme;

/// aspect-bake's README, whose quick start writes a page with vector-sink (which depends on
/// aspect-bake, so aspect-bake cannot run it itself).
#[cfg(doctest)]
#[doc = include_str!("../../aspect-bake/README.md")]
pub struct AspectBakeReadme;
