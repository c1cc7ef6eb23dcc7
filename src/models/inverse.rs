//! The inverse a/λ(p̄/E*) of a contact law, by bracketed root finding.
//!
//! A law is invertible when it is non-negative and non-decreasing on a/λ ∈ [0, ½]. That is
//! checked before every inversion on a uniform grid of [`SHAPE_SAMPLES`] intervals: a WNL
//! law evaluated far outside its fit domain can dip below zero or turn back (R9), and then
//! the equation p̄(a) = p̄ has no root or several, so the inverse refuses with the place where
//! the law misbehaves instead of returning one arbitrary root. Above the full-contact pressure
//! there is no root either (the contact is complete): that is an error too, never a clamp.
//! Inside a bracket the root is polished by Brent's method (argmin's `BrentRoot`).

use super::PressureLaw;
use argmin::core::{CostFunction, Executor};
use argmin::solver::brent::BrentRoot;
use thiserror::Error;

/// Number of uniform intervals of [0, ½] on which the law's sign and monotonicity are checked.
pub const SHAPE_SAMPLES: usize = 4096;

/// Why a/λ cannot be recovered from p̄/E*.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum InverseError {
    #[error("p_over_estar = {p_over_estar} is not a finite number ≥ 0")]
    NegativeOrNotFinite { p_over_estar: f64 },
    #[error(
        "p_over_estar = {p_over_estar} exceeds the full-contact pressure {full_contact_p_over_estar:.6} \
         of this model; allowed range: [0, {full_contact_p_over_estar:.6}]"
    )]
    AboveFullContact {
        p_over_estar: f64,
        full_contact_p_over_estar: f64,
    },
    #[error(
        "the model is not finite (p/E* = {p_over_estar}) at a/λ = {a_over_lambda:.4}: it overflows \
         for these inputs"
    )]
    NotFinite {
        a_over_lambda: f64,
        p_over_estar: f64,
    },
    #[error(
        "the model gives a negative pressure p/E* = {p_over_estar:.6e} at a/λ = {a_over_lambda:.4}; \
         it has no physical inverse"
    )]
    NegativeModel {
        a_over_lambda: f64,
        p_over_estar: f64,
    },
    #[error(
        "the model is not monotonic in a/λ: p/E* decreases after a/λ = {a_over_lambda:.4} \
         (from {p_over_estar:.6}); the inverse would not be unique"
    )]
    NonMonotonic {
        a_over_lambda: f64,
        p_over_estar: f64,
    },
    #[error("root finding failed: {0}")]
    RootFinding(String),
}

/// Checks that `law` is non-negative and non-decreasing on [0, ½] (sampled; see the module doc).
pub fn check_invertible<L: PressureLaw + ?Sized>(law: &L) -> Result<(), InverseError> {
    let n = SHAPE_SAMPLES;
    let samples: Vec<(f64, f64)> = (0..=n)
        .map(|i| {
            let x = 0.5 * i as f64 / n as f64;
            (x, law.p_over_estar(x))
        })
        .collect();
    let scale = samples
        .iter()
        .map(|s| s.1.abs())
        .fold(f64::MIN_POSITIVE, f64::max);
    let round_off = 1e-13 * scale;
    if let Some(&(x, p)) = samples.iter().find(|s| !s.1.is_finite()) {
        return Err(InverseError::NotFinite {
            a_over_lambda: x,
            p_over_estar: p,
        });
    }
    if let Some(&(x, p)) = samples.iter().find(|s| s.1 < -round_off) {
        return Err(InverseError::NegativeModel {
            a_over_lambda: x,
            p_over_estar: p,
        });
    }
    if let Some(w) = samples.windows(2).find(|w| w[1].1 < w[0].1 - round_off) {
        return Err(InverseError::NonMonotonic {
            a_over_lambda: w[0].0,
            p_over_estar: w[0].1,
        });
    }
    Ok(())
}

/// The contact half-width a/λ ∈ [0, ½] at which `law` gives the mean pressure `p_over_estar`.
pub fn a_over_lambda_at<L: PressureLaw + ?Sized>(
    law: &L,
    p_over_estar: f64,
) -> Result<f64, InverseError> {
    if !p_over_estar.is_finite() || p_over_estar < 0.0 {
        return Err(InverseError::NegativeOrNotFinite { p_over_estar });
    }
    check_invertible(law)?;
    let full = law.p_over_estar(0.5);
    if p_over_estar > full {
        return Err(InverseError::AboveFullContact {
            p_over_estar,
            full_contact_p_over_estar: full,
        });
    }
    if p_over_estar == full {
        return Ok(0.5);
    }
    let residual = |x: f64| law.p_over_estar(x) - p_over_estar;
    // Bracket on the same grid as the shape check: the law is non-decreasing, so the first
    // sample at or above the target closes the bracket.
    let n = SHAPE_SAMPLES;
    let mut lo = 0.0;
    let mut hi = 0.5;
    for i in 1..=n {
        let x = 0.5 * i as f64 / n as f64;
        let r = residual(x);
        if r == 0.0 {
            return Ok(x);
        }
        if r > 0.0 {
            hi = x;
            break;
        }
        lo = x;
    }
    if residual(lo) == 0.0 {
        return Ok(lo);
    }
    let problem = Residual { f: &residual };
    let solver = BrentRoot::new(lo, hi, 1e-16);
    let result = Executor::new(problem, solver)
        .configure(|state| state.param(0.5 * (lo + hi)).max_iters(200))
        .run()
        .map_err(|e| InverseError::RootFinding(e.to_string()))?;
    result
        .state
        .best_param
        .ok_or_else(|| InverseError::RootFinding("Brent's method returned no root".into()))
}

struct Residual<'a, F: Fn(f64) -> f64> {
    f: &'a F,
}

impl<F: Fn(f64) -> f64> CostFunction for Residual<'_, F> {
    type Param = f64;
    type Output = f64;
    fn cost(&self, x: &Self::Param) -> Result<Self::Output, argmin::core::Error> {
        Ok((self.f)(*x))
    }
}
