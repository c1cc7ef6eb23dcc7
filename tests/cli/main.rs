//! The `wavy` binary as a user runs it: commands, arguments, spec files, exit codes and interrupts.
//!
//! One test binary per concern, each module one file as it was before the grouping (fewer binaries
//! link faster, and the tests of a binary share its threads).

mod cli_specs;
mod commands;
mod common;
mod interrupt;
