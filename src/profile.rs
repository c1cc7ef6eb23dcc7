//! Even, λ-periodic rigid surface profiles given as cosine harmonics (units of λ):
//!
//! ```text
//! y_s(x) = −Σ_k Δ_k (1 − cos 2π n_k x),   AR_k = Δ_k n_k
//! ```
//!
//! Each harmonic is named by its order `n_k` (it has `n_k` waves per λ) and its own aspect
//! ratio `AR_k`: its amplitude over its own wavelength `λ/n_k`. The first harmonic is the big
//! wave, order 1, with a positive aspect ratio; the others are finer (orders ≥ 2, strictly
//! increasing). Every term is `≤ 0` and vanishes at `x = 0`, so the peak `x = 0` is the highest
//! point and first contact happens there. A single sinusoid is the profile `1:AR`.
//!
//! A Weierstrass profile ([`Weierstrass`], `weierstrass:AR0,gamma,D,K`) is the list of `K`
//! harmonics of orders `γ^k` (integer `γ ≥ 2`, fractal dimension `D ∈ (1, 2)`):
//!
//! ```text
//! y_s(x) = −g₀ Σ_{k=0}^{K−1} γ^{(D−2)k} (1 − cos 2π γ^k x),   Δ_k = g₀ γ^{(D−2)k},  n_k = γ^k,
//! AR_k = Δ_k n_k = AR₀ γ^{(D−1)k},   AR₀ = g₀/λ
//! ```
//!
//! (each scale's amplitude over its own wavelength, as above: the scales steepen by `γ^{D−1}`).

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// One cosine harmonic of a profile.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Harmonic {
    /// Waves per wavelength λ (`n_k ≥ 1`).
    pub order: u32,
    /// Its own aspect ratio `AR_k = Δ_k n_k/λ` (`≥ 0`).
    pub aspect_ratio: f64,
}

impl Harmonic {
    /// Amplitude `Δ_k/λ = AR_k/n_k`.
    pub fn amplitude(&self) -> f64 {
        self.aspect_ratio / self.order as f64
    }
}

/// Most harmonics a profile may have (a Weierstrass profile of up to 16 scales).
pub const MAX_HARMONICS: usize = 16;

/// The finer harmonics of a profile (orders ≥ 2, strictly increasing; at most
/// [`MAX_HARMONICS`] − 1); empty for a single sinusoid. A fixed-capacity list, so that the
/// problem description that holds it stays `Copy`; read and written as a list.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "Vec<Harmonic>", into = "Vec<Harmonic>")]
pub struct FinerHarmonics {
    /// The harmonics first, then `None`s.
    items: [Option<Harmonic>; MAX_HARMONICS - 1],
}

impl FinerHarmonics {
    /// No finer harmonic: a single sinusoid.
    pub const NONE: FinerHarmonics = FinerHarmonics {
        items: [None; MAX_HARMONICS - 1],
    };

    /// The finer harmonics, checked ([`ProfileError`]).
    pub fn new(harmonics: &[Harmonic]) -> Result<Self, ProfileError> {
        if harmonics.len() > MAX_HARMONICS - 1 {
            return Err(ProfileError::TooMany {
                count: harmonics.len() + 1,
            });
        }
        let mut out = Self::NONE;
        let mut last_order = 1;
        for &h in harmonics {
            if h.order <= last_order {
                return Err(ProfileError::Order {
                    order: h.order,
                    after: last_order,
                });
            }
            if !(h.aspect_ratio.is_finite() && h.aspect_ratio >= 0.0) {
                return Err(ProfileError::AspectRatio {
                    order: h.order,
                    value: h.aspect_ratio,
                    allowed: ">= 0",
                });
            }
            out.items[out.iter().count()] = Some(h);
            last_order = h.order;
        }
        Ok(out)
    }

    /// The harmonics, in order.
    pub fn iter(&self) -> impl Iterator<Item = Harmonic> + '_ {
        self.items.iter().map_while(|h| *h)
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.items[0].is_none()
    }
}

impl TryFrom<Vec<Harmonic>> for FinerHarmonics {
    type Error = ProfileError;
    fn try_from(v: Vec<Harmonic>) -> Result<Self, Self::Error> {
        Self::new(&v)
    }
}

impl From<FinerHarmonics> for Vec<Harmonic> {
    fn from(f: FinerHarmonics) -> Self {
        f.iter().collect()
    }
}

/// A profile the solver cannot take, naming the harmonic and the limit.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProfileError {
    /// No harmonic, or the first is not of order 1.
    #[error("a profile starts with the harmonic of order 1 (the wavelength λ), `1:AR`; got {got}")]
    FirstHarmonic {
        /// What was given first, in words.
        got: String,
    },
    /// Orders not strictly increasing.
    #[error("harmonic orders must increase strictly: order {order} follows order {after}")]
    Order {
        /// The offending order.
        order: u32,
        /// The order before it.
        after: u32,
    },
    /// An aspect ratio out of range.
    #[error("harmonic {order}: aspect ratio {value} is out of range; allowed: {allowed}")]
    AspectRatio {
        /// Its order.
        order: u32,
        /// The value given.
        value: f64,
        /// The range, in words.
        allowed: &'static str,
    },
    /// More harmonics than [`MAX_HARMONICS`].
    #[error("a profile has at most {MAX_HARMONICS} harmonics; got {count}")]
    TooMany {
        /// How many were given.
        count: usize,
    },
    /// Text that is not `order:aspect_ratio` pairs.
    #[error("`{text}` is not a profile: comma-separated `order:aspect_ratio` pairs expected, e.g. `1:0.1,16:0.05`, or `weierstrass:AR0,gamma,D,K`, e.g. `weierstrass:0.05,3,1.3,3`")]
    Syntax {
        /// The text given.
        text: String,
    },
    /// A Weierstrass parameter out of range.
    #[error("Weierstrass profile: {field} = {value} is out of range; allowed: {allowed}")]
    Weierstrass {
        /// The parameter (`AR0`, `gamma`, `D`, `K`).
        field: &'static str,
        /// The value given, as text.
        value: String,
        /// The range, in words.
        allowed: String,
    },
}

/// A Weierstrass profile (module doc): `K` scales of orders `γ^k`, aspect ratios
/// `AR_k = AR₀ γ^{(D−1)k}`, `k = 0 … K−1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Weierstrass {
    /// `AR₀ = g₀/λ`, the big wave's aspect ratio (`> 0`).
    pub aspect_ratio_0: f64,
    /// The order ratio of successive scales `γ` (integer `≥ 2`, so the profile is λ-periodic).
    pub gamma: u32,
    /// The fractal dimension `D ∈ (1, 2)`.
    pub dimension: f64,
    /// The number of scales `K` (`1 … MAX_HARMONICS`).
    pub scales: u32,
}

impl Weierstrass {
    /// The profile's parameters, checked ([`ProfileError::Weierstrass`]): the finest order
    /// `γ^{K−1}` must fit a `u32`.
    pub fn new(
        aspect_ratio_0: f64,
        gamma: u32,
        dimension: f64,
        scales: u32,
    ) -> Result<Self, ProfileError> {
        let refuse = |field, value: String, allowed: String| {
            Err(ProfileError::Weierstrass {
                field,
                value,
                allowed,
            })
        };
        if !(aspect_ratio_0.is_finite() && aspect_ratio_0 > 0.0) {
            return refuse("AR0", aspect_ratio_0.to_string(), "> 0".into());
        }
        if gamma < 2 {
            return refuse("gamma", gamma.to_string(), "an integer >= 2".into());
        }
        if !(dimension > 1.0 && dimension < 2.0) {
            return refuse("D", dimension.to_string(), "1 < D < 2".into());
        }
        if !(1..=MAX_HARMONICS as u32).contains(&scales) {
            return refuse("K", scales.to_string(), format!("1 ... {MAX_HARMONICS}"));
        }
        if gamma.checked_pow(scales - 1).is_none() {
            return refuse(
                "K",
                scales.to_string(),
                format!("a finest order gamma^(K-1) below 2^32 (gamma = {gamma})"),
            );
        }
        Ok(Self {
            aspect_ratio_0,
            gamma,
            dimension,
            scales,
        })
    }

    /// `AR_k = AR₀ γ^{(D−1)k}`.
    pub fn aspect_ratio(&self, k: u32) -> f64 {
        self.aspect_ratio_0 * (self.gamma as f64).powf((self.dimension - 1.0) * k as f64)
    }

    /// The harmonics `(γ^k, AR_k)`, `k = 0 … K−1`.
    pub fn harmonics(&self) -> Vec<Harmonic> {
        (0..self.scales)
            .map(|k| Harmonic {
                order: self.gamma.pow(k),
                aspect_ratio: self.aspect_ratio(k),
            })
            .collect()
    }

    /// The profile of its harmonics.
    pub fn profile(&self) -> Profile {
        Profile::new(&self.harmonics()).expect("checked parameters give a valid harmonic list")
    }
}

impl FromStr for Weierstrass {
    type Err = ProfileError;
    /// `AR0,gamma,D,K`, e.g. `0.05,3,1.3,3`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let syntax = || ProfileError::Syntax {
            text: format!("weierstrass:{s}"),
        };
        let parts: Vec<&str> = s.split(',').map(str::trim).collect();
        let [ar0, gamma, d, k] = parts[..] else {
            return Err(syntax());
        };
        Self::new(
            ar0.parse().map_err(|_| syntax())?,
            gamma.parse().map_err(|_| syntax())?,
            d.parse().map_err(|_| syntax())?,
            k.parse().map_err(|_| syntax())?,
        )
    }
}

/// An even, λ-periodic profile: the big wave (order 1) and its finer harmonics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Profile {
    /// Aspect ratio of the big wave (order 1), `> 0`.
    pub aspect_ratio: f64,
    /// The finer harmonics.
    pub finer: FinerHarmonics,
}

impl Profile {
    /// The single sinusoid `1:AR`.
    pub fn sinusoid(aspect_ratio: f64) -> Self {
        Self {
            aspect_ratio,
            finer: FinerHarmonics::NONE,
        }
    }

    /// The profile of a list of harmonics, the first of order 1 ([`ProfileError`]).
    pub fn new(harmonics: &[Harmonic]) -> Result<Self, ProfileError> {
        let Some((first, finer)) = harmonics.split_first() else {
            return Err(ProfileError::FirstHarmonic {
                got: "no harmonic".into(),
            });
        };
        if first.order != 1 {
            return Err(ProfileError::FirstHarmonic {
                got: format!("order {}", first.order),
            });
        }
        if !(first.aspect_ratio.is_finite() && first.aspect_ratio > 0.0) {
            return Err(ProfileError::AspectRatio {
                order: 1,
                value: first.aspect_ratio,
                allowed: "> 0",
            });
        }
        Ok(Self {
            aspect_ratio: first.aspect_ratio,
            finer: FinerHarmonics::new(finer)?,
        })
    }

    /// The profile of `(order, aspect_ratio)` pairs, the first of order 1, as a spec lists
    /// them (`profile = [[1, 0.1], [16, 0.05]]`; [`Profile::new`]).
    pub fn from_pairs(pairs: &[(u32, f64)]) -> Result<Self, ProfileError> {
        let harmonics: Vec<Harmonic> = pairs
            .iter()
            .map(|&(order, aspect_ratio)| Harmonic {
                order,
                aspect_ratio,
            })
            .collect();
        Self::new(&harmonics)
    }

    /// Every harmonic, the big wave first.
    pub fn harmonics(&self) -> impl Iterator<Item = Harmonic> + '_ {
        std::iter::once(Harmonic {
            order: 1,
            aspect_ratio: self.aspect_ratio,
        })
        .chain(self.finer.iter())
    }

    /// Whether this is a single sinusoid: no finer harmonic at all (a finer harmonic of zero
    /// amplitude still makes a profile, solved by node events).
    pub fn is_sinusoid(&self) -> bool {
        self.finer.is_empty()
    }

    /// The highest order `max n_k`.
    pub fn max_order(&self) -> u32 {
        self.harmonics().map(|h| h.order).max().unwrap_or(1)
    }

    /// `Σ Δ_k/λ`: the scale of the profile's heights (`Δ` of a single sinusoid).
    pub fn amplitude_sum(&self) -> f64 {
        self.harmonics().map(|h| h.amplitude()).sum()
    }

    /// The largest slope any harmonic can reach, `Σ 2π AR_k` (a bound on `|y_s'|`).
    pub fn slope_bound(&self) -> f64 {
        self.harmonics()
            .map(|h| std::f64::consts::TAU * h.aspect_ratio)
            .sum()
    }

    /// `y_s(x)` (units of λ).
    pub fn y(&self, x: f64) -> f64 {
        self.harmonics()
            .map(|h| -h.amplitude() * (1.0 - (std::f64::consts::TAU * h.order as f64 * x).cos()))
            .sum()
    }

    /// `y_s'(x)`.
    pub fn slope(&self, x: f64) -> f64 {
        self.harmonics()
            .map(|h| {
                let k = std::f64::consts::TAU * h.order as f64;
                -h.amplitude() * k * (k * x).sin()
            })
            .sum()
    }

    /// `y_s''(x)`.
    pub fn curvature(&self, x: f64) -> f64 {
        self.harmonics()
            .map(|h| {
                let k = std::f64::consts::TAU * h.order as f64;
                -h.amplitude() * k * k * (k * x).cos()
            })
            .sum()
    }
}

impl FromStr for Profile {
    type Err = ProfileError;
    /// `order:aspect_ratio` pairs separated by commas, e.g. `1:0.1,16:0.05`, or a Weierstrass
    /// profile `weierstrass:AR0,gamma,D,K` ([`Weierstrass`]).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if let Some(parameters) = s.trim().strip_prefix("weierstrass:") {
            return Ok(parameters.parse::<Weierstrass>()?.profile());
        }
        let syntax = || ProfileError::Syntax { text: s.into() };
        let harmonics = s
            .split(',')
            .map(|pair| {
                let (n, ar) = pair.trim().split_once(':').ok_or_else(syntax)?;
                Ok(Harmonic {
                    order: n.trim().parse().map_err(|_| syntax())?,
                    aspect_ratio: ar.trim().parse().map_err(|_| syntax())?,
                })
            })
            .collect::<Result<Vec<_>, ProfileError>>()?;
        Self::new(&harmonics)
    }
}

impl fmt::Display for Profile {
    /// The form [`FromStr`] reads.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let parts: Vec<String> = self
            .harmonics()
            .map(|h| format!("{}:{}", h.order, h.aspect_ratio))
            .collect();
        f.write_str(&parts.join(","))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_prints_a_two_scale_profile() {
        let p: Profile = "1:0.1, 16:0.05".parse().unwrap();
        assert_eq!(p.to_string(), "1:0.1,16:0.05");
        assert_eq!(p.max_order(), 16);
        assert!((p.amplitude_sum() - (0.1 + 0.05 / 16.0)).abs() < 1e-15);
        assert!(!p.is_sinusoid());
    }

    #[test]
    fn refuses_bad_profiles_naming_the_harmonic() {
        let err = |s: &str| s.parse::<Profile>().unwrap_err().to_string();
        assert!(err("2:0.1").contains("order 1"), "{}", err("2:0.1"));
        assert!(err("1:0.1,16:0.05,8:0.1").contains("order 8 follows order 16"));
        assert!(err("1:0.1,16:-0.05").contains("harmonic 16"));
        assert!(err("1:0").contains("harmonic 1"));
        assert!(err("1:0.1;2:0.1").contains("order:aspect_ratio"));
        let many: Vec<String> = (1..=17).map(|n| format!("{n}:0.01")).collect();
        assert!(err(&many.join(",")).contains("at most 16"));
        let sixteen: Vec<String> = (1..=16).map(|n| format!("{n}:0.01")).collect();
        assert_eq!(
            sixteen.join(",").parse::<Profile>().unwrap().max_order(),
            16
        );
    }

    /// `weierstrass:AR0,gamma,D,K` is the harmonic list `γ^k : AR₀ γ^{(D−1)k}`, and its height is
    /// the issue's `−g₀ Σ γ^{(D−2)k} (1 − cos 2πγ^k x)` with `g₀ = AR₀` (λ = 1).
    #[test]
    fn a_weierstrass_profile_is_its_harmonic_list() {
        let p: Profile = "weierstrass:0.05,3,1.3,3".parse().unwrap();
        let orders: Vec<u32> = p.harmonics().map(|h| h.order).collect();
        assert_eq!(orders, [1, 3, 9]);
        for (k, h) in p.harmonics().enumerate() {
            let expected = 0.05 * 3f64.powf(0.3 * k as f64);
            assert!((h.aspect_ratio / expected - 1.0).abs() < 1e-15, "{h:?}");
        }
        // 0.0695, 0.0967 as the issue lists them (to its three digits)
        let listed: Profile = "1:0.05,3:0.0695,9:0.0967".parse().unwrap();
        for (a, b) in p.harmonics().zip(listed.harmonics()) {
            assert!(
                (a.aspect_ratio - b.aspect_ratio).abs() < 5e-5,
                "{a:?} vs {b:?}"
            );
        }
        let t = std::f64::consts::TAU;
        for x in [0.0, 0.01, 0.13, 0.37, 0.5] {
            let issue: f64 = -0.05
                * (0..3)
                    .map(|k| 3f64.powf(-0.7 * k as f64) * (1.0 - (t * 3f64.powi(k) * x).cos()))
                    .sum::<f64>();
            assert!((p.y(x) - issue).abs() < 1e-16, "x = {x}");
        }
        let k16: Profile = "weierstrass:0.01,2,1.5,16".parse().unwrap();
        assert_eq!(k16.max_order(), 1 << 15);
    }

    #[test]
    fn refuses_bad_weierstrass_parameters_naming_them() {
        let err = |s: &str| s.parse::<Profile>().unwrap_err().to_string();
        assert!(err("weierstrass:0,3,1.3,3").contains("AR0 = 0"));
        assert!(err("weierstrass:0.1,1,1.3,3").contains("gamma = 1"));
        assert!(err("weierstrass:0.1,3,2,3").contains("D = 2"));
        assert!(err("weierstrass:0.1,3,1,3").contains("D = 1"));
        assert!(err("weierstrass:0.1,3,1.5,0").contains("K = 0"));
        assert!(err("weierstrass:0.1,3,1.5,17").contains("K = 17"));
        let e = err("weierstrass:0.1,1000,1.5,5");
        assert!(e.contains("K = 5") && e.contains("2^32"), "{e}");
        for bad in [
            "weierstrass:0.1,3,1.5",
            "weierstrass:0.1,3.5,1.5,3",
            "weierstrass:a,3,1.5,3",
        ] {
            assert!(
                err(bad).contains("weierstrass:AR0,gamma,D,K"),
                "{}",
                err(bad)
            );
        }
    }

    /// A single sinusoid's height, slope and curvature are the closed forms, bit for bit.
    #[test]
    fn a_sinusoid_is_the_closed_form() {
        let p = Profile::sinusoid(0.3);
        let t = std::f64::consts::TAU;
        for x in [0.0, 0.013, 0.2, 0.37, 0.5] {
            assert_eq!(p.y(x), -0.3 * (1.0 - (t * x).cos()));
            assert_eq!(p.slope(x), -0.3 * t * (t * x).sin());
            assert_eq!(p.curvature(x), -0.3 * t * t * (t * x).cos());
        }
    }

    /// Slope and curvature are the derivatives of the height (central differences).
    #[test]
    fn derivatives_match_differences() {
        let p: Profile = "1:0.1,8:0.1".parse().unwrap();
        let h = 1e-6;
        for x in [0.01, 0.1, 0.23, 0.41] {
            let dy = (p.y(x + h) - p.y(x - h)) / (2.0 * h);
            let d2y = (p.slope(x + h) - p.slope(x - h)) / (2.0 * h);
            assert!((dy - p.slope(x)).abs() < 1e-8, "x = {x}");
            assert!((d2y - p.curvature(x)).abs() < 1e-6, "x = {x}");
        }
        assert!(p.y(0.0) == 0.0 && (0..=50).all(|i| p.y(i as f64 / 100.0) <= 0.0));
    }
}
