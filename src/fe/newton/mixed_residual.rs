//! The residual of a Newton iterate in the mixed method's own variables: what the line search of
//! a frictional pass that starts after an active-set change measures.
//!
//! The displacement method's residual carries each element's pressure `κ (v/V − 1)` of the
//! current positions, and with it `κ` times the error of the current element areas: an element's
//! area is quadratic in its nodes, so a full Newton step of the nearly incompressible layer leaves
//! an area error of the order of the square of the step, and the residual at the step's end is
//! dominated by `κ` times it (docs/performance.md measures by how much), though the step is the
//! mixed method's Newton step and the next one removes it. The backtracking line search then cuts
//! the step to a fraction for many iterations.
//! Measured in the mixed method's variables the residual is the displacement equations with the
//! iterate's pressures (their friction forces read from the same forces,
//! [`crate::fe::contact::friction::NormalForce`]) and each element's constraint
//! `v/V − 1 − p/κ` at the size the shear modulus gives a strain error
//! ([`Model::iterate_constraint_forces`]). Used only where a pass starts from the converged state
//! of the pass before with a node released or activated: the first pass of a step starts from the
//! predictor, where the displacement residual's merit measured fewer iterations
//! (docs/performance.md, "friction's pieces from the iterate's forces").

use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::Forces;

/// The 2-norm of the mixed method's residual at `st`, given its assembled `forces`; the
/// displacement method's residual `‖forces.resid‖₂` where `st` has no pressure iterate.
pub(crate) fn mixed_residual_norm(model: &Model, st: &State, forces: &Forces) -> f64 {
    let Some(iterate) = model.iterate_forces(st, &forces.grad) else {
        return forces.resid.iter().map(|r| r * r).sum::<f64>().sqrt();
    };
    let map = model.slot_map(st);
    let mut resid = forces.resid.clone();
    // a node that exact stick holds keeps its constraint row, which no pressure enters; the
    // others' friction forces are read from the iterate's forces
    let mut held = vec![false; resid.len()];
    let mut friction_change = Vec::new();
    if let Some(law) = model.friction {
        for (k, &n) in model.mesh.bottom.iter().enumerate() {
            if !st.active[k] || map[n][0].is_none() {
                continue;
            }
            let in_residual = model.friction_eval(st, k, (&forces.grad, Some(&iterate)), &law);
            held[2 * n] = in_residual.held(&law);
            if !held[2 * n] {
                let on_iterate = model.friction_eval(st, k, (&iterate, None), &law);
                friction_change.push((2 * n, on_iterate.force - in_residual.force));
            }
        }
    }
    for (n, slots) in map.iter().enumerate() {
        for (s, slot) in slots.iter().enumerate() {
            let Some(c) = slot else { continue };
            if held[2 * n + s] {
                continue;
            }
            let dx = forces.grad[2 * n] - iterate[2 * n];
            let dy = forces.grad[2 * n + 1] - iterate[2 * n + 1];
            resid[2 * n + s] -= c[0] * dx + c[1] * dy;
        }
    }
    for (row, change) in friction_change {
        resid[row] += change;
    }
    let constraint = model.iterate_constraint_forces(st);
    let squares: f64 = resid.iter().chain(&constraint).map(|r| r * r).sum();
    squares.sqrt()
}
