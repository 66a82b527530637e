//! Fuzz target `glb`: the check [`fuzz_checks::loaders::glb`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::loaders::glb(data));
