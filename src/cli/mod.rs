//! The command line: argument types, their validation and the commands, on top of the library
//! (`wavy::runner` for specs, `wavy::fe` and `wavy::models` for single evaluations). Nothing in
//! the library depends on this module: it is part of the binary only.

pub mod diff;
pub mod eval;
pub mod input;
pub mod output;
pub mod reference;
pub mod solve;
pub mod specs;
pub mod timing;
pub mod tolerance;

#[cfg(test)]
mod fuzz;
