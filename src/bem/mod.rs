//! A periodic FFT boundary-element reference solver: a rigid, even, λ-periodic profile
//! ([`Profile`]) pressed without friction onto a linear elastic half-plane (plane strain), or a
//! layer bonded to a rigid base ([`ElasticBody`], [`solve_on`]: the finite-element model's body),
//! under a given mean pressure. Independent of the finite-element solver ([`crate::fe`]): small
//! strain, linear elasticity, the body's exact Fourier compliance.
//!
//! Units: lengths over λ, pressures over E* (the plane-strain modulus `E/(1 − ν²)`).
//!
//! # Method
//!
//! `N` equally spaced points `x_i = i/N` on one wavelength (`N` a power of two). The rigid surface
//! lies `s(x) = −y_s(x) ≥ 0` below its peak; the gap is `g = s + u − δ`, where the surface
//! displacement `u` follows from the pressure harmonic by harmonic, `ũ_k = 2 p̃_k/(E* q_k)` with
//! `q_k = 2πk` (Johnson, *Contact Mechanics*, §13.2; [`half_plane_compliance`]), by FFT
//! (`rustfft`), and the rigid approach `δ` takes the place of the `k = 0` term, fixed by the
//! mean pressure (pressure control). The complementarity problem `p ≥ 0`, `g ≥ 0`, `p g = 0`,
//! `mean(p) = p̄` is solved by the constrained conjugate gradient of Polonsky & Keer (Wear 231,
//! 206–219, 1999) to `|g| ≤ tol · Σ_k Δ_k` on the contact and `g ≥ −tol · Σ_k Δ_k` off it.
//! Patch edges are placed between grid points by extrapolating the gap, which grows like
//! `distance^{3/2}` out of an edge, to zero (`src/bem/edges.rs`).
//!
//! # Full contact
//!
//! In full contact `u = δ − s` everywhere, so `u`'s harmonics are those of the profile,
//! `Σ_k Δ_k cos(2π n_k x)`, and the pressure is
//! `p(x) = p̄ + Σ_k (E* q_k Δ_k/2) cos(2π n_k x) = p̄ + E* Σ_k π AR_k cos(2π n_k x)`
//! (`q_k Δ_k/2 = π AR_k`). That is admissible (`p ≥ 0`) exactly when
//! `p̄ ≥ p̄_full = E* max_x[−Σ_k π AR_k cos(2π n_k x)]` ([`full_contact_pressure`]), which is at
//! most `E* Σ_k π AR_k` and equals it when every harmonic has its trough at the same point (`π AR`
//! for a single sinusoid, Westergaard's full contact). At and beyond `p̄_full` the contact is
//! full and nothing is left to solve; [`solve`] refuses it.
//!
//! # Accuracy (measured, `src/bem/solver_tests.rs`)
//!
//! Against Westergaard's single sinusoid (`a/λ` = 0.07, 0.19, 0.33) the contact fraction is off by
//! at most 3.8e-5, 9.3e-6, 3.3e-6 at N = 1024, 4096, 16384: first order in `1/N` (observed 0.9),
//! each edge within a few hundredths of a grid step, some 25 times closer than counting contact
//! points. The pressure's mean error is 1.1e-6 p̄ at N = 16384 (order 1.5), 7e-9 p̄ away from the
//! edges (order 2). Two-scale profiles converge likewise, at first order with some scatter.
//! Cost: `O(N log N)` per iteration, a few hundred iterations (about 0.2 s at N = 16384).

mod compliance;
mod edges;
#[cfg(test)]
mod friction_tests;
pub mod frictional_contact;
pub mod frictional_curve;
mod grid;
mod polonsky_keer;
mod shear_active_set;
#[cfg(test)]
mod solver_tests;

pub use compliance::{
    dundurs_beta, half_plane_compliance, layer_compliance, layer_compliance_deficit,
    layer_to_half_plane_ratio, ElasticBody, HarmonicCompliance,
};

use crate::profile::{Profile, ProfileError};

/// Why the solver gives no answer.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BemError {
    /// A number out of its range.
    #[error(
        "invalid input to the boundary-element solver: {field} = {value} (allowed: {allowed})"
    )]
    InvalidInput {
        /// What it is.
        field: &'static str,
        /// The value given.
        value: f64,
        /// The range, in words.
        allowed: &'static str,
    },
    /// The profile is not a valid one.
    #[error("boundary-element solver: {0}")]
    Profile(#[from] ProfileError),
    /// The grid is not a power of two, or too coarse for the profile.
    #[error("boundary-element solver: {points} points per wavelength: a power of two ≥ {minimum} is needed ({why})")]
    Grid {
        /// Points given.
        points: usize,
        /// The least allowed for this profile.
        minimum: usize,
        /// Why the minimum is what it is.
        why: String,
    },
    /// The mean pressure flattens the profile completely.
    #[error("boundary-element solver: p̄/E* = {p_over_estar} is at or beyond full contact, which this profile reaches at p̄/E* = {full_contact:.10} (no gap left to solve for)")]
    FullContact {
        /// The mean pressure asked for (over E*).
        p_over_estar: f64,
        /// Where full contact starts ([`full_contact_pressure`]).
        full_contact: f64,
    },
    /// A load curve's target not reached by its increments.
    #[error("boundary-element solver: the load curve stops short of its target {target} (reached {reached} after {increments} increments)")]
    TargetOutOfReach {
        target: f64,
        reached: f64,
        increments: usize,
    },
    /// The caller asked the load curve to stop after this many committed increments.
    #[error("boundary-element solver: stopped by the caller after {increments} increments")]
    Stopped { increments: usize },
    /// Polonsky–Keer iteration did not meet the tolerance.
    #[error("boundary-element solver did not converge for p̄/E* = {p_over_estar}, N = {points}: {reason} after {iterations} iterations (complementarity residual {residual:.3e} × tol, tol = {tol:e})")]
    NoConvergence {
        /// The mean pressure (over E*).
        p_over_estar: f64,
        /// Points per wavelength.
        points: usize,
        /// Iterations done.
        iterations: usize,
        /// The last residual over the tolerance (> 1).
        residual: f64,
        /// The relative tolerance asked for.
        tol: f64,
        /// What stopped it.
        reason: &'static str,
    },
}

/// The solution over one wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct HalfSpaceContact {
    /// `p(x_i)/E*` at `x_i = i/N`, `i = 0 … N−1`; `≥ 0`, mean `p̄/E*`.
    pub pressure_over_estar: Vec<f64>,
    /// `g(x_i)/λ`: the rigid surface's distance from the deformed elastic surface; within
    /// `tol · Σ Δ_k` of 0 where the pressure is positive, `≥ −tol · Σ Δ_k` elsewhere.
    pub gap_over_lambda: Vec<f64>,
    /// Contact length over λ in one period (`2a/λ` for a single sinusoid), from the sub-grid
    /// patch edges: twice the total length of [`Self::patches`].
    pub contact_fraction: f64,
    /// The contact intervals `[start, end]` in `x/λ ∈ [0, ½]` (the profile is even), in order;
    /// a patch through the peak starts at 0.
    pub patches: Vec<[f64; 2]>,
    /// Polonsky–Keer iterations done.
    pub iterations: usize,
    /// `δ/λ`: how far the rigid peak has moved past the mean plane of the deformed elastic
    /// surface (`g = s + u − δ`, `u` of zero mean); `Σ Δ_k` at full contact.
    pub approach_over_lambda: f64,
}

/// The mean pressure over E* at which the profile is flattened completely on the half-plane
/// (module doc): `max_x[−Σ_k π AR_k cos(2π n_k x)]`, found by sampling 64 points per shortest
/// wavelength and refining the best by golden-section search (to rounding).
pub fn full_contact_pressure(profile: &Profile) -> f64 {
    full_contact_pressure_on(profile, ElasticBody::HalfPlane).expect("the half-plane's compliance")
}

/// [`full_contact_pressure`] on `body`: in full contact each harmonic's pressure is its
/// displacement over the body's compliance, `π AR_k / S_k` for a layer
/// (`S_k = S(2π n_k h, ν)`), so the full-contact pressure is `max_x[−Σ_k π AR_k cos(2π n_k x)/S_k]`.
pub fn full_contact_pressure_on(profile: &Profile, body: ElasticBody) -> Result<f64, BemError> {
    let weights = profile
        .harmonics()
        .map(|h| {
            let q = std::f64::consts::TAU * h.order as f64;
            Ok((
                h,
                std::f64::consts::PI * h.aspect_ratio / body.over_half_plane(q)?,
            ))
        })
        .collect::<Result<Vec<_>, BemError>>()?;
    let f = |x: f64| -> f64 {
        -weights
            .iter()
            .map(|(h, w)| w * (std::f64::consts::TAU * h.order as f64 * x).cos())
            .sum::<f64>()
    };
    let samples = 64 * profile.max_order() as usize;
    let dx = 0.5 / samples as f64;
    let best = (0..=samples)
        .map(|i| i as f64 * dx)
        .max_by(|a, b| f(*a).total_cmp(&f(*b)))
        .unwrap_or(0.0);
    // golden section on [best − dx, best + dx], where f is unimodal at this sampling
    let (mut lo, mut hi) = (best - dx, best + dx);
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let (a, b) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
        if f(a) > f(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    Ok(f(best).max(f(0.5 * (lo + hi))))
}

/// The least grid for a profile: 16 points on the shortest harmonic's wavelength, and 64 in all.
pub fn min_points_per_wavelength(profile: &Profile) -> usize {
    (16 * profile.max_order() as usize).max(64)
}

/// Largest grid accepted (2²⁴ points).
pub const MAX_POINTS_PER_WAVELENGTH: usize = 1 << 24;

/// `Ok` when `n` grid points per wavelength resolve `profile`: a power of two, at least
/// [`min_points_per_wavelength`], at most [`MAX_POINTS_PER_WAVELENGTH`].
pub(crate) fn check_grid(profile: &Profile, n: usize) -> Result<(), BemError> {
    let minimum = min_points_per_wavelength(profile);
    if !n.is_power_of_two() || n < minimum || n > MAX_POINTS_PER_WAVELENGTH {
        return Err(BemError::Grid {
            points: n,
            minimum,
            why: format!(
                "16 points on the wavelength of the highest order {}, at least 64, at most 2^24",
                profile.max_order()
            ),
        });
    }
    Ok(())
}

/// The conjugate-gradient iteration cap for `n` points (Polonsky–Keer, and the stick-zone solves
/// of the frictional solver): `1000 + 20√N` (3560 at N = 16384, where
/// 200–1000 are measured at tol = 1e-10).
pub(super) fn max_iterations(n: usize) -> usize {
    1000 + 20 * (n as f64).sqrt() as usize
}

/// Solves the contact of `profile` on the half-plane at the mean pressure `p_over_estar` (p̄/E*)
/// on `points_per_wavelength` grid points (a power of two, at least
/// [`min_points_per_wavelength`]) to the relative tolerance `tol` (`0 < tol < 1`; the gap
/// residual over `Σ Δ_k`, module doc).
pub fn solve(
    profile: &Profile,
    p_over_estar: f64,
    points_per_wavelength: usize,
    tol: f64,
) -> Result<HalfSpaceContact, BemError> {
    solve_on(
        profile,
        ElasticBody::HalfPlane,
        p_over_estar,
        points_per_wavelength,
        tol,
    )
}

/// [`solve`] on `body`: the half-plane, or a layer bonded to a rigid base (its Fourier
/// compliance, [`layer_compliance`]), the finite-element model's body in the linear limit.
pub fn solve_on(
    profile: &Profile,
    body: ElasticBody,
    p_over_estar: f64,
    points_per_wavelength: usize,
    tol: f64,
) -> Result<HalfSpaceContact, BemError> {
    let solution = solve_grid(profile, body, p_over_estar, points_per_wavelength, tol)?;
    let patches = edges::patches(&solution.pressure, &solution.gap);
    let contact_fraction = 2.0 * patches.iter().map(|[a, b]| b - a).sum::<f64>();
    Ok(HalfSpaceContact {
        pressure_over_estar: solution.pressure,
        gap_over_lambda: solution.gap,
        contact_fraction,
        patches,
        iterations: solution.iterations,
        approach_over_lambda: solution.approach,
    })
}

/// The checks of [`solve`] and its grid solution.
fn solve_grid(
    profile: &Profile,
    body: ElasticBody,
    p_over_estar: f64,
    n: usize,
    tol: f64,
) -> Result<polonsky_keer::GridSolution, BemError> {
    let harmonics: Vec<_> = profile.harmonics().collect();
    let profile = Profile::new(&harmonics)?;
    if !(p_over_estar.is_finite() && p_over_estar > 0.0) {
        return Err(BemError::InvalidInput {
            field: "mean pressure p̄/E*",
            value: p_over_estar,
            allowed: "finite, > 0",
        });
    }
    if !(tol.is_finite() && tol > 0.0 && tol < 1.0) {
        return Err(BemError::InvalidInput {
            field: "relative tolerance",
            value: tol,
            allowed: "0 < tol < 1",
        });
    }
    check_grid(&profile, n)?;
    let full_contact = full_contact_pressure_on(&profile, body)?;
    if p_over_estar >= full_contact {
        return Err(BemError::FullContact {
            p_over_estar,
            full_contact,
        });
    }
    let s: Vec<f64> = (0..n).map(|i| -profile.y(i as f64 / n as f64)).collect();
    let mut k_op = grid::GridCompliance::on(n, body)?;
    let gap_tol = tol * profile.amplitude_sum();
    polonsky_keer::solve(
        None,
        &s,
        p_over_estar,
        &mut k_op,
        gap_tol,
        max_iterations(n),
    )
    .map_err(|stalled| BemError::NoConvergence {
        p_over_estar,
        points: n,
        iterations: stalled.iterations,
        residual: stalled.residual,
        tol,
        reason: stalled.reason,
    })
}
