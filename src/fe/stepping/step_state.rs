//! The deformed state of every converged point, for a caller that asks for it
//! ([`crate::fe::solve_with_states`]): what a field viewer shows of a step (reference and current
//! coordinates, each element's dilatation, the contact status, tractions and slip of the face).
//!
//! The load stepping ([`crate::fe::stepping::loading`], [`crate::fe::stepping::unloading`]) hands each converged point to
//! its observer with a `Converged` view of the state (references, nothing computed); only
//! `StepStates` turns the view into a [`StepState`], so an ordinary solve pays nothing.

use crate::fe::contact::measure::{deformed_state, HALF_WAVELENGTH};
use crate::fe::model::element::shoelace;
use crate::fe::model::{Model, State};
use crate::fe::{CurvePoint, DeformedState, LoadDirection};
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;

/// A converged state as the load stepping holds it when it reports a point: the model, the
/// state and its internal forces `∂Π/∂x` (units `G λ`).
#[derive(Clone, Copy)]
pub(crate) struct Converged<'a> {
    pub(crate) model: &'a Model,
    pub(crate) state: &'a State,
    pub(crate) grad: &'a [f64],
}

/// The deformed state of one converged point, with what a field viewer needs beyond
/// [`DeformedState`]. Lengths in units of λ.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StepState {
    /// Current positions, quads, contact-face nodes, contact status and the tractions `p/E*`,
    /// `τ/E*` of the face (as [`crate::fe::Curve::final_state`]).
    pub deformed: DeformedState,
    /// Reference (undeformed) node positions `X`; the displacement is `deformed.nodes − X`.
    pub reference_nodes: Vec<[f64; 2]>,
    /// Per quad, its current area over its reference area `v_e/V_e`: the mean dilatation `J`
    /// that the Q1/P0 element's volumetric energy uses ([`crate::fe::model::element`]).
    pub element_dilatation: Vec<f64>,
    /// Per contact-face node (order of `deformed.bottom`), its slip along the indenter since
    /// it touched (units of λ, signed: positive toward larger `x`, away from the peak): the
    /// arc length along the indenter `y_s` (for linear kinematics, the change of `x`) from
    /// where the node was at the first converged point of its current contact spell to
    /// where it is now, summed over the converged points between. Free nodes have 0, and a
    /// node that lets go and touches again starts from 0. With friction it is the relative
    /// tangential displacement of the two surfaces that a friction map shows: the elastic
    /// slip of the regularised stick (at most `e_c`) plus the sliding; without friction the
    /// same measure, the sliding alone.
    pub face_slip_over_lambda: Vec<f64>,
    /// The elastic energy stored in the layer, per unit ridge length and per wavelength, over
    /// `E* λ²`. With the face's work of friction
    /// ([`CurvePoint::friction_work_over_estar_lambda2`]) it accounts for the work of the load,
    /// `∫ p̄ dd = elastic energy + friction work` along the path (docs/verification.md, "The
    /// energy audit").
    pub elastic_energy_over_estar_lambda2: f64,
}

/// The observer of a solve with states: keeps the slip of the contact face from one
/// converged point to the next and builds each point's [`StepState`].
pub(crate) struct StepStates<'a> {
    estar: f64,
    /// Per contact-face node: its current `x` at the last converged point where it was in
    /// contact, `None` where it was free.
    last_contact_x: Vec<Option<f64>>,
    slip: Vec<f64>,
    on_step: &'a mut dyn FnMut(LoadDirection, &CurvePoint, &StepState) -> ControlFlow<()>,
}

impl<'a> StepStates<'a> {
    /// An observer for a solve on `model` with `E*/G = estar` that hands every point's
    /// state to `on_step`.
    pub(crate) fn new(
        model: &Model,
        estar: f64,
        on_step: &'a mut dyn FnMut(LoadDirection, &CurvePoint, &StepState) -> ControlFlow<()>,
    ) -> Self {
        let n = model.mesh.bottom.len();
        Self {
            estar,
            last_contact_x: vec![None; n],
            slip: vec![0.0; n],
            on_step,
        }
    }

    /// Build the state of the converged point `point` on branch `direction` and hand it on.
    pub(crate) fn observe(
        &mut self,
        direction: LoadDirection,
        point: &CurvePoint,
        at: Converged<'_>,
    ) -> ControlFlow<()> {
        let Converged { model, state, grad } = at;
        self.advance_slip(model, state);
        let step = StepState {
            deformed: deformed_state(model, state, grad, self.estar),
            reference_nodes: model.mesh.nodes.clone(),
            element_dilatation: element_dilatation(model, state),
            face_slip_over_lambda: self.slip.clone(),
            elastic_energy_over_estar_lambda2: model
                .energy(state)
                .expect("a converged state is not inverted")
                / HALF_WAVELENGTH
                / self.estar,
        };
        (self.on_step)(direction, point, &step)
    }

    /// The slip of each contact-face node after the converged state `st`
    /// ([`StepState::face_slip_over_lambda`]).
    fn advance_slip(&mut self, model: &Model, st: &State) {
        for (k, &n) in model.mesh.bottom.iter().enumerate() {
            let x = st.x[n][0];
            if !st.active[k] {
                self.last_contact_x[k] = None;
                self.slip[k] = 0.0;
                continue;
            }
            match self.last_contact_x[k] {
                Some(x_last) => self.slip[k] += model.contact_arc(x_last, x),
                None => self.slip[k] = 0.0,
            }
            self.last_contact_x[k] = Some(x);
        }
    }
}

/// Current over reference area of every quad of `st` ([`StepState::element_dilatation`]).
fn element_dilatation(model: &Model, st: &State) -> Vec<f64> {
    model
        .mesh
        .quads
        .iter()
        .zip(&model.refs)
        .map(|(q, r)| shoelace(&q.map(|n| st.x[n])) / r.area)
        .collect()
}
