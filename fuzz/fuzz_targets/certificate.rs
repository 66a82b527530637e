//! Fuzz target `certificate`: the check [`fuzz_checks::certificate::certificate`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::certificate::certificate(data));
