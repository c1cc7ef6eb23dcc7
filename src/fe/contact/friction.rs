//! Interface law: Coulomb–Orowan friction, with exact or regularised stick
//! (docs/replication.md R3).
//!
//! # The law
//! With [`Interface::CoulombOrowan`] the indenter also exerts a tangential force `T` on
//! each active node, along the surface tangent `t = (1, y_s')/w`, `w = √(1 + y_s'²)`. The
//! normal force is `N = n·g = (g_y − y_s' g_x)/w` (`g = ∂Π/∂x` the node's internal force,
//! `n = (−y_s', 1)/w`), and the nodal slip threshold is the traction bound
//! `τ_sl = min(μ p, τ_max)` integrated over the node's tributary length `ℓ` on the deformed
//! face (half of each adjacent face segment, chords):
//!
//! ```text
//! L = min(μ N, τ_max ℓ)
//! ```
//!
//! Stick is regularised as in penalty friction: the tangential force grows with the
//! *elastic slip* `e` and reaches the threshold at `e_c` (a small fraction of the element
//! size, [`CoulombOrowan::elastic_slip_over_element`]). Return mapping, per load step,
//! from the committed history `(e_n, S_n)` (elastic slip and arc-length position on the
//! indenter at the last converged step, [`SlipHistory`]):
//!
//! ```text
//! e* = e_n + S(x) − S_n            (trial elastic slip; S the arc length along y_s)
//! φ  = e*/e_c  if |e*| ≤ e_c (stick),   sign(e*) otherwise (slip)
//! T  = −L φ                        (opposes the slip)
//! ```
//!
//! and on convergence `e_{n+1} = e_c φ`, `S_{n+1} = S(x)`.
//!
//! # Exact stick (`e_c = 0`)
//! With no elastic slip, stick is a constraint: a *held* node stays at its anchor (where the
//! last converged step left it) and its friction force is the reaction `T = −(c·g)/w`, which
//! the law bounds by `|T| ≤ L`; a *sliding* node has `T = −L φ`, `φ = ±1`, and slides the way
//! of `φ`. Which piece a node is on is part of the state ([`SlipHistory::held`]), decided in
//! each Newton step by the primal–dual active-set rule [`Branch::decide`] on the step's
//! linearised force, slip and threshold ([`crate::fe::newton::friction_step`]). The
//! decision's stiffness `c_t` ([`crate::fe::NewtonOptions::stick_decision_stiffness`]) sets the
//! path to a solution; where an increment has more than one solution it may pick another
//! (docs/replication.md R3). The regularised law above converges to this one at first order in
//! `e_c` (test `penalty_stick_converges_to_exact_stick_at_first_order`).
//!
//! # Residual and tangent rows
//! The reduced residual of an active node's sliding unknown `x` (slot vector
//! `c = (1, y_s')`, see [`crate::fe::contact::indenter`]) becomes
//!
//! ```text
//! r_x = c·g + w L φ
//! ```
//!
//! (zero: the tangential internal force balances the friction force). Its derivatives,
//! with `dS/dx = w`, `dw/dx = y_s' y_s''/w`, `dφ/dx = w/e_c` in stick and 0 in slip:
//!
//! * Coulomb regime, `w L φ = μ φ (−y_s', 1)·g`: a modified left vector on the element
//!   Hessian rows of the node,
//!   `∂(w L φ)/∂q_t = μ φ (−y_s', 1) H[node, ·] c_t`, plus on the node's own unknown
//!   `μ (dφ/dx) (g_y − y_s' g_x) − μ φ y_s'' g_x`;
//! * Orowan regime, `w L φ = w τ_max ℓ φ`: it depends on the neighbours' positions `P_m`
//!   through `ℓ`,
//!   `∂(w L φ)/∂q_m = w τ_max φ (∂ℓ/∂P_m)·c_m` on a neighbour's slot, and on the own
//!   unknown `τ_max (y_s' y_s''/w ℓ φ + w φ (∂ℓ/∂P)·c + w ℓ dφ/dx)`.
//!
//! Under exact stick a held node's equation is `k (x − x_anchor) = 0` instead (`k` =
//! [`FrictionLaw::hold_stiffness`]), a sliding node's the row above with `dφ/dx = 0`
//! ([`crate::fe::newton::friction_rows`]).
//!
//! The tangent is not symmetric: its friction rows are a low-rank update of the symmetric
//! part, solved by the Woodbury identity (see [`crate::fe::linsys`]). The law is piecewise
//! smooth (stick or slip either way; open, Coulomb or Orowan threshold): each node's row is
//! kept under either regime (`FrictionRow`, assembled in
//! [`crate::fe::newton::friction_rows`]), so that the Newton step can put a node on
//! another piece of the law without reassembling, a semismooth Newton step
//! ([`crate::fe::newton::friction_step`]). With [`Interface::Frictionless`] none of this
//! is built. For linear kinematics the same law
//! acts on `u_x` at the reference position (`y_s' = 0`, `S = x`).

use crate::fe::model::material::{estar_over_g, NeoHooke};

/// Interface law between the layer and the indenter.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Interface {
    /// Adhesionless, frictionless.
    #[default]
    Frictionless,
    /// Adhesionless, regularised Coulomb–Orowan friction.
    CoulombOrowan(CoulombOrowan),
}

impl Interface {
    /// The interface for friction coefficient `μ` and shear strength `τ_max/E*`:
    /// frictionless when either is zero (`τ_sl = min(μ p, τ_max) ≡ 0`), so that no
    /// friction machinery is built for a frictionless scene.
    pub fn coulomb_orowan(
        friction_coefficient: f64,
        tau_max_over_estar: f64,
        elastic_slip_over_element: f64,
    ) -> Self {
        if friction_coefficient == 0.0 || tau_max_over_estar == 0.0 {
            Interface::Frictionless
        } else {
            Interface::CoulombOrowan(CoulombOrowan {
                friction_coefficient,
                tau_max_over_estar,
                elastic_slip_over_element,
            })
        }
    }
}

/// Regularised Coulomb–Orowan friction, `τ_sl = min(μ p, τ_max)` (docs/replication.md R3).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CoulombOrowan {
    /// Friction coefficient `μ` (> 0).
    pub friction_coefficient: f64,
    /// Interfacial shear strength over the plane-strain modulus, `τ_max/E*` (> 0).
    pub tau_max_over_estar: f64,
    /// Elastic slip at which the full threshold is mobilised, over the mean element length
    /// along the contact face (> 0). Abaqus's penalty friction uses 0.005 by default.
    pub elastic_slip_over_element: f64,
}

/// Committed friction history of one contact-face node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlipHistory {
    /// Elastic slip `e_n` at the last converged step (units of λ, `|e_n| ≤ e_c`; 0 under
    /// exact stick).
    pub elastic: f64,
    /// Current `x` at the last converged step; the step's slip is the arc length from
    /// here.
    pub anchor_x: f64,
    /// Under exact stick (`e_c = 0`), the node's piece of the law in the current iterate:
    /// held at its anchor, or sliding either way. It is part of the state because stick
    /// and slip at zero slip are both possible: the semismooth Newton step decides it
    /// ([`crate::fe::newton::friction_step`]). Under the penalty law the piece follows from
    /// `e*` ([`Branch::of`]) and this field is not read.
    pub held: Branch,
    /// Tangential force `T` at the last converged step (units `G λ` per unit depth; 0 on a
    /// node that is free or has just touched): where the next step's work of friction starts
    /// ([`FrictionLaw::commit`]).
    pub force: f64,
    /// The node was in contact at the last converged step. Such a node, released by an
    /// active-set pass of the next step and put back in contact before the step converges,
    /// keeps this history ([`crate::fe::model::Model::activate`]).
    pub in_contact: bool,
}

impl SlipHistory {
    /// No elastic slip, anchored at `x`: a node that is free or has just touched. Under
    /// exact stick it starts held; its first Newton step lets it slide if its threshold
    /// cannot hold it.
    pub(in crate::fe) fn fresh(x: f64) -> Self {
        Self {
            elastic: 0.0,
            anchor_x: x,
            held: Branch::Stick,
            force: 0.0,
            in_contact: false,
        }
    }

    /// Trial elastic slip `e* = e_n + S(x) − S_n`, given the arc length
    /// `S(x) − S_n` travelled along the indenter from the anchor.
    pub(in crate::fe) fn trial_elastic_slip(&self, arc_from_anchor: f64) -> f64 {
        self.elastic + arc_from_anchor
    }
}

/// Friction law in solver units (`G = 1`, lengths in λ).
#[derive(Clone, Copy, Debug)]
pub(in crate::fe) struct FrictionLaw {
    /// Friction coefficient `μ`.
    pub mu: f64,
    /// `τ_max/G`.
    pub tau_max: f64,
    /// Elastic slip `e_c` at which the threshold is reached (units of λ); 0 is exact
    /// stick ([`FrictionLaw::exact_stick`]).
    pub slip_c: f64,
    /// Scale `k` of a held node's row `k (x − x_anchor)` under exact stick, and of the
    /// law's complementarity residual ([`crate::fe::newton::friction_rows`]): the shear
    /// modulus (units `G`), the stiffness of a face node per unit of its displacement.
    pub hold_stiffness: f64,
}

/// Friction regime of one active node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(in crate::fe) enum Regime {
    /// `N ≤ 0`: no threshold (the node is about to be released).
    Open,
    /// `L = μ N`.
    Coulomb,
    /// `L = τ_max ℓ`.
    Orowan,
}

/// The normal force `N` of one active node at a Newton iterate, from two sets of internal
/// forces. `residual`: the displacement method's, with each element's pressure `κ (v/V − 1)`
/// of the current positions, from which the residual and the Newton step are formed.
/// `iterate`: the mixed method's, with the element pressures of the iterate
/// ([`crate::fe::model::mixed_pressure`]). The two agree at a converged state; away from it
/// the first carries `κ` times the error of the current element areas (at a full Newton step
/// of the nearly incompressible layer it dominates the residual), the second does not. Which
/// piece of the law a node is on (open, Coulomb or Orowan) is read from the iterate's, as the
/// mixed method's Newton step linearises it; the Coulomb threshold `μ N` that enters the
/// residual is the residual's, since the mixed step's right-hand side, condensed, is the
/// displacement method's (docs/performance.md, "friction's pieces from the iterate's
/// forces").
#[derive(Clone, Copy, Debug, PartialEq)]
pub(in crate::fe) struct NormalForce {
    /// From the displacement method's forces.
    pub(in crate::fe) residual: f64,
    /// From the pressure iterate's forces (the residual's where there is no iterate).
    pub(in crate::fe) iterate: f64,
}

impl NormalForce {
    /// The normal force of a state without a pressure iterate.
    pub(in crate::fe) fn converged(normal: f64) -> Self {
        Self {
            residual: normal,
            iterate: normal,
        }
    }
}

/// Friction force of one active node and what its derivatives need.
#[derive(Clone, Copy, Debug)]
pub(in crate::fe) struct FrictionEval {
    /// `y_s'`, `y_s''` at the node, `w = √(1 + y_s'²)`.
    pub(in crate::fe) s: f64,
    pub(in crate::fe) c: f64,
    pub(in crate::fe) w: f64,
    /// Trial elastic slip `e*` and its branch of the return mapping ([`Branch`]).
    pub(in crate::fe) trial_slip: f64,
    pub(in crate::fe) branch: Branch,
    /// Which bound is the threshold.
    pub regime: Regime,
    /// Tributary length `ℓ` and `∂ℓ/∂P` of the node and its two neighbours (zero where
    /// absent): `[previous, node, next]`.
    pub(in crate::fe) ell: f64,
    pub(in crate::fe) dell: [[f64; 2]; 3],
    /// Threshold `L` (units `G λ`).
    pub limit: f64,
    /// Residual contribution `w L φ`.
    pub force: f64,
}

impl FrictionEval {
    /// Whether exact stick holds this node at its anchor: stuck and not open. Its equation is
    /// then the constraint `k (x − x_anchor)` instead of its equilibrium (the friction force is
    /// the reaction); under the penalty law no node is held.
    pub(in crate::fe) fn held(&self, law: &FrictionLaw) -> bool {
        law.exact_stick() && self.branch == Branch::Stick && self.regime != Regime::Open
    }
}

impl FrictionLaw {
    /// The law of `interface` in solver units: `τ_max/G = (τ_max/E*) (E*/G)` with the
    /// material's `E*/G`, and `e_c` the given fraction of the mean element length
    /// `face_width / face_elements` along the contact face.
    pub(in crate::fe) fn in_solver_units(
        interface: &CoulombOrowan,
        mat: &NeoHooke,
        face_width: f64,
        face_elements: usize,
    ) -> Self {
        Self {
            mu: interface.friction_coefficient,
            tau_max: interface.tau_max_over_estar * estar_over_g(mat.kappa / mat.g) * mat.g,
            slip_c: interface.elastic_slip_over_element * face_width / face_elements as f64,
            hold_stiffness: mat.g,
        }
    }

    /// Whether stick is exact (`e_c = 0`): a stuck node is held at its anchor by a
    /// constraint and its friction force is the reaction, `|τ| ≤ L`; the law then has no
    /// regularisation that moves the answer.
    pub(in crate::fe) fn exact_stick(&self) -> bool {
        self.slip_c == 0.0
    }

    /// Friction force of one active node (return mapping from its committed history).
    ///
    /// `slope`, `curvature`: `y_s'`, `y_s''` under the node; `history`: the node's
    /// history and its trial elastic slip `e*` ([`SlipHistory::trial_elastic_slip`]);
    /// `node`, `neighbours`: current positions of the node and of its previous and next
    /// contact-face neighbours (if any); `normal`: the normal force `N` ([`NormalForce`]: the
    /// iterate's decides the regime, the residual's is the Coulomb threshold). Under exact stick
    /// the branch is the held one of the history, and a held node's force is its reaction,
    /// which the residual row replaces (`force` 0 here).
    pub(in crate::fe) fn eval(
        &self,
        (slope, curvature): (f64, f64),
        (history, trial_slip): (&SlipHistory, f64),
        node: [f64; 2],
        neighbours: [Option<[f64; 2]>; 2],
        normal: NormalForce,
    ) -> FrictionEval {
        let w = (1.0 + slope * slope).sqrt();
        let branch = match self.exact_stick() {
            true => history.held,
            false => Branch::of(trial_slip, self.slip_c),
        };
        let (phi, _) = branch.mobilisation(trial_slip, self.slip_c, w);
        let (ell, dell) = tributary_length(node, neighbours);
        let (regime, limit) = self.threshold(normal, ell);
        FrictionEval {
            s: slope,
            c: curvature,
            w,
            trial_slip,
            branch,
            regime,
            ell,
            dell,
            limit,
            force: w * limit * phi,
        }
    }

    /// Regime and threshold `L = min(μ N, τ_max ℓ)` (none when `N ≤ 0`): the regime by the
    /// iterate's normal force, the Coulomb threshold `μ N` by the residual's
    /// ([`NormalForce`]).
    fn threshold(&self, normal: NormalForce, ell: f64) -> (Regime, f64) {
        if normal.iterate <= 0.0 {
            (Regime::Open, 0.0)
        } else if self.mu * normal.iterate <= self.tau_max * ell {
            (Regime::Coulomb, self.mu * normal.residual)
        } else {
            (Regime::Orowan, self.tau_max * ell)
        }
    }

    /// History after a converged load step, and the work of friction in the step: on an
    /// active node (`step = Some((e*, T))`, its trial elastic slip and tangential force at the
    /// converged state) `e_{n+1} = e_c φ` (`e*` clamped to `[−e_c, e_c]`) and `S_{n+1} = S(x)`;
    /// no elastic slip on a free one (`None`). Under exact stick `e_{n+1} = 0`, and the node
    /// keeps its held piece of the law as the first guess of the next step.
    ///
    /// The work is what the face does against friction in the step, `−½ (T_n + T_{n+1}) ΔS`
    /// (units `G λ²` per unit depth), `ΔS = e* − e_n` the arc the node slid along the indenter
    /// and `T` the force opposing it: the trapezoidal rule, as the loop's work `∮ p̄ dd` is
    /// taken (docs/verification.md, "The energy audit": it converges with the load step, at
    /// first order where the slip reverses inside a step). Under the penalty law it includes
    /// the work the elastic slip stores, which returns as the node unloads, and as it lets go:
    /// a node that left contact in the step adds `½ T_n e_n` (≤ 0: its force and elastic slip
    /// fall to zero), so that a loop that only ever stuck closes with no work at the face.
    pub(in crate::fe) fn commit(
        &self,
        step: Option<(f64, f64)>,
        x: f64,
        history: &SlipHistory,
    ) -> (SlipHistory, f64) {
        let Some((trial_slip, force)) = step else {
            // let go: the force falls to zero and the elastic slip with it
            return (SlipHistory::fresh(x), 0.5 * history.force * history.elastic);
        };
        let work = -0.5 * (history.force + force) * (trial_slip - history.elastic);
        let committed = SlipHistory {
            elastic: trial_slip.clamp(-self.slip_c, self.slip_c),
            held: history.held,
            force,
            in_contact: true,
            ..SlipHistory::fresh(x)
        };
        (committed, work)
    }
}

/// Tributary length `ℓ` of a contact-face node, half of each adjacent chord of the
/// deformed face, and `∂ℓ/∂P` of `[previous, node, next]`.
fn tributary_length(node: [f64; 2], neighbours: [Option<[f64; 2]>; 2]) -> (f64, [[f64; 2]; 3]) {
    let mut ell = 0.0;
    let mut dell = [[0.0; 2]; 3];
    for (j, m) in neighbours.into_iter().enumerate() {
        let Some(pm) = m else { continue };
        let d = [pm[0] - node[0], pm[1] - node[1]];
        let len = d[0].hypot(d[1]);
        ell += 0.5 * len;
        let u = [0.5 * d[0] / len, 0.5 * d[1] / len];
        dell[2 * j] = u;
        dell[1] = [dell[1][0] - u[0], dell[1][1] - u[1]];
    }
    (ell, dell)
}

/// Branch of the return mapping that a node's trial elastic slip `e*` falls on; under
/// exact stick, the piece of the law a node is on ([`Branch::decide`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Branch {
    /// `|e*| ≤ e_c`: `φ = e*/e_c`.
    Stick,
    /// `e* > e_c`: `φ = 1`.
    SlipForward,
    /// `e* < −e_c`: `φ = −1`.
    SlipBackward,
}

impl Branch {
    /// The primal–dual active-set decision of exact stick (Hüeber, Stadler & Wohlmuth
    /// 2008; in 2D the Alart–Curnier complementarity function): a node with friction force
    /// `τ` (along `+x`), slip `s` since its anchor and threshold `L` is held where
    /// `|τ + c_t s| ≤ L` and slides the way of `τ + c_t s` otherwise. At a solution the
    /// decision is the law (a held node has `s = 0` and `|τ| ≤ L`; a sliding one `τ = ±L`
    /// with its slip the same way), whatever `c_t > 0`: `c_t` changes the Newton path, and where
    /// an increment has several solutions, which one the path reaches.
    pub(in crate::fe) fn decide(force: f64, slip: f64, limit: f64, c_t: f64) -> Self {
        let xi = force + c_t * slip;
        if xi.abs() <= limit {
            Branch::Stick
        } else if xi > 0.0 {
            Branch::SlipForward
        } else {
            Branch::SlipBackward
        }
    }

    /// `φ` of a sliding branch (`±1`), 0 when held.
    pub(in crate::fe) fn sign(self) -> f64 {
        match self {
            Branch::Stick => 0.0,
            Branch::SlipForward => 1.0,
            Branch::SlipBackward => -1.0,
        }
    }

    /// The branch of trial slip `e*` under the elastic-slip limit `e_c`. The band's edges
    /// `|e*| = e_c` belong to the slip branches (`φ` is continuous there, the tangent is the
    /// one-sided one of continued slip): a node committed while sliding sits there
    /// (`e_{n+1} = ±e_c`), and its load tangent and first Newton step then see it slide on
    /// instead of holding it on the stiff stick spring (fewer tangent assemblies:
    /// docs/performance.md, frictional speed).
    pub(in crate::fe) fn of(trial_slip: f64, slip_c: f64) -> Self {
        if trial_slip.abs() < slip_c {
            Branch::Stick
        } else if trial_slip > 0.0 {
            Branch::SlipForward
        } else {
            Branch::SlipBackward
        }
    }

    /// `φ` and `dφ/dx` of this branch's affine law at `e*` (`dS/dx = w`); on the stick
    /// branch `φ = e*/e_c` also beyond the band (the branch's own affine extension). Under
    /// exact stick (`e_c = 0`) a held node's force is its reaction, not `φ L`: `(0, 0)`.
    pub(in crate::fe) fn mobilisation(self, trial_slip: f64, slip_c: f64, w: f64) -> (f64, f64) {
        match self {
            Branch::Stick if slip_c == 0.0 => (0.0, 0.0),
            Branch::Stick => (trial_slip / slip_c, w / slip_c),
            Branch::SlipForward => (1.0, 0.0),
            Branch::SlipBackward => (-1.0, 0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `∂ℓ/∂P` of [`tributary_length`] against central differences, for an interior node
    /// and for either end of the face.
    #[test]
    fn tributary_length_derivative_matches_central_differences() {
        let node = [0.2, -0.01];
        let (prev, next) = ([0.17, -0.004], [0.235, -0.02]);
        let h = 1e-7;
        for neighbours in [
            [Some(prev), Some(next)],
            [None, Some(next)],
            [Some(prev), None],
        ] {
            let points = [neighbours[0], Some(node), neighbours[1]];
            let (_, dell) = tributary_length(node, neighbours);
            for (j, p) in points.iter().enumerate() {
                let Some(p) = *p else {
                    assert_eq!(dell[j], [0.0; 2], "absent neighbour {j}");
                    continue;
                };
                for i in 0..2 {
                    let ell_moved = |delta: f64| {
                        let mut moved = points;
                        let mut q = p;
                        q[i] += delta;
                        moved[j] = Some(q);
                        tributary_length(moved[1].expect("node"), [moved[0], moved[2]]).0
                    };
                    let fd = (ell_moved(h) - ell_moved(-h)) / (2.0 * h);
                    assert!(
                        (fd - dell[j][i]).abs() <= 1e-7,
                        "∂ℓ/∂P[{j}][{i}] = {} vs finite difference {fd}",
                        dell[j][i]
                    );
                }
            }
        }
    }

    /// Return mapping: `φ` is continuous at `|e*| = e_c` (the slip branch's edge) and
    /// saturates beyond, the threshold is `min(μ N, τ_max ℓ)`, and the committed slip is
    /// `e_c φ`.
    #[test]
    fn return_mapping_saturates_at_the_threshold() {
        let law = FrictionLaw {
            mu: 0.5,
            tau_max: 0.1,
            slip_c: 1e-3,
            hold_stiffness: 1.0,
        };
        let w = 1.2;
        let mobilisation = |e: f64| Branch::of(e, law.slip_c).mobilisation(e, law.slip_c, w);
        for sign in [1.0, -1.0] {
            // the band's edge belongs to the slip branch: φ continuous, the slip tangent
            assert_eq!(mobilisation(sign * law.slip_c), (sign, 0.0));
            assert_eq!(mobilisation(sign * 2.0 * law.slip_c), (sign, 0.0));
            let (phi, dphi) = mobilisation(sign * 0.5 * law.slip_c);
            assert_eq!((phi, dphi), (sign * 0.5, w / law.slip_c));
            // from e_n = e_c/2, slid 2.5 e_c along the indenter against a force growing from
            // 0.4 to 0.6: the trapezoidal work ½ (0.4 + 0.6) 2.5 e_c
            let before = SlipHistory {
                elastic: sign * 0.5 * law.slip_c,
                force: -sign * 0.4,
                ..SlipHistory::fresh(0.2)
            };
            let step = Some((sign * 3.0 * law.slip_c, -sign * 0.6));
            let (committed, work) = law.commit(step, 0.25, &before);
            assert_eq!(
                (committed.elastic, committed.anchor_x, committed.force),
                (sign * law.slip_c, 0.25, -sign * 0.6)
            );
            assert!((work - 0.5 * 2.5 * law.slip_c).abs() < 1e-15 * law.slip_c);
        }
        // letting go returns the work the elastic slip stored
        let before = SlipHistory {
            elastic: 0.5 * law.slip_c,
            force: -0.4,
            ..SlipHistory::fresh(0.2)
        };
        assert_eq!(
            law.commit(None, 0.25, &before),
            (SlipHistory::fresh(0.25), -0.1 * law.slip_c)
        );
        let converged = NormalForce::converged;
        assert_eq!(law.threshold(converged(-1.0), 0.02), (Regime::Open, 0.0));
        assert_eq!(
            law.threshold(converged(1e-3), 0.02),
            (Regime::Coulomb, 0.5 * 1e-3)
        );
        assert_eq!(
            law.threshold(converged(1.0), 0.02),
            (Regime::Orowan, 0.1 * 0.02)
        );
    }

    /// At an iterate the regime is the iterate's normal force's and the Coulomb threshold the
    /// residual's ([`NormalForce`]): a node the residual reads as tensile is on the Coulomb
    /// piece, with a negative threshold, where the iterate presses it; one the iterate reads as
    /// tensile is open whatever the residual says.
    #[test]
    fn the_iterate_decides_the_regime_and_the_residual_the_threshold() {
        let law = FrictionLaw {
            mu: 0.5,
            tau_max: 0.1,
            slip_c: 1e-3,
            hold_stiffness: 1.0,
        };
        let at = |residual, iterate| NormalForce { residual, iterate };
        assert_eq!(
            law.threshold(at(-2e-3, 1e-3), 0.02),
            (Regime::Coulomb, -1e-3)
        );
        assert_eq!(law.threshold(at(1e-3, -1e-3), 0.02), (Regime::Open, 0.0));
        assert_eq!(
            law.threshold(at(1e-3, 1.0), 0.02),
            (Regime::Orowan, 0.1 * 0.02)
        );
    }
}
