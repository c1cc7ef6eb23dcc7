//! The house rules: the layers point one way, the file structure, and the docs agree with the CSVs
//! they restate.
//!
//! One test binary per concern, each module one file as it was before the grouping (fewer binaries
//! link faster, and the tests of a binary share its threads).

mod doc_tables;
mod file_structure;
mod layers;
mod solver_fingerprint;
mod tree;
