//! The constrained conjugate-gradient method of Polonsky & Keer (Wear 231, 206–219, 1999) for the
//! frictionless contact of a rigid surface on an elastic body under a given mean pressure.
//!
//! Unknown: the grid pressure `p ≥ 0` with `mean(p) = p̄`. The gap is `g = s + K p − δ`, where
//! `s ≥ 0` is the rigid surface's depth below its peak, `K` the zero-mean compliance
//! ([`GridCompliance`]) and `δ` the rigid approach, fixed on the way as the mean of `s + K p`
//! over the contact set `{p > 0}`. One iteration: a conjugate-gradient step on the contact set
//! (the gradient of the energy ½ pᵀKp + pᵀs there is `g`), pressures that turn negative set to
//! zero, points out of contact that overlap (`g < 0`) brought back in (and the conjugacy
//! restarted), then the pressures rescaled to the mean `p̄`.
//!
//! A step that clamps no pressure and brings no point back in changes the pressure linearly, so
//! the displacement is then updated from the step's own `K t` instead of a new FFT pair (this
//! halves the work once the contact set has settled); it is recomputed from the pressure every
//! 32 iterations and always before an answer is accepted.
//!
//! Stopping rule (on the pressure whose gap was just computed from it, so what is returned is
//! consistent): `|g| ≤ tol·Σ Δ_k` on the contact set and `g ≥ −tol·Σ Δ_k` off it; `p ≥ 0` and
//! `mean(p) = p̄` hold by construction.

use super::grid::GridCompliance;

/// A converged grid solution.
pub(super) struct GridSolution {
    pub(super) pressure: Vec<f64>,
    pub(super) gap: Vec<f64>,
    pub(super) approach: f64,
    pub(super) iterations: usize,
}

/// Why the iteration stopped without an answer.
pub(super) struct Stalled {
    pub(super) iterations: usize,
    /// The last complementarity residual (units of the tolerance).
    pub(super) residual: f64,
    pub(super) reason: &'static str,
}

/// Where the displacement `K p` stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum DisplacementState {
    /// Just computed from the pressure.
    Fresh,
    /// Updated linearly this many times since.
    Updated(u32),
    /// To be computed.
    Stale,
}

/// Solves for the pressure on the grid (see the module doc). `s` is the rigid depth below the
/// peak (λ), `p_mean` the mean pressure (E*), `gap_tol` the absolute gap tolerance (λ). The
/// iteration starts from the uniform pressure, or from `initial` (non-negative, a positive sum;
/// rescaled to the mean first): a nearby solution's pressure, so that a sequence of close
/// problems (the frictional solver's alternation, [`super::frictional_contact`]) starts each
/// from the last.
pub(super) fn solve(
    initial: Option<Vec<f64>>,
    s: &[f64],
    p_mean: f64,
    k_op: &mut GridCompliance,
    gap_tol: f64,
    max_iterations: usize,
) -> Result<GridSolution, Stalled> {
    let mut p = match initial {
        Some(mut p) => match rescale_to_mean(&mut p, p_mean) {
            Some(_) => p,
            None => vec![p_mean; s.len()],
        },
        None => vec![p_mean; s.len()],
    };
    let n = s.len();
    let mut t = vec![0.0; n];
    let mut g = vec![0.0; n];
    let mut r = vec![0.0; n];
    // u = K p, computed afresh (`Fresh`), updated linearly (`Updated(count)`), or stale
    let mut u = vec![0.0; n];
    let mut u_state = DisplacementState::Stale;
    let mut g_norm_old = 1.0;
    let mut conjugate = false;
    let mut residual = f64::INFINITY;
    // The step for the overlap correction if the contact set leaves no descent direction.
    let fallback_step = 1.0 / k_op.diagonal();
    for iteration in 0..max_iterations {
        if matches!(
            u_state,
            DisplacementState::Stale | DisplacementState::Updated(32..)
        ) {
            k_op.apply(&p, &mut u);
            u_state = DisplacementState::Fresh;
        }
        let (approach, count, max_violation) = gap_and_residual(&mut g, &u, s, &p);
        residual = max_violation;
        if !residual.is_finite() {
            break;
        }
        if residual <= gap_tol {
            if u_state != DisplacementState::Fresh {
                u_state = DisplacementState::Stale;
                continue;
            }
            return Ok(GridSolution {
                pressure: p,
                gap: g,
                approach,
                iterations: iteration,
            });
        }

        g_norm_old = conjugate_direction(&mut t, &g, &p, conjugate, g_norm_old);
        k_op.apply(&t, &mut r);
        let step = step_length(&p, &g, &t, &r, count, fallback_step);
        let (overlap, clamped) = step_and_project(&mut p, &g, &t, step);
        conjugate = !overlap;
        let Some(scale) = rescale_to_mean(&mut p, p_mean) else {
            return Err(Stalled {
                iterations: iteration + 1,
                residual: residual / gap_tol,
                reason: "every pressure vanished (breakdown)",
            });
        };
        u_state = next_displacement_state(u_state, overlap || clamped);
        if u_state != DisplacementState::Stale {
            for (ui, &ri) in u.iter_mut().zip(&r) {
                *ui = scale * (*ui - step * ri);
            }
        }
    }
    Err(Stalled {
        iterations: max_iterations,
        residual: residual / gap_tol,
        reason: if residual.is_finite() {
            "iteration cap reached"
        } else {
            "non-finite gap"
        },
    })
}

/// Writes the gap `g = u + s − δ` and returns the approach `δ` (the mean of `u + s` over the
/// contact set `{p > 0}`), the number of contact points and the complementarity residual: the
/// largest `|g|` on the contact set and `−g` off it.
fn gap_and_residual(g: &mut [f64], u: &[f64], s: &[f64], p: &[f64]) -> (f64, usize, f64) {
    let (mut sum, mut count) = (0.0, 0usize);
    for (((gi, &ui), &si), &pi) in g.iter_mut().zip(u).zip(s).zip(p) {
        *gi = ui + si;
        if pi > 0.0 {
            sum += *gi;
            count += 1;
        }
    }
    // mean(p) = p̄ > 0, so count ≥ 1
    let approach = sum / count as f64;
    let mut residual: f64 = 0.0;
    for (gi, &pi) in g.iter_mut().zip(p) {
        *gi -= approach;
        let violation = if pi > 0.0 { gi.abs() } else { -*gi };
        residual = residual.max(violation);
    }
    (approach, count, residual)
}

/// Writes the conjugate direction `t = g + β t` on the contact set (zero off it; `β = 0` unless
/// `conjugate`, else the ratio of the squared gap norms on the contact set to `g_norm_old`) and
/// returns the new squared norm, the next call's `g_norm_old`.
fn conjugate_direction(
    t: &mut [f64],
    g: &[f64],
    p: &[f64],
    conjugate: bool,
    g_norm_old: f64,
) -> f64 {
    let g_norm: f64 = g
        .iter()
        .zip(p)
        .filter(|(_, &pi)| pi > 0.0)
        .map(|(gi, _)| gi * gi)
        .sum();
    let beta = if conjugate { g_norm / g_norm_old } else { 0.0 };
    for ((ti, &gi), &pi) in t.iter_mut().zip(g).zip(p) {
        *ti = if pi > 0.0 { gi + beta * *ti } else { 0.0 };
    }
    g_norm
}

/// The exact line-search step along `t` on the contact set (`count` points), `r = K t` taken
/// relative to its mean there; `fallback_step` when that step is not finite and positive.
fn step_length(
    p: &[f64],
    g: &[f64],
    t: &[f64],
    r: &[f64],
    count: usize,
    fallback_step: f64,
) -> f64 {
    let r_mean = p
        .iter()
        .zip(r)
        .filter(|(&pi, _)| pi > 0.0)
        .map(|(_, ri)| ri)
        .sum::<f64>()
        / count as f64;
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..p.len() {
        if p[i] > 0.0 {
            num += g[i] * t[i];
            den += (r[i] - r_mean) * t[i];
        }
    }
    let step = num / den;
    if step.is_finite() && step > 0.0 {
        step
    } else {
        fallback_step
    }
}

/// Steps the contact pressures by `−step·t`, clamps those that turn negative to zero and brings
/// overlapping points out of contact (`p = 0`, `g < 0`) back in with `p = −step·g`. Returns
/// whether any point overlapped and whether any pressure was clamped.
fn step_and_project(p: &mut [f64], g: &[f64], t: &[f64], step: f64) -> (bool, bool) {
    let (mut overlap, mut clamped) = (false, false);
    for i in 0..p.len() {
        if p[i] > 0.0 {
            let stepped = p[i] - step * t[i];
            clamped |= stepped < 0.0;
            p[i] = stepped.max(0.0);
        }
        if p[i] == 0.0 && g[i] < 0.0 {
            p[i] = -step * g[i];
            overlap = true;
        }
    }
    (overlap, clamped)
}

/// Rescales the pressures to the mean `p_mean` and returns the factor, or `None` if their sum
/// is not positive and finite (every pressure vanished).
fn rescale_to_mean(p: &mut [f64], p_mean: f64) -> Option<f64> {
    let total: f64 = p.iter().sum();
    if !(total > 0.0 && total.is_finite()) {
        return None;
    }
    let scale = p_mean * p.len() as f64 / total;
    p.iter_mut().for_each(|pi| *pi *= scale);
    Some(scale)
}

/// Where the displacement stands after a step: stale if the step was not linear (a pressure
/// clamped or a point brought back in), else one more linear update.
fn next_displacement_state(state: DisplacementState, nonlinear: bool) -> DisplacementState {
    match state {
        _ if nonlinear => DisplacementState::Stale,
        DisplacementState::Fresh => DisplacementState::Updated(1),
        DisplacementState::Updated(k) => DisplacementState::Updated(k + 1),
        DisplacementState::Stale => DisplacementState::Stale,
    }
}
