//! Fuzz target `bake`: the check [`fuzz_checks::bake::bake`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::bake::bake(data));
