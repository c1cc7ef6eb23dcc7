//! The element pressures of the mixed (Q1/P0) method as a Newton iterate.
//!
//! The element's volumetric energy `V κ/2 (v/V − 1)²` is the mean-dilatation element with its
//! pressure `p = κ (v/V − 1)` condensed out ([`crate::fe::model::element`]). Condensed at the
//! current positions, `p` carries `κ` times any error of the current area, and its geometric
//! stiffness `p ∇²v` with it: at a predicted state of the nearly incompressible layer (κ/G 1000)
//! the elements by the contact edge carry pressure errors of several `G`, and the tangent there
//! is not the solution's. Kept as an unknown of its own, as the mixed method keeps it, the
//! pressure is linearised instead (`p ← κ (v/V − 1) + κ ∇v·δx / V` after a step `δx`) and
//! predicted along the load path from its own derivatives, which are free of that `κ`.
//!
//! The residual is the displacement method's, `∂Π/∂x` with `κ (v/V − 1)`, whatever the pressure
//! iterate: the two methods share their equations and their converged states. The iterate
//! changes the tangent a Newton step is solved with, the piece of the friction law each node is
//! on ([`crate::fe::contact::friction::NormalForce`]), and what the line search of a pass after
//! an active-set change measures ([`crate::fe::newton::mixed_residual`]).

use crate::fe::model::element::{area_gradient, shoelace};
use crate::fe::model::{Model, Role, State};
use crate::fe::Kinematics;

impl State {
    /// The state with the pressure iterate `pressure` ([`State::pressure`]).
    pub(crate) fn with_pressure(self, pressure: Option<Vec<f64>>) -> Self {
        Self { pressure, ..self }
    }

    /// Whether `other` has this state's forces: the same in everything but the pressure
    /// iterate, which only the tangent reads.
    pub(crate) fn same_forces(&self, other: &State) -> bool {
        // every field named, so that a field added to the state is decided here
        let State {
            x,
            active,
            d,
            dx,
            slip,
            friction_work,
            pressure: _,
        } = self;
        *x == other.x
            && *active == other.active
            && *d == other.d
            && *dx == other.dx
            && *slip == other.slip
            && *friction_work == other.friction_work
    }
}

impl Model {
    /// `κ (v/V − 1)` of element `e` at `st` and the gradient `∂v/∂x` of its area.
    fn condensed_pressure(&self, st: &State, e: usize) -> (f64, [f64; 8]) {
        let x = self.elem_x(st, e);
        let area = self.refs[e].area;
        (
            self.mat.kappa * (shoelace(&x) / area - 1.0),
            area_gradient(&x),
        )
    }

    /// The internal forces `∂Π/∂x` of `st` with each element's volumetric force taken at the
    /// pressure iterate instead of `κ (v/V − 1)`: `grad` (the displacement method's) less
    /// `(κ (v/V − 1) − p) ∇v` per element. The mixed method's forces, free of `κ` times the
    /// error of the current areas; the friction law reads its pieces from them
    /// ([`crate::fe::contact::friction::NormalForce`]). `None` without an iterate.
    pub(crate) fn iterate_forces(&self, st: &State, grad: &[f64]) -> Option<Vec<f64>> {
        let iterate = st.pressure.as_ref()?;
        let mut forces = grad.to_vec();
        for (e, &p) in iterate.iter().enumerate() {
            let (condensed, dv) = self.condensed_pressure(st, e);
            for (a, &n) in self.mesh.quads[e].iter().enumerate() {
                forces[2 * n] -= dv[2 * a] * (condensed - p);
                forces[2 * n + 1] -= dv[2 * a + 1] * (condensed - p);
            }
        }
        Some(forces)
    }

    /// The constraint residual of the mixed method per element, `v/V − 1 − p/κ` (the iterate's
    /// pressure against the current area), each times `G |∇v|`, so that it reads as a force
    /// of the size the shear modulus gives a strain error: the part of
    /// [`crate::fe::newton::mixed_residual`] that the displacement method folds into its
    /// residual multiplied by `κ` instead. Empty without an iterate.
    pub(crate) fn iterate_constraint_forces(&self, st: &State) -> Vec<f64> {
        let Some(iterate) = st.pressure.as_ref() else {
            return Vec::new();
        };
        (iterate.iter().enumerate())
            .map(|(e, &p)| {
                let (condensed, dv) = self.condensed_pressure(st, e);
                let dv_norm = dv.iter().map(|d| d * d).sum::<f64>().sqrt();
                self.mat.g * (condensed - p) / self.mat.kappa * dv_norm
            })
            .collect()
    }

    /// `st` given a pressure iterate at its own element pressures `κ (v/V − 1)`, where it has
    /// none, under finite kinematics: the start of a Newton solve from a converged state (the
    /// pass after an active-set change), whose steps then carry it ([`Self::carry_pressure`]).
    pub(crate) fn start_pressure_iterate(&self, st: &mut State) {
        if st.pressure.is_some() || self.kin != Kinematics::Finite {
            return;
        }
        let pressure = (0..self.mesh.quads.len())
            .map(|e| self.condensed_pressure(st, e).0)
            .collect();
        st.pressure = Some(pressure);
    }

    /// The pressure iterate after the step from `from` to `to` taken at the fraction `alpha`
    /// of a Newton step: each element's `(1 − α) p + α κ (v/V − 1) + κ ∇v·(x_to − x_from)/V`,
    /// the linearisation of the mixed method's pressure equation, all at `from`. Nothing where
    /// `from` has no pressure iterate.
    pub(crate) fn carry_pressure(&self, from: &State, to: &mut State, alpha: f64) {
        let Some(old) = from.pressure.as_ref() else {
            return;
        };
        let pressure = (0..self.mesh.quads.len())
            .map(|e| {
                let (condensed, dv) = self.condensed_pressure(from, e);
                let moved: f64 = (self.mesh.quads[e].iter().enumerate())
                    .map(|(a, &n)| {
                        dv[2 * a] * (to.x[n][0] - from.x[n][0])
                            + dv[2 * a + 1] * (to.x[n][1] - from.x[n][1])
                    })
                    .sum();
                (1.0 - alpha) * old[e]
                    + alpha * condensed
                    + self.mat.kappa * moved / self.refs[e].area
            })
            .collect();
        to.pressure = Some(pressure);
    }

    /// The element pressures at the slab displacement `cur.d + dd` along the load path of the
    /// converged state `cur`, from the path's slot-wise derivatives `rate = ∂q/∂d` and, where
    /// known, `curvature = ∂²q/∂d²`: to first order `p + p′ dd` and, with the curvature, to
    /// second order `p + p′ dd + ½ p″ dd²`, where `p′ = κ ∇v·ẋ / V` and
    /// `p″ = κ (ẋ·∇²v ẋ + ∇v·ẍ) / V`, `ẋ`, `ẍ` the nodes' velocities and accelerations along
    /// the path. `None` under linear kinematics, whose tangent has no geometric term.
    pub(crate) fn predicted_pressure(
        &self,
        cur: &State,
        rate: &[f64],
        curvature: Option<&[f64]>,
        dd: f64,
    ) -> Option<PredictedPressure> {
        if self.kin != Kinematics::Finite {
            return None;
        }
        let velocity = self.node_velocities(cur, rate);
        let acceleration = curvature.map(|w| self.node_accelerations(cur, w, &velocity));
        let (mut first_order, mut second_order) = (Vec::new(), Vec::new());
        for e in 0..self.mesh.quads.len() {
            let (p, dv) = self.condensed_pressure(cur, e);
            let q = self.mesh.quads[e];
            let along = |m: &[[f64; 2]]| -> f64 {
                (0..4)
                    .map(|a| dv[2 * a] * m[q[a]][0] + dv[2 * a + 1] * m[q[a]][1])
                    .sum()
            };
            let scale = self.mat.kappa / self.refs[e].area;
            let first = p + scale * along(&velocity) * dd;
            first_order.push(first);
            if let Some(acc) = &acceleration {
                let ve = q.map(|n| velocity[n]);
                let second = scale * (2.0 * shoelace(&ve) + along(acc));
                second_order.push(first + 0.5 * second * dd * dd);
            }
        }
        Some(PredictedPressure {
            first_order,
            second_order: acceleration.map(|_| second_order),
        })
    }

    /// The slot vector `z` as node motions `Σ_s c_s z_s` along each node's slots.
    fn slot_motion(&self, st: &State, z: &[f64]) -> Vec<[f64; 2]> {
        let map = self.slot_map(st);
        (0..self.mesh.nodes.len())
            .map(|n| {
                let mut m = [0.0; 2];
                for (s, slot) in map[n].iter().enumerate() {
                    if let Some(c) = slot {
                        m[0] += c[0] * z[2 * n + s];
                        m[1] += c[1] * z[2 * n + s];
                    }
                }
                m
            })
            .collect()
    }

    /// The nodes' velocities `ẋ` along the load path from `rate = ∂q/∂d`: the top moving down
    /// with the slab, an active face node along the indenter.
    fn node_velocities(&self, st: &State, rate: &[f64]) -> Vec<[f64; 2]> {
        let mut velocity = self.slot_motion(st, rate);
        for (n, v) in velocity.iter_mut().enumerate() {
            if self.role[n] == Role::Top {
                v[1] = -1.0;
            }
        }
        velocity
    }

    /// The nodes' accelerations `ẍ` along the load path from `curvature = ∂²q/∂d²` and the
    /// velocities: an active face node also turning with the indenter, `ÿ = y_s′ ẍ + y_s″ ẋ²`.
    fn node_accelerations(
        &self,
        st: &State,
        curvature: &[f64],
        velocity: &[[f64; 2]],
    ) -> Vec<[f64; 2]> {
        let mut acceleration = self.slot_motion(st, curvature);
        for (k, &n) in self.mesh.bottom.iter().enumerate() {
            if st.active[k] && self.role[n] == Role::Bottom {
                let vx = velocity[n][0];
                acceleration[n][1] += self.indenter.curvature(st.x[n][0]) * vx * vx;
            }
        }
        acceleration
    }
}

/// The element pressures a predictor predicts ([`Model::predicted_pressure`]): to first order,
/// and to second order where the path's curvature is known.
pub(crate) struct PredictedPressure {
    /// `p + p′ dd`, per element (units `G`).
    pub first_order: Vec<f64>,
    /// `p + p′ dd + ½ p″ dd²`, per element (units `G`).
    pub second_order: Option<Vec<f64>>,
}

#[cfg(test)]
mod tests {
    use crate::fe::model::element::shoelace;
    use crate::fe::model::{Model, State};
    use crate::fe::stepping::predictor::{load_tangent, predictor};
    use crate::fe::stepping::test_fixtures::loaded_sinusoid;
    use crate::fe::stepping::touched_hold::TouchedNodes;

    /// Each element's `κ (v/V − 1)` at `st`.
    fn condensed(model: &Model, st: &State) -> Vec<f64> {
        (0..model.mesh.quads.len())
            .map(|e| model.condensed_pressure(st, e).0)
            .collect()
    }

    /// The position of the outermost contact-face node in contact (units of λ).
    fn edge_x(model: &Model, st: &State) -> f64 {
        let last = st.active.iter().rposition(|&a| a).unwrap_or(0);
        st.x[model.mesh.bottom[last]][0]
    }

    fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
    }

    /// Along the frictionless AR 0.3 path (coarse mesh, κ/G 1000, from each of the events at
    /// a/λ ≈ 0.1, 0.2 and 0.3 to the next), the pressures predicted from the path's own
    /// derivatives are within 0.007–0.02 G of the next event's (asserted 0.03 G), where the
    /// pressures condensed at the predicted positions, which carry `κ` times the positions'
    /// error, are 8–17 G off: 830–1240 times further (asserted 500), the order of κ/G.
    #[test]
    fn the_predicted_pressures_are_closer_than_the_condensed_ones() {
        let (model, mut asm, _, states) = loaded_sinusoid(0.3, 0.35);
        for target in [0.1, 0.2, 0.3] {
            let i = (states.iter())
                .position(|s| edge_x(&model, s) >= target)
                .expect("an event beyond the target");
            let (from, next) = (&states[i], &states[i + 1]);
            let tangent = load_tangent(&model, &mut asm, from, TouchedNodes::Held, None)
                .expect("a converged state");
            let dd = next.d - from.d;
            let predicted =
                predictor(&model, from, None, dd, Some(&tangent)).expect("not inverted");
            let truth = condensed(&model, next);
            let iterate = predicted.pressure.as_deref().expect("predicted pressures");
            let own = largest_difference(iterate, &truth);
            let at_positions = largest_difference(&condensed(&model, &predicted), &truth);
            eprintln!(
                "a/λ {target}: pressure error predicted {own:.3e} G, condensed at the predicted \
                 positions {at_positions:.3e} G (ratio {:.1})",
                at_positions / own
            );
            assert!(own <= 0.03, "a/λ {target}: {own} G");
            assert!(
                500.0 * own < at_positions,
                "a/λ {target}: {own} against {at_positions}"
            );
        }
    }

    /// The carried pressure is the linearisation of `κ (v/V − 1)` about the state a step starts
    /// from: after a full step `δ` it differs from the condensed pressure at the new positions by
    /// exactly `κ δᵀ∇²v δ / (2V)`, the second-order part of the bilinear area, and a step of zero
    /// length at `α = 0` keeps the iterate.
    #[test]
    fn the_carried_pressure_is_the_linearised_one() {
        let (model, _, _, states) = loaded_sinusoid(0.3, 0.2);
        let (from, to) = (&states[states.len() - 2], &states[states.len() - 1]);
        let start = vec![0.25; model.mesh.quads.len()];
        let from = from.clone().with_pressure(Some(start.clone()));
        let mut kept = from.clone();
        model.carry_pressure(&from, &mut kept, 0.0);
        assert_eq!(kept.pressure.as_deref(), Some(&start[..]));
        let mut stepped = to.clone();
        model.carry_pressure(&from, &mut stepped, 1.0);
        let carried = stepped.pressure.expect("carried");
        let kappa = model.mat.kappa;
        for (e, (p, c)) in carried.iter().zip(condensed(&model, to)).enumerate() {
            let q = model.mesh.quads[e];
            let step = q.map(|n| [to.x[n][0] - from.x[n][0], to.x[n][1] - from.x[n][1]]);
            let second_order = kappa * shoelace(&step) / model.refs[e].area;
            assert!(
                (p - (c - second_order)).abs() <= 1e-9 * kappa,
                "element {e}: carried {p}, condensed {c}, second-order part {second_order}"
            );
        }
    }
}
