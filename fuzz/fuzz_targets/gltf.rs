//! Fuzz target `gltf`: the check [`fuzz_checks::loaders::gltf`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::loaders::gltf(data));
