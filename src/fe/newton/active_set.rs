//! The active-set loop of one load step: Newton solves ([`crate::fe::newton`]) alternating with
//! updates of the contact set until it no longer changes.
//!
//! After each converged Newton solve, nodes with `λ < 0` (with friction: normal force
//! `N < 0`) are released and penetrating nodes activated (moved to their closest point on
//! the indenter, see [`crate::fe::contact::indenter`]); then again. Passes whose active set may still
//! change are converged loosely, the confirming pass tightly. [`equilibrate`] holds the
//! slab displacement fixed; [`equilibrate_event`] solves for it too, bringing the event's
//! target node onto the indenter.

use crate::fe::error::{FailCause, StepFail};
use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::Assembly;
use crate::fe::newton::{newton, newton_bordered, Pass};
use crate::fe::SolveOptions;

/// Floor of the multiplier scale `max|λ|` of the release test
/// `λ < −multiplier_rtol · max|λ|`: when every multiplier vanishes the test stays a
/// comparison with a (tiny) negative number. Safeguard, far below any force of the
/// problem and above the underflow threshold of doubles.
const MULTIPLIER_SCALE_FLOOR: f64 = 1e-300;

/// Contact-face nodes whose contact status the active-set updates of one load step leave as
/// they are.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Hold {
    /// Never activated: the target of a touchdown event, below its event.
    pub(crate) free: Option<usize>,
    /// Never released: the node of a release event, before its release
    /// ([`crate::fe::stepping::release_events`]).
    pub(crate) active: Option<usize>,
}

impl Hold {
    /// Every node follows the active-set rules.
    pub(crate) const NONE: Hold = Hold {
        free: None,
        active: None,
    };

    /// Node `k` is held free (if any), the others follow the rules.
    pub(crate) fn free(k: Option<usize>) -> Hold {
        Hold {
            free: k,
            active: None,
        }
    }
}

/// Converge one load step at its slab displacement: Newton passes ([`newton`]) and
/// active-set updates, the nodes of `hold` kept as they are. Returns the total number of
/// Newton iterations.
pub(crate) fn equilibrate(
    model: &Model,
    asm: &mut Assembly,
    st: &mut State,
    opts: &SolveOptions,
    hold: Hold,
) -> Result<usize, StepFail> {
    active_set_passes(model, asm, st, opts, hold, |model, asm, st, pass| {
        newton(model, asm, st, opts, pass)
    })
}

/// Converge the edge event on contact-face node `node`: the slab displacement is an unknown
/// too and the node, held free, is brought onto the indenter within `gap_tol` (bordered
/// Newton passes, [`newton_bordered`]), with active-set updates. Returns the total number
/// of Newton iterations.
pub(crate) fn equilibrate_event(
    model: &Model,
    asm: &mut Assembly,
    st: &mut State,
    opts: &SolveOptions,
    node: usize,
    gap_tol: f64,
) -> Result<usize, StepFail> {
    active_set_passes(
        model,
        asm,
        st,
        opts,
        Hold::free(Some(node)),
        |model, asm, st, pass| newton_bordered(model, asm, st, opts, node, gap_tol, pass.rtol),
    )
}

/// What the release test compares, per contact-face node of the state `st` with internal forces
/// `grad`: the vertical multiplier λ = ∂Π/∂y without friction (the same sign as the normal
/// force at equilibrium, and insensitive to the tangential residual left by loose passes:
/// testing N there costs more Newton iterations); the normal force N with friction, where
/// λ = (N + y_s' T)/w can differ in sign from N. A node is released when its value is below
/// `−multiplier_rtol` times the largest magnitude ([`release_scale`]).
pub(crate) fn release_forces(model: &Model, st: &State, grad: &[f64]) -> Vec<f64> {
    if model.is_potential() {
        model.multipliers(st, grad)
    } else {
        model.normal_forces(st, grad)
    }
}

/// Releases the contact patches' edge nodes (active, with a free neighbour on the face) of the
/// predicted state `st` whose release force ([`release_forces`]) fails the active-set passes'
/// release test (`multiplier_rtol`); nothing where `st` is inverted. For an unloading step's
/// predicted state ([`crate::fe::stepping::displacement_step::unloading_step`]).
///
/// With friction the forces are the mixed method's where `st` carries the element pressures
/// predicted with its positions ([`Model::iterate_forces`],
/// [`crate::fe::stepping::predictor::taylor_prediction`]): the displacement method's carry `κ`
/// times the error of the predicted element areas, which at the contact's edge makes the edge
/// node's force the largest of the face, of either sign, where it converges near zero
/// (docs/performance.md, "the prediction's force from its predicted pressures"). Without
/// friction the unloading branch steps from release event to release event, so the edge's
/// force vanishes at each step's end and the reading decides between two valid states; there
/// the displacement method's forces are kept (the predicted pressures' stopped a coarse AR 0.4
/// loop with an inverted element, the same page).
pub(crate) fn release_tensile_edges(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    st: &mut State,
) {
    let Some(f) = asm.assemble(model, st, false) else {
        return;
    };
    let forces = match model.is_potential() {
        true => f.grad,
        false => model.iterate_forces(st, &f.grad).unwrap_or(f.grad),
    };
    let release_force = release_forces(model, st, &forces);
    let threshold = release_threshold(opts, &release_force);
    let n = st.active.len();
    let free = |k: Option<usize>| k.is_some_and(|k| k < n && !st.active[k]);
    let edge = |k: usize| st.active[k] && (free(k.checked_sub(1)) || free(Some(k + 1)));
    let tensile: Vec<usize> = (0..n)
        .filter(|&k| edge(k) && release_force[k] < threshold)
        .collect();
    for k in tensile {
        st.active[k] = false;
    }
}

/// The release test's threshold on `release_force` ([`release_forces`]): `−multiplier_rtol`
/// times its scale ([`release_scale`]); a node whose value lies below it is released.
fn release_threshold(opts: &SolveOptions, release_force: &[f64]) -> f64 {
    -opts.contact.multiplier_rtol * release_scale(release_force)
}

/// The scale of the release test: the largest magnitude of `release_force`
/// ([`release_forces`]), at least [`MULTIPLIER_SCALE_FLOOR`].
pub(crate) fn release_scale(release_force: &[f64]) -> f64 {
    release_force
        .iter()
        .fold(0.0_f64, |m, l| m.max(l.abs()))
        .max(MULTIPLIER_SCALE_FLOOR)
}

/// The active-set loop: `newton_pass` at a residual tolerance, then release and activation
/// (the nodes of `hold` left as they are), until a pass at the tight tolerance leaves the set
/// as it is.
fn active_set_passes(
    model: &Model,
    asm: &mut Assembly,
    st: &mut State,
    opts: &SolveOptions,
    hold: Hold,
    mut newton_pass: impl FnMut(&Model, &mut Assembly, &mut State, Pass) -> Result<usize, StepFail>,
) -> Result<usize, StepFail> {
    let mut total = 0;
    // Passes whose active set may still change are converged loosely
    // (`loose_residual_rtol`); the pass that confirms the set is converged tightly.
    let mut loose = true;
    let mut after_change = false;
    for _ in 0..opts.newton.max_active_set_updates {
        let rtol = if loose {
            opts.newton.loose_residual_rtol
        } else {
            opts.newton.residual_rtol
        };
        total += newton_pass(model, asm, st, Pass { rtol, after_change })
            .map_err(|failed| failed.after(total))?;
        let f = asm
            .assemble(model, st, false)
            .ok_or(StepFail::from(FailCause::Inverted {
                iteration: total,
                residual: f64::NAN,
            }))?;
        let release_force = release_forces(model, st, &f.grad);
        let gaps = model.gaps(st);
        let threshold = release_threshold(opts, &release_force);
        let gap_tol = opts.contact.gap_tolerance_over_amplitude * model.indenter.amplitude();
        let mut changed = false;
        for k in 0..st.active.len() {
            if st.active[k] {
                if release_force[k] < threshold && hold.active != Some(k) {
                    st.active[k] = false;
                    changed = true;
                }
            } else if gaps[k] < -gap_tol && hold.free != Some(k) {
                model.activate(st, k);
                changed = true;
            }
        }
        after_change = changed;
        if !changed {
            if !loose {
                return Ok(total);
            }
            loose = false;
        }
        model.enforce_constraints(st);
    }
    Err(StepFail::cycling(opts.newton.max_active_set_updates, total))
}
