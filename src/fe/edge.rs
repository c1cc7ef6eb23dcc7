//! Contact-edge events: where the contact edge lies at an event, and how the event load
//! is found.
//!
//! # Edge events
//! The points of the load curve are *edge events*: the slab displacement `d` at which a
//! chosen contact-face node `k` (by default the first free node; see
//! [`SolveOptions::da_target`]) touches the indenter with zero contact force
//! (`next_target`). Node `k` is kept free and the extra equation `g_k = 0` fixes `d`:
//! first by the bordered Newton method (`newton_edge`, `d` an unknown); if that fails,
//! by a secant/regula-falsi (Illinois) search on `d` with ordinary Newton solves, in
//! which a failed trial load is retried from the last open-gap state with half the
//! increment (`EventSearch::find`). The other nodes follow the active-set rules.
//!
//! # Contact-edge location at an event
//! The discrete solution has zero gap up to `x_k`, but its nodal forces are the
//! work-equivalent integrals `∫ p N_i dx`, so zero force on node `k` means the pressure
//! vanishes beyond `x_{k−1}`: the edge lies in `[x_{k−1}, x_k]` (current positions). The
//! default rule ([`EdgeRule`], `edge_position`) puts it at the fixed fraction
//! [`DISCRETE_EDGE_FRACTION`] of that interval, calibrated on Westergaard's solution.
//! Measured (AR = 0.01, linear, a/λ ≈ 0.11): `a = x_k` errs by −5 % in `p̄` and the
//! midpoint by +2 % (48×24 mesh). Gap fits through the next free nodes
//! ([`EdgeRule::GapPower`], [`EdgeRule::PeriodicGap`]) converge only at first order at
//! AR = 0.3 (Richardson error of the default mesh 0.6–0.9 %), the fixed fraction there and
//! at AR = 0.1 is within 0.2 % (`tests/fe_convergence.rs`).

use serde::{Deserialize, Serialize};

use super::error::SolveError;
use super::model::{Model, State};
use super::solver::{
    equilibrate, inf_norm, l2_norm, line_search, predictor, residual_tolerance,
    solve_newton_system, tangent_at, Decrease, StepFail,
};
use super::{Kinematics, SolveOptions};

/// Rule placing the contact edge `a` inside `[x_{k−1}, x_k]` (current positions) at an
/// edge event on node `k`: node `k` touches with zero force, node `k − 1` carries force
/// (see the [module documentation](self)).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum EdgeRule {
    /// `a = x_{k−1} + φ (x_k − x_{k−1})` with a fixed fraction `φ`. Near the edge the
    /// discrete solution is self-similar at the scale of the element (the far field is
    /// the `√(a − x)` pressure / `(x − a)^{3/2}` gap of the continuum, the mesh is locally
    /// uniform), so the edge of the continuum solution sits at a mesh-independent
    /// fraction `φ` of the last loaded element; any rule that uses nodal values at a
    /// distance `O(h)` from the edge errs by `O(h)` unless it reproduces that fraction.
    /// Default [`DISCRETE_EDGE_FRACTION`].
    Fraction(f64),
    /// Fit of the periodic Westergaard gap shape `g ∝ G(x; a)` through the vertical gaps
    /// of nodes `k + 1`, `k + 2` (exact in the linear limit, `(x − a)^{3/2}` near the
    /// edge). Measured: as good as [`EdgeRule::Fraction`] at AR = 0.1, but at AR = 0.3
    /// the finite-strain gap is not of that shape and the rule errs by ≈ 0.2 `h`.
    PeriodicGap,
    /// Fit of `g ∝ (x − a)^{3/2}` through the vertical gaps of nodes `k + 1`, `k + 2`.
    GapPower,
}

/// The discrete edge fraction `φ` of [`EdgeRule::Fraction`] for the Q1/P0 element with
/// the default [`super::Grading`], calibrated on the exact solution: with linear
/// kinematics, AR = 0.01, κ/G = 1000, the `a` that Westergaard's
/// `p̄/E* = π (Δ/λ) sin²(π a/λ)` gives for the computed `p̄` lies at `φ = 0.633 … 0.655`
/// of `[x_{k−1}, x_k]` over a/λ ∈ [0.1, 0.35] on the 32×16, 64×32 and 128×64 meshes
/// (medians 0.639, 0.638, 0.644; `PHI_CALIB=1 cargo run --release --example fe_study`).
/// With `peak_ratio = 2` the same measurement gives 0.643 … 0.668 (medians 0.645–0.647):
/// `φ` depends only weakly on the shape of the surface elements. Check, finite
/// kinematics: the Richardson-extrapolated edge of the AR = 0.1 and AR = 0.3 curves sits
/// at `φ = 0.60 … 0.67`.
pub const DISCRETE_EDGE_FRACTION: f64 = 0.64;

impl Default for EdgeRule {
    fn default() -> Self {
        EdgeRule::Fraction(DISCRETE_EDGE_FRACTION)
    }
}

/// A free node whose gap is at most this times the amplitude `Δ` counts as touching: a
/// node released at the last event with a vanishing multiplier sits at gap ≈ 0 and is
/// neither a target nor left free ([`next_target`], [`activate_touching`]). Safeguard
/// between two scales, not tuned: far above the round-off of a gap (≈ 10⁻¹⁶ λ) and far
/// below the gap of a node that is really open.
const OPEN_GAP_OVER_AMPLITUDE: f64 = 1e-9;

/// Floor of the event's gap tolerance `edge_gap_rtol · |g₀|` over the amplitude `Δ`, for a
/// target node that starts nearly closed (`g₀ → 0`): of the order of the round-off of a
/// gap, a difference of positions of order λ (one ulp of ½ is 1.1·10⁻¹⁶), below which
/// the tolerance could not be met.
const EVENT_GAP_FLOOR_OVER_AMPLITUDE: f64 = 1e-15;

/// The bordered solve converges the target's gap to this fraction of the event
/// tolerance, so that its result passes the event's acceptance test `|g_k| ≤ tol` with a
/// margin of two. Safeguard.
const BORDERED_GAP_FRACTION: f64 = 0.5;

/// Gap tolerance of the loose passes of the bordered solve (those whose active set may
/// still change, see [`SolveOptions::loose_residual_rtol`]) over that of the tight pass:
/// they only need to settle the active set; the confirming pass converges the gap
/// tightly. Safeguard value, not tuned.
const LOOSE_GAP_FACTOR: f64 = 100.0;

/// Smallest `|∇c·z₂| = |∂g_k/∂d|` (dimensionless) the bordered step divides by: guards
/// the division against an exact zero (a target node that does not move with the load).
/// Safeguard, far below any rate met in practice and above the underflow threshold of
/// doubles.
const INSENSITIVE_GAP_RATE: f64 = 1e-300;

/// A failed trial increment is cut by this factor before it is retried
/// ([`SolveOptions::max_step_cuts`] counts the cuts): halving.
const STEP_CUT_FACTOR: f64 = 0.5;

/// Illinois modification of regula falsi: when the same end of the bracket is kept
/// twice, its gap is scaled by this factor (Dowell & Jarratt 1971); the value defines
/// the method (superlinear, order ≈ 1.44, instead of the linear order of plain regula
/// falsi).
const ILLINOIS_FACTOR: f64 = 0.5;

/// A regula-falsi trial lies at this fraction of the bracket at least, and at
/// [`SECANT_FRACTION_MAX`] at most: safeguard that keeps every trial strictly inside the
/// bracket, so that it shrinks.
const SECANT_FRACTION_MIN: f64 = 0.02;

/// Upper bound of the regula-falsi fraction ([`SECANT_FRACTION_MIN`]).
const SECANT_FRACTION_MAX: f64 = 0.98;

/// Without a bracket and without a usable secant (no earlier trial with a larger open
/// gap), the next trial advances by this many times the larger of the distance from the
/// last event and the last event's increment (then bounded by
/// [`SolveOptions::max_step_growth`]). Safeguard, not tuned.
const BLIND_SPAN_FACTOR: f64 = 2.0;

/// Smallest advance of an extrapolated trial over the largest allowed one: a secant
/// through nearly equal gaps cannot stall the search. Safeguard, not tuned.
const MIN_SPAN_OVER_GROWTH: f64 = 1e-3;

/// Bisections of [`periodic_gap_fit`]: `2⁻⁶⁰` of an interval shorter than λ/2
/// (< 4.4·10⁻¹⁹ λ) is below one ulp of any `x ≥ 2⁻⁹ λ`: the bisection ends at round-off.
const GAP_FIT_BISECTIONS: usize = 60;

/// Gap below which a free node counts as touching (units of λ, see
/// [`OPEN_GAP_OVER_AMPLITUDE`]).
fn open_gap_tolerance(model: &Model) -> f64 {
    OPEN_GAP_OVER_AMPLITUDE * model.indenter.amplitude
}

/// Last active contact-face node (the peak node 0 if none).
fn last_active(st: &State) -> usize {
    (0..st.active.len())
        .rev()
        .find(|&i| st.active[i])
        .unwrap_or(0)
}

/// The target of the next edge event: the first contact-face node beyond the last
/// active one that lies at least `da_target` beyond the current edge `a` and has a
/// clearly open gap (a node released with a vanishing multiplier sits at gap 0), up to
/// and including the valley node (`x = λ/2`): its event puts the edge in the last element,
/// the largest `a` the mesh resolves. `None` once the valley node is in contact (full
/// contact: no edge event is left).
pub(crate) fn next_target(model: &Model, st: &State, a: f64, da_target: f64) -> Option<usize> {
    let nb = model.mesh.bottom.len();
    let c = last_active(st);
    if c + 1 >= nb {
        return None;
    }
    let xs: Vec<f64> = model.mesh.bottom.iter().map(|&n| st.x[n][0]).collect();
    let gaps = model.gaps(st);
    let open_tol = open_gap_tolerance(model);
    let mut k = c + 1;
    while k + 1 < nb && (xs[k] < a + da_target || gaps[k] <= open_tol) {
        k += 1;
    }
    Some(k)
}

/// Activate the nodes that [`next_target`] skipped because they touch with a vanishing
/// force (released at the last event): they carry load as soon as the load grows, so they
/// enter the step active (left free, they penetrate deeply and their late activation
/// stalls the edge solve).
pub(crate) fn activate_touching(model: &Model, st: &mut State, target: usize) {
    let gaps = model.gaps(st);
    let open_tol = open_gap_tolerance(model);
    let touching: Vec<usize> = (last_active(st) + 1..target)
        .filter(|&i| gaps[i] <= open_tol)
        .collect();
    if !touching.is_empty() {
        for i in touching {
            model.activate(st, i);
        }
        model.enforce_constraints(st);
    }
}

/// Gap tolerance of an event whose target starts at gap `g0`:
/// `max(edge_gap_rtol · |g₀|, 10⁻¹⁵ Δ)` ([`EVENT_GAP_FLOOR_OVER_AMPLITUDE`]).
pub(crate) fn event_gap_tolerance(model: &Model, opts: &SolveOptions, g0: f64) -> f64 {
    (opts.edge_gap_rtol * g0.abs()).max(EVENT_GAP_FLOOR_OVER_AMPLITUDE * model.indenter.amplitude)
}

/// Change `∇g_k · z` of the gap of the free contact-face node `k` along the slot vector
/// `z`: with the load tangent `z` ([`super::solver::load_tangent`]) the rate `∂g_k/∂d` at
/// which it closes.
fn gap_rate(model: &Model, st: &State, k: usize, z: &[f64]) -> f64 {
    gap_rate_along(model, st, k)(z)
}

/// [`gap_rate`] as a function of `z` alone (it holds what it needs of the model and the
/// state, so that it can be used while the model is borrowed for a solve).
fn gap_rate_along(model: &Model, st: &State, k: usize) -> impl Fn(&[f64]) -> f64 {
    let node = model.mesh.bottom[k];
    let (_, dc) = model.edge_constraint(st, k);
    move |z: &[f64]| dc[0] * z[2 * node] + dc[1] * z[2 * node + 1]
}

/// Increment of `d` at which free node `k`, at gap `g0`, closes along the load tangent
/// `z`: `g₀ / (−∂g_k/∂d)`; `None` if the gap does not close along it.
pub(crate) fn closing_increment(
    model: &Model,
    st: &State,
    k: usize,
    g0: f64,
    z: &[f64],
) -> Option<f64> {
    let rate = gap_rate(model, st, k, z);
    (rate < 0.0).then(|| g0 / -rate)
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
pub(crate) fn newton_edge(
    model: &mut Model,
    st: &mut State,
    opts: &SolveOptions,
    k: usize,
    event_tol: f64,
    rtol: f64,
) -> Result<usize, StepFail> {
    let gap_tol = BORDERED_GAP_FRACTION * event_tol;
    let mut last_res = f64::NAN;
    let mut kscale = 0.0;
    // the residual's part of the merit: its largest entry without friction; with friction
    // its 2-norm, so that one node's row (a stick node's stiff spring) does not decide the
    // step alone (measured: 4710 against 5306 tangent assemblies over eight frictional
    // curves at AR 0.1–0.3; without friction the 2-norm changed nothing but the path)
    let potential = model.is_potential();
    let residual_merit = move |r: &[f64]| if potential { inf_norm(r) } else { l2_norm(r) };
    for it in 0..=opts.max_newton_iterations {
        // convergence check on the forces alone (cached after the line search), the
        // matrix only when another iteration follows
        let Some(f) = model.assemble(st, false) else {
            return Err(StepFail::Inverted {
                iteration: it,
                residual: last_res,
            });
        };
        let (c, _) = model.edge_constraint(st, k);
        let res = inf_norm(&f.resid);
        last_res = res;
        let gtol = if rtol > opts.residual_rtol {
            LOOSE_GAP_FACTOR * gap_tol
        } else {
            gap_tol
        };
        if res <= residual_tolerance(model, opts, rtol, f.force_scale) && c.abs() <= gtol {
            return Ok(it);
        }
        if it == opts.max_newton_iterations || !res.is_finite() || !c.is_finite() {
            break;
        }
        let f = model
            .assemble(st, true)
            .expect("state assembled above is not inverted");
        if it == 0 {
            kscale = inf_norm(&f.dresid_dd);
        }
        let merit = residual_merit(&f.resid) + kscale * c.abs();
        if !merit.is_finite() {
            break;
        }
        let mut rhs = vec![
            f.resid.iter().map(|r| -r).collect::<Vec<f64>>(),
            f.dresid_dd.iter().map(|r| -r).collect::<Vec<f64>>(),
        ];
        // the bordered step `(δd, δq)` from the two solutions
        let rate = gap_rate_along(model, st, k);
        let bordered_step = |z1: &[f64], z2: &[f64]| {
            let dd = -(c + rate(z1)) / rate(z2);
            let dq: Vec<f64> = z1.iter().zip(z2).map(|(a, b)| a + b * dd).collect();
            (dd, dq)
        };
        solve_newton_system(model, opts, &mut rhs, it, |z| bordered_step(&z[0], &z[1]).1)?;
        let (z1, z2) = (&rhs[0], &rhs[1]);
        let den = rate(z2);
        if den.abs() < INSENSITIVE_GAP_RATE {
            return Err(StepFail::Diverged {
                iteration: it,
                residual: res,
                reason: "edge constraint insensitive to the slab displacement".into(),
            });
        }
        let (dd, dq) = bordered_step(z1, z2);
        let edge_merit = |m: &Model, trial: &State, ft: &super::model::Forces| {
            let (ct, _) = m.edge_constraint(trial, k);
            residual_merit(&ft.resid) + kscale * ct.abs()
        };
        let decrease = if model.kin == Kinematics::Linear && model.is_potential() {
            Decrease::Exact
        } else {
            Decrease::Merit {
                initial: merit,
                merit: &edge_merit,
            }
        };
        let trial_at = |m: &Model, alpha: f64| {
            let mut trial = st.clone();
            trial.d += alpha * dd;
            m.enforce_constraints(&mut trial);
            m.updated(&trial, &dq, alpha)
        };
        match line_search(model, opts.max_edge_line_search, trial_at, decrease) {
            Some(t) => *st = t,
            None => {
                return Err(StepFail::Diverged {
                    iteration: it,
                    residual: res,
                    reason: "edge line search found no acceptable step".into(),
                })
            }
        }
    }
    Err(StepFail::Diverged {
        iteration: opts.max_newton_iterations,
        residual: last_res,
        reason: "maximum Newton iterations reached (edge solve)".into(),
    })
}

/// The search for one edge event, from the converged state of the last one.
pub(crate) struct EventSearch<'a> {
    /// Numerical options.
    pub opts: &'a SolveOptions,
    /// Converged state of the last event (the nodes touching there already active).
    pub from: &'a State,
    /// The event before it, if any (for the extrapolating predictor).
    pub before: Option<&'a State>,
    /// Target contact-face node `k` ([`next_target`]).
    pub node: usize,
    /// Its gap at `from` (units of λ).
    pub gap0: f64,
    /// Gap tolerance of the event ([`event_gap_tolerance`]).
    pub gap_tol: f64,
    /// Load tangent `∂q/∂d` at `from` (tangent predictor), if any.
    pub tangent: Option<Vec<f64>>,
    /// First trial increment of `d` (units of λ).
    pub first_increment: f64,
    /// Increment of `d` of the last event (the scale of the secant search's advances).
    pub last_increment: f64,
}

impl EventSearch<'_> {
    /// The converged state at the event and the Newton iterations spent: the bordered
    /// solve first (if [`SolveOptions::bordered_edge_solve`]; in committed sub-steps
    /// with friction), else the secant search.
    pub(crate) fn find(
        &self,
        model: &mut Model,
        step: usize,
    ) -> Result<(State, usize), SolveError> {
        let bordered = if !self.opts.bordered_edge_solve {
            None
        } else if model.is_potential() {
            self.bordered(
                model,
                self.from,
                self.before,
                self.tangent.as_deref(),
                self.first_increment,
            )
        } else {
            self.bordered_in_substeps(model)
        };
        let (found, iters) = match bordered {
            Some(found) => found,
            None => self.secant(model, step)?,
        };
        if found.d <= self.from.d {
            return Err(SolveError::EdgeSearch {
                step,
                node: self.node,
                gap: self.gap0,
            });
        }
        Ok((found, iters))
    }

    /// Gap of the target node.
    fn gap(&self, model: &Model, st: &State) -> f64 {
        model.gaps(st)[self.node]
    }

    /// Converged state at `base.d + increment` with the target held free (predicted
    /// from `base`, the state before it and the load tangent), and its Newton iterations.
    fn held_free(
        &self,
        model: &mut Model,
        base: &State,
        base_prev: Option<&State>,
        tangent: Option<&[f64]>,
        increment: f64,
    ) -> Result<(State, usize), StepFail> {
        match predictor(model, base, base_prev, increment, tangent) {
            Some(mut st) => {
                equilibrate(model, &mut st, self.opts, Some(self.node), None).map(|it| (st, it))
            }
            None => Err(StepFail::Inverted {
                iteration: 0,
                residual: f64::NAN,
            }),
        }
    }

    /// One bordered attempt ([`newton_edge`] in the active-set loop), predicted for
    /// `base.d + increment`: accepted if the target's gap is within the tolerance and the
    /// load has advanced beyond the last event.
    fn bordered(
        &self,
        model: &mut Model,
        base: &State,
        base_prev: Option<&State>,
        tangent: Option<&[f64]>,
        increment: f64,
    ) -> Option<(State, usize)> {
        predictor(model, base, base_prev, increment, tangent).and_then(|mut st| {
            let it = equilibrate(
                model,
                &mut st,
                self.opts,
                Some(self.node),
                Some(self.gap_tol),
            )
            .ok()?;
            let g = self.gap(model, &st);
            (g.abs() <= self.gap_tol && st.d > self.from.d).then_some((st, it))
        })
    }

    /// With friction the step is path dependent: when the event cannot be reached in one
    /// increment, advance by converged, committed sub-steps (the trial increment cut
    /// each time, the target node held free) and retry the bordered solve from there.
    fn bordered_in_substeps(&self, model: &mut Model) -> Option<(State, usize)> {
        let mut base = self.from.clone();
        let mut base_prev = self.before.cloned();
        let mut tangent = self.tangent.clone();
        let mut increment = self.first_increment;
        let mut spent = 0;
        for _ in 0..=self.opts.max_step_cuts {
            if let Some((st, it)) = self.bordered(
                model,
                &base,
                base_prev.as_ref(),
                tangent.as_deref(),
                increment,
            ) {
                return Some((st, it + spent));
            }
            increment *= STEP_CUT_FACTOR;
            let sub = self.held_free(
                model,
                &base,
                base_prev.as_ref(),
                tangent.as_deref(),
                increment,
            );
            if let Ok((mut st, it)) = sub {
                spent += it;
                if self.gap(model, &st) > self.gap_tol {
                    model.commit_slip(&mut st);
                    base_prev = Some(std::mem::replace(&mut base, st));
                    tangent = tangent_at(model, self.opts, &base);
                }
            }
        }
        None
    }

    /// Secant/regula-falsi (Illinois) search on `d` with ordinary Newton solves, the
    /// target held free; a failed trial is cut back towards the last open-gap state.
    fn secant(&self, model: &mut Model, step: usize) -> Result<(State, usize), SolveError> {
        let opts = self.opts;
        let mut bracket = Bracket {
            lo: (self.from.clone(), self.gap0),
            lo_prev: self.before.map(|p| (p.clone(), self.gap(model, p))),
            hi: None,
            last_kept: None,
        };
        let (mut iters, mut cuts, mut evals) = (0, 0, 0);
        let mut trial = self.from.d + self.first_increment;
        loop {
            evals += 1;
            if evals > opts.max_edge_iterations {
                return Err(SolveError::EdgeSearch {
                    step,
                    node: self.node,
                    gap: bracket.lo.1,
                });
            }
            let base = &bracket.lo.0;
            let base_d = base.d;
            let tangent = tangent_at(model, opts, base);
            let base_prev = bracket.lo_prev.as_ref().map(|p| &p.0);
            match self.held_free(model, base, base_prev, tangent.as_deref(), trial - base_d) {
                Err(f) => {
                    cuts += 1;
                    if cuts > opts.max_step_cuts {
                        return Err(f.into_error(step, trial));
                    }
                    trial = base_d + STEP_CUT_FACTOR * (trial - base_d);
                }
                Ok((st, it)) => {
                    iters += it;
                    let g = self.gap(model, &st);
                    if g.abs() <= self.gap_tol {
                        return Ok((st, iters));
                    }
                    bracket.insert(st, g);
                    trial =
                        bracket.next_load(self.from.d, self.last_increment, opts.max_step_growth);
                }
            }
        }
    }
}

/// End of the bracket kept by the last update (Illinois).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kept {
    /// The open-gap end was replaced, the closed one kept.
    Closed,
    /// The closed-gap end was replaced, the open one kept.
    Open,
}

/// Trial states of the secant search with their target gaps.
struct Bracket {
    /// Last trial with an open gap (`g > 0`; initially the last event).
    lo: (State, f64),
    /// The open-gap state before it, if any (secant extrapolation).
    lo_prev: Option<(State, f64)>,
    /// Last trial with a closed gap (`g < 0`), once one is found.
    hi: Option<(State, f64)>,
    last_kept: Option<Kept>,
}

impl Bracket {
    /// Insert a converged trial with target gap `g`; the Illinois modification scales the
    /// gap of an end kept twice in a row by [`ILLINOIS_FACTOR`].
    fn insert(&mut self, st: State, g: f64) {
        if g > 0.0 {
            let old = std::mem::replace(&mut self.lo, (st, g));
            self.lo_prev = Some(old);
            if self.last_kept == Some(Kept::Closed) {
                if let Some(h) = self.hi.as_mut() {
                    h.1 *= ILLINOIS_FACTOR;
                }
            }
            self.last_kept = Some(Kept::Closed);
        } else {
            if self.last_kept == Some(Kept::Open) {
                self.lo.1 *= ILLINOIS_FACTOR;
            }
            self.last_kept = Some(Kept::Open);
            self.hi = Some((st, g));
        }
    }

    /// Next trial load: regula falsi inside the bracket once it is closed; before, the
    /// secant through the last two open-gap trials extrapolated to `g = 0`, bounded by
    /// `max_step_growth` times the larger of the distance from the last event (at
    /// `from_d`) and the last event's increment.
    fn next_load(&self, from_d: f64, last_increment: f64, max_step_growth: f64) -> f64 {
        let lo = &self.lo;
        match &self.hi {
            Some((hs, hg)) => {
                let t = lo.1 / (lo.1 - hg);
                lo.0.d + t.clamp(SECANT_FRACTION_MIN, SECANT_FRACTION_MAX) * (hs.d - lo.0.d)
            }
            None => {
                let span = match &self.lo_prev {
                    Some((ps, pg)) if pg > &lo.1 && lo.0.d > ps.d => {
                        lo.1 * (lo.0.d - ps.d) / (pg - lo.1)
                    }
                    _ => BLIND_SPAN_FACTOR * (lo.0.d - from_d).max(last_increment),
                };
                let grow = max_step_growth * (lo.0.d - from_d).max(last_increment);
                lo.0.d + span.clamp(MIN_SPAN_OVER_GROWTH * grow, grow)
            }
        }
    }
}

/// The node that plays the edge event's target in a state that is not an event (the
/// unloading branch): the node after the last one whose vertical contact multiplier `λ` is
/// clearly positive (above `multiplier_rtol` times the largest), so that the edge lies in the
/// last loaded element as at an event. At an event state it is the event's node whether or
/// not the solve left that node, touching with zero force, active; the peak node 0 when no
/// node carries load; at most the valley node.
pub(crate) fn loaded_edge_node(
    model: &Model,
    st: &State,
    grad: &[f64],
    multiplier_rtol: f64,
) -> usize {
    let lam = model.multipliers(st, grad);
    let scale = lam.iter().fold(0.0_f64, |m, l| m.max(l.abs()));
    match (0..lam.len())
        .rev()
        .find(|&i| lam[i] > multiplier_rtol * scale)
    {
        Some(i) => (i + 1).min(lam.len() - 1),
        None => 0,
    }
}

/// Contact half-width at an edge event on node `k` (rule documented at [`EdgeRule`]; the
/// gap fits fall back to the midpoint of `[x_{k−1}, x_k]` unless the gaps of nodes
/// `k + 1`, `k + 2` are positive and increasing).
pub(crate) fn edge_position(model: &Model, st: &State, k: usize, rule: EdgeRule) -> f64 {
    let b = &model.mesh.bottom;
    let x = |i: usize| st.x[b[i]][0];
    let lo = x(k.saturating_sub(1));
    let hi = x(k);
    if let EdgeRule::Fraction(phi) = rule {
        return lo + phi * (hi - lo);
    }
    if k + 2 < b.len() {
        let gaps = model.gaps(st);
        let (g1, g2) = (gaps[k + 1], gaps[k + 2]);
        if g1 > 0.0 && g2 > g1 {
            return match rule {
                EdgeRule::GapPower => {
                    let r = (g1 / g2).powf(2.0 / 3.0);
                    ((x(k + 1) - r * x(k + 2)) / (1.0 - r)).clamp(lo, hi)
                }
                EdgeRule::PeriodicGap => periodic_gap_fit(x(k + 1), x(k + 2), g1 / g2, lo, hi),
                EdgeRule::Fraction(_) => unreachable!("handled above"),
            };
        }
    }
    0.5 * (lo + hi)
}

/// Gap shape of the periodic (Westergaard) contact beyond the edge `a`, up to a
/// constant factor (units of λ, `a < x ≤ ½`):
///
/// ```text
/// g'(x) ∝ cos πx √(sin²πx − sin²πa)
/// G(x; a) = ½ [ s √(s² − c²) − c² ln((s + √(s² − c²))/c) ],  s = sin πx, c = sin πa
/// ```
///
/// (`∝ (s − c)^{3/2}` near the edge). Exact in the linear limit.
fn periodic_gap_shape(x: f64, a: f64) -> f64 {
    let pi = std::f64::consts::PI;
    let (s, c) = ((pi * x).sin(), (pi * a).sin());
    if s <= c {
        return 0.0;
    }
    if c <= 0.0 {
        return 0.5 * s * s;
    }
    let r = (s * s - c * c).sqrt();
    0.5 * (s * r - c * c * ((s + r) / c).ln())
}

/// The `a ∈ [lo, hi]` with `G(x₁; a)/G(x₂; a) = ratio` ([`periodic_gap_shape`]; the
/// ratio decreases with `a`), clamped to the interval; bisection.
fn periodic_gap_fit(x1: f64, x2: f64, ratio: f64, lo: f64, hi: f64) -> f64 {
    let r = |a: f64| periodic_gap_shape(x1, a) / periodic_gap_shape(x2, a);
    if r(lo) <= ratio {
        return lo;
    }
    if r(hi) >= ratio {
        return hi;
    }
    let (mut l, mut h) = (lo, hi);
    for _ in 0..GAP_FIT_BISECTIONS {
        let m = 0.5 * (l + h);
        if r(m) > ratio {
            l = m;
        } else {
            h = m;
        }
    }
    0.5 * (l + h)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`periodic_gap_fit`] inverts the gap ratio of [`periodic_gap_shape`] inside the
    /// interval and clamps outside it.
    #[test]
    fn periodic_gap_fit_recovers_the_edge() {
        let (lo, hi) = (0.2, 0.22);
        let (x1, x2) = (0.24, 0.26);
        let ratio = |a: f64| periodic_gap_shape(x1, a) / periodic_gap_shape(x2, a);
        for a in [0.201, 0.21, 0.219] {
            let fit = periodic_gap_fit(x1, x2, ratio(a), lo, hi);
            assert!((fit - a).abs() < 1e-12, "a = {a}: fit {fit}");
        }
        assert_eq!(periodic_gap_fit(x1, x2, ratio(0.19), lo, hi), lo);
        assert_eq!(periodic_gap_fit(x1, x2, ratio(0.23), lo, hi), hi);
    }

    fn at_load(d: f64) -> State {
        State {
            x: Vec::new(),
            active: Vec::new(),
            d,
            dx: 0.0,
            slip: Vec::new(),
        }
    }

    /// The secant search: extrapolation to `g = 0` before a closed gap is found,
    /// regula falsi inside the bracket after, and the Illinois scaling of an end kept
    /// twice.
    #[test]
    fn bracket_extrapolates_then_brackets_with_illinois() {
        let mut bracket = Bracket {
            lo: (at_load(1.0), 1.0),
            lo_prev: Some((at_load(0.0), 2.0)),
            hi: None,
            last_kept: None,
        };
        // secant through (0, 2) and (1, 1): g = 0 at d = 2
        assert_eq!(bracket.next_load(0.0, 1.0, 3.0), 2.0);
        bracket.insert(at_load(2.0), -1.0);
        // regula falsi between (1, 1) and (2, −1)
        assert_eq!(bracket.next_load(0.0, 1.0, 3.0), 1.5);
        bracket.insert(at_load(1.5), -0.5);
        // the open end is kept twice: its gap is scaled
        assert_eq!(bracket.lo.1, ILLINOIS_FACTOR);
        let t = ILLINOIS_FACTOR / (ILLINOIS_FACTOR + 0.5);
        assert_eq!(bracket.next_load(0.0, 1.0, 3.0), 1.0 + t * 0.5);
    }
}
