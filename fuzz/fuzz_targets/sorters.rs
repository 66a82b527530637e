//! Fuzz target `sorters`: the check [`fuzz_checks::sorters::sorters`].
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| fuzz_checks::sorters::sorters(data));
