//! The closed-form laws (Westergaard, WNL, the superposition), their inverses and their extremes, and
//! the coefficient sets.
//!
//! One test binary per concern, each module one file as it was before the grouping (fewer binaries
//! link faster, and the tests of a binary share its threads).

mod coefficient_sets;
mod extremes_models;
mod laws;
mod recursion_vs_bem;
