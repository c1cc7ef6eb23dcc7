//! The options of a solve, grouped by concern: what the curve loads to and on which mesh
//! ([`SolveOptions`] itself), where the contact edge lies and when a node touches or lets go
//! ([`ContactOptions`]), how the load steps ([`StepOptions`]), and how Newton converges a step
//! ([`NewtonOptions`]). Each group's `Default` is the solver's setting.

use serde::{Deserialize, Serialize};

use crate::fe::contact::edge_rule::EdgeRule;
use crate::fe::model::mesh::{Grading, MeshLevel};
use crate::fe::stepping::loading::Stepping;
use crate::fe::stepping::slip_front::SlipFront;
use crate::fe::stepping::touched_hold::TouchedNodes;

/// The options of a solve: the curve's stop targets, its mesh, and the numerical settings by
/// concern.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SolveOptions {
    /// Stop once the contact half-width reaches this `a/λ` (in `(0, ½)`).
    pub until_a_over_lambda: f64,
    /// Instead: load until the mean pressure `p̄/E*` is this (> 0): the last point is the
    /// state at this mean pressure (within 10⁻⁹ relative), not an edge event; `until_a_over_lambda`
    /// is then the largest contact half-width allowed on the way (a curve that reaches it
    /// first is incomplete). For a profile the cap is full contact instead: its outermost
    /// patch edge reaches ½ when the valley's crest touches, long before.
    pub until_p_over_estar: Option<f64>,
    /// Instead: load until the contact fraction (total contact length over λ,
    /// [`crate::fe::contact::patches`]) reaches this (in `(0, 1)`): the last point is the first
    /// node event at or beyond it (once every node touches, the first of the slab steps that let
    /// the last openings close, `stepping::loading`); `until_a_over_lambda` is then not a stop. A
    /// profile's counterpart of `until_a_over_lambda`.
    #[serde(default)]
    pub until_contact_fraction: Option<f64>,
    /// How the load steps from one contact event to the next ([`Stepping`]).
    #[serde(default)]
    pub stepping: Stepping,
    /// Mesh resolution.
    pub mesh: MeshLevel,
    /// Mesh grading.
    pub grading: Grading,
    /// The contact edge and the contact set's tolerances.
    pub contact: ContactOptions,
    /// The load steps: their size, their cuts, the event search.
    pub steps: StepOptions,
    /// Newton's method and its convergence.
    pub newton: NewtonOptions,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            until_a_over_lambda: 0.45,
            until_p_over_estar: None,
            until_contact_fraction: None,
            stepping: Stepping::Auto,
            mesh: MeshLevel::Default,
            grading: Grading::default(),
            contact: ContactOptions::default(),
            steps: StepOptions::default(),
            newton: NewtonOptions::default(),
        }
    }
}

/// Where the contact edge lies, and when a contact-face node enters or leaves contact.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ContactOptions {
    /// Contact-edge location rule.
    pub edge_rule: EdgeRule,
    /// Release threshold: `λ < −multiplier_rtol · max|λ|`.
    pub multiplier_rtol: f64,
    /// Activation threshold: penetration deeper than this times `Δ`.
    pub gap_tolerance_over_amplitude: f64,
}

impl Default for ContactOptions {
    fn default() -> Self {
        Self {
            edge_rule: EdgeRule::default(),
            multiplier_rtol: 1e-9,
            gap_tolerance_over_amplitude: 1e-10,
        }
    }
}

/// The load steps: which event comes next, the first increment, how a failing step is cut,
/// and how an event's slab displacement is found.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StepOptions {
    /// Target advance of `a/λ` per load step of a frictionless curve: the next edge node is the
    /// first one at least this far beyond the current edge, so the points no longer grow with the
    /// mesh, each still an edge event on a node; 0, the default, steps node by node. A step that
    /// skips nodes is predicted through their closings one after another (a load tangent at each,
    /// no Newton iteration); its points lie on the node-by-node curve, and the curve read between
    /// them ([`crate::fe::convergence::p_at`]) is the node-by-node curve far below the
    /// discretisation error (docs/performance.md, "frictionless steps over several nodes").
    /// `wavy solve` and `wavy.solve` step 0.01 by default; the scenes step node by
    /// node, since some read curves linearly between points, which coarser points make less
    /// accurate. A frictional curve steps node by node whatever this says
    /// ([`Self::da_target_for`]).
    pub da_target: f64,
    /// First slab-displacement increment in units of the amplitude `Δ`.
    pub first_step_over_amplitude: f64,
    /// Largest growth factor of the trial displacement increment in the secant
    /// fallback of the edge search.
    pub max_step_growth: f64,
    /// Maximum consecutive halvings of a failing step.
    pub max_step_cuts: usize,
    /// Maximum number of load steps.
    pub max_steps: usize,
    /// Edge search: relative gap tolerance (w.r.t. the target node's initial gap).
    pub edge_gap_rtol: f64,
    /// Edge search: solve for the event's slab displacement with the bordered Newton method (`d` as
    /// an unknown) first, falling back to the secant search if it fails.
    pub bordered_edge_solve: bool,
    /// Edge search: maximum trial slab displacements per step.
    pub max_edge_iterations: usize,
    /// Use the tangent (Euler) predictor (else extrapolate the last increment).
    pub tangent_predictor: bool,
    /// Under the penalty friction law, how the load tangent treats the contact-face nodes that
    /// have just touched: held where they touched (the default), or free to slide as the
    /// consistent tangent has them at zero normal force
    /// ([`crate::fe::stepping::touched_hold`]). It changes the Newton path, not the converged
    /// state (test `holding_the_touched_node_in_the_tangent_changes_the_path_not_the_curve`;
    /// docs/performance.md, "the node that has just touched").
    #[serde(default)]
    pub touched_nodes: TouchedNodes,
    /// Under the penalty friction law, how an unloading step's prediction treats the stuck nodes
    /// that start to slide in it: followed through their switches to slip (the default), or
    /// held stuck as the load tangent has them ([`crate::fe::stepping::slip_front`]). It changes
    /// the Newton path, not the converged state (test
    /// `following_the_slip_front_changes_the_path_not_the_curve`; docs/performance.md, "the
    /// slip front followed").
    #[serde(default)]
    pub slip_front: SlipFront,
    /// Unloading steps per loading step (≥ 1): the unloading branch retraces the loading
    /// events' slab displacements, each interval in this many equal steps. The friction
    /// history of a loop is integrated at first order in the step, so the dissipation converges
    /// with it (docs/verification.md, "The energy audit").
    #[serde(default = "one_substep")]
    pub unloading_substeps: usize,
}

impl StepOptions {
    /// The target advance of `a/λ` per load step on a model with (`frictional`) or without
    /// friction: [`Self::da_target`] without; 0, node by node, with. A frictional curve's
    /// history is where each node was anchored when it touched: a step that ends on a node's
    /// touchdown anchors it exactly, one that passes it only where the prediction puts it, and
    /// steps of 0.01 so anchored move a frictional curve by more than its discretisation error
    /// (docs/performance.md, "the anchors of the nodes it passes").
    pub fn da_target_for(&self, frictional: bool) -> f64 {
        if frictional {
            0.0
        } else {
            self.da_target
        }
    }
}

fn one_substep() -> usize {
    1
}

impl Default for StepOptions {
    fn default() -> Self {
        Self {
            da_target: 0.0,
            first_step_over_amplitude: 0.005,
            max_step_growth: 3.0,
            max_step_cuts: 12,
            max_steps: 2000,
            edge_gap_rtol: 1e-6,
            bordered_edge_solve: true,
            max_edge_iterations: 60,
            tangent_predictor: true,
            touched_nodes: TouchedNodes::Held,
            slip_front: SlipFront::Followed,
            unloading_substeps: one_substep(),
        }
    }
}

/// Newton's method within a load step: its iteration and line-search limits, the active-set
/// passes, the convergence tolerances, and the choice of each friction node's piece of the law.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct NewtonOptions {
    /// Maximum Newton iterations per active-set pass.
    pub max_iterations: usize,
    /// Maximum line-search halvings.
    pub max_line_search: usize,
    /// Maximum line-search halvings of the bordered edge solve. A bordered step that
    /// needs more is a poor start, and the regula-falsi search takes over sooner than
    /// after [`NewtonOptions::max_line_search`] halvings, with the same results.
    pub max_edge_line_search: usize,
    /// Maximum active-set updates per load step.
    pub max_active_set_updates: usize,
    /// Relative residual tolerance (w.r.t. the largest nodal force).
    pub residual_rtol: f64,
    /// Relative residual tolerance of Newton passes whose active set may still change.
    pub loose_residual_rtol: f64,
    /// Absolute residual tolerance in units of `(G + κ) λ` (the round-off floor of the
    /// nodal forces grows with `κ`).
    pub residual_atol: f64,
    /// Newton corrections below this (`∞`-norm, units of λ) count as converged.
    pub increment_atol: f64,
    /// With friction, choose each node's stick/slip branch in the Newton step by where
    /// the step lands (semismooth Newton, [`crate::fe::newton::friction_step`]); else the
    /// branch of the current state.
    pub semismooth_friction: bool,
    /// Under exact stick, the stiffness `c_t` of the active-set decision
    /// ([`crate::fe::contact::friction::Branch::decide`]) over the shear modulus: how far a
    /// sliding node's reversed slip counts against its threshold. It changes the Newton path, not
    /// the converged curve where each increment has one solution (test
    /// `exact_stick_decision_stiffness_changes_the_path_not_the_curve`; docs/replication.md R3).
    pub stick_decision_stiffness: f64,
    /// Carry each element's pressure through a Newton solve as an unknown of its own, the
    /// mixed method's pressure iterate, predicted with the positions
    /// ([`crate::fe::model::mixed_pressure`]): the tangent's geometric volumetric term then
    /// uses it instead of `κ (v/V − 1)` of the current positions. It changes the Newton path,
    /// not the converged state (docs/performance.md, "the pressure iterate").
    pub pressure_iterate: bool,
    /// Under the penalty friction law, hold a sliding node that lies beyond its stick band at
    /// the band's middle in a Newton step that puts it on stick, instead of linearising it on
    /// the band's spring continued out to where it is ([`crate::fe::newton::friction_step`]).
    /// It changes the Newton path, not the converged state (test
    /// `returning_into_the_band_changes_the_path_not_the_curve`; docs/performance.md, "a node
    /// beyond its band returned to it").
    pub return_into_band: bool,
    /// With friction, a Newton pass that starts from the predictor's pressure iterate accepts a
    /// line-search trial where either residual falls enough, the displacement method's or the
    /// mixed method's ([`crate::fe::newton::mixed_residual::FrictionMerit::Either`]), instead
    /// of the displacement method's alone. It changes the Newton path, not the converged
    /// state (test `either_residual_changes_the_path_not_the_curve`; docs/performance.md,
    /// "either residual").
    pub either_residual_merit: bool,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            max_iterations: 30,
            max_line_search: 40,
            max_edge_line_search: 8,
            max_active_set_updates: 40,
            residual_rtol: 1e-10,
            loose_residual_rtol: 1e-5,
            residual_atol: 1e-13,
            increment_atol: 1e-14,
            semismooth_friction: true,
            stick_decision_stiffness: 1.0,
            pressure_iterate: true,
            return_into_band: true,
            either_residual_merit: true,
        }
    }
}
