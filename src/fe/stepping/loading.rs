//! The loading branch: slab-displacement stepping from one contact-edge event to the next
//! ([`crate::fe::stepping::event_search`]; for a profile, from one node event to the next:
//! [`crate::fe::stepping::node_events`], [`crate::fe::stepping::release_events`]), from first contact to the target
//! contact width, contact fraction or mean pressure.
//!
//! Predictor: the step along the load path from the last converged state (second order where
//! its curvature is known, [`crate::fe::stepping::predictor`]) to the slab displacement at which
//! the target node closes along it, scaled by the previous event's ratio of actual to
//! extrapolated increment. Nodes left touching with a vanishing
//! force at the last event enter the next step active.

use serde::{Deserialize, Serialize};

use crate::fe::contact::measure::{measure, measure_between_events, EdgeAt, Measured};
use crate::fe::error::{CurveFailure, SolveError};
use crate::fe::model::{Model, State};
use crate::fe::newton::active_set::{equilibrate, Hold};
use crate::fe::newton::assembly::Assembly;
use crate::fe::stepping::displacement_step::displacement_step;
use crate::fe::stepping::event_search::{
    activate_touching, event_gap_tolerance, next_target, predicted_closing, EventSearch,
};
use crate::fe::stepping::load_path::{LoadPath, OnStep};
use crate::fe::stepping::node_events::{
    activate_touching_anywhere, earliest_touchdown, passed_touchdowns,
};
use crate::fe::stepping::predictor::{tangent_at, third_order_term, LoadTangent};
use crate::fe::stepping::pressure_target::{land_on_pressure, Overshoot, PRESSURE_TARGET_RTOL};
use crate::fe::stepping::release_events::{first_release, ReleaseSearch};
use crate::fe::{Curve, SolveOptions};

/// How the load steps from one contact event to the next.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Stepping {
    /// Edge by edge for a single sinusoid (its contact is one patch growing from the peak:
    /// the next event is the first free node beyond the edge), node events for a profile.
    #[default]
    Auto,
    /// Node events ([`crate::fe::stepping::node_events`]): the next event is whichever free node touches
    /// first, wherever it lies; a node that the step found touching before the target
    /// becomes the target. Any profile; a single sinusoid gives the edge-by-edge curve.
    NodeEvents,
}

/// Most times one step's target may be replaced by a node that touched before it
/// ([`passed_touchdowns`]). Each replacement moves the event to a strictly smaller slab
/// displacement, so the chain is short; a safeguard.
const MAX_RETARGETS: usize = 8;

/// Trace the load curve up to `opts.until_a_over_lambda`, one edge event per point (see
/// [`crate::fe::stepping::event_search`] for the events, [`crate::fe::contact::edge_rule`] for the contact-edge
/// location). `on_step` sees every converged point with a view of its state.
pub(crate) fn trace(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    estar: f64,
    on_step: &mut OnStep<'_>,
) -> Result<Curve, Box<CurveFailure>> {
    let path = loading_branch(model, asm, opts, estar, on_step)?;
    Ok(path.finish(model, asm, estar, Vec::new()))
}

/// The loading branch: from first contact, one edge event per point, until the contact
/// half-width reaches `opts.until_a_over_lambda` (or, with `opts.until_p_over_estar`, until
/// the mean pressure reaches that: the event that would overshoot it is replaced by the
/// state on the target, [`land_on_pressure`]). `on_step` sees every converged point with a
/// view of its state; its `Break` ends the branch with [`SolveError::Stopped`].
pub(crate) fn loading_branch(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    estar: f64,
    on_step: &mut OnStep<'_>,
) -> Result<LoadPath, Box<CurveFailure>> {
    let mut path = LoadPath::start(model, opts);
    let sinusoid = model.indenter.profile.is_sinusoid();
    let targets = Targets {
        opts,
        profile: !sinusoid,
    };
    let branch = Branch {
        model,
        opts,
        estar,
        events: Events::of(opts.stepping, sinusoid),
    };
    let mut step = 1;
    while !targets.any_reached(&path) {
        if step > opts.steps.max_steps {
            let error = SolveError::TooManySteps {
                steps: opts.steps.max_steps,
                a_over_lambda: path.a,
            };
            return Err(path.fail(model, error, on_step));
        }
        let Some((k, tangent)) = branch.next_event_node(asm, &mut path) else {
            // every node touches: no event is left
            if opts.until_contact_fraction.is_some() {
                let closed = load_past_full_contact(model, asm, opts, estar, &mut path, on_step);
                if let Err(error) = closed {
                    return Err(path.fail(model, error, on_step));
                }
            }
            break;
        };
        let point = branch.event_point(asm, &path, k, tangent, step);
        let (point, on_target) = match point {
            Ok(point) => point,
            Err(error) => return Err(path.fail(model, error, on_step)),
        };
        let EventPoint {
            state,
            measured,
            extrapolated,
            released,
            third_order,
        } = point;
        path.third_order = third_order;
        if let Err(error) = path.record(model, state, measured, (extrapolated, released), on_step) {
            return Err(path.fail(model, error, on_step));
        }
        if on_target {
            break; // on the pressure target
        }
        step += 1;
    }
    if let Err(error) = path.show_final(model, true, on_step) {
        return Err(path.fail(model, error, on_step));
    }
    targets.check_reached(path, model, on_step)
}

/// Most slab steps of [`load_past_full_contact`]: with the increment doubled at each, 2³² times
/// the last event's increment, far beyond any load the layer carries; a safeguard.
const FULL_CONTACT_STEPS: usize = 32;

/// Every contact-face node touches, so no event is left; but the openings of the continuum
/// solution that the last touchdowns left close only as their nodes take up load
/// ([`crate::fe::contact::patch_edge`]), so the contact fraction is still short of 1. Toward a
/// contact-fraction target not reached yet, the slab goes on by the last event's increment,
/// doubled at each step, until the fraction reaches it: the first state at or beyond the
/// target is the curve's last point, as with events. `on_step` sees every converged point; its
/// `Break` is [`SolveError::Stopped`].
fn load_past_full_contact(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    estar: f64,
    path: &mut LoadPath,
    on_step: &mut OnStep<'_>,
) -> Result<(), SolveError> {
    let Some(target) = opts.until_contact_fraction else {
        return Ok(());
    };
    let mut increment = path.last_increment.abs();
    for step in 1..=FULL_CONTACT_STEPS {
        if path
            .points
            .last()
            .is_some_and(|p| p.contact_fraction >= target)
            || increment <= 0.0
        {
            return Ok(());
        }
        let d = path.cur.d + increment;
        let (mut st, iterations) = displacement_step(model, asm, opts, &path.cur, d, Hold::NONE)
            .map_err(|f| f.into_error(step, d))?;
        asm.commit_slip(model, &mut st);
        let mut measured = measure_between_events(model, asm, &st, estar, opts);
        measured.point.newton_iterations = iterations;
        path.record(model, st, measured, (None, None), on_step)?;
        increment *= 2.0;
    }
    Ok(())
}

/// The three stop targets of the loading branch: the contact width, the mean pressure and the
/// contact fraction ([`SolveOptions`]).
struct Targets<'a> {
    opts: &'a SolveOptions,
    /// The indenter is a profile with finer harmonics: its contact half-width (the outermost
    /// patch edge) reaches ½ when the valley's crest touches, long before full contact, so with
    /// a pressure target it is no cap; full contact is.
    profile: bool,
}

impl Targets<'_> {
    /// The mean-pressure target, reached when loading landed on it (within its tolerance, so
    /// possibly a hair below).
    fn pressure_reached(&self, path: &LoadPath) -> bool {
        match (self.opts.until_p_over_estar, path.points.last()) {
            (Some(target), Some(p)) => p.p_over_estar >= target * (1.0 - PRESSURE_TARGET_RTOL),
            _ => false,
        }
    }

    fn fraction_reached(&self, path: &LoadPath) -> bool {
        match (self.opts.until_contact_fraction, path.points.last()) {
            (Some(target), Some(p)) => p.contact_fraction >= target,
            _ => false,
        }
    }

    /// With a contact-fraction target the contact width is no stop, nor for a profile loaded to
    /// a pressure.
    fn width_reached(&self, path: &LoadPath) -> bool {
        self.opts.until_contact_fraction.is_none()
            && !self.profile_to_pressure()
            && path.a >= self.opts.until_a_over_lambda
    }

    fn profile_to_pressure(&self) -> bool {
        self.profile && self.opts.until_p_over_estar.is_some()
    }

    fn any_reached(&self, path: &LoadPath) -> bool {
        self.width_reached(path) || self.pressure_reached(path) || self.fraction_reached(path)
    }

    /// The branch as it ended, or the error that says which target it fell short of (full
    /// contact came first).
    fn check_reached(
        &self,
        path: LoadPath,
        model: &Model,
        on_step: &mut OnStep<'_>,
    ) -> Result<LoadPath, Box<CurveFailure>> {
        let opts = self.opts;
        if let Some(target) = opts.until_p_over_estar {
            let p_over_estar = path.points.last().map_or(0.0, |p| p.p_over_estar);
            if self.profile_to_pressure() && !self.pressure_reached(&path) {
                let error = SolveError::PressureTargetBeyondFullContact {
                    p_over_estar,
                    target,
                };
                return Err(path.fail(model, error, on_step));
            }
            if !self.pressure_reached(&path) && path.a >= opts.until_a_over_lambda {
                let error = SolveError::PressureTargetBeyondLimit {
                    a_over_lambda: path.a,
                    p_over_estar: path.points.last().map_or(0.0, |p| p.p_over_estar),
                    target,
                };
                return Err(path.fail(model, error, on_step));
            }
        }
        if let Some(target) = opts.until_contact_fraction {
            if !self.fraction_reached(&path) && !self.pressure_reached(&path) {
                let error = SolveError::ContactFractionBeyondMesh {
                    contact_fraction: path.points.last().map_or(0.0, |p| p.contact_fraction),
                    target,
                };
                return Err(path.fail(model, error, on_step));
            }
            return Ok(path);
        }
        if path.a < opts.until_a_over_lambda && !self.pressure_reached(&path) {
            let error = SolveError::TargetBeyondMesh {
                a_over_lambda: path.a,
                target: opts.until_a_over_lambda,
            };
            return Err(path.fail(model, error, on_step));
        }
        Ok(path)
    }
}

/// Which node's touchdown is the next event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Events {
    /// The first free node beyond the contact edge: a single sinusoid's one patch growing from
    /// the peak.
    EdgeByEdge,
    /// Whichever free node touches first, wherever it lies; a release is an event too
    /// ([`crate::fe::stepping::node_events`], [`crate::fe::stepping::release_events`]).
    AnyNode,
}

impl Events {
    /// The events of a [`Stepping`] choice: node events when asked for, or for a profile.
    fn of(stepping: Stepping, sinusoid: bool) -> Events {
        match (stepping, sinusoid) {
            (Stepping::Auto, true) => Events::EdgeByEdge,
            (Stepping::NodeEvents, _) | (Stepping::Auto, false) => Events::AnyNode,
        }
    }
}

/// What every load step of one loading branch reads: the model, the options, the plane-strain
/// modulus `E*` the points are measured in, and which node's touchdown is the next event.
struct Branch<'a> {
    model: &'a Model,
    opts: &'a SolveOptions,
    estar: f64,
    events: Events,
}

/// A found event: the state where its node touches with zero force, the node, the Newton
/// iterations spent, and the increment the load tangent predicted.
struct Found {
    state: State,
    node: usize,
    iterations: usize,
    extrapolated: Option<f64>,
}

/// An event settled in equilibrium, before it is measured: the state, where its contact edge
/// is measured from, the node it released (a release event), the tangent's predicted increment
/// (none for a release) and the Newton iterations so far.
struct SettledEvent {
    state: State,
    edge: EdgeAt,
    released: Option<usize>,
    extrapolated: Option<f64>,
    node: usize,
    iterations: usize,
}

/// The point a load step adds to the curve: its state (slip committed), what was measured
/// there, the tangent's predicted increment, the node a release event let go, and the path's
/// third-order term measured on the step (none for a release or a landing).
struct EventPoint {
    state: State,
    measured: Measured,
    extrapolated: Option<f64>,
    released: Option<usize>,
    third_order: Option<Vec<[f64; 2]>>,
}

impl Branch<'_> {
    /// The target advance of `a/λ` per step on this branch's model
    /// ([`crate::fe::StepOptions::da_target_for`]: node by node with friction).
    fn da_target(&self) -> f64 {
        self.opts.steps.da_target_for(!self.model.is_potential())
    }

    /// One load step's point, and whether it lies on the mean-pressure target: the event on
    /// node `k` found, settled and measured; an event beyond the target replaced by the state on
    /// it ([`Self::land_between`]).
    fn event_point(
        &self,
        asm: &mut Assembly,
        path: &LoadPath,
        k: usize,
        tangent: Option<LoadTangent>,
        step: usize,
    ) -> Result<(EventPoint, bool), SolveError> {
        let step_path = tangent.clone();
        let found = self.find_event(asm, path, k, tangent, step)?;
        let mut settled = self.settle_event(asm, path, found, step)?;
        let third_order = (step_path.as_ref())
            .filter(|_| settled.released.is_none() && self.da_target() == 0.0)
            .and_then(|z| third_order_term(self.model, &path.cur, z, &settled.state));
        let measured = self.measure_event(asm, &mut settled);
        let overshot = self
            .opts
            .until_p_over_estar
            .filter(|&t| measured.point.p_over_estar > t);
        let point = EventPoint {
            state: settled.state,
            measured,
            extrapolated: settled.extrapolated,
            released: settled.released,
            third_order,
        };
        match overshot {
            None => Ok((point, false)),
            Some(target) => {
                let overshoot = Overshoot {
                    below: &path.cur,
                    below_p_over_estar: path.points.last().map_or(0.0, |p| p.p_over_estar),
                    node: settled.node,
                    event: (point.state.d, point.measured.point.p_over_estar),
                };
                let (state, measured) = self.land_between(
                    asm,
                    overshoot,
                    point.measured.point.newton_iterations,
                    target,
                    step,
                )?;
                let landed = EventPoint {
                    state,
                    measured,
                    extrapolated: None,
                    released: point.released,
                    third_order: None,
                };
                Ok((landed, true))
            }
        }
    }

    /// The next event's node and the load tangent at the last event, or `None` at full
    /// contact: edge by edge, the first free node beyond the edge (nodes skipped because they
    /// touch enter the step active); with node events, the free node that closes first along the
    /// load tangent (every touching free node enters active).
    fn next_event_node(
        &self,
        asm: &mut Assembly,
        path: &mut LoadPath,
    ) -> Option<(usize, Option<LoadTangent>)> {
        let (model, opts) = (self.model, self.opts);
        match self.events {
            Events::AnyNode => {
                activate_touching_anywhere(model, &mut path.cur, path.released);
                path.touching_before_step();
                let tangent = tangent_at(model, asm, opts, &path.cur);
                let k = earliest_touchdown(model, &path.cur, tangent.as_deref())?;
                Some((k, path.with_third_order(tangent)))
            }
            Events::EdgeByEdge => {
                let k = next_target(model, &path.cur, path.a, self.da_target())?;
                activate_touching(model, &mut path.cur, k);
                let tangent = tangent_at(model, asm, opts, &path.cur);
                Some((k, path.with_third_order(tangent)))
            }
        }
    }

    /// The slab displacement at which node `k` touches with zero force, predicted along the
    /// load tangent (scaled by the previous event's ratio of actual to extrapolated increment)
    /// and found by [`EventSearch`]. With node events, a node that touched on the way came first
    /// and becomes the target ([`passed_touchdowns`], at most [`MAX_RETARGETS`] times); the
    /// iterations of every search count.
    fn find_event(
        &self,
        asm: &mut Assembly,
        path: &LoadPath,
        mut k: usize,
        tangent: Option<LoadTangent>,
        step: usize,
    ) -> Result<Found, SolveError> {
        let model = self.model;
        let (mut retargets, mut spent) = (0, 0);
        loop {
            let gap0 = model.gaps(&path.cur)[k];
            let extrapolated = tangent
                .as_ref()
                .and_then(|z| predicted_closing(model, &path.cur, k, gap0, z));
            let search = EventSearch {
                opts: self.opts,
                from: &path.cur,
                before: path.prev.as_ref(),
                node: k,
                gap0,
                gap_tol: event_gap_tolerance(model, self.opts, gap0),
                tangent: tangent.clone(),
                first_increment: extrapolated.map_or(path.last_increment, |e| e * path.event_ratio),
                last_increment: path.last_increment,
            };
            let (st, iterations) = search.find(model, asm, step)?;
            spent += iterations;
            match passed_touchdowns(model, &path.cur, &st, tangent.as_deref()) {
                Some(j) if self.events == Events::AnyNode && retargets < MAX_RETARGETS => {
                    retargets += 1;
                    k = j;
                }
                _ => {
                    return Ok(Found {
                        state: st,
                        node: k,
                        iterations: spent,
                        extrapolated,
                    })
                }
            }
        }
    }

    /// The found event in equilibrium: with node events, a contact node that the step released
    /// let go before node `k` touched, and the release is the event ([`first_release`]); else
    /// node `k` enters contact and the state is equilibrated.
    fn settle_event(
        &self,
        asm: &mut Assembly,
        path: &LoadPath,
        found: Found,
        step: usize,
    ) -> Result<SettledEvent, SolveError> {
        let (model, opts) = (self.model, self.opts);
        let Found {
            state: mut st,
            node: k,
            mut iterations,
            extrapolated,
        } = found;
        let search = match self.events {
            Events::AnyNode => first_release(model, asm, opts, &path.cur, &st, k)
                .map_err(|f| f.into_error(step, st.d))?,
            Events::EdgeByEdge => ReleaseSearch::default(),
        };
        iterations += search.iterations;
        if let Some(r) = search.release {
            return Ok(SettledEvent {
                state: r.state,
                edge: EdgeAt::OutermostPatch(None),
                released: Some(r.node),
                extrapolated: None,
                node: k,
                iterations,
            });
        }
        model.activate(&mut st, k);
        model.enforce_constraints(&mut st);
        iterations += equilibrate(model, asm, &mut st, opts, Hold::NONE)
            .map_err(|f| f.into_error(step, st.d))?;
        let edge = match self.events {
            Events::AnyNode => EdgeAt::OutermostPatch(Some(k)),
            Events::EdgeByEdge => EdgeAt::Node(k),
        };
        Ok(SettledEvent {
            state: st,
            edge,
            released: None,
            extrapolated,
            node: k,
            iterations,
        })
    }

    /// Commits the slip of a settled event and measures its point (its Newton iterations those
    /// of the event).
    fn measure_event(&self, asm: &mut Assembly, event: &mut SettledEvent) -> Measured {
        asm.commit_slip(self.model, &mut event.state);
        let mut measured = measure(
            self.model,
            asm,
            &event.state,
            self.estar,
            event.edge,
            self.opts,
        );
        measured.point.newton_iterations = event.iterations;
        measured
    }

    /// The event that overshoots the pressure target replaced by the state on it, between the
    /// last converged state and this event ([`land_on_pressure`]); its Newton iterations those
    /// the event spent, `event_iterations`, and the landing's.
    fn land_between(
        &self,
        asm: &mut Assembly,
        overshoot: Overshoot<'_>,
        event_iterations: usize,
        target: f64,
        step: usize,
    ) -> Result<(State, Measured), SolveError> {
        let event_d = overshoot.event.0;
        let (st, mut landed, it) =
            land_on_pressure(self.model, asm, self.opts, self.estar, overshoot, target)
                .map_err(|f| f.into_error(step, event_d))?;
        landed.point.newton_iterations = event_iterations + it;
        Ok((st, landed))
    }
}
