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
/// peak (λ), `p_mean` the mean pressure (E*), `gap_tol` the absolute gap tolerance (λ).
pub(super) fn solve(
    s: &[f64],
    p_mean: f64,
    k_op: &mut GridCompliance,
    gap_tol: f64,
    max_iterations: usize,
) -> Result<GridSolution, Stalled> {
    let n = s.len();
    let mut p = vec![p_mean; n];
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
        let (mut sum, mut count) = (0.0, 0usize);
        for (((gi, &ui), &si), &pi) in g.iter_mut().zip(&u).zip(s).zip(&p) {
            *gi = ui + si;
            if pi > 0.0 {
                sum += *gi;
                count += 1;
            }
        }
        // mean(p) = p̄ > 0, so count ≥ 1
        let approach = sum / count as f64;
        residual = 0.0;
        for (gi, &pi) in g.iter_mut().zip(&p) {
            *gi -= approach;
            let violation = if pi > 0.0 { gi.abs() } else { -*gi };
            residual = residual.max(violation);
        }
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

        // conjugate direction on the contact set
        let g_norm: f64 = g
            .iter()
            .zip(&p)
            .filter(|(_, &pi)| pi > 0.0)
            .map(|(gi, _)| gi * gi)
            .sum();
        let beta = if conjugate { g_norm / g_norm_old } else { 0.0 };
        g_norm_old = g_norm;
        for ((ti, &gi), &pi) in t.iter_mut().zip(&g).zip(&p) {
            *ti = if pi > 0.0 { gi + beta * *ti } else { 0.0 };
        }
        k_op.apply(&t, &mut r);
        let r_mean = p
            .iter()
            .zip(&r)
            .filter(|(&pi, _)| pi > 0.0)
            .map(|(_, ri)| ri)
            .sum::<f64>()
            / count as f64;
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..n {
            if p[i] > 0.0 {
                num += g[i] * t[i];
                den += (r[i] - r_mean) * t[i];
            }
        }
        let step = num / den;
        let step = if step.is_finite() && step > 0.0 {
            step
        } else {
            fallback_step
        };

        // step, projection onto p ≥ 0, overlap correction
        let (mut overlap, mut clamped) = (false, false);
        for i in 0..n {
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
        conjugate = !overlap;
        let total: f64 = p.iter().sum();
        if !(total > 0.0 && total.is_finite()) {
            return Err(Stalled {
                iterations: iteration + 1,
                residual: residual / gap_tol,
                reason: "every pressure vanished (breakdown)",
            });
        }
        let scale = p_mean * n as f64 / total;
        p.iter_mut().for_each(|pi| *pi *= scale);
        u_state = match u_state {
            _ if overlap || clamped => DisplacementState::Stale,
            DisplacementState::Fresh => DisplacementState::Updated(1),
            DisplacementState::Updated(k) => DisplacementState::Updated(k + 1),
            DisplacementState::Stale => DisplacementState::Stale,
        };
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
