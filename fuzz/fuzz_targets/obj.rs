//! Fuzz target `obj`: the check [`fuzz_checks::loaders::obj`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::loaders::obj(data));
