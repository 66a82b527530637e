//! Tests of the command line (one binary, modules by command): the commands run as a user
//! runs them, their files read back, and the docs that cannot drift.

mod bake;
mod cli;
mod docs;
mod house;
mod ship;
