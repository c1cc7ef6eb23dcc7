//! Contact-edge events: which node touches next, and at which slab displacement.
//!
//! The points of the load curve are *edge events*: the slab displacement `d` at which a
//! chosen contact-face node `k` (by default the first free node; see
//! [`StepOptions::da_target`]) touches the indenter with zero contact force
//! ([`next_target`]). Node `k` is kept free and the extra equation `g_k = 0` fixes `d`:
//! first by the bordered Newton method ([`crate::fe::newton::newton_bordered`], `d` an
//! unknown); if that fails, by a regula-falsi (Illinois) search on `d` with ordinary Newton
//! solves, in which a failed trial is retried from the last open-gap state with half the
//! increment ([`EventSearch::find`]). The other nodes follow the active-set rules. Where
//! the contact edge lies at an event is the edge rule's ([`crate::fe::contact::edge_rule`]).
//! Frictionless, an event beyond free nodes is predicted through their closings
//! ([`EventSearch::predicted_through_closings`]).

use crate::fe::error::SolveError;
use crate::fe::error::{FailCause, StepFail};
use crate::fe::model::{Model, State};
use crate::fe::newton::active_set::{equilibrate, equilibrate_event, Hold};
use crate::fe::newton::assembly::Assembly;
use crate::fe::stepping::predictor::{load_tangent, predictor, tangent_at, LoadTangent};
use crate::fe::stepping::step_control::{RegulaFalsi, StepCuts, Trial, STEP_CUT_FACTOR};
use crate::fe::SolveOptions;

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

/// A regula-falsi trial lies at this fraction of the bracket at least, and at
/// [`SECANT_FRACTION_MAX`] at most: safeguard that keeps every trial strictly inside the
/// bracket, so that it shrinks.
const SECANT_FRACTION_MIN: f64 = 0.02;

/// Upper bound of the regula-falsi fraction ([`SECANT_FRACTION_MIN`]).
const SECANT_FRACTION_MAX: f64 = 0.98;

/// Without a bracket and without a usable secant (no earlier trial with a larger open
/// gap), the next trial advances by this many times the larger of the distance from the
/// last event and the last event's increment (then bounded by
/// [`StepOptions::max_step_growth`]). Safeguard, not tuned.
const BLIND_SPAN_FACTOR: f64 = 2.0;

/// Smallest advance of an extrapolated trial over the largest allowed one: a secant
/// through nearly equal gaps cannot stall the search. Safeguard, not tuned.
const MIN_SPAN_OVER_GROWTH: f64 = 1e-3;

/// Gap below which a free node counts as touching (units of λ, see
/// [`OPEN_GAP_OVER_AMPLITUDE`]).
pub(crate) fn open_gap_tolerance(model: &Model) -> f64 {
    OPEN_GAP_OVER_AMPLITUDE * model.indenter.amplitude()
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
    let last = last_active(st);
    if last + 1 >= nb {
        return None;
    }
    let xs: Vec<f64> = model.mesh.bottom.iter().map(|&n| st.x[n][0]).collect();
    let gaps = model.gaps(st);
    let open_tol = open_gap_tolerance(model);
    let mut k = last + 1;
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
    let range = last_active(st) + 1..target;
    activate_touching_among(model, st, range);
}

/// Activate those of the free contact-face nodes `nodes` that touch (gap at most
/// [`open_gap_tolerance`]), then put the active nodes back on the indenter.
pub(crate) fn activate_touching_among(
    model: &Model,
    st: &mut State,
    nodes: impl Iterator<Item = usize>,
) {
    let gaps = model.gaps(st);
    let open_tol = open_gap_tolerance(model);
    let touching: Vec<usize> = nodes
        .filter(|&i| !st.active[i] && gaps[i] <= open_tol)
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
    (opts.steps.edge_gap_rtol * g0.abs())
        .max(EVENT_GAP_FLOOR_OVER_AMPLITUDE * model.indenter.amplitude())
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
    let rate = model.gap_rate_along(st, k)(z);
    (rate < 0.0).then(|| g0 / -rate)
}

/// Increment of `d` at which free node `k`, at gap `g0`, closes along the load path
/// `tangent`: the smallest positive root of `g₀ + ġ dd + ½ g̈ dd² = 0`, with `ġ = ∇c·q'` and
/// `g̈ = ∇c·q''` where the path's curvature is known (the gap's own curvature in `x`,
/// `−y_s'' (∂x/∂d)²`, left out: this is the first trial of the bordered solve, which finds the
/// event's `d` itself), else
/// [`closing_increment`]; `None` if the gap does not close along it.
pub(crate) fn predicted_closing(
    model: &Model,
    st: &State,
    k: usize,
    g0: f64,
    tangent: &LoadTangent,
) -> Option<f64> {
    let linear = closing_increment(model, st, k, g0, tangent)?;
    let Some(w) = tangent.curvature() else {
        return Some(linear);
    };
    let gap_rate = model.gap_rate_along(st, k);
    let (rate, accel) = (gap_rate(tangent), gap_rate(w));
    // g₀ + rate dd + ½ accel dd² = 0, rate < 0: the root nearest zero, by the stable form
    let disc = rate * rate - 2.0 * accel * g0;
    if disc < 0.0 {
        return Some(linear);
    }
    let root = 2.0 * g0 / (-rate + disc.sqrt());
    Some(if root.is_finite() && root > 0.0 {
        root
    } else {
        linear
    })
}

/// Where one try of an event starts: a converged state, the one before it (for the
/// extrapolating predictor), its load path, and the trial increment of `d` (units of λ).
#[derive(Clone, Copy)]
struct TryStart<'a> {
    base: &'a State,
    base_prev: Option<&'a State>,
    tangent: Option<&'a LoadTangent>,
    increment: f64,
}

impl TryStart<'_> {
    /// The predicted state at `base.d + increment` ([`predictor`]).
    fn predicted(&self, model: &Model) -> Option<State> {
        predictor(
            model,
            self.base,
            self.base_prev,
            self.increment,
            self.tangent,
        )
    }
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
    pub tangent: Option<LoadTangent>,
    /// First trial increment of `d` (units of λ).
    pub first_increment: f64,
    /// Increment of `d` of the last event (the scale of the regula-falsi search's advances).
    pub last_increment: f64,
}

impl EventSearch<'_> {
    /// The converged state at the event and the Newton iterations spent: the bordered
    /// solve first (if [`StepOptions::bordered_edge_solve`]; in committed sub-steps
    /// with friction), else the regula-falsi search; failed tries count.
    pub(crate) fn find(
        &self,
        model: &Model,
        asm: &mut Assembly,
        step: usize,
    ) -> Result<(State, usize), SolveError> {
        let bordered = if !self.opts.steps.bordered_edge_solve {
            Err(0)
        } else if model.is_potential() {
            let start = TryStart {
                base: self.from,
                base_prev: self.before,
                tangent: self.tangent.as_ref(),
                increment: self.first_increment,
            };
            self.bordered(model, asm, start)
        } else {
            self.bordered_in_substeps(model, asm)
        };
        let (found, iters) = match bordered {
            Ok(found) => found,
            Err(spent) => {
                let (found, iters) = self.regula_falsi(model, asm, step)?;
                (found, iters + spent)
            }
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
        model: &Model,
        asm: &mut Assembly,
        start: TryStart<'_>,
    ) -> Result<(State, usize), StepFail> {
        match start.predicted(model) {
            Some(mut st) => {
                equilibrate(model, asm, &mut st, self.opts, Hold::free(Some(self.node)))
                    .map(|it| (st, it))
            }
            None => Err(StepFail::from(FailCause::Inverted {
                iteration: 0,
                residual: f64::NAN,
            })),
        }
    }

    /// One bordered attempt ([`equilibrate_event`]), predicted for
    /// `base.d + increment`: accepted if the target's gap is within the tolerance and the
    /// slab displacement has advanced beyond the last event; else the iterations it spent.
    fn bordered(
        &self,
        model: &Model,
        asm: &mut Assembly,
        start: TryStart<'_>,
    ) -> Result<(State, usize), usize> {
        let mut st = self.predicted_event(model, asm, start).ok_or(0usize)?;
        let it = equilibrate_event(model, asm, &mut st, self.opts, self.node, self.gap_tol)
            .map_err(|f| f.iterations())?;
        let g = self.gap(model, &st);
        match g.abs() <= self.gap_tol && st.d > self.from.d {
            true => Ok((st, it)),
            false => Err(it),
        }
    }

    /// The predicted state of the event at `base.d + increment`: when the target may lie beyond
    /// free nodes ([`StepOptions::da_target_for`], frictionless), followed through their closings
    /// ([`Self::predicted_through_closings`]); else [`predictor`]'s.
    fn predicted_event(
        &self,
        model: &Model,
        asm: &mut Assembly,
        start: TryStart<'_>,
    ) -> Option<State> {
        match start.tangent {
            Some(z) if self.opts.steps.da_target_for(!model.is_potential()) > 0.0 => {
                self.predicted_through_closings(model, asm, start, z)
            }
            _ => start.predicted(model),
        }
    }

    /// The predicted state at `base.d + increment` of `start`, followed through the closings of
    /// the free nodes before the target, one after another: Taylor ([`predictor`]) along the load
    /// path `tangent` to where the next of them closes ([`predicted_closing`]), that node activated,
    /// and the load path taken again there ([`load_tangent`], one factorisation, no Newton
    /// iteration), until no free node before the target closes within the increment. The path
    /// kinks at each closing; a single Taylor step across them misses the kinks by a fraction of
    /// an element, which a nearly incompressible layer turns into pressures tens of G off and
    /// Newton into many damped iterations (docs/performance.md, "steps over several nodes"). The
    /// third-order term of the path is left out: measured over a step whose contact set changed,
    /// it is not the path's. `None` where a prediction is inverted or a tangent cannot be solved.
    fn predicted_through_closings(
        &self,
        model: &Model,
        asm: &mut Assembly,
        start: TryStart<'_>,
        tangent: &LoadTangent,
    ) -> Option<State> {
        let end = start.base.d + start.increment;
        let mut cur = start.base.clone();
        let mut tangent = tangent.clone().with_third_order(None);
        loop {
            let gaps = model.gaps(&cur);
            let next = (last_active(&cur) + 1..self.node)
                .filter(|&j| !cur.active[j])
                .filter_map(|j| {
                    predicted_closing(model, &cur, j, gaps[j], &tangent).map(|dd| (j, dd))
                })
                .min_by(|a, b| a.1.total_cmp(&b.1));
            let Some((j, dd)) = next.filter(|&(_, dd)| cur.d + dd < end) else {
                return predictor(model, &cur, None, end - cur.d, Some(&tangent));
            };
            let mut closed = predictor(model, &cur, None, dd, Some(&tangent))?;
            model.activate(&mut closed, j);
            model.enforce_constraints(&mut closed);
            tangent = load_tangent(model, asm, &closed, self.opts.steps.touched_nodes, None)?;
            cur = closed;
        }
    }

    /// With friction the step is path dependent: when the event cannot be reached in one
    /// increment, advance by a converged, committed sub-step (half the failed try's increment,
    /// halved again while it fails; the target node held free) and retry the bordered solve from
    /// there, its increment predicted afresh from the sub-step's gap and load path
    /// ([`predicted_closing`]): the event lies that far on, whatever the sub-step's size, and a
    /// bordered try that starts short of it has the whole remaining way to go. Failing, the
    /// iterations every try spent.
    fn bordered_in_substeps(
        &self,
        model: &Model,
        asm: &mut Assembly,
    ) -> Result<(State, usize), usize> {
        let mut base = self.from.clone();
        let mut base_prev = self.before.cloned();
        let mut tangent = self.tangent.clone();
        let mut increment = self.first_increment;
        let mut spent = 0;
        for _ in 0..=self.opts.steps.max_step_cuts {
            let start = TryStart {
                base: &base,
                base_prev: base_prev.as_ref(),
                tangent: tangent.as_ref(),
                increment,
            };
            match self.bordered(model, asm, start) {
                Ok((st, it)) => return Ok((st, it + spent)),
                Err(it) => spent += it,
            }
            increment *= STEP_CUT_FACTOR;
            let sub = self.held_free(model, asm, TryStart { increment, ..start });
            match sub {
                Ok((mut st, it)) => {
                    spent += it;
                    let gap = self.gap(model, &st);
                    if gap > self.gap_tol {
                        asm.commit_slip(model, &mut st);
                        base_prev = Some(std::mem::replace(&mut base, st));
                        tangent = tangent_at(model, asm, self.opts, &base);
                        let remaining = (tangent.as_ref())
                            .and_then(|z| predicted_closing(model, &base, self.node, gap, z));
                        increment = remaining.unwrap_or(increment);
                    }
                }
                Err(f) => spent += f.iterations(),
            }
        }
        Err(spent)
    }

    /// Regula-falsi (Illinois) search on `d` with ordinary Newton solves, the target held
    /// free; a failed trial is cut back towards the last open-gap state.
    fn regula_falsi(
        &self,
        model: &Model,
        asm: &mut Assembly,
        step: usize,
    ) -> Result<(State, usize), SolveError> {
        let opts = self.opts;
        let open_gap = |st: &State| Trial {
            x: st.d,
            f: self.gap(model, st),
            at: st.clone(),
        };
        let first = Trial {
            x: self.from.d,
            f: self.gap0,
            at: self.from.clone(),
        };
        let mut search = RegulaFalsi::new(first, self.before.map(open_gap));
        let mut cuts = StepCuts::new(opts.steps.max_step_cuts);
        let (mut iters, mut evals) = (0, 0);
        let mut trial = self.from.d + self.first_increment;
        loop {
            evals += 1;
            if evals > opts.steps.max_edge_iterations {
                return Err(SolveError::EdgeSearch {
                    step,
                    node: self.node,
                    gap: search.below.f,
                });
            }
            let base = &search.below.at;
            let base_d = base.d;
            let tangent = tangent_at(model, asm, opts, base);
            let base_prev = search.below_prev.as_ref().map(|p| &p.at);
            let start = TryStart {
                base,
                base_prev,
                tangent: tangent.as_ref(),
                increment: trial - base_d,
            };
            match self.held_free(model, asm, start) {
                Err(f) => {
                    iters += f.iterations();
                    match cuts.cut(base_d, trial) {
                        Some(cut) => trial = cut,
                        None => return Err(f.into_error(step, trial)),
                    }
                }
                Ok((st, it)) => {
                    iters += it;
                    let g = self.gap(model, &st);
                    if g.abs() <= self.gap_tol {
                        return Ok((st, iters));
                    }
                    search.insert(Trial {
                        x: st.d,
                        f: g,
                        at: st,
                    });
                    trial = search
                        .next(SECANT_FRACTION_MIN, SECANT_FRACTION_MAX)
                        .unwrap_or_else(|| {
                            extrapolated(
                                &search,
                                self.from.d,
                                self.last_increment,
                                opts.steps.max_step_growth,
                            )
                        });
                }
            }
        }
    }
}

/// The next trial before the event is bracketed: the secant through the last two open-gap
/// trials extrapolated to `g = 0`, bounded by `max_step_growth` times the larger of the
/// distance from the last event (at `from_d`) and the last event's increment.
fn extrapolated<S>(
    search: &RegulaFalsi<S>,
    from_d: f64,
    last_increment: f64,
    max_step_growth: f64,
) -> f64 {
    let below = &search.below;
    let span = match &search.below_prev {
        Some(prev) if prev.f > below.f && below.x > prev.x => {
            below.f * (below.x - prev.x) / (prev.f - below.f)
        }
        _ => BLIND_SPAN_FACTOR * (below.x - from_d).max(last_increment),
    };
    let grow = max_step_growth * (below.x - from_d).max(last_increment);
    below.x + span.clamp(MIN_SPAN_OVER_GROWTH * grow, grow)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Before a closed gap is found the next trial extrapolates the secant to `g = 0`,
    /// bounded by the growth limit; without a usable secant it advances blindly.
    #[test]
    fn extrapolates_the_secant_before_the_bracket() {
        let trial = |x: f64, f: f64| Trial { x, f, at: () };
        // secant through (0, 2) and (1, 1): g = 0 at d = 2
        let search = RegulaFalsi::new(trial(1.0, 1.0), Some(trial(0.0, 2.0)));
        assert_eq!(extrapolated(&search, 0.0, 1.0, 3.0), 2.0);
        // the same secant, growth bounded to 0.5 × 1
        assert_eq!(extrapolated(&search, 0.0, 1.0, 0.5), 1.5);
        // no earlier trial: twice the distance from the last event
        let blind = RegulaFalsi::new(trial(1.0, 1.0), None);
        assert_eq!(extrapolated(&blind, 0.0, 0.5, 3.0), 1.0 + BLIND_SPAN_FACTOR);
    }
}
