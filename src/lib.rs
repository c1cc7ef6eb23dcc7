//! wavy: the contact area of a soft solid on a rigid wavy surface.
//!
//! The core (no I/O): [`models`] (Westergaard and the WNL model, with their inverse),
//! [`fe`] (the finite-strain finite-element solver), [`fit`] (re-deriving Table 1).
//! On top: [`spec`] (TOML experiment specs), [`runner`] (scenes → tables and figures, sweeps),
//! [`plot`] (deterministic SVG), [`numfmt`] (the one float formatter of every output),
//! [`cli`] (the command line's argument validation).

pub mod cli;
pub mod coefficient_sets;
pub mod defaults;
pub mod fe;
pub mod fit;
pub mod models;
pub mod numfmt;
pub mod plot;
pub mod runner;
pub mod spec;
pub mod table;
