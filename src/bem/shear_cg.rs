//! The tangential half of a frictional increment: the shear traction `q` on the grid that
//! minimises `½ qᵀ K q + qᵀ b` subject to `|q_i| ≤ f_i`, by a conjugate gradient on the points
//! off their bound, projected onto the box (the bound-constrained counterpart of
//! [`super::polonsky_keer`]).
//!
//! The gradient `K q + b` is the increment of the surface's tangential displacement over the
//! increment, the slip against the rigid surface (which does not move sideways: the profile is
//! even, so `q` is odd and has no resultant). Its optimality conditions are the
//! Coulomb–Orowan law of the increment: where `|q_i| < f_i` the point sticks (no slip); where
//! `q_i = ±f_i` it slips against the traction (`q_i · slip_i ≤ 0`); `f_i = 0` off the contact
//! keeps `q = 0` there. `K` is positive definite on zero-mean grid functions, so the minimiser
//! is unique.
//!
//! One iteration: the points that may move (inside their bound, or on it with the gradient
//! pointing inside) take a conjugate-gradient step with the exact line search; values beyond a
//! bound are set to it, which restarts the conjugacy. Stopping rule: the largest slip of a point
//! that may move is at most `slip_tol` (the optimality conditions hold to that tolerance).

use super::grid::GridCompliance;
use super::polonsky_keer::Stalled;

/// A converged tangential solution.
pub(super) struct ShearSolution {
    /// `q/E*` on the grid.
    pub(super) shear: Vec<f64>,
    /// The slip of the increment, `K q + b` (λ).
    pub(super) slip: Vec<f64>,
    pub(super) iterations: usize,
}

/// Solves the box-constrained problem of the module doc from `q` (projected onto the box
/// first). `bound` is `f ≥ 0` (E*), `b` the slip at `q = 0` (λ).
pub(super) fn solve(
    mut q: Vec<f64>,
    b: &[f64],
    bound: &[f64],
    k_op: &mut GridCompliance,
    slip_tol: f64,
    max_iterations: usize,
) -> Result<ShearSolution, Stalled> {
    let n = b.len();
    for (qi, &fi) in q.iter_mut().zip(bound) {
        *qi = qi.clamp(-fi, fi);
    }
    let mut slip = vec![0.0; n];
    let mut direction = vec![0.0; n];
    let mut k_direction = vec![0.0; n];
    let mut free = vec![false; n];
    let mut last_norm = 1.0;
    let mut conjugate = false;
    let mut residual = f64::INFINITY;
    for iteration in 0..max_iterations {
        k_op.apply(&q, &mut slip);
        slip.iter_mut().zip(b).for_each(|(s, &bi)| *s += bi);
        let changed = classify(&mut free, &q, &slip, bound);
        residual = max_free_slip(&free, &slip);
        if !residual.is_finite() {
            break;
        }
        if residual <= slip_tol {
            return Ok(ShearSolution {
                shear: q,
                slip,
                iterations: iteration,
            });
        }
        last_norm = conjugate_direction(
            &mut direction,
            &slip,
            &free,
            conjugate && !changed,
            last_norm,
        );
        k_op.apply(&direction, &mut k_direction);
        let step = exact_step(&direction, &slip, &k_direction, &free);
        conjugate = !step_and_project(&mut q, &direction, step, bound);
    }
    Err(Stalled {
        iterations: max_iterations,
        residual: residual / slip_tol,
        reason: if residual.is_finite() {
            "iteration cap reached (shear)"
        } else {
            "non-finite slip (shear)"
        },
    })
}

/// Marks the points that may move: inside their bound, or on it with the slip pointing back
/// inside (`q_i = f_i > 0` and slip > 0, the descent `−slip` lowering `q_i`; likewise below).
/// Returns whether the set changed.
fn classify(free: &mut [bool], q: &[f64], slip: &[f64], bound: &[f64]) -> bool {
    let mut changed = false;
    for i in 0..q.len() {
        let f = bound[i];
        let may_move = f > 0.0
            && (q[i].abs() < f || (q[i] >= f && slip[i] > 0.0) || (q[i] <= -f && slip[i] < 0.0));
        changed |= may_move != free[i];
        free[i] = may_move;
    }
    changed
}

/// The largest `|slip|` among the points that may move (0 when none may).
fn max_free_slip(free: &[bool], slip: &[f64]) -> f64 {
    free.iter()
        .zip(slip)
        .filter(|(&f, _)| f)
        .fold(0.0, |m: f64, (_, s)| m.max(s.abs()))
}

/// `t = slip + γ t` on the points that may move (zero elsewhere; `γ = 0` unless `conjugate`);
/// returns the squared norm of the slip there, the next call's `last_norm`.
fn conjugate_direction(
    t: &mut [f64],
    slip: &[f64],
    free: &[bool],
    conjugate: bool,
    last_norm: f64,
) -> f64 {
    let norm: f64 = free
        .iter()
        .zip(slip)
        .filter(|(&f, _)| f)
        .map(|(_, s)| s * s)
        .sum();
    let gamma = if conjugate { norm / last_norm } else { 0.0 };
    for i in 0..t.len() {
        t[i] = if free[i] { slip[i] + gamma * t[i] } else { 0.0 };
    }
    norm
}

/// The minimising step along `−t`: `(slip·t)/(t·K t)`, or 0 when that is not finite and
/// positive (then the projection has nothing to do and the next iteration restarts).
fn exact_step(t: &[f64], slip: &[f64], k_t: &[f64], free: &[bool]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..t.len() {
        if free[i] {
            num += slip[i] * t[i];
            den += k_t[i] * t[i];
        }
    }
    let step = num / den;
    if step.is_finite() && step > 0.0 {
        step
    } else {
        0.0
    }
}

/// `q ← clamp(q − step·t, −f, f)`; returns whether any value was clamped.
fn step_and_project(q: &mut [f64], t: &[f64], step: f64, bound: &[f64]) -> bool {
    let mut clamped = false;
    for i in 0..q.len() {
        if t[i] != 0.0 {
            let stepped = q[i] - step * t[i];
            let f = bound[i];
            clamped |= stepped.abs() > f;
            q[i] = stepped.clamp(-f, f);
        }
    }
    clamped
}
