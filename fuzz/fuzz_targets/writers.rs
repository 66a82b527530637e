//! Fuzz target `writers`: the check [`fuzz_checks::writers::writers`].
#![no_main]

// libfuzzer-sys aborts on every panic, even one caught inside the library: the loaders turn
// a dependency's panic into a typed error (their contract), so the default hook comes back
// and only a panic that escapes the check is a crash (libfuzzer-sys aborts on it).
libfuzzer_sys::fuzz_target!(
    init: drop(std::panic::take_hook()),
    |data: &[u8]| fuzz_checks::writers::writers(data)
);
