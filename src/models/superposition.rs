//! Two-scale profiles by superposing single-scale laws: the paper's closing proposal
//! (Sec. 5, "solutions for single-scale roughness can be superimposed"), made precise for a big
//! wave plus one finer harmonic (docs/replication.md R13); applied scale by scale for many
//! scales in `recursion` (R14), of which [`superposed_contact`] is the one-scale case.
//!
//! Units: lengths over the big wavelength λ (each small wave's own half-width over its own
//! wavelength λ/n where named so), pressures over E*. The profile is the big wave (order 1,
//! aspect ratio AR₁) plus one harmonic of order n ≥ 2 (wavelength λ/n, aspect ratio AR₂ = its
//! amplitude over λ/n), as in `crate::profile`.
//!
//! **Model.** At a mean pressure p̄/E* (0 < p̄ < the big wave's full-contact pressure):
//!
//! 1. The big wave alone carries p̄: its law (`big`, built for AR₁) gives its contact
//!    half-width a₁/λ by inversion ([`a_over_lambda_at`]).
//! 2. Its pressure distribution is Westergaard's shape at that half-width, scaled to mean p̄
//!    (λ = 1, s = sin πa₁):
//!    `p(x) = 2 p̄ cos(πx) √(s² − sin²(πx)) / s²` for |x| < a₁ (mod 1), zero elsewhere. Its
//!    mean over one wavelength is p̄ ([`BigWaveDistribution`]).
//! 3. Small wave j = 0 … n−1 has its crest at x_j = j/n and its period
//!    [x_j − 1/(2n), x_j + 1/(2n)]. It carries the local mean pressure p_j, the mean of p(x)
//!    over its period, and its own law (`small`, built for AR₂, dimensionless in λ/n) gives
//!    its half-width a₂,j/(λ/n) by inversion; p_j at or above that law's full-contact pressure
//!    is full contact (½), p_j = 0 is no contact (0).
//! 4. The contact fraction (contact length over λ, per wavelength λ) is
//!    `Σ_j 2 a₂,j/λ = (1/n) Σ_j 2 a₂,j/(λ/n)`.
//!
//! The period means are exact: with u = sin(πx)/s = sin θ the load over [0, x] is
//! `(p̄/π)(θ + sin θ cos θ)` (the substitution removes the square-root edge), evaluated near
//! the contact edge through the complement angle φ = π/2 − θ so that tiny loads keep their
//! relative accuracy. Hence Σ_j p_j / n = p̄ to round-off.
//!
//! **Assumptions.** Scale separation (each small wave sees a uniform mean pressure, the mean
//! of the big wave's pressure over its period); no elastic interaction between neighbouring
//! small contacts beyond what that mean pressure carries; the big wave's pressure distribution
//! is not changed by the small waves (and is Westergaard's shape even when `big` is WNL); the
//! small-wave law is the single-scale law at its own aspect ratio and the same τ_max/E*.
//!
//! **Limits.** AR₂ → 0 at fixed n: the small law's full-contact pressure πAR₂ (Westergaard)
//! vanishes, so every crest with p_j > 0 ends in full contact and the fraction becomes exactly
//! N₊/n, N₊ the number of periods that overlap the open big contact (−a₁, a₁):
//! N₊ = min(2m + 1, n), m = ⌈n a₁ + ½⌉ − 1, so 2a₁ ≤ N₊/n < 2a₁ + 2/n. It is reached exactly
//! once πAR₂ ≤ the smallest positive p_j, not only asymptotically: the model does not return
//! the big wave's 2a₁, but 2a₁ rounded up to whole small periods. n → ∞ at fixed AR₂: the sum
//! is a Riemann sum of cell means and tends to
//! `F_∞ = ∫_{−½}^{½} 2 (a₂/λ₂)(p(x)) dx < 2a₁` ([`contact_fraction_limit`]); with
//! Westergaard for both waves `2a₁ − F_∞ ≈ (3/4) (π AR₂ / K)²` as AR₂ → 0, where
//! p(x) ≈ K √(a₁ − x) at the edge, K = 2 p̄ cos(πa₁) √(π sin 2πa₁) / s².

use super::inverse::check_invertible;
use super::{a_over_lambda_at, InverseError, PressureLaw};
pub use recursion::{order_ratios, profile_contact, recursive_contact, FinerScale};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
use thiserror::Error;

/// Largest small-wave order taken, and largest finest order of the recursion (one
/// [`CrestContact`] per crest is returned).
pub const MAX_ORDER: u32 = 1_000_000;

/// Why a two-scale contact cannot be computed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SuperpositionError {
    #[error("mean pressure p̄/E* = {p_over_estar}: allowed a finite number > 0")]
    Pressure { p_over_estar: f64 },
    #[error("small-wave order n = {order}: allowed 2 ≤ n ≤ {MAX_ORDER}")]
    Order { order: u32 },
    #[error(
        "p̄/E* = {p_over_estar} is at or beyond the big wave's full-contact pressure \
         {full_contact_p_over_estar:.6}: the big wave is flat against the solid and the \
         superposition model has no pressure peaks to share; allowed: 0 < p̄/E* < \
         {full_contact_p_over_estar:.6}"
    )]
    BigFullContact {
        p_over_estar: f64,
        full_contact_p_over_estar: f64,
    },
    #[error("the big wave's law (order 1) has no contact half-width at p̄/E* = {p_over_estar}")]
    BigInverse {
        p_over_estar: f64,
        #[source]
        source: InverseError,
    },
    #[error(
        "big-wave contact half-width a₁/λ = {half_width_over_lambda} at p̄/E* = {p_over_estar}: \
         allowed 0 < a₁/λ < ½ (the law gives no partial contact there)"
    )]
    BigHalfWidth {
        half_width_over_lambda: f64,
        p_over_estar: f64,
    },
    #[error(
        "harmonic order {order} does not divide into whole waves of order {after}: the \
         recursive superposition needs each order a multiple (≥ 2) of the one before"
    )]
    NotNested { order: u32, after: u32 },
    #[error("the small wave's law cannot be inverted")]
    SmallLaw {
        #[source]
        source: InverseError,
    },
    #[error(
        "the small wave's law has no half-width at x/λ = {x_over_lambda}, local mean \
         pressure p/E* = {p_over_estar}"
    )]
    SmallInverse {
        x_over_lambda: f64,
        p_over_estar: f64,
        #[source]
        source: InverseError,
    },
}

impl SuperpositionError {
    /// Whether the mean pressure lies at or beyond the big wave's full contact, where the model
    /// has no answer (the big wave flat against the solid), rather than the model failing.
    pub fn is_beyond_big_full_contact(&self) -> bool {
        matches!(
            self,
            SuperpositionError::BigFullContact { .. }
                | SuperpositionError::BigInverse {
                    source: InverseError::AboveFullContact { .. },
                    ..
                }
        )
    }
}

/// How a small wave touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CrestState {
    /// p_j = 0: its period lies outside the big wave's contact.
    Free,
    /// 0 < p_j < the small law's full-contact pressure.
    Partial,
    /// p_j at or above the small law's full-contact pressure: a₂ = half its wavelength.
    Full,
}

/// One small wave of the big wavelength.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrestContact {
    /// Crest position x_j/λ = j/n.
    pub x_over_lambda: f64,
    /// Local mean pressure p_j/E*: the mean of the big wave's pressure over the crest's period.
    pub p_over_estar: f64,
    /// Contact half-width over the small wavelength, a₂,j/(λ/n) ∈ [0, ½].
    pub half_width_over_wavelength: f64,
    pub state: CrestState,
}

/// The superposition model's answer at one mean pressure (two scales, or many:
/// [`recursive_contact`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SuperposedContact {
    /// Total contact length over λ, per wavelength λ: Σ_j 2 a₂,j/λ ∈ [0, 1] over the finest
    /// scale's crests.
    pub contact_fraction: f64,
    /// The big wave's contact half-width a₁/λ at p̄ (so its own fraction is 2a₁/λ).
    pub big_half_width_over_lambda: f64,
    /// The finest scale's waves of one big wavelength, j = 0 … n−1 (n its order).
    pub crests: Vec<CrestContact>,
    /// Each scale's own contact fraction, the big wave's 2a₁/λ first, the finest's
    /// (`contact_fraction`) last.
    pub scale_fractions: Vec<f64>,
}

/// Westergaard's pressure distribution under a rigid sinusoid of unit wavelength, with contact
/// half-width a₁ and mean pressure p̄ (step 2 of the module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BigWaveDistribution {
    half_width: f64,
    p_mean: f64,
    /// sin(π a₁)
    s: f64,
}

/// The load (p̄/π)·Φ on [0, x], Φ = θ + sin θ cos θ, with its complement C = π/2 − Φ; each of the
/// two is computed directly where it is the small one, so differences keep relative accuracy.
#[derive(Debug, Clone, Copy)]
struct Phase {
    /// Φ
    value: f64,
    /// C = π/2 − Φ
    complement: f64,
    /// True when C was the one computed directly (θ > π/4, near the contact edge).
    near_edge: bool,
}

impl BigWaveDistribution {
    /// The distribution at half-width `half_width_over_lambda` ∈ (0, ½) and mean
    /// `p_over_estar` > 0.
    pub fn new(half_width_over_lambda: f64, p_over_estar: f64) -> Result<Self, SuperpositionError> {
        if !(p_over_estar.is_finite() && p_over_estar > 0.0) {
            return Err(SuperpositionError::Pressure { p_over_estar });
        }
        if !(half_width_over_lambda > 0.0 && half_width_over_lambda < 0.5) {
            return Err(SuperpositionError::BigHalfWidth {
                half_width_over_lambda,
                p_over_estar,
            });
        }
        Ok(Self {
            half_width: half_width_over_lambda,
            p_mean: p_over_estar,
            s: (PI * half_width_over_lambda).sin(),
        })
    }

    /// a₁/λ.
    pub fn half_width_over_lambda(&self) -> f64 {
        self.half_width
    }

    /// p(x)/E* at a finite `x_over_lambda` (the distribution is even and 1-periodic).
    pub fn pressure_at(&self, x_over_lambda: f64) -> f64 {
        let x = (x_over_lambda - x_over_lambda.round()).abs();
        if x >= self.half_width {
            return 0.0;
        }
        // s² − sin²(πx) = (s − sin πx)(s + sin πx), the first factor from a₁ − x directly.
        let a = self.half_width;
        let gap = 2.0 * (0.5 * PI * (a + x)).cos() * (0.5 * PI * (a - x)).sin();
        let root = (gap * (self.s + (PI * x).sin())).sqrt();
        2.0 * self.p_mean * (PI * x).cos() * root / (self.s * self.s)
    }

    fn phase(&self, x: f64) -> Phase {
        let a = self.half_width;
        if x >= a {
            return Phase {
                value: FRAC_PI_2,
                complement: 0.0,
                near_edge: true,
            };
        }
        let u = (PI * x).sin() / self.s;
        if u <= FRAC_PI_4.sin() {
            let value = u.asin() + u * (1.0 - u * u).sqrt();
            return Phase {
                value,
                complement: FRAC_PI_2 - value,
                near_edge: false,
            };
        }
        // 1 − u from a₁ − x, then φ = π/2 − θ = arccos u = 2 asin √((1 − u)/2).
        let one_minus_u = 2.0 * (0.5 * PI * (a + x)).cos() * (0.5 * PI * (a - x)).sin() / self.s;
        let angle = 2.0 * (0.5 * one_minus_u).sqrt().asin();
        let complement = half_t_minus_sin_t(2.0 * angle);
        Phase {
            value: FRAC_PI_2 - complement,
            complement,
            near_edge: true,
        }
    }

    /// ∫ p dx over [x1, x2], 0 ≤ x1 ≤ x2 ≤ ½.
    fn load(&self, x1: f64, x2: f64) -> f64 {
        let (p1, p2) = (self.phase(x1), self.phase(x2));
        let difference = if p1.near_edge {
            p1.complement - p2.complement
        } else {
            p2.value - p1.value
        };
        self.p_mean / PI * difference.max(0.0)
    }

    /// The period means p_k of crests at |x| = k/n, k = 0 … ⌊n/2⌋ (crest j has k = min(j, n − j)).
    fn crest_means_by_distance(&self, order: u32) -> Vec<f64> {
        let n = order as f64;
        let boundary = |m: u32| (2 * m + 1) as f64 / (2.0 * n);
        (0..=order / 2)
            .map(|k| {
                if k == 0 {
                    2.0 * n * self.load(0.0, boundary(0))
                } else if 2 * k == order {
                    2.0 * n * self.load(boundary(k - 1), 0.5)
                } else {
                    n * self.load(boundary(k - 1), boundary(k))
                }
            })
            .collect()
    }

    /// p_j/E* for the crests j = 0 … n−1 of the harmonic of order n = `order` (none for 0): the
    /// mean of p(x) over [j/n − 1/(2n), j/n + 1/(2n)], exact to round-off (module doc).
    pub fn crest_mean_pressures(&self, order: u32) -> Vec<f64> {
        let by_distance = self.crest_means_by_distance(order);
        (0..order)
            .map(|j| by_distance[j.min(order - j) as usize])
            .collect()
    }
}

/// (t − sin t)/2, by its series below t = ½ where the difference would cancel.
fn half_t_minus_sin_t(t: f64) -> f64 {
    if t >= 0.5 {
        return 0.5 * (t - t.sin());
    }
    // t³/3! − t⁵/5! + …: at t = ½ the term of t¹⁷ is below 1e-16 of the sum.
    let (mut term, mut sum, t2) = (t * t * t / 6.0, 0.0, t * t);
    for k in 2..10 {
        sum += term;
        term *= -t2 / ((2 * k) as f64 * (2 * k + 1) as f64);
    }
    0.5 * sum
}

fn check_order(order: u32) -> Result<(), SuperpositionError> {
    if (2..=MAX_ORDER).contains(&order) {
        Ok(())
    } else {
        Err(SuperpositionError::Order { order })
    }
}

/// Steps 1–2: the big wave's half-width and pressure distribution at p̄.
fn big_wave(
    big: &dyn PressureLaw,
    p_over_estar: f64,
) -> Result<BigWaveDistribution, SuperpositionError> {
    if !(p_over_estar.is_finite() && p_over_estar > 0.0) {
        return Err(SuperpositionError::Pressure { p_over_estar });
    }
    let full = big.full_contact_p_over_estar();
    if p_over_estar >= full {
        return Err(SuperpositionError::BigFullContact {
            p_over_estar,
            full_contact_p_over_estar: full,
        });
    }
    let a1 =
        a_over_lambda_at(big, p_over_estar).map_err(|source| SuperpositionError::BigInverse {
            p_over_estar,
            source,
        })?;
    BigWaveDistribution::new(a1, p_over_estar)
}

/// a₂/λ₂ of the small law at the local mean pressure `p` (0 and ½ without inversion), with its
/// state.
fn small_width(
    small: &dyn PressureLaw,
    full: f64,
    p: f64,
) -> Result<(f64, CrestState), InverseError> {
    if p <= 0.0 {
        Ok((0.0, CrestState::Free))
    } else if p >= full {
        Ok((0.5, CrestState::Full))
    } else {
        Ok((a_over_lambda_at(small, p)?, CrestState::Partial))
    }
}

/// The superposition model (module doc) for the big wave's law `big` (built for AR₁), the
/// small wave's law `small` (built for AR₂, in units of its own wavelength), the small wave's
/// order `order` (2 ≤ n ≤ [`MAX_ORDER`]), at the mean pressure `p_over_estar` = p̄/E*: the
/// recursive superposition ([`recursive_contact`]) with one finer scale.
pub fn superposed_contact(
    big: &dyn PressureLaw,
    small: &dyn PressureLaw,
    order: u32,
    p_over_estar: f64,
) -> Result<SuperposedContact, SuperpositionError> {
    let scale = FinerScale {
        ratio: order,
        law: small,
    };
    recursive_contact(big, &[scale], p_over_estar)
}

/// Gauss–Legendre panels per segment of [`contact_fraction_limit`]'s quadrature.
const LIMIT_PANELS: usize = 8;
/// Gauss–Legendre points per panel.
const LIMIT_POINTS: usize = 16;

/// The n → ∞ limit of the contact fraction at fixed AR₂ (module doc, "Limits"):
/// F_∞ = ∫_{−½}^{½} 2 (a₂/λ₂)(p(x)) dx, the small law inverted at the big wave's pressure p(x)
/// itself. Where p(x) ≥ the small law's full-contact pressure (|x| ≤ x*, x* in closed form) the
/// integrand is 1; on [x*, a₁] the square-root ends are removed by x = x* + σ² and
/// x = a₁ − t⁴, each segment integrated by composite Gauss–Legendre (8 panels × 16 points; the
/// integrand is analytic in σ and t, and 2 or 32 panels agree to 2e-16, module tests).
pub fn contact_fraction_limit(
    big: &dyn PressureLaw,
    small: &dyn PressureLaw,
    p_over_estar: f64,
) -> Result<f64, SuperpositionError> {
    contact_fraction_limit_with(big, small, p_over_estar, LIMIT_PANELS)
}

fn contact_fraction_limit_with(
    big: &dyn PressureLaw,
    small: &dyn PressureLaw,
    p_over_estar: f64,
    panels: usize,
) -> Result<f64, SuperpositionError> {
    let distribution = big_wave(big, p_over_estar)?;
    check_invertible(small).map_err(|source| SuperpositionError::SmallLaw { source })?;
    let full = small.full_contact_p_over_estar();
    let a = distribution.half_width;
    let width_at = |x: f64| {
        let p = distribution.pressure_at(x);
        small_width(small, full, p)
            .map(|(w, _)| 2.0 * w)
            .map_err(|source| SuperpositionError::SmallInverse {
                x_over_lambda: x,
                p_over_estar: p,
                source,
            })
    };
    let x_full = full_contact_extent(&distribution, full);
    let (nodes, weights) = gauss_legendre(LIMIT_POINTS);
    // ∫ over [0, L] of g(σ) dσ, composite.
    let integrate = |length: f64, g: &dyn Fn(f64) -> Result<f64, SuperpositionError>| {
        let h = length / panels as f64;
        let mut sum = 0.0;
        for i in 0..panels {
            for (z, w) in nodes.iter().zip(&weights) {
                let sigma = h * (i as f64 + 0.5 * (z + 1.0));
                sum += 0.5 * h * w * g(sigma)?;
            }
        }
        Ok::<f64, SuperpositionError>(sum)
    };
    // Edge segment [x_m, a] with x = a − t⁴.
    let edge = |x_m: f64| {
        integrate((a - x_m).powf(0.25), &|t: f64| {
            Ok(width_at(a - t.powi(4))? * 4.0 * t.powi(3))
        })
    };
    let half = match x_full {
        None => edge(0.0)?,
        Some(x_star) => {
            let x_m = 0.5 * (x_star + a);
            let inner = integrate((x_m - x_star).sqrt(), &|sigma: f64| {
                Ok(width_at(x_star + sigma * sigma)? * 2.0 * sigma)
            })?;
            x_star + inner + edge(x_m)?
        }
    };
    Ok(2.0 * half)
}

/// x* ∈ (0, a₁) with p(x*) = `full`, if p(0) = 2p̄/s exceeds it: from
/// p² s⁴/(4p̄²) = c²(c² − cos²πa₁), c = cos πx, a quadratic in c².
fn full_contact_extent(d: &BigWaveDistribution, full: f64) -> Option<f64> {
    if 2.0 * d.p_mean / d.s <= full {
        return None;
    }
    let big_c2 = (PI * d.half_width).cos().powi(2);
    let q = (full * d.s * d.s / (2.0 * d.p_mean)).powi(2);
    let c2 = 0.5 * (big_c2 + (big_c2 * big_c2 + 4.0 * q).sqrt());
    Some(c2.sqrt().min(1.0).acos() / PI)
}

/// Nodes and weights of the `m`-point Gauss–Legendre rule on [−1, 1] (Newton on Pₘ).
fn gauss_legendre(m: usize) -> (Vec<f64>, Vec<f64>) {
    let (mut nodes, mut weights) = (vec![0.0; m], vec![0.0; m]);
    for (i, (node, weight)) in nodes.iter_mut().zip(weights.iter_mut()).enumerate() {
        let mut x = (PI * (i as f64 + 0.75) / (m as f64 + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=m {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            derivative = m as f64 * (x * p1 - p0) / (x * x - 1.0);
            let step = p1 / derivative;
            x -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        *node = x;
        *weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
    (nodes, weights)
}

mod recursion;
#[cfg(test)]
mod superposition_tests;
