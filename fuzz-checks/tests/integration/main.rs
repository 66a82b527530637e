//! The committed fuzz corpora, regressions and loader cases replayed under `cargo test` (one
//! binary).

mod loader_cases;
mod replay;
