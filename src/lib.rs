//! wavy: the contact area of a soft solid on a rigid wavy surface.
//!
//! The core (no I/O): [`models`] (Westergaard and the WNL model, with their inverse).
//! On top: [`spec`] (TOML experiment specs), [`runner`] (scenes → tables and figures),
//! [`plot`] (deterministic SVG), [`numfmt`] (the one float formatter of every output).

pub mod cli;
pub mod coefficient_sets;
pub mod defaults;
pub mod fit;
pub mod models;
pub mod numfmt;
pub mod plot;
pub mod runner;
pub mod spec;
pub mod table;
