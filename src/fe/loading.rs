//! The loading branch: slab-displacement stepping from one contact-edge event to the next
//! ([`super::event_search`]; for a profile, from one node event to the next:
//! [`super::node_events`], [`super::release_events`]), from first contact to the target
//! contact width, contact fraction or mean pressure.
//!
//! Predictor: the tangent (Euler) step from the last converged state to the slab
//! displacement at which the target node closes along that tangent, scaled by the previous
//! event's ratio of actual to extrapolated increment. Nodes left touching with a vanishing
//! force at the last event enter the next step active.

use serde::{Deserialize, Serialize};

use super::active_set::{equilibrate, Hold};
use super::assembly::Assembly;
use super::error::{CurveFailure, SolveError};
use super::event_search::{
    activate_touching, closing_increment, event_gap_tolerance, next_target, EventSearch,
};
use super::measure::{deformed_state, measure, EdgeAt, Measured};
use super::model::{Model, State};
use super::node_events::{activate_touching_anywhere, earliest_touchdown, passed_touchdowns};
use super::predictor::tangent_at;
use super::pressure_target::{land_on_pressure, Overshoot, PRESSURE_TARGET_RTOL};
use super::release_events::first_release;
use super::step_state::Converged;
use super::{Curve, CurvePoint, SolveOptions};

/// Bounds of the ratio of actual to tangent-extrapolated displacement increment that scales the
/// next event's first trial. Safeguard, not tuned: one odd event (a node released and
/// re-touching) cannot throw the next prediction far off.
const EVENT_RATIO_MIN: f64 = 0.5;

/// Upper bound of the event ratio ([`EVENT_RATIO_MIN`]).
const EVENT_RATIO_MAX: f64 = 4.0;

/// How the load steps from one contact event to the next.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Stepping {
    /// Edge by edge for a single sinusoid (its contact is one patch growing from the peak:
    /// the next event is the first free node beyond the edge), node events for a profile.
    #[default]
    Auto,
    /// Node events ([`super::node_events`]): the next event is whichever free node touches
    /// first, wherever it lies; a node that the step found touching before the target
    /// becomes the target. Any profile; a single sinusoid gives the edge-by-edge curve.
    NodeEvents,
}

/// Most times one step's target may be replaced by a node that touched before it
/// ([`passed_touchdowns`]). Each replacement moves the event to a strictly smaller slab
/// displacement, so the chain is short; a safeguard.
const MAX_RETARGETS: usize = 8;

/// What the load stepping carries from one edge event to the next.
pub(crate) struct LoadPath {
    /// Converged state of the last event, and of the one before.
    pub(crate) cur: State,
    pub(crate) prev: Option<State>,
    /// Contact half-width `a/λ` of the last event.
    pub(crate) a: f64,
    /// Slab-displacement increment of the last event (units of λ; before the first, the
    /// first trial).
    pub(crate) last_increment: f64,
    /// Ratio of the actual to the tangent-extrapolated increment of the last event.
    pub(crate) event_ratio: f64,
    /// Points converged so far.
    pub(crate) points: Vec<CurvePoint>,
    /// The contact patches of each point.
    pub(crate) patch_edges: Vec<Vec<[f64; 2]>>,
    /// Internal forces `∂Π/∂x` of `cur`.
    pub(crate) grad: Vec<f64>,
    /// The contact-face node the last event released, if it was a release.
    pub(crate) released: Option<usize>,
}

impl LoadPath {
    /// The undeformed state with the peak node in contact.
    pub(crate) fn start(model: &Model, opts: &SolveOptions) -> Self {
        Self {
            cur: model.initial_state(),
            prev: None,
            a: 0.0,
            last_increment: opts.first_step_over_amplitude * model.indenter.amplitude(),
            event_ratio: 1.0,
            points: Vec::new(),
            patch_edges: Vec::new(),
            grad: vec![0.0; 2 * model.num_nodes()],
            released: None,
        }
    }

    /// Move on to the converged event `st` with its point, forces and patches; `extrapolated` is
    /// the increment the load tangent predicted for it; `released`, the node it released if it
    /// is a release event.
    pub(crate) fn advance(
        &mut self,
        st: State,
        measured: Measured,
        extrapolated: Option<f64>,
        released: Option<usize>,
    ) {
        let Measured {
            point,
            grad,
            patches,
        } = measured;
        self.a = point.a_over_lambda;
        self.points.push(point);
        self.patch_edges.push(patches);
        self.grad = grad;
        self.last_increment = st.d - self.cur.d;
        if let Some(e) = extrapolated {
            self.event_ratio = (self.last_increment / e).clamp(EVENT_RATIO_MIN, EVENT_RATIO_MAX);
        }
        self.prev = Some(std::mem::replace(&mut self.cur, st));
        self.released = released;
    }

    /// The failure `error` with the points converged so far.
    pub(crate) fn fail(self, error: SolveError) -> Box<CurveFailure> {
        Box::new(CurveFailure {
            error,
            points: self.points,
            unloading: Vec::new(),
        })
    }

    /// The curve: the loading points, `unloading`, the last converged state and the work
    /// done (`asm`).
    pub(crate) fn finish(
        self,
        model: &Model,
        asm: &Assembly,
        estar: f64,
        unloading: Vec<CurvePoint>,
    ) -> Curve {
        Curve {
            final_state: deformed_state(model, &self.cur, &self.grad, estar),
            points: self.points,
            patch_edges: self.patch_edges,
            unloading,
            work: asm.work(),
        }
    }
}

/// Trace the load curve up to `opts.until_a_over_lambda`, one edge event per point (see
/// [`super::event_search`] for the events, [`super::edge_rule`] for the contact-edge
/// location). `on_step` sees every converged point with a view of its state.
pub(crate) fn trace(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    estar: f64,
    on_step: &mut dyn FnMut(&CurvePoint, Converged<'_>),
) -> Result<Curve, Box<CurveFailure>> {
    let path = loading_branch(model, asm, opts, estar, on_step)?;
    Ok(path.finish(model, asm, estar, Vec::new()))
}

/// The loading branch: from first contact, one edge event per point, until the contact
/// half-width reaches `opts.until_a_over_lambda` (or, with `opts.until_p_over_estar`, until
/// the mean pressure reaches that: the event that would overshoot it is replaced by the
/// state on the target, [`land_on_pressure`]). `on_step` sees every converged point with a
/// view of its state.
pub(crate) fn loading_branch(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    estar: f64,
    on_step: &mut dyn FnMut(&CurvePoint, Converged<'_>),
) -> Result<LoadPath, Box<CurveFailure>> {
    let mut path = LoadPath::start(model, opts);
    let mut step = 1;
    // reached when loading landed on it (within its tolerance, so possibly a hair below)
    let pressure_reached = |path: &LoadPath| match (opts.until_p_over_estar, path.points.last()) {
        (Some(target), Some(p)) => p.p_over_estar >= target * (1.0 - PRESSURE_TARGET_RTOL),
        _ => false,
    };
    let fraction_reached = |path: &LoadPath| match (opts.until_contact_fraction, path.points.last())
    {
        (Some(target), Some(p)) => p.contact_fraction >= target,
        _ => false,
    };
    // with a contact-fraction target the contact width is no stop
    let width_reached = |path: &LoadPath| {
        opts.until_contact_fraction.is_none() && path.a >= opts.until_a_over_lambda
    };
    let node_events =
        opts.stepping == Stepping::NodeEvents || !model.indenter.profile.is_sinusoid();
    while !width_reached(&path) && !pressure_reached(&path) && !fraction_reached(&path) {
        if step > opts.max_steps {
            let error = SolveError::TooManySteps {
                steps: opts.max_steps,
                a_over_lambda: path.a,
            };
            return Err(path.fail(error));
        }
        // the next event's node: the first free node beyond the edge (edge by edge; nodes
        // skipped because they touch enter the step active), or the free node that closes
        // first along the load tangent (node events; every touching free node enters active)
        let (mut k, tangent) = if node_events {
            activate_touching_anywhere(model, &mut path.cur, path.released);
            let tangent = tangent_at(model, asm, opts, &path.cur);
            match earliest_touchdown(model, &path.cur, tangent.as_deref()) {
                Some(k) => (k, tangent),
                None => break, // full contact
            }
        } else {
            let Some(k) = next_target(model, &path.cur, path.a, opts.da_target) else {
                break; // full contact
            };
            activate_touching(model, &mut path.cur, k);
            (k, tangent_at(model, asm, opts, &path.cur))
        };
        let mut retargets = 0;
        let (mut st, mut iters, extrapolated) = loop {
            // predict: the slab displacement at which node k closes along the load tangent,
            // scaled by the previous event's ratio of actual to extrapolated increment
            let gap0 = model.gaps(&path.cur)[k];
            let extrapolated = tangent
                .as_deref()
                .and_then(|z| closing_increment(model, &path.cur, k, gap0, z));
            let search = EventSearch {
                opts,
                from: &path.cur,
                before: path.prev.as_ref(),
                node: k,
                gap0,
                gap_tol: event_gap_tolerance(model, opts, gap0),
                tangent: tangent.clone(),
                first_increment: extrapolated.map_or(path.last_increment, |e| e * path.event_ratio),
                last_increment: path.last_increment,
            };
            // the event: node k touches with zero force
            let (st, iters) = match search.find(model, asm, step) {
                Ok(found) => found,
                Err(error) => return Err(path.fail(error)),
            };
            // a node that touched on the way came first: it is the event
            match passed_touchdowns(model, &path.cur, &st, tangent.as_deref()) {
                Some(j) if node_events && retargets < MAX_RETARGETS => {
                    retargets += 1;
                    k = j;
                }
                _ => break (st, iters, extrapolated),
            }
        };
        // a contact node that the step released let go before node k touched: the release
        // is the event
        let release = if node_events {
            match first_release(model, asm, opts, &path.cur, &st, k) {
                Ok(r) => r,
                Err(f) => return Err(path.fail(f.into_error(step, st.d))),
            }
        } else {
            None
        };
        let (edge, released, extrapolated) = match release {
            Some(r) => {
                st = r.state;
                iters += r.iterations;
                (EdgeAt::OutermostPatch(None), Some(r.node), None)
            }
            None => {
                // node k enters contact; equilibrate
                model.activate(&mut st, k);
                model.enforce_constraints(&mut st);
                match equilibrate(model, asm, &mut st, opts, Hold::NONE) {
                    Ok(it) => iters += it,
                    Err(f) => return Err(path.fail(f.into_error(step, st.d))),
                }
                let edge = if node_events {
                    EdgeAt::OutermostPatch(Some(k))
                } else {
                    EdgeAt::Node(k)
                };
                (edge, None, extrapolated)
            }
        };
        // commit the slip and measure
        model.commit_slip(&mut st);
        let mut measured = measure(model, asm, &st, estar, edge, opts);
        measured.point.newton_iterations = iters;
        let overshot = opts
            .until_p_over_estar
            .filter(|&t| measured.point.p_over_estar > t);
        // the event that overshoots the pressure target is replaced by the state on it,
        // between the last converged state and this event
        let (st, measured, extrapolated) = match overshot {
            None => (st, measured, extrapolated),
            Some(target) => {
                let event = (st.d, measured.point.p_over_estar);
                let overshoot = Overshoot {
                    below: &path.cur,
                    below_p_over_estar: path.points.last().map_or(0.0, |p| p.p_over_estar),
                    node: k,
                    event,
                };
                match land_on_pressure(model, asm, opts, estar, overshoot, target) {
                    Ok((st, mut landed, it)) => {
                        landed.point.newton_iterations = iters + it;
                        (st, landed, None)
                    }
                    Err(f) => return Err(path.fail(f.into_error(step, event.0))),
                }
            }
        };
        let at = Converged {
            model,
            state: &st,
            grad: &measured.grad,
        };
        on_step(&measured.point, at);
        path.advance(st, measured, extrapolated, released);
        if overshot.is_some() {
            break; // on the pressure target
        }
        step += 1;
    }
    if let Some(target) = opts.until_p_over_estar {
        if !pressure_reached(&path) && path.a >= opts.until_a_over_lambda {
            let error = SolveError::PressureTargetBeyondLimit {
                a_over_lambda: path.a,
                p_over_estar: path.points.last().map_or(0.0, |p| p.p_over_estar),
                target,
            };
            return Err(path.fail(error));
        }
    }
    if let Some(target) = opts.until_contact_fraction {
        if !fraction_reached(&path) && !pressure_reached(&path) {
            let error = SolveError::ContactFractionBeyondMesh {
                contact_fraction: path.points.last().map_or(0.0, |p| p.contact_fraction),
                target,
            };
            return Err(path.fail(error));
        }
        return Ok(path);
    }
    if path.a < opts.until_a_over_lambda && !pressure_reached(&path) {
        let error = SolveError::TargetBeyondMesh {
            a_over_lambda: path.a,
            target: opts.until_a_over_lambda,
        };
        return Err(path.fail(error));
    }
    Ok(path)
}
