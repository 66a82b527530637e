//! Fuzz target `texture`: the check [`fuzz_checks::loaders::texture`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::loaders::texture(data));
