//! What the load stepping carries from one contact event to the next: the last two converged
//! states, the points so far, and when the step callback sees them.
//!
//! A sinusoid's point is final when its state converges, and the callback sees it at once. A
//! profile's point is final once the touchdowns that place its travelling patch edges have come
//! ([`crate::fe::contact::edge_tracks`]), a few points later: its state is held until then, and the
//! callback sees the points in order, each with its own state, as they become final (at most
//! [`crate::fe::contact::edge_tracks::MAX_LAG`] points late; all of them when the branch ends or
//! fails).

use std::collections::VecDeque;
use std::ops::ControlFlow;

use crate::fe::contact::edge_tracks::EdgeTracks;
use crate::fe::contact::measure::{deformed_state, peak_x, Measured};
use crate::fe::error::{CurveFailure, SolveError};
use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::Assembly;
use crate::fe::stepping::predictor::LoadTangent;
use crate::fe::stepping::step_state::Converged;
use crate::fe::{Curve, CurvePoint, SolveOptions};

/// Bounds of the ratio of actual to tangent-extrapolated displacement increment that scales the
/// next event's first trial. Safeguard, not tuned: one odd event (a node released and
/// re-touching) cannot throw the next prediction far off.
const EVENT_RATIO_MIN: f64 = 0.5;

/// Upper bound of the event ratio ([`EVENT_RATIO_MIN`]).
const EVENT_RATIO_MAX: f64 = 4.0;

/// A recorded point the step callback has not seen yet: its index and its converged state with
/// its internal forces.
struct Held {
    index: usize,
    state: State,
    grad: Vec<f64>,
}

/// The step callback of the loading branch: each point with a view of its converged state.
pub(crate) type OnStep<'a> = dyn FnMut(&CurvePoint, Converged<'_>) -> ControlFlow<()> + 'a;

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
    /// The path's third-order term that the last step measured, for the next step's predictor
    /// ([`crate::fe::stepping::predictor::third_order_term`]).
    pub(crate) third_order: Option<Vec<[f64; 2]>>,
    /// A profile's edge placement by the load (`None` for a sinusoid).
    tracks: Option<EdgeTracks>,
    /// The points the step callback has not seen yet, in order.
    held: VecDeque<Held>,
}

impl LoadPath {
    /// The undeformed state with the peak node in contact.
    pub(crate) fn start(model: &Model, opts: &SolveOptions) -> Self {
        let profile = !model.indenter.profile.is_sinusoid();
        Self {
            cur: model.initial_state(),
            prev: None,
            a: 0.0,
            last_increment: opts.steps.first_step_over_amplitude * model.indenter.amplitude(),
            event_ratio: 1.0,
            points: Vec::new(),
            patch_edges: Vec::new(),
            grad: vec![0.0; 2 * model.num_nodes()],
            released: None,
            third_order: None,
            tracks: profile.then(|| EdgeTracks::new(model.mesh.bottom.len())),
            held: VecDeque::new(),
        }
    }

    /// The load tangent of the last converged state with the third-order term its step measured
    /// (the predictor's, [`crate::fe::stepping::predictor::predictor`]).
    pub(crate) fn with_third_order(&self, tangent: Option<LoadTangent>) -> Option<LoadTangent> {
        tangent.map(|z| z.with_third_order(self.third_order.clone()))
    }

    /// Nodes of the last converged state found touching and brought into contact before the next
    /// step: they touched at the last point.
    pub(crate) fn touching_before_step(&mut self) {
        if let Some(tracks) = &mut self.tracks {
            tracks.touching_before_step(&self.cur.active);
        }
    }

    /// Move on to the converged event `st` with its point, forces and patches; `extrapolated` is
    /// the increment the load tangent predicted for it; `released`, the node it released if it
    /// is a release event.
    fn advance(
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
            ..
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

    /// Moves on to the converged `st` and its point ([`Self::advance`] with `(extrapolated,
    /// released)`) and shows `on_step` every point that is final now (module documentation); its
    /// `Break` is [`SolveError::Stopped`], with the points up to the one it saw.
    pub(crate) fn record(
        &mut self,
        model: &Model,
        st: State,
        mut measured: Measured,
        (extrapolated, released): (Option<f64>, Option<usize>),
        on_step: &mut OnStep<'_>,
    ) -> Result<(), SolveError> {
        let Some(tracks) = &mut self.tracks else {
            let at = Converged {
                model,
                state: &st,
                grad: &measured.grad,
            };
            let flow = on_step(&measured.point, at);
            self.advance(st, measured, extrapolated, released);
            return match flow {
                ControlFlow::Break(()) => Err(SolveError::Stopped {
                    points: self.points.len(),
                }),
                ControlFlow::Continue(()) => Ok(()),
            };
        };
        let travelling = std::mem::take(&mut measured.travelling);
        let stick_runs = std::mem::take(&mut measured.stick_runs);
        let stick = (stick_runs, peak_x(model, &st));
        tracks.record(measured.point.p_over_estar, &st.active, travelling, stick);
        self.held.push_back(Held {
            index: self.points.len(),
            state: st.clone(),
            grad: measured.grad.clone(),
        });
        self.advance(st, measured, extrapolated, released);
        self.show_final(model, false, on_step)
    }

    /// Shows `on_step` the held points that are final, in order (all of them when the branch is
    /// `complete`), each placed by the load first
    /// ([`crate::fe::contact::edge_tracks::EdgeTracks::place`]). On `Break` the points after
    /// the one it saw are dropped: [`SolveError::Stopped`].
    pub(crate) fn show_final(
        &mut self,
        model: &Model,
        complete: bool,
        on_step: &mut OnStep<'_>,
    ) -> Result<(), SolveError> {
        let Some(tracks) = &self.tracks else {
            return Ok(());
        };
        while let Some(front) = self.held.front() {
            let k = front.index;
            if !tracks.settled(k, complete) {
                break;
            }
            let Held { state, grad, .. } = self.held.pop_front().expect("a front");
            tracks.place(k, &mut self.points[k], &mut self.patch_edges[k]);
            let at = Converged {
                model,
                state: &state,
                grad: &grad,
            };
            if on_step(&self.points[k], at).is_break() {
                self.points.truncate(k + 1);
                self.patch_edges.truncate(k + 1);
                self.held.clear();
                return Err(SolveError::Stopped { points: k + 1 });
            }
        }
        Ok(())
    }

    /// The failure `error` with the points converged so far, each shown to `on_step` first (a
    /// `Break` then changes nothing: the branch has failed).
    pub(crate) fn fail(
        mut self,
        model: &Model,
        error: SolveError,
        on_step: &mut OnStep<'_>,
    ) -> Box<CurveFailure> {
        // a `Break` here only drops the points after the one it saw
        let _ = self.show_final(model, true, on_step);
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
