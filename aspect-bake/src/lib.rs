//! Exact aspect-graph bakes (reserved).
//!
//! This crate will hold, per DESIGN.md, the event functions `a·cos θ + b·sin θ + c` solved in
//! closed form, the cells `[lo, hi)` of constant painter order along an animation axis, the
//! sampling baseline and verification. It is empty today: no bake is implemented yet, and the
//! crate exists so that the workspace layout is stable for that work.
