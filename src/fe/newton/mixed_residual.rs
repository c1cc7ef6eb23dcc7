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
//! ([`Model::iterate_constraint_forces`]). Where a pass starts from the converged state of the
//! pass before with a node released or activated, the line search measures it alone; where a pass
//! starts from the predictor's iterate, a trial passes where either it or the displacement
//! method's residual falls enough ([`FrictionMerit`]).

use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::Forces;
use crate::fe::NewtonOptions;

/// The 2-norm of `v`.
pub(crate) fn l2_norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// A line-search merit: the value of a trial state given its forces.
pub(crate) type Merit = dyn Fn(&Model, &State, &Forces) -> f64;

/// What the line search of a frictional Newton pass must decrease (a frictionless pass
/// decreases the energy where its step is a descent direction of it, else the displacement
/// method's residual).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum FrictionMerit {
    /// The displacement method's residual: a frictionless pass, a first pass from a state
    /// without a pressure iterate, or one with [`NewtonOptions::either_residual_merit`] off.
    Displacement,
    /// The mixed method's residual ([`mixed_residual_norm`]): a pass after an active-set
    /// change, started from the converged state of the pass before with its own pressures as
    /// the iterate. Alone there, as either residual measured more iterations
    /// (docs/performance.md, "either residual").
    Mixed,
    /// Either residual falling by the sufficient decrease, the displacement method's or the
    /// mixed method's: a pass that starts from the predictor's iterate. The displacement
    /// residual alone rejects full steps for `κ` times their area error, which the next step
    /// removes; the mixed residual alone accepts steps of round-off length where the pieces of
    /// the law that the step was solved on are not the ones it lands on, and the pass stalls
    /// (docs/performance.md, "either residual").
    Either,
}

impl FrictionMerit {
    /// The merit of a pass after an active-set change (`after_change`) or not, from a state
    /// with a pressure iterate (`has_iterate`) or not.
    pub(crate) fn for_pass(
        model: &Model,
        opts: &NewtonOptions,
        after_change: bool,
        has_iterate: bool,
    ) -> Self {
        if model.is_potential() || !opts.pressure_iterate {
            FrictionMerit::Displacement
        } else if after_change {
            FrictionMerit::Mixed
        } else if has_iterate && opts.either_residual_merit {
            FrictionMerit::Either
        } else {
            FrictionMerit::Displacement
        }
    }

    /// The merit at the start of a Newton iteration, `st` with forces `f`, and the merit of a
    /// trial state. [`FrictionMerit::Either`] measures each residual relative to its value at
    /// `st`, and a trial by the smaller ratio (its start value 1): the line search's test
    /// `m(α) < (1 − c α) m(0)` then passes where either residual passes it.
    pub(crate) fn at(self, model: &Model, st: &State, f: &Forces) -> (f64, Box<Merit>) {
        match self {
            FrictionMerit::Displacement => {
                (l2_norm(&f.resid), Box::new(|_, _, ft| l2_norm(&ft.resid)))
            }
            FrictionMerit::Mixed => (
                mixed_residual_norm(model, st, f),
                Box::new(mixed_residual_norm),
            ),
            FrictionMerit::Either => {
                let start = [l2_norm(&f.resid), mixed_residual_norm(model, st, f)];
                let ratio = |norm: f64, at_start: f64| match at_start > 0.0 {
                    true => norm / at_start,
                    false => f64::INFINITY,
                };
                let merit = move |m: &Model, t: &State, ft: &Forces| {
                    let displacement = ratio(l2_norm(&ft.resid), start[0]);
                    displacement.min(ratio(mixed_residual_norm(m, t, ft), start[1]))
                };
                (1.0, Box::new(merit))
            }
        }
    }
}

/// The 2-norm of the mixed method's residual at `st`, given its assembled `forces`; the
/// displacement method's residual `‖forces.resid‖₂` where `st` has no pressure iterate.
pub(crate) fn mixed_residual_norm(model: &Model, st: &State, forces: &Forces) -> f64 {
    let Some(iterate) = model.iterate_forces(st, &forces.grad) else {
        return l2_norm(&forces.resid);
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
