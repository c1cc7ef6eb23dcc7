//! `wavy solve` and `wavy eval` without their arguments, shared by the command line and the Python
//! bindings: a request in the command line's names and units is checked ([`input_checks`],
//! [`tolerance_choice`]), prepared and computed ([`solve_request`], [`eval_request`]), and
//! returned as rows ([`solve_outcome`]) or as a [`request_error::RequestError`] whose `Display` is
//! the command line's message.

pub mod bem_solve;
pub mod cost_estimate;
pub mod eval_request;
pub mod input_checks;
pub mod loading_points;
pub mod profile_mesh;
pub mod request_error;
pub mod solve_outcome;
pub mod solve_request;
pub mod solver;
pub mod tolerance_choice;
