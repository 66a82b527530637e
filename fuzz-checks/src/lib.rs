//! The checks behind the workspace's coverage-guided fuzz targets.
//!
//! Each target is one function from the fuzzer's bytes that **panics when it finds a bug**
//! and returns otherwise. The libFuzzer targets in `fuzz/` call these functions and
//! nothing else, and `cargo test -p fuzz-checks` replays every committed input (the
//! minimised corpora under `fuzz/corpus/TARGET/` and the regressions under
//! `fuzz/regressions/TARGET/`) through the same functions, so a finding stays fixed.
//!
//! | target | input | the check |
//! | --- | --- | --- |
//! | [`obj`](loaders::obj) | OBJ text, optionally `\0` and an MTL library it names | [`test_support::loaders`]' loader check |
//! | [`gltf`](loaders::gltf) | glTF JSON | the same |
//! | [`glb`](loaders::glb) | binary glTF | the same |
//! | [`texture`](loaders::texture) | PNG or JPEG bytes | decoded within limits, or a typed error |
//! | [`sorters`](sorters::sorters) | a small mesh and a view, any numbers | a typed error, or an exact list from every exact sorter |
//! | [`writers`](writers::writers) | a small mesh, materials, names, colours, options | SVG, HTML and PDF that real parsers accept |
//! | [`bake`](bake::bake) | a small mesh, a spin axis | a typed error, or a bake that `verify` passes |
//! | [`certificate`](certificate::certificate) | a saved `Presorted` certificate | a typed error, or a sorter that orders views |
//!
//! Every target keeps its own inputs small (a few faces, at most a few kilobytes read), so a
//! run does millions of executions. Resource budgets are part of the contract: each check
//! states what it bounds, and libFuzzer runs with `-rss_limit_mb` and `-timeout`
//! (`cargo xtask fuzz --libfuzzer`).

/// The crate's README: its example is compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

pub mod bake;
pub mod certificate;
mod input;
pub mod loaders;
pub mod sorters;
pub mod writers;

/// A fuzz target: its name (the `fuzz/fuzz_targets/NAME.rs` file and the corpus folder) and
/// its check.
#[derive(Clone, Copy, Debug)]
pub struct Target {
    /// The target's name.
    pub name: &'static str,
    /// The check: panics on a bug.
    pub check: fn(&[u8]),
}

/// Every target, in the order of the table above.
pub const TARGETS: [Target; 8] = [
    Target {
        name: "obj",
        check: loaders::obj,
    },
    Target {
        name: "gltf",
        check: loaders::gltf,
    },
    Target {
        name: "glb",
        check: loaders::glb,
    },
    Target {
        name: "texture",
        check: loaders::texture,
    },
    Target {
        name: "sorters",
        check: sorters::sorters,
    },
    Target {
        name: "writers",
        check: writers::writers,
    },
    Target {
        name: "bake",
        check: bake::bake,
    },
    Target {
        name: "certificate",
        check: certificate::certificate,
    },
];

/// The folder of the libFuzzer project: `fuzz/` at the workspace root.
#[must_use]
pub fn fuzz_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("fuzz")
}
