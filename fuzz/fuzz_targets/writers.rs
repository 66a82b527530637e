//! Fuzz target `writers`: the check [`fuzz_checks::writers::writers`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::writers::writers(data));
