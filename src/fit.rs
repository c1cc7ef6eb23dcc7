//! Re-deriving the WNL coefficients (paper Table 1) from pressure–area curves.
//!
//! Every reading of Eq. 4 is **linear in its twelve coefficients**: with x = a/λ, p̄_W the
//! Westergaard pressure and m(AR, τ) = [1, AR, τ, AR², AR·τ, τ²],
//!
//! - `bracket-sq`: p̄/E* = Σ bₖ·p̄_W·mₖ + Σ aₖ·p̄_W·x·cos²(πx)·mₖ
//! - `bracket-2x`: p̄/E* = Σ bₖ·p̄_W·mₖ + Σ aₖ·p̄_W·x·cos(2πx)·mₖ
//! - `literal`:    p̄/E* = Σ bₖ·p̄_W·mₖ + Σ aₖ·x·cos²(πx)·mₖ
//!
//! so the paper's "nonlinear regression" in p̄/E* is an ordinary linear least-squares problem
//! whose minimiser Gauss–Newton or Levenberg–Marquardt would reach in one step. We solve it
//! directly with a column-pivoted QR factorisation (faer), on columns scaled to unit norm, and
//! report what a convergence check would: the relative optimality ‖Jᵀr‖/(‖J‖‖r‖) of the
//! solution and the condition number of the scaled design matrix.

use crate::models::wnl::quadratic_monomials;
use crate::models::{Coefficients, FitDomain, PressureLaw, Reading, Westergaard, Wnl};
use faer::prelude::*;
use faer::Mat;
use thiserror::Error;

/// One point of one pressure–area curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveSample {
    pub aspect_ratio: f64,
    pub tau_max_mpa: f64,
    pub a_over_lambda: f64,
    pub p_over_estar: f64,
}

/// A least-squares fit of the twelve coefficients.
#[derive(Debug, Clone, PartialEq)]
pub struct Refit {
    pub reading: Reading,
    pub coefficients: Coefficients,
    /// Mean squared error of p̄/E* over all samples.
    pub mse: f64,
    pub samples: usize,
    /// ‖Jᵀr‖ / (‖J‖_F ‖r‖): zero at an exact least-squares minimum (round-off ≈ 1e-13).
    pub relative_optimality: f64,
    /// Ratio of extreme singular values of the column-scaled design matrix.
    pub condition_number: f64,
}

#[derive(Debug, Error, PartialEq)]
pub enum FitError {
    #[error("{samples} samples cannot determine 12 coefficients")]
    TooFewSamples { samples: usize },
    #[error("sample {index} is not finite: {sample:?}")]
    NotFinite { index: usize, sample: CurveSample },
    #[error("the samples do not determine the 12 coefficients (condition number {condition_number:.3e}); they need at least three aspect ratios and three shear strengths")]
    RankDeficient { condition_number: f64 },
    #[error("singular value decomposition failed")]
    Svd,
}

/// The regressors of sample `s` under `reading`: columns 0–5 multiply b₀…b₅, 6–11 a₀…a₅
/// (p̄/E* = p̄_W/E*·B + s(x)·A, [`Reading::a_shape`]).
fn regressors(s: &CurveSample, reading: Reading) -> [f64; 12] {
    let x = s.a_over_lambda;
    let p_w = Westergaard::new(s.aspect_ratio).p_over_estar(x);
    let shape = reading.a_shape(x, p_w);
    let m = quadratic_monomials(s.aspect_ratio, s.tau_max_mpa);
    let mut row = [0.0; 12];
    for k in 0..6 {
        row[k] = p_w * m[k];
        row[6 + k] = shape * m[k];
    }
    row
}

/// Fits the twelve coefficients of `reading` to `samples` in the least-squares sense.
/// `domain` records where the result is valid (the span of the samples, normally).
pub fn refit(
    samples: &[CurveSample],
    reading: Reading,
    domain: FitDomain,
) -> Result<Refit, FitError> {
    check_samples(samples)?;
    let rows: Vec<[f64; 12]> = samples.iter().map(|s| regressors(s, reading)).collect();
    let (theta, condition_number) = least_squares(&rows, samples)?;
    let mut b = [0.0; 6];
    let mut a = [0.0; 6];
    b.copy_from_slice(&theta[..6]);
    a.copy_from_slice(&theta[6..]);
    let coefficients = Coefficients { a, b, domain };

    // Residual r = J θ − y in the unscaled problem.
    let residual: Vec<f64> = rows
        .iter()
        .zip(samples)
        .map(|(r, s)| r.iter().zip(&theta).map(|(u, t)| u * t).sum::<f64>() - s.p_over_estar)
        .collect();
    let r_norm = residual.iter().map(|r| r * r).sum::<f64>().sqrt();
    Ok(Refit {
        reading,
        coefficients,
        mse: r_norm * r_norm / samples.len() as f64,
        samples: samples.len(),
        relative_optimality: relative_optimality(&rows, &residual),
        condition_number,
    })
}

/// At least twelve samples, every number finite.
fn check_samples(samples: &[CurveSample]) -> Result<(), FitError> {
    let n = samples.len();
    if n < 12 {
        return Err(FitError::TooFewSamples { samples: n });
    }
    if let Some((index, sample)) = samples.iter().enumerate().find(|(_, s)| {
        ![
            s.aspect_ratio,
            s.tau_max_mpa,
            s.a_over_lambda,
            s.p_over_estar,
        ]
        .iter()
        .all(|v| v.is_finite())
    }) {
        return Err(FitError::NotFinite {
            index,
            sample: *sample,
        });
    }
    Ok(())
}

/// The coefficients `θ` minimising `‖J θ − y‖` (`J` the regressor `rows`, `y` the samples'
/// p̄/E*), solved with each column scaled to unit norm by a column-pivoted QR, and the scaled
/// design's condition number; an error where it is rank deficient (condition above 10¹²).
fn least_squares(rows: &[[f64; 12]], samples: &[CurveSample]) -> Result<(Vec<f64>, f64), FitError> {
    let scale: Vec<f64> = (0..12)
        .map(|j| {
            rows.iter()
                .map(|r| r[j] * r[j])
                .sum::<f64>()
                .sqrt()
                .max(f64::MIN_POSITIVE)
        })
        .collect();
    let design = Mat::from_fn(rows.len(), 12, |i, j| rows[i][j] / scale[j]);
    let rhs = Mat::from_fn(rows.len(), 1, |i, _| samples[i].p_over_estar);

    let sv = design.singular_values().map_err(|_| FitError::Svd)?;
    let (smax, smin) = sv.iter().fold((0.0_f64, f64::INFINITY), |(hi, lo), &s| {
        (hi.max(s), lo.min(s))
    });
    let condition_number = smax / smin;
    if !condition_number.is_finite() || condition_number > 1e12 {
        return Err(FitError::RankDeficient { condition_number });
    }
    let solution = design.col_piv_qr().solve_lstsq(&rhs);
    let theta = (0..12).map(|j| solution[(j, 0)] / scale[j]).collect();
    Ok((theta, condition_number))
}

/// The optimality of a least-squares solution, `‖Jᵀr‖/(‖J‖‖r‖)` (0 for a zero residual): the
/// cosine between the residual `r` and the regressor `rows`' column space.
fn relative_optimality(rows: &[[f64; 12]], residual: &[f64]) -> f64 {
    let r_norm = residual.iter().map(|r| r * r).sum::<f64>().sqrt();
    let j_norm = rows
        .iter()
        .flat_map(|r| r.iter())
        .map(|v| v * v)
        .sum::<f64>()
        .sqrt();
    let jtr: f64 = (0..12)
        .map(|j| {
            rows.iter()
                .zip(residual)
                .map(|(r, e)| r[j] * e)
                .sum::<f64>()
                .powi(2)
        })
        .sum::<f64>()
        .sqrt();
    if r_norm == 0.0 {
        0.0
    } else {
        jtr / (j_norm * r_norm)
    }
}

/// Mean squared error of p̄/E* of the WNL law (`reading`, `coefficients`) over `samples`.
pub fn mse(samples: &[CurveSample], reading: Reading, coefficients: Coefficients) -> f64 {
    let sum: f64 = samples
        .iter()
        .map(|s| {
            let law = Wnl::new(s.aspect_ratio, s.tau_max_mpa, reading, coefficients);
            (law.p_over_estar(s.a_over_lambda) - s.p_over_estar).powi(2)
        })
        .sum();
    sum / samples.len().max(1) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Curves drawn from a known law must give that law back.
    fn samples_of(reading: Reading, c: Coefficients) -> Vec<CurveSample> {
        let mut out = vec![];
        for ar in [0.1, 0.18, 0.3] {
            for tau in [0.0, 0.01, 0.05, 0.1, 0.15, 0.2] {
                for i in 1..=9 {
                    let x = 0.05 * i as f64;
                    let p = Wnl::new(ar, tau, reading, c).p_over_estar(x);
                    out.push(CurveSample {
                        aspect_ratio: ar,
                        tau_max_mpa: tau,
                        a_over_lambda: x,
                        p_over_estar: p,
                    });
                }
            }
        }
        out
    }

    #[test]
    fn recovers_table1_from_its_own_curves_in_every_reading() {
        let c = Coefficients::PAPER_TABLE1;
        for reading in Reading::ALL {
            let fit = refit(&samples_of(reading, c), reading, FitDomain::PAPER).unwrap();
            for k in 0..6 {
                assert!(
                    (fit.coefficients.a[k] - c.a[k]).abs() <= 1e-8 * c.a[k].abs().max(1.0),
                    "{reading} a{k}"
                );
                assert!(
                    (fit.coefficients.b[k] - c.b[k]).abs() <= 1e-8 * c.b[k].abs().max(1.0),
                    "{reading} b{k}"
                );
            }
            assert!(fit.mse < 1e-24, "{reading}: mse {}", fit.mse);
        }
    }

    #[test]
    fn least_squares_optimum_is_reached_with_noise() {
        // A perturbation orthogonal to nothing in particular: the residual must be orthogonal
        // to the regressors at the minimum.
        let mut s = samples_of(Reading::BracketSq, Coefficients::PAPER_TABLE1);
        for (i, v) in s.iter_mut().enumerate() {
            v.p_over_estar += 1e-3 * ((i * 7919 % 13) as f64 - 6.0) / 6.0;
        }
        let fit = refit(&s, Reading::BracketSq, FitDomain::PAPER).unwrap();
        assert!(
            fit.relative_optimality < 1e-10,
            "{}",
            fit.relative_optimality
        );
        assert!(fit.mse > 0.0 && fit.mse < 1e-6);
        assert!((mse(&s, Reading::BracketSq, fit.coefficients) - fit.mse).abs() < 1e-15);
    }

    #[test]
    fn refuses_data_that_cannot_determine_the_coefficients() {
        let c = Coefficients::PAPER_TABLE1;
        let one_ar: Vec<CurveSample> = samples_of(Reading::BracketSq, c)
            .into_iter()
            .filter(|s| s.aspect_ratio == 0.1)
            .collect();
        assert!(matches!(
            refit(&one_ar, Reading::BracketSq, FitDomain::PAPER),
            Err(FitError::RankDeficient { .. })
        ));
        assert_eq!(
            refit(&one_ar[..5], Reading::BracketSq, FitDomain::PAPER),
            Err(FitError::TooFewSamples { samples: 5 })
        );
    }
}
