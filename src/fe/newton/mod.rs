//! Newton's method at a fixed active set: the plain step, and the bordered step of an edge
//! event in which the slab displacement is an unknown too.
//!
//! Both use the consistent tangent of the reduced problem ([`crate::fe::newton::assembly`]), its
//! geometric volumetric term on the state's pressure iterate where it has one (the mixed method's,
//! [`crate::fe::model::mixed_pressure`]; each step carries it, a converged state drops it), solved by
//! [`crate::fe::newton::friction_step`] (the factorisations are described in [`crate::fe::linsys`]), and one
//! backtracking [`line_search`]: on the energy `Π` (Armijo) or, if the Newton direction is
//! not a descent direction or the problem has friction, on a residual merit (in a frictional
//! pass after an active-set change, the mixed method's residual, in one from the predictor's
//! pressure iterate either that or the displacement method's, [`FrictionMerit`]). Inverted trial
//! configurations (`J ≤ 0`) are backtracked. Convergence: `‖r‖∞ ≤ rtol · f_e + atol`, `f_e`
//! the largest element-level nodal force (the round-off scale of the assembled residual) and
//! `atol = residual_atol · (G + κ) λ`; an iteration whose correction is below
//! `increment_atol` (round-off of the positions) on pieces of the friction law that the state
//! obeys also ends the iteration, and so does one whose
//! correction is below [`ROUND_OFF_INCREMENT`] when the last step no longer halved the residual:
//! the residual has reached the round-off floor of the mesh ([`at_round_off_floor`]).

pub mod active_set;
pub mod assembly;
pub mod friction_rows;
pub mod friction_step;
pub mod line_search;
pub mod mixed_residual;

use crate::fe::contact::friction::Branch;
use crate::fe::error::{FailCause, StepFail};
use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::{Assembly, Forces};
use crate::fe::newton::friction_step::solve_newton_step;
use crate::fe::newton::line_search::{line_search, Decrease};
use crate::fe::newton::mixed_residual::{l2_norm, FrictionMerit};
use crate::fe::{Kinematics, SolveOptions};

/// A Newton correction this small (`∞`-norm, units of λ: a millionth of a millionth of the
/// wavelength) carries no information once the residual has stopped falling: it is the
/// round-off of the solve. On fine meshes the round-off floor of the residual lies above the
/// absolute tolerance: at 768 face elements (192 across the thickness) the residual stalls at
/// 1.4–2e-10 (the tall elements deep in the layer, `residual_atol · (G + κ)` = 1e-10) with
/// corrections of 2–4e-14, above `increment_atol`, and the first event failed after 30 iterations
/// (docs/verification.md, two-scale profiles).
pub(crate) const ROUND_OFF_INCREMENT: f64 = 1e-12;

/// How far above the tolerance a residual may stall and still count as the round-off floor:
/// the floors measured lie within 2× of it; a residual 100× above it is a failed solve, however
/// small the correction.
const ROUND_OFF_RESIDUAL_FACTOR: f64 = 100.0;

/// Whether a Newton iteration has reached the round-off floor of the residual: its correction
/// `dq_norm` is below [`ROUND_OFF_INCREMENT`], the residual `res` is no less than half the
/// last iteration's `prev` (a correct step at that size would reduce it quadratically) and
/// within [`ROUND_OFF_RESIDUAL_FACTOR`] of the tolerance `tol`.
fn at_round_off_floor(dq_norm: f64, res: f64, prev: f64, tol: f64) -> bool {
    dq_norm <= ROUND_OFF_INCREMENT && res > 0.5 * prev && res <= ROUND_OFF_RESIDUAL_FACTOR * tol
}

/// Residual bound of Newton convergence, `rtol · f_e + residual_atol · (G + κ)`, with
/// `force_scale = f_e` the largest element-level nodal force.
pub(crate) fn residual_tolerance(
    model: &Model,
    opts: &SolveOptions,
    rtol: f64,
    force_scale: f64,
) -> f64 {
    let atol = opts.newton.residual_atol * (model.mat.g + model.mat.kappa);
    rtol * force_scale + atol
}

pub(crate) fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// The largest entry of a state's residual, or its distance from the exact-stick friction
/// law if that is larger ([`Forces::friction_complementarity`]).
fn convergence_norm(f: &Forces) -> f64 {
    inf_norm(&f.resid).max(f.friction_complementarity)
}

/// The trial `trial` of a Newton step from `from` taken at the fraction `alpha`: with the
/// exact-stick pieces of the law that the step was solved with ([`solve_newton_step`]; none under
/// the penalty law) and the pressure iterate carried through the step ([`Model::carry_pressure`]).
fn stepped(
    model: &Model,
    from: &State,
    mut trial: State,
    alpha: f64,
    held: Option<&[(usize, Branch)]>,
) -> State {
    for &(k, branch) in held.unwrap_or_default() {
        trial.slip[k].held = branch;
    }
    model.carry_pressure(from, &mut trial, alpha);
    trial
}

/// A failed iteration when the caller asked the solve to stop ([`crate::fe::interrupt`]): read
/// before each iteration, so a solve stops within one iteration; the failure ends the solve,
/// which the caller that set the flag reports as interrupted.
fn interrupted(iteration: usize, residual: f64) -> Result<(), StepFail> {
    match crate::fe::interrupt::requested() {
        false => Ok(()),
        true => Err(StepFail::from(FailCause::Diverged {
            iteration,
            residual,
            reason: crate::fe::interrupt::INTERRUPTED.into(),
        })),
    }
}

/// One Newton pass of the active-set loop ([`crate::fe::newton::active_set`]): its residual
/// tolerance, and whether the active set changed before it (the pass then starts from the
/// converged state of the pass before).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pass {
    /// Relative residual tolerance.
    pub(crate) rtol: f64,
    /// The pass follows an active-set change.
    pub(crate) after_change: bool,
}

/// Newton iterations at a fixed active set, to the residual tolerance of `pass`. Returns the
/// number of iterations. With friction, a pass after an active-set change starts from a
/// converged state, which has no pressure iterate: it is given one at its own pressures, and its
/// line search measures the residual in the mixed method's variables; a pass from the
/// predictor's pressure iterate accepts a step where either that residual or the displacement
/// method's falls enough ([`FrictionMerit`]).
pub(crate) fn newton(
    model: &Model,
    asm: &mut Assembly,
    st: &mut State,
    opts: &SolveOptions,
    pass: Pass,
) -> Result<usize, StepFail> {
    let rtol = pass.rtol;
    let mut last_res = f64::NAN;
    let mut last_step = f64::INFINITY;
    let merit = FrictionMerit::for_pass(
        model,
        &opts.newton,
        pass.after_change,
        st.pressure.is_some(),
    );
    if !opts.newton.pressure_iterate {
        st.pressure = None;
    } else if merit == FrictionMerit::Mixed {
        model.start_pressure_iterate(st);
    }
    for it in 0..=opts.newton.max_iterations {
        interrupted(it, last_res)?;
        // convergence check on the forces alone (cached after the line search), the
        // matrix only when another iteration follows
        let Some(f) = asm.assemble(model, st, false) else {
            return Err(StepFail::from(FailCause::Inverted {
                iteration: it,
                residual: last_res,
            }));
        };
        let res = convergence_norm(&f);
        let prev = std::mem::replace(&mut last_res, res);
        let tol = residual_tolerance(model, opts, rtol, f.force_scale);
        if res <= tol || at_round_off_floor(last_step, res, prev, tol) {
            st.pressure = None;
            return Ok(it);
        }
        if it == opts.newton.max_iterations || !res.is_finite() {
            break;
        }
        let f = asm
            .assemble(model, st, true)
            .expect("state assembled above is not inverted");
        let mut rhs = vec![f.resid.iter().map(|r| -r).collect::<Vec<f64>>()];
        let held = solve_newton_step(model, asm, opts, &mut rhs, it, |x| (x[0].clone(), 0.0))?;
        let dq = rhs.pop().expect("one right-hand side");
        last_step = inf_norm(&dq);
        let trial_at = |m: &Model, alpha: f64| {
            stepped(m, st, m.updated(st, &dq, alpha), alpha, held.as_deref())
        };
        let same_pieces = held
            .as_deref()
            .is_none_or(|h| h.iter().all(|&(k, b)| st.slip[k].held == b));
        if last_step <= opts.newton.increment_atol
            && same_pieces
            && f.friction_complementarity <= tol
        {
            // correction below the round-off of the positions, on the same pieces of the
            // friction law, and those pieces obeyed: converged (a state whose sliding nodes
            // slide against their force is not, however small the step that keeps it)
            *st = trial_at(model, 1.0);
            st.pressure = None;
            return Ok(it + 1);
        }
        if model.kin == Kinematics::Linear && model.is_potential() {
            // quadratic energy: the Newton step is exact
            *st = trial_at(model, 1.0);
            continue;
        }
        let slope: f64 = f.resid.iter().zip(&dq).map(|(r, d)| r * d).sum();
        let (initial, residual_merit) = merit.at(model, st, &f);
        let decrease = if slope < 0.0 && model.is_potential() {
            Decrease::Energy {
                initial: f.energy,
                slope,
            }
        } else {
            Decrease::Merit {
                initial,
                merit: residual_merit.as_ref(),
            }
        };
        match line_search(model, asm, opts.newton.max_line_search, trial_at, decrease) {
            Some(t) => *st = t,
            None => {
                let reason = "line search found no acceptable step";
                return Err(diverged(model, asm, (it, res), reason));
            }
        }
    }
    let reason = "maximum Newton iterations reached";
    let last = (opts.newton.max_iterations, last_res);
    Err(diverged(model, asm, last, reason))
}

/// What a frictionless solve's divergence adds to its reason when the last tangent was
/// indefinite: the energy is not convex there, the signature of the coarse layer's loss of
/// stability at large aspect ratios, which a finer mesh delays (docs/verification.md,
/// "Robustness grid"). With friction the symmetric part is indefinite in ordinary steps, so
/// it says nothing.
const INDEFINITE_TANGENT: &str = "the tangent stiffness was indefinite at the last iterate: \
     the energy is not convex there, the signature of the discrete layer losing stability, which \
     at large aspect ratios a finer mesh delays (docs/verification.md, \"Robustness grid\")";

/// The failure of a Newton solve at `(iteration, residual)` for `reason`, with
/// [`INDEFINITE_TANGENT`] where it applies, and the node at the friction law's crossover
/// where the last tangent's largest residual sits on one ([`at_crossover`]).
fn diverged(
    model: &Model,
    asm: &Assembly,
    (iteration, residual): (usize, f64),
    reason: &str,
) -> StepFail {
    let indefinite = model.is_potential() && asm.sys.held_factorisation_indefinite();
    let mut reason = match indefinite {
        true => format!("{reason}; {INDEFINITE_TANGENT}"),
        false => reason.into(),
    };
    if let Some(note) = at_crossover(asm) {
        reason = format!("{reason}; {note}");
    }
    StepFail::from(FailCause::Diverged {
        iteration,
        residual,
        reason,
    })
}

/// How close the two bounds of the threshold, `μN` and `τ_max ℓ`, must be (relative to the
/// larger) for a divergence's reason to place its largest residual at the Coulomb–Orowan
/// crossover. A diagnostic's threshold, not a parameter of the law: the unloading stalls
/// of docs/verification.md ("Robustness grid") sit far inside it (2.1·10⁻⁹ on the AR 0.3,
/// μ 100 loops of 32 and 48 face elements).
const CROSSOVER_RTOL: f64 = 1e-2;

/// Where the largest residual entry of the last tangent's state is the sliding unknown of an
/// active face node whose threshold sits at the Coulomb–Orowan crossover: which node, and how
/// close its two bounds are. At that kink of the law Newton's model of the row is wrong on
/// either side, and at a large friction coefficient this is where unloading stops.
fn at_crossover(asm: &Assembly) -> Option<String> {
    let slot = asm.tangent_largest_residual?;
    let row = asm.friction_rows.iter().find(|r| r.row == slot)?;
    let (coulomb, orowan) = (row.coulomb.w_limit, row.orowan.w_limit);
    let larger = coulomb.max(orowan);
    let apart = (coulomb - orowan).abs() / larger;
    (larger > 0.0 && apart <= CROSSOVER_RTOL).then(|| {
        format!(
            "the largest residual is on the sliding unknown of contact-face node {}, whose \
             friction threshold sits at the Coulomb–Orowan crossover (μN and τ_max ℓ {:.1e} \
             apart), a kink of the law that Newton's steps alternate across; at a large friction \
             coefficient unloading stops at such a node (docs/verification.md, \"Robustness grid\")",
            row.face, apart
        )
    })
}

/// The bordered solve converges the target's gap to this fraction of the event
/// tolerance, so that its result passes the event's acceptance test `|g_k| ≤ tol` with a
/// margin of two. Safeguard.
const BORDERED_GAP_FRACTION: f64 = 0.5;

/// Gap tolerance of the loose passes of the bordered solve (those whose active set may
/// still change, see [`NewtonOptions::loose_residual_rtol`]) over that of the tight pass:
/// they only need to settle the active set; the confirming pass converges the gap
/// tightly. Safeguard value, not tuned.
const LOOSE_GAP_FACTOR: f64 = 100.0;

/// Smallest `|∇c·z₂| = |∂g_k/∂d|` (dimensionless) the bordered step divides by: guards
/// the division against an exact zero (a target node that does not move with the slab).
/// Safeguard, far below any rate met in practice and above the underflow threshold of
/// doubles.
const INSENSITIVE_GAP_RATE: f64 = 1e-300;

/// One bordered Newton step `(δq, δd)` and the pieces of the friction law it was solved on.
struct BorderedStep {
    /// The correction `δq` of the unknowns, slot-wise (units of λ).
    dq: Vec<f64>,
    /// The correction `δd` of the slab displacement (units of λ).
    dd: f64,
    /// Under exact stick, each friction node's piece of the law in the step solved
    /// (`(face index, branch)`); `None` otherwise.
    held: Option<Vec<(usize, Branch)>>,
}

/// Newton iterations for the edge event on node `k` at a fixed active set: the slab
/// displacement `d` is an extra unknown and the extra equation is the gap of node `k`
/// (held free), `c(q) = 0`, converged to [`BORDERED_GAP_FRACTION`] of the event tolerance
/// `event_tol` ([`LOOSE_GAP_FACTOR`] times that in loose passes). Bordered solve with one
/// factorisation:
///
/// ```text
/// K z₁ = −r,   K z₂ = −∂r/∂d,   δd = −(c + ∇c·z₁)/(∇c·z₂),   δq = z₁ + z₂ δd
/// ```
///
/// Line search on the merit `‖r‖∞ + |∂r/∂d|∞ |c|` (forces), backtracking also on
/// inversion; the linear frictionless problem takes the first non-inverted trial.
/// Each iteration: check convergence, linearise, solve for the bordered step, search along it.
pub(crate) fn newton_bordered(
    model: &Model,
    asm: &mut Assembly,
    st: &mut State,
    opts: &SolveOptions,
    k: usize,
    event_tol: f64,
    rtol: f64,
) -> Result<usize, StepFail> {
    let gap_tol = BORDERED_GAP_FRACTION * event_tol;
    let gtol = if rtol > opts.newton.residual_rtol {
        LOOSE_GAP_FACTOR * gap_tol
    } else {
        gap_tol
    };
    let mut last_res = f64::NAN;
    let mut last_step = f64::INFINITY;
    let mut kscale = 0.0;
    if !opts.newton.pressure_iterate {
        st.pressure = None;
    }
    for it in 0..=opts.newton.max_iterations {
        interrupted(it, last_res)?;
        // convergence check on the forces alone (cached after the line search), the
        // matrix only when another iteration follows
        let Some(f) = asm.assemble(model, st, false) else {
            return Err(StepFail::from(FailCause::Inverted {
                iteration: it,
                residual: last_res,
            }));
        };
        let (c, _) = model.edge_constraint(st, k);
        let res = convergence_norm(&f);
        let prev = std::mem::replace(&mut last_res, res);
        let tol = residual_tolerance(model, opts, rtol, f.force_scale);
        let forces_converged = res <= tol || at_round_off_floor(last_step, res, prev, tol);
        if forces_converged && c.abs() <= gtol {
            st.pressure = None;
            return Ok(it);
        }
        if it == opts.newton.max_iterations || !res.is_finite() || !c.is_finite() {
            break;
        }
        let f = asm
            .assemble(model, st, true)
            .expect("state assembled above is not inverted");
        if it == 0 {
            kscale = inf_norm(&f.dresid_dd);
        }
        let merit = EdgeMerit {
            potential: model.is_potential(),
            node: k,
            kscale,
        };
        let initial = merit.of(&f.resid, c);
        if !initial.is_finite() {
            break;
        }
        let step = bordered_step(model, asm, opts, st, (k, c), &f, (it, res))?;
        last_step = inf_norm(&step.dq);
        let searched = edge_line_search(model, asm, opts, st, &step, merit, initial);
        let reason = "edge line search found no acceptable step";
        *st = searched.ok_or_else(|| diverged(model, asm, (it, res), reason))?;
    }
    let reason = "maximum Newton iterations reached (edge solve)";
    let last = (opts.newton.max_iterations, last_res);
    Err(diverged(model, asm, last, reason))
}

/// The merit of the bordered line search: the residual's part (its largest entry without
/// friction; with friction its 2-norm, so that one node's row, a stick node's stiff spring,
/// does not decide the step alone: fewer tangent assemblies, docs/performance.md) plus
/// `kscale |c|`, `kscale` the largest entry of `∂r/∂d` at the first iteration.
#[derive(Clone, Copy, Debug)]
struct EdgeMerit {
    /// Whether the problem is frictionless (a potential problem): the residual's largest entry.
    potential: bool,
    /// Contact-face index of the event's target node.
    node: usize,
    /// `|∂r/∂d|∞` at the first iteration (force per unit of λ).
    kscale: f64,
}

impl EdgeMerit {
    /// The merit of residual `resid` and target gap `c`.
    fn of(&self, resid: &[f64], c: f64) -> f64 {
        let residual = if self.potential {
            inf_norm(resid)
        } else {
            l2_norm(resid)
        };
        residual + self.kscale * c.abs()
    }
}

/// The bordered step of iteration `it` (residual norm `res`) from `st`, whose target node `k`
/// has gap `c`
/// and assembled forces `f` (the tangent assembled): both columns `K z₁ = −r`, `K z₂ = −∂r/∂d`
/// solved on one factorisation ([`solve_newton_step`], with friction's pieces chosen on the
/// bordered step), combined into `(δq, δd)`. Fails where the target's gap does not move with the
/// slab (`|∇c·z₂|` below [`INSENSITIVE_GAP_RATE`]).
fn bordered_step(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    st: &State,
    (k, c): (usize, f64),
    f: &Forces,
    (it, res): (usize, f64),
) -> Result<BorderedStep, StepFail> {
    let mut rhs = vec![
        f.resid.iter().map(|r| -r).collect::<Vec<f64>>(),
        f.dresid_dd.iter().map(|r| -r).collect::<Vec<f64>>(),
    ];
    let rate = model.gap_rate_along(st, k);
    let combine = |z1: &[f64], z2: &[f64]| {
        let dd = -(c + rate(z1)) / rate(z2);
        let dq: Vec<f64> = z1.iter().zip(z2).map(|(a, b)| a + b * dd).collect();
        (dq, dd)
    };
    let held = solve_newton_step(model, asm, opts, &mut rhs, it, |z| combine(&z[0], &z[1]))?;
    let (z1, z2) = (&rhs[0], &rhs[1]);
    if rate(z2).abs() < INSENSITIVE_GAP_RATE {
        return Err(StepFail::from(FailCause::Diverged {
            iteration: it,
            residual: res,
            reason: "edge constraint insensitive to the slab displacement".into(),
        }));
    }
    let (dq, dd) = combine(z1, z2);
    Ok(BorderedStep { dq, dd, held })
}

/// The line search along the bordered step from `st` ([`line_search`], at most
/// `max_edge_line_search` halvings): on `merit` from its value `initial`, or, for the linear
/// frictionless problem, the first non-inverted trial. `None` if no trial is accepted.
fn edge_line_search(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    st: &State,
    step: &BorderedStep,
    merit: EdgeMerit,
    initial: f64,
) -> Option<State> {
    let edge_merit = |m: &Model, trial: &State, ft: &Forces| {
        let (ct, _) = m.edge_constraint(trial, merit.node);
        merit.of(&ft.resid, ct)
    };
    let decrease = if model.kin == Kinematics::Linear && model.is_potential() {
        Decrease::Exact
    } else {
        Decrease::Merit {
            initial,
            merit: &edge_merit,
        }
    };
    let trial_at = |m: &Model, alpha: f64| {
        let mut trial = st.clone();
        trial.d += alpha * step.dd;
        m.enforce_constraints(&mut trial);
        stepped(
            m,
            st,
            m.updated(&trial, &step.dq, alpha),
            alpha,
            step.held.as_deref(),
        )
    };
    line_search(
        model,
        asm,
        opts.newton.max_edge_line_search,
        trial_at,
        decrease,
    )
}

#[cfg(test)]
mod tests {
    use super::at_round_off_floor;

    /// The stall measured on mesh 768 × 192 (residual 1.4–2e-10 against a tolerance of 1e-10,
    /// corrections 2–4e-14) ends the iteration; a residual still halving, a correction above
    /// round-off or a residual far above the tolerance does not.
    #[test]
    fn only_a_stalled_residual_near_the_tolerance_is_the_round_off_floor() {
        assert!(at_round_off_floor(3e-14, 1.6e-10, 1.5e-10, 1e-10));
        assert!(at_round_off_floor(3e-14, 1.4e-10, 2.0e-10, 1e-10));
        assert!(
            !at_round_off_floor(3e-14, 1.4e-10, 3.0e-10, 1e-10),
            "still halving"
        );
        assert!(
            !at_round_off_floor(1e-9, 1.6e-10, 1.5e-10, 1e-10),
            "a real correction"
        );
        assert!(
            !at_round_off_floor(3e-14, 2e-8, 2e-8, 1e-10),
            "far above the tolerance"
        );
        assert!(
            !at_round_off_floor(f64::INFINITY, 1.6e-10, 1.5e-10, 1e-10),
            "first iteration"
        );
    }
}
