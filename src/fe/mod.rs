//! Finite-element solver for a periodic elastic layer pressed onto a rigid sinusoid.
//!
//! # Problem (plane strain, units of the wavelength λ)
//! Half a wavelength of a layer, `X ∈ [0, ½]`, `Y ∈ [0, h]`, is bonded on `Y = h` to a
//! rigid slab that moves down by `d`; `u_x = 0` on `X = 0` and `X = ½` (symmetry). The
//! face `Y = 0` is pressed onto the rigid indenter `y_s(x) = −Δ(1 − cos 2πx)`, whose peak
//! touches the undeformed layer. The interface is adhesionless, and frictionless or with
//! regularised Coulomb–Orowan friction `τ_sl = min(μ p, τ_max)` ([`Interface`]). The mean
//! pressure is `p̄ = F/(λ/2)`, reported as `p̄/E*` with the plane-strain modulus
//! `E* = E/(1 − ν²)`. The contact half-width `a` is the current `x` of the contact
//! edge.
//!
//! # Method, in the order a solve reads
//! * [`model`]: the discrete model (boundary conditions, constraints, gaps, contact forces,
//!   the friction history: what a solve does not change), built on [`model::mesh`] (the
//!   structured Q1 mesh graded toward the contact face and the peak), [`model::material`] and
//!   [`model::element`] (compressible neo-Hookean, mean-dilatation Q1/P0 energy, locking-free
//!   for `κ/G` from 10 to 10⁴);
//! * [`contact`]: the indenter and exact normal contact by nonlinear elimination on the analytic
//!   surface in the current configuration, the Coulomb–Orowan law, where the contact edges lie,
//!   the contact patches, and the point and deformed state of a converged state;
//! * [`stepping`]: what one load step does: the load stepping from one contact-edge event to the
//!   next, to a contact width or a mean pressure, and back to zero load; which node touches or
//!   lets go next and at which slab displacement; the regula falsi and the cutting of failed
//!   steps; the load tangent and the predicted state; the deformed states a caller asks for;
//! * [`newton`]: what one Newton iteration does: Newton with line search (the plain and the
//!   bordered, edge-event step), the passes that alternate with contact-set updates, the reduced
//!   residual and tangent of a state ([`newton::assembly`]: the mutable side of a solve), and the
//!   linear solve of a step with the semismooth choice of each friction node's piece of the law;
//! * [`linsys`]: the sparse direct solves through faer (the fallback chain of the
//!   factorisations is described there);
//! * [`curve`]: the computed curve (points, unloading points, last deformed state), the CSV
//!   row of a point, and the work of a cycle; [`error`]: why a curve could not be completed,
//!   with the points converged before; [`convergence`]: interpolation of curves at fixed `a/λ`
//!   and the mesh-convergence (Richardson) table;
//! * [`shear_test`]: a block pressed onto a flat and sheared, verifying the friction law.
//!
//! docs/architecture.md walks one frictional Newton iteration through these files.
//!
//! The solver does no I/O, and takes every physical parameter as an argument (the
//! defaults live above it, in `crate::defaults`). A curve is complete (it reaches
//! `until_a_over_lambda`) or an error that carries the points converged before it.

// Index loops mirror the tensor index notation of the documented formulas.
#![allow(clippy::needless_range_loop)]

pub mod contact;
pub mod convergence;
pub mod curve;
pub mod error;
pub mod input_ranges;
pub mod interrupt;
pub mod linsys;
pub mod model;
pub mod newton;
pub mod options;
pub mod shear_test;
pub mod stepping;
#[cfg(test)]
pub(crate) mod test_problems;

pub use contact::edge_rule::{EdgeRule, DISCRETE_EDGE_FRACTION, EDGE_FRACTION_BY_ASPECT};
pub use contact::friction::{Branch, CoulombOrowan, Interface};
pub use contact::patch_edge::EDGE_PROGRESS_BY_FORCE_RATIO;
pub use convergence::{
    convergence_table, mesh_convergence, mesh_convergence_levels, p_at, ConvergenceRow,
    ConvergenceTable,
};
pub use curve::{
    cycle_friction_work_over_estar_lambda2, cycle_work_over_estar_lambda2, Curve, CurvePoint,
    CurvePointParseError, DeformedState, LoadDirection, SolveWork,
};
pub use error::{CurveFailure, SolveError};
pub use model::material::{estar_over_g, poisson_ratio};
pub use model::mesh::{Grading, MeshLevel, MeshLevelParseError};
pub use options::{ContactOptions, NewtonOptions, SolveOptions, StepOptions};
pub use stepping::loading::Stepping;
pub use stepping::slip_front::SlipFront;
pub use stepping::step_state::StepState;
pub use stepping::touched_hold::TouchedNodes;

use serde::{Deserialize, Serialize};

use crate::profile::{FinerHarmonics, Profile};
use std::ops::ControlFlow;

/// Kinematic model; named `finite` and `linear` in specs and on the command line.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kinematics {
    /// Finite deformation, compressible neo-Hookean, contact in the current
    /// configuration.
    #[default]
    Finite,
    /// Small strain, linear elastic with the same `G`, `ν`; gap at the reference `X`
    /// (`u_y(X) ≥ y_s(X)`).
    Linear,
}

impl Kinematics {
    /// Every kinematic model, in the order they are listed in messages.
    pub const ALL: [Kinematics; 2] = [Kinematics::Finite, Kinematics::Linear];

    /// The name used in specs, on the command line and in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Kinematics::Finite => "finite",
            Kinematics::Linear => "linear",
        }
    }
}

/// A kinematics name that is neither `finite` nor `linear`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown kinematics `{0}`; allowed: finite, linear")]
pub struct KinematicsParseError(pub String);

impl std::str::FromStr for Kinematics {
    type Err = KinematicsParseError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Kinematics::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| KinematicsParseError(s.into()))
    }
}

/// Physical problem.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LayerProblem {
    /// Indenter aspect ratio `Δ/λ` (> 0): of the single sinusoid, or of a profile's big
    /// wave (order 1).
    pub aspect_ratio: f64,
    /// A profile's finer harmonics (none for a single sinusoid; [`crate::profile`]).
    #[serde(default)]
    pub finer_harmonics: FinerHarmonics,
    /// Layer thickness `h/λ` (> 0).
    pub thickness_over_lambda: f64,
    /// Bulk-to-shear modulus ratio `κ/G` (> 0).
    pub kappa_over_g: f64,
    /// Kinematics.
    pub kinematics: Kinematics,
    /// Interface law.
    pub interface: Interface,
}

impl LayerProblem {
    /// The indenter's profile: the big wave of [`LayerProblem::aspect_ratio`] and the finer
    /// harmonics.
    pub fn profile(&self) -> Profile {
        Profile {
            aspect_ratio: self.aspect_ratio,
            finer: self.finer_harmonics,
        }
    }
}

fn check_range(
    field: &'static str,
    value: f64,
    ok: bool,
    allowed: &'static str,
) -> Result<(), SolveError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(SolveError::InvalidInput {
            field,
            value,
            allowed,
        })
    }
}

/// Validate the inputs.
pub fn validate(problem: &LayerProblem, opts: &SolveOptions) -> Result<(), SolveError> {
    input_ranges::ASPECT_RATIO.check(problem.aspect_ratio)?;
    input_ranges::THICKNESS_OVER_LAMBDA.check(problem.thickness_over_lambda)?;
    input_ranges::KAPPA_OVER_G.check(problem.kappa_over_g)?;
    input_ranges::UNTIL_A_OVER_LAMBDA.check(opts.until_a_over_lambda)?;
    if let Interface::CoulombOrowan(f) = problem.interface {
        input_ranges::FRICTION_COEFFICIENT.check(f.friction_coefficient)?;
        input_ranges::TAU_MAX_OVER_ESTAR.check(f.tau_max_over_estar)?;
        input_ranges::ELASTIC_SLIP_OVER_ELEMENT.check(f.elastic_slip_over_element)?;
    }
    if let Some(c) = opts.until_contact_fraction {
        input_ranges::UNTIL_CONTACT_FRACTION.check(c)?;
        check_range(
            "until_contact_fraction",
            c,
            opts.until_p_over_estar.is_none(),
            "unset when until_p_over_estar is set",
        )?;
    }
    if let Some(p) = opts.until_p_over_estar {
        input_ranges::UNTIL_P_OVER_ESTAR.check(p)?;
    }
    input_ranges::DA_TARGET.check(opts.steps.da_target)?;
    input_ranges::UNLOADING_SUBSTEPS.check(opts.steps.unloading_substeps as f64)?;
    if let EdgeRule::Fraction(phi) = opts.contact.edge_rule {
        input_ranges::EDGE_FRACTION.check(phi)?;
    }
    let (nx, ny) = opts.mesh.counts();
    check_range("mesh.nx", nx as f64, nx >= 2, ">= 2")?;
    check_range("mesh.ny", ny as f64, ny >= 1, ">= 1")?;
    input_ranges::PEAK_RATIO.check(opts.grading.peak_ratio)?;
    input_ranges::FIRST_LAYER_OVER_DX.check(opts.grading.first_layer_over_dx)?;
    input_ranges::COARSEN_AT_ASPECT.check(opts.grading.coarsen_at_aspect)?;
    validate_profile(&problem.profile(), problem.kinematics, nx, opts.grading)
}

/// Least face elements per wavelength of a profile's finer harmonic, where the face mesh is
/// coarsest: a cosine sampled at 8 points per period is represented by the piecewise-linear
/// face to within `1 − cos(π/8) ≈ 8 %` of its amplitude at a crest, and the contact patches of a
/// crest then span several elements before they merge.
pub const MIN_ELEMENTS_PER_HARMONIC_WAVELENGTH: f64 = 8.0;

/// Largest slope bound `Σ 2π AR_k` of a profile with finer harmonics under finite kinematics:
/// that of the steepest sinusoid the solver is verified on, AR = 0.3 (the paper's range,
/// docs/verification.md). Linear kinematics has no slope limit: small-strain contact is linear
/// elasticity whatever the profile, as in the boundary-element reference.
pub const PROFILE_SLOPE_LIMIT: f64 = std::f64::consts::TAU * 0.3;

/// A profile with finer harmonics must be resolved by the face mesh
/// ([`MIN_ELEMENTS_PER_HARMONIC_WAVELENGTH`] where it is coarsest; a harmonic of zero amplitude
/// needs none) and, under finite kinematics, not steeper than [`PROFILE_SLOPE_LIMIT`]. A single
/// sinusoid is not checked here (its limits are the solver's own errors).
fn validate_profile(
    profile: &Profile,
    kinematics: Kinematics,
    nx: usize,
    grading: Grading,
) -> Result<(), SolveError> {
    if profile.is_sinusoid() {
        return Ok(());
    }
    // the largest face spacing, at X = ½ (model::mesh::Mesh::graded): ratio/((ratio + 1) nx)
    let ratio = grading.peak_ratio;
    let largest_spacing = ratio / ((ratio + 1.0) * nx as f64);
    for h in profile.finer.iter().filter(|h| h.aspect_ratio > 0.0) {
        let elements = 1.0 / (h.order as f64 * largest_spacing);
        if elements < MIN_ELEMENTS_PER_HARMONIC_WAVELENGTH {
            return Err(SolveError::ProfileUnresolved {
                order: h.order,
                elements_per_wavelength: elements,
                min: MIN_ELEMENTS_PER_HARMONIC_WAVELENGTH,
            });
        }
    }
    let slope_bound = profile.slope_bound();
    if kinematics == Kinematics::Finite && slope_bound > PROFILE_SLOPE_LIMIT {
        let steepest = profile
            .harmonics()
            .max_by(|a, b| a.aspect_ratio.total_cmp(&b.aspect_ratio))
            .expect("a profile has a harmonic");
        return Err(SolveError::ProfileTooSteep {
            slope_bound,
            limit: PROFILE_SLOPE_LIMIT,
            steepest_order: steepest.order,
            steepest_slope: std::f64::consts::TAU * steepest.aspect_ratio,
        });
    }
    Ok(())
}

/// Build the discrete model for a problem (exposed for tests and diagnostics).
pub fn build_model(problem: &LayerProblem, opts: &SolveOptions) -> model::Model {
    let (nx, ny) = opts.mesh.counts();
    let profile = problem.profile();
    // the stretch under a steep peak is finite kinematics' (model::mesh::Grading::for_sinusoid)
    let grading = match profile.is_sinusoid() && problem.kinematics == Kinematics::Finite {
        true => opts.grading.for_sinusoid(profile.aspect_ratio),
        false => opts.grading,
    };
    let mesh = model::mesh::Mesh::graded(nx, ny, problem.thickness_over_lambda, grading);
    let mat = model::material::NeoHooke {
        g: 1.0,
        kappa: problem.kappa_over_g,
    };
    model::Model::new(
        mesh,
        mat,
        problem.kinematics,
        contact::indenter::Indenter { profile },
        problem.interface,
        model::Lateral::Symmetric,
    )
}

/// Trace the load curve `p̄/E*(a/λ)` from first contact to `opts.until_a_over_lambda`.
///
/// `on_step` is called with every converged point; its `ControlFlow::Break` stops the solve,
/// which then returns [`SolveError::Stopped`] with the points converged so far. On failure the
/// error comes with the points converged so far.
pub fn solve_curve(
    problem: &LayerProblem,
    opts: &SolveOptions,
    on_step: &mut dyn FnMut(&CurvePoint) -> ControlFlow<()>,
) -> Result<Curve, Box<CurveFailure>> {
    let (model, estar) = validated_model(problem, opts)?;
    let mut asm = newton::assembly::Assembly::new(&model);
    stepping::loading::trace(&model, &mut asm, opts, estar, &mut |p, _| on_step(p))
}

/// The model of a validated problem and `E*/G`, or the input error as a failed curve.
fn validated_model(
    problem: &LayerProblem,
    opts: &SolveOptions,
) -> Result<(model::Model, f64), Box<CurveFailure>> {
    if let Err(error) = validate(problem, opts) {
        return Err(Box::new(CurveFailure {
            error,
            points: Vec::new(),
            unloading: Vec::new(),
        }));
    }
    Ok((
        build_model(problem, opts),
        estar_over_g(problem.kappa_over_g),
    ))
}

/// A loading–unloading cycle: the load curve as [`solve_curve`], then the unloading branch
/// from `opts.until_a_over_lambda` back to zero load, with the friction history carried
/// through ([`Curve::unloading`]; the stepping is described at `stepping::unloading::unload`).
///
/// `on_step` is called with every converged point and its branch (`Break` stops the solve, as
/// in [`solve_curve`]). On failure the error comes with the points of both branches converged
/// so far.
pub fn solve_cycle(
    problem: &LayerProblem,
    opts: &SolveOptions,
    on_step: &mut dyn FnMut(LoadDirection, &CurvePoint) -> ControlFlow<()>,
) -> Result<Curve, Box<CurveFailure>> {
    let (model, estar) = validated_model(problem, opts)?;
    let mut asm = newton::assembly::Assembly::new(&model);
    stepping::unloading::trace_cycle(&model, &mut asm, opts, estar, &mut |dir, p, _| {
        on_step(dir, p)
    })
}

/// [`solve_curve`] (or, with `unload`, [`solve_cycle`]) that also hands `on_step`, with every
/// converged point of loading and of unloading, that point's deformed state ([`StepState`]:
/// reference and current coordinates, each element's dilatation, the contact status,
/// pressure, shear and slip of the face). The states are built for this caller only; the
/// curve is the same, bit for bit, as the other entry points give.
pub fn solve_with_states(
    problem: &LayerProblem,
    opts: &SolveOptions,
    unload: bool,
    on_step: &mut dyn FnMut(LoadDirection, &CurvePoint, &StepState) -> ControlFlow<()>,
) -> Result<Curve, Box<CurveFailure>> {
    let (model, estar) = validated_model(problem, opts)?;
    let mut asm = newton::assembly::Assembly::new(&model);
    let mut states = stepping::step_state::StepStates::new(&model, estar, on_step);
    if unload {
        stepping::unloading::trace_cycle(&model, &mut asm, opts, estar, &mut |dir, p, at| {
            states.observe(dir, p, at)
        })
    } else {
        stepping::loading::trace(&model, &mut asm, opts, estar, &mut |p, at| {
            states.observe(LoadDirection::Loading, p, at)
        })
    }
}
