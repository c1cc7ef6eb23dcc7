//! The recursive superposition for many scales (docs/replication.md R14): the two-scale model of
//! the parent module applied scale by scale, after Ciavarella, Demelio, Barber & Jang (2000,
//! Proc. R. Soc. A 456, 387) for a Weierstrass profile.
//!
//! Scale 0 is the big wave (order 1); scale k + 1 has `m_k ≥ 2` waves per wavelength of scale k
//! (order `n_{k+1} = m_k n_k`), `n_k` crests per λ at `x_j = j/n_k`. At a mean pressure p̄:
//!
//! 1. Scale 0 carries p̄ (steps 1–2 of the parent module: its law's half-width a₁, Westergaard's
//!    pressure shape).
//! 2. Each crest of scale k + 1 carries the mean, over its own period, of the pressure that the
//!    crests of scale k lay down: a crest of scale k with mean pressure p in partial contact
//!    (its law inverted at p gives its half-width) spreads Westergaard's shape at that half-width
//!    with mean p over its own period ([`BigWaveDistribution`]); in full contact
//!    (p ≥ its law's full-contact pressure p*) it spreads `p + p* cos(2π n_k (x − x_j))`,
//!    Westergaard's exact full-contact pressure, and the limit of the partial shape as the
//!    half-width reaches ½ (for WNL the same shape with WNL's p*); a free crest spreads nothing.
//!    With an even ratio `m_k` the child at a parent's valley straddles two parents' periods and
//!    takes half its load from each.
//! 3. Each crest of scale k + 1 inverts its own law (built for its aspect ratio, in units of its
//!    own wavelength) at that mean: free, partial or full, as in the two-scale model.
//! 4. The contact fraction is the sum over the finest scale's contacts,
//!    `Σ_j 2 a_j/λ = (1/n_{K−1}) Σ_j 2 a_j/λ_{K−1}`.
//!
//! Each scale's loads sum to p̄ (the period means are exact, parent module). With one finer
//! scale this is the two-scale model, bit for bit (the parent's [`superposed_contact`] is this
//! function with one scale); with none, the single law (2a₁).
//!
//! [`superposed_contact`]: super::superposed_contact

use super::{big_wave, check_order, small_width, BigWaveDistribution, CrestContact, CrestState};
use super::{SuperposedContact, SuperpositionError, MAX_ORDER};
use crate::models::inverse::check_invertible;
use crate::models::PressureLaw;
use crate::profile::Profile;
use std::f64::consts::PI;

/// A scale below the big wave: its waves per wavelength of the scale above, and its law (built
/// for its own aspect ratio, dimensionless in its own wavelength).
#[derive(Clone, Copy)]
pub struct FinerScale<'a> {
    /// `m_k = n_{k+1}/n_k`, an integer ≥ 2.
    pub ratio: u32,
    /// The single-scale law of this scale.
    pub law: &'a dyn PressureLaw,
}

/// The pressure a crest lays down over its own period (step 2 of the module doc).
enum CrestPressure {
    /// A free crest: none.
    Free,
    /// Westergaard's shape at the crest's half-width, mean p.
    Partial(BigWaveDistribution),
    /// Full contact: `p + p* cos(2π x)` in the crest's own wavelength.
    Full { mean: f64, amplitude: f64 },
}

impl CrestPressure {
    /// The means over the periods of its children at distance `d = 0 … ⌊m/2⌋` children from the
    /// crest (the one at `d = m/2`, m even, over the whole period about the valley, as if the
    /// neighbour were this crest; step 2 takes half from each); empty for a free crest.
    fn child_means_by_distance(&self, ratio: u32) -> Vec<f64> {
        match self {
            CrestPressure::Free => Vec::new(),
            CrestPressure::Partial(d) => d.crest_means_by_distance(ratio),
            CrestPressure::Full { mean, amplitude } => {
                // mean of cos 2πx over [d/m − 1/(2m), d/m + 1/(2m)] = cos(2πd/m) sin(π/m)/(π/m)
                let m = ratio as f64;
                let sinc = (PI / m).sin() / (PI / m);
                (0..=ratio / 2)
                    .map(|d| mean + amplitude * (2.0 * PI * d as f64 / m).cos() * sinc)
                    .collect()
            }
        }
    }
}

/// The mean pressure of each child, c = 0 … n·m − 1, from its parents' child means by distance
/// (`by_parent[j]`, empty for a free parent): child c is nearest parent `c/m` or `c/m + 1`
/// (periodic); one at a valley (m even) takes half from each of the two.
fn child_means(by_parent: &[Vec<f64>], ratio: u32) -> Vec<f64> {
    let parents = by_parent.len();
    let m = ratio as usize;
    let from = |j: usize, d: usize| by_parent[j % parents].get(d).copied().unwrap_or(0.0);
    (0..parents * m)
        .map(|c| {
            let (j, d) = (c / m, c % m);
            if 2 * d < m {
                from(j, d)
            } else if 2 * d > m {
                from(j + 1, m - d)
            } else {
                0.5 * (from(j, d) + from(j + 1, d))
            }
        })
        .collect()
}

/// The finest order `Π m_k`, each ratio checked (2 ≤ m ≤ [`MAX_ORDER`], and the product too).
fn finest_order(finer: &[FinerScale<'_>]) -> Result<u32, SuperpositionError> {
    finer.iter().try_fold(1u32, |order, scale| {
        check_order(scale.ratio)?;
        order
            .checked_mul(scale.ratio)
            .filter(|&n| n <= MAX_ORDER)
            .ok_or(SuperpositionError::Order {
                order: order.saturating_mul(scale.ratio),
            })
    })
}

/// The crests of one scale: each crest's mean (`means`) inverted in `law` (step 3).
fn crests_of(
    law: &dyn PressureLaw,
    means: &[f64],
) -> Result<Vec<CrestContact>, SuperpositionError> {
    let full = law.full_contact_p_over_estar();
    let n = means.len() as f64;
    means
        .iter()
        .enumerate()
        .map(|(j, &p)| {
            let x_over_lambda = j as f64 / n;
            let (width, state) =
                small_width(law, full, p).map_err(|source| SuperpositionError::SmallInverse {
                    x_over_lambda,
                    p_over_estar: p,
                    source,
                })?;
            Ok(CrestContact {
                x_over_lambda,
                p_over_estar: p,
                half_width_over_wavelength: width,
                state,
            })
        })
        .collect()
}

/// What a crest of law `law` lays down (step 2).
fn pressure_of(
    law: &dyn PressureLaw,
    crest: &CrestContact,
) -> Result<CrestPressure, SuperpositionError> {
    Ok(match crest.state {
        CrestState::Free => CrestPressure::Free,
        CrestState::Full => CrestPressure::Full {
            mean: crest.p_over_estar,
            amplitude: law.full_contact_p_over_estar(),
        },
        CrestState::Partial => CrestPressure::Partial(BigWaveDistribution::new(
            crest.half_width_over_wavelength,
            crest.p_over_estar,
        )?),
    })
}

/// The order ratios `m_k = n_{k+1}/n_k` of a profile's harmonics, each a whole number ≥ 2
/// ([`SuperpositionError::NotNested`] otherwise): the scales of [`recursive_contact`]. A
/// Weierstrass profile's are all γ.
pub fn order_ratios(profile: &Profile) -> Result<Vec<u32>, SuperpositionError> {
    let orders: Vec<u32> = profile.harmonics().map(|h| h.order).collect();
    orders
        .windows(2)
        .map(|w| match w[1] % w[0] {
            0 => Ok(w[1] / w[0]),
            _ => Err(SuperpositionError::NotNested {
                order: w[1],
                after: w[0],
            }),
        })
        .collect()
}

/// The recursive superposition over `profile`'s harmonics (their orders must nest,
/// [`order_ratios`]), the law `law_at(AR_k)` at each scale, at p̄/E* = `p_over_estar`
/// ([`recursive_contact`]).
pub fn profile_contact<L: PressureLaw>(
    profile: &Profile,
    law_at: impl Fn(f64) -> L,
    p_over_estar: f64,
) -> Result<SuperposedContact, SuperpositionError> {
    let ratios = order_ratios(profile)?;
    let laws: Vec<L> = profile
        .harmonics()
        .map(|h| law_at(h.aspect_ratio))
        .collect();
    let finer: Vec<FinerScale> = ratios
        .into_iter()
        .zip(&laws[1..])
        .map(|(ratio, law)| FinerScale { ratio, law })
        .collect();
    recursive_contact(&laws[0], &finer, p_over_estar)
}

/// The recursive superposition (module doc) of the big wave's law `big` (built for AR₀) and the
/// finer scales `finer`, coarsest first, at the mean pressure `p_over_estar` = p̄/E*
/// (0 < p̄ < the big wave's full-contact pressure). The crests returned are the finest scale's
/// (the big wave itself when `finer` is empty); the finest order may be at most [`MAX_ORDER`].
pub fn recursive_contact(
    big: &dyn PressureLaw,
    finer: &[FinerScale<'_>],
    p_over_estar: f64,
) -> Result<SuperposedContact, SuperpositionError> {
    finest_order(finer)?;
    let distribution = big_wave(big, p_over_estar)?;
    let a1 = distribution.half_width_over_lambda();
    let mut crests = vec![CrestContact {
        x_over_lambda: 0.0,
        p_over_estar,
        half_width_over_wavelength: a1,
        state: CrestState::Partial,
    }];
    let mut pressures = vec![CrestPressure::Partial(distribution)];
    let mut scale_fractions = vec![2.0 * a1];
    for (k, scale) in finer.iter().enumerate() {
        check_invertible(scale.law).map_err(|source| SuperpositionError::SmallLaw { source })?;
        let by_parent: Vec<Vec<f64>> = pressures
            .iter()
            .map(|p| p.child_means_by_distance(scale.ratio))
            .collect();
        crests = crests_of(scale.law, &child_means(&by_parent, scale.ratio))?;
        let fraction = crests
            .iter()
            .map(|c| 2.0 * c.half_width_over_wavelength)
            .sum::<f64>()
            / crests.len() as f64;
        scale_fractions.push(fraction);
        if k + 1 < finer.len() {
            pressures = crests
                .iter()
                .map(|c| pressure_of(scale.law, c))
                .collect::<Result<_, _>>()?;
        }
    }
    Ok(SuperposedContact {
        contact_fraction: *scale_fractions.last().expect("scale 0's"),
        big_half_width_over_lambda: a1,
        crests,
        scale_fractions,
    })
}

#[cfg(test)]
#[path = "recursion_tests.rs"]
mod tests;
