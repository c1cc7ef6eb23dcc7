//! wavy: the contact area of a soft solid on a rigid wavy surface.
//!
//! Layers, each using only the ones above it in this list (`tests/house/layers.rs` enforces it;
//! `docs/architecture.md` draws it):
//! - the core, with no I/O: [`models`] (Westergaard and the WNL model, their coefficient sets
//!   and inverse), [`fe`] (the finite-strain finite-element solver), [`fit`] (re-deriving
//!   Table 1), [`accuracy`] (the tiers that answer p̄(a), their measured errors and costs, and
//!   the choice of the cheapest that meets a tolerance), [`profile`] (even periodic surface profiles
//!   as cosine harmonics), [`bem`] (the periodic FFT boundary-element reference solver: a rigid
//!   profile on a linear elastic half-plane), [`csv_text`] (the one reader of our CSV
//!   tables as text);
//! - output primitives: [`numfmt`] (the one float formatter), [`table`] (tables, CSV,
//!   comparison), [`plot`] (deterministic SVG), [`vtk`] (the deformed states as a ParaView
//!   time series), [`atomic_write`] (complete files or none);
//! - [`defaults`] (the open physical parameters) and [`spec`] (TOML field types and checks);
//! - [`runner`] (the scene registry, scenes → tables and figures, sweeps, check).
//!
//! The command line lives in the binary (`src/main.rs`, `src/cli/`), so no library module can
//! depend on it.

pub mod accuracy;
pub mod atomic_write;
pub mod bem;
pub mod csv_text;
pub mod defaults;
pub mod fe;
pub mod fit;
pub mod models;
pub mod numfmt;
pub mod plot;
pub mod profile;
pub mod runner;
pub mod spec;
pub mod table;
pub mod vtk;
