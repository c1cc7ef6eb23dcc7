//! The finite-element solver against closed forms, mesh convergence, equilibrium, its extremes and its
//! inputs, and its ParaView output.
//!
//! One test binary per concern, each module one file as it was before the grouping (fewer binaries
//! link faster, and the tests of a binary share its threads).

mod curve_pairs;
mod energy_audit;
mod fe_convergence;
mod fe_equilibrium;
mod fe_extremes;
mod fe_friction;
mod fe_hysteresis;
mod fe_inputs;
mod fe_locking;
mod fe_newton;
mod fe_profiles;
mod fe_reach;
mod fe_small_ar;
mod fe_tangent;
mod fe_westergaard;
mod friction_fe_vs_bem;
mod robustness;
mod stick_zone;
mod two_scale_linear;
mod vtk;
