//! The tangential half of a frictional increment: the shear traction `q` on the grid that
//! minimises `½ qᵀ K q + qᵀ b` subject to `|q_i| ≤ f_i`, by a primal–dual active set (Hintermüller,
//! Ito & Kunisch, SIAM J. Optim. 13, 865, 2002) whose linear solves are conjugate gradients on
//! the points that stick.
//!
//! The gradient `K q + b` is the increment of the surface's tangential displacement over the
//! increment, the slip against the rigid surface (which does not move sideways: the profile is
//! even, so `q` is odd and has no resultant). Its optimality conditions are the Coulomb–Orowan
//! law of the increment: where `|q_i| < f_i` the point sticks (no slip); where `q_i = ±f_i` it
//! slips against the traction (`q_i · slip_i ≤ 0`); `f_i = 0` off the contact keeps `q = 0`
//! there. `K` is positive definite on zero-mean grid functions, so the minimiser is unique.
//!
//! One outer iteration: with every point's status fixed (stuck, or slipping at `+f` or `−f`),
//! the stuck points' shear solves `slip = 0` there (conjugate gradients with the slipping and
//! free points' shear held); then every status is decided again at once: a stuck point whose
//! shear exceeds its bound slips at it, a slipping point whose slip turned against its traction
//! sticks. It ends when no status changes and the conditions hold to `slip_tol`.

use super::grid::GridCompliance;
use super::polonsky_keer::Stalled;

/// A converged tangential solution.
pub(super) struct ShearSolution {
    /// `q/E*` on the grid.
    pub(super) shear: Vec<f64>,
    /// The slip of the increment, `K q + b` (λ).
    pub(super) slip: Vec<f64>,
    /// Conjugate-gradient iterations over all outer iterations.
    pub(super) iterations: usize,
}

/// A point's status in the active set.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Status {
    /// Off the contact (`f = 0`): `q = 0`.
    Free,
    /// Sticking: `q` unknown, slip 0.
    Stuck,
    /// Slipping with `q = +f` (`+1`) or `q = −f` (`−1`).
    Slipping(i8),
}

/// The most outer iterations (each a full set of status changes).
const MAX_OUTER: usize = 200;

/// Solves the box-constrained problem of the module doc from `q` (its statuses read from it:
/// at or beyond a bound, slipping there). `bound` is `f ≥ 0` (E*), `b` the slip at `q = 0` (λ).
pub(super) fn solve(
    mut q: Vec<f64>,
    b: &[f64],
    bound: &[f64],
    k_op: &mut GridCompliance,
    slip_tol: f64,
    max_iterations: usize,
) -> Result<ShearSolution, Stalled> {
    let n = b.len();
    let mut status: Vec<Status> = q
        .iter()
        .zip(bound)
        .map(|(&qi, &f)| initial_status(qi, f))
        .collect();
    let mut slip = vec![0.0; n];
    let mut iterations = 0;
    for _ in 0..MAX_OUTER {
        hold(&mut q, &status, bound);
        iterations +=
            stick_solve(&mut q, &status, b, k_op, slip_tol, max_iterations).map_err(|s| {
                Stalled {
                    iterations: iterations + s.iterations,
                    ..s
                }
            })?;
        k_op.apply(&q, &mut slip);
        slip.iter_mut().zip(b).for_each(|(s, &bi)| *s += bi);
        let changed = update_status(&mut status, &q, &slip, bound, slip_tol);
        if !changed {
            return Ok(ShearSolution {
                shear: q,
                slip,
                iterations,
            });
        }
    }
    Err(Stalled {
        iterations,
        residual: f64::NAN,
        reason: "the stick–slip statuses kept changing (shear)",
    })
}

/// The status a shear `q` under the bound `f` starts from.
fn initial_status(q: f64, f: f64) -> Status {
    if f <= 0.0 {
        Status::Free
    } else if q >= f {
        Status::Slipping(1)
    } else if q <= -f {
        Status::Slipping(-1)
    } else {
        Status::Stuck
    }
}

/// Sets the shear the statuses prescribe: 0 off the contact, `±f` where slipping.
fn hold(q: &mut [f64], status: &[Status], bound: &[f64]) {
    for ((qi, s), &f) in q.iter_mut().zip(status).zip(bound) {
        match s {
            Status::Free => *qi = 0.0,
            Status::Slipping(sign) => *qi = f64::from(*sign) * f,
            Status::Stuck => {}
        }
    }
}

/// The stuck points' shear that makes their slip vanish, the others held: conjugate gradients
/// on `K_SS q_S = −(b + K q_held)_S` from the current values, to `slip_tol` in the largest
/// stuck slip. Returns the iterations.
fn stick_solve(
    q: &mut [f64],
    status: &[Status],
    b: &[f64],
    k_op: &mut GridCompliance,
    slip_tol: f64,
    max_iterations: usize,
) -> Result<usize, Stalled> {
    let n = q.len();
    let stuck: Vec<bool> = status.iter().map(|s| *s == Status::Stuck).collect();
    let mut residual = vec![0.0; n];
    k_op.apply(q, &mut residual);
    // r = −slip on the stuck points (the descent direction), 0 elsewhere
    for i in 0..n {
        residual[i] = if stuck[i] { -(residual[i] + b[i]) } else { 0.0 };
    }
    let mut direction = residual.clone();
    let mut k_direction = vec![0.0; n];
    let mut norm = dot(&residual, &residual);
    let mut largest = max_abs(&residual);
    for iteration in 0..max_iterations {
        if largest <= slip_tol {
            return Ok(iteration);
        }
        k_op.apply(&direction, &mut k_direction);
        k_direction
            .iter_mut()
            .zip(&stuck)
            .for_each(|(v, &s)| *v = if s { *v } else { 0.0 });
        let step = norm / dot(&direction, &k_direction);
        if !step.is_finite() {
            break;
        }
        for i in 0..n {
            q[i] += step * direction[i];
            residual[i] -= step * k_direction[i];
        }
        let next = dot(&residual, &residual);
        let ratio = next / norm;
        norm = next;
        for i in 0..n {
            direction[i] = residual[i] + ratio * direction[i];
        }
        largest = max_abs(&residual);
    }
    Err(Stalled {
        iterations: max_iterations,
        residual: largest / slip_tol,
        reason: "iteration cap reached (shear of the stick zone)",
    })
}

/// Decides every status again from the new shear and slip (module doc; a slip against the
/// traction within `slip_tol` is round-off and keeps the point slipping); returns whether any
/// changed.
fn update_status(
    status: &mut [Status],
    q: &[f64],
    slip: &[f64],
    bound: &[f64],
    slip_tol: f64,
) -> bool {
    let mut changed = false;
    for i in 0..q.len() {
        let f = bound[i];
        let next = match status[i] {
            Status::Free => Status::Free,
            Status::Stuck if q[i] > f => Status::Slipping(1),
            Status::Stuck if q[i] < -f => Status::Slipping(-1),
            Status::Stuck => Status::Stuck,
            // slipping at +f needs slip ≤ 0, at −f slip ≥ 0
            Status::Slipping(sign) if f64::from(sign) * slip[i] > slip_tol => Status::Stuck,
            Status::Slipping(sign) => Status::Slipping(sign),
        };
        changed |= next != status[i];
        status[i] = next;
    }
    changed
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn max_abs(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m: f64, x| m.max(x.abs()))
}
