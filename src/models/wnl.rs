//! The WNL ("Westergaard NonLinear") model: Westergaard's law corrected by two quadratic
//! polynomials A(AR, τ_max) and B(AR, τ_max) (paper Eq. 4–6, docs/replication.md R5).
//!
//! The paper's Eq. 4 lost its fences and a superscript when it was typeset to text, so its
//! form is a hypothesis. Three readings are implemented, by name (x = a/λ, p̄_W = Westergaard):
//!
//! | name         | p̄/E*                                   |
//! |--------------|----------------------------------------|
//! | `bracket-sq` | p̄_W/E* · [B + x·A·cos²(πx)]  (default) |
//! | `bracket-2x` | p̄_W/E* · [B + x·A·cos(2πx)]            |
//! | `literal`    | p̄_W/E* · B + x·A·cos²(πx)              |
//!
//! A = a₀ + a₁ AR + a₂ τ + a₃ AR² + a₄ AR τ + a₅ τ², and B likewise with bᵢ, τ = τ_max in MPa.

use super::{FitDomain, PressureLaw, Westergaard};
use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;

/// Which reading of the paper's Eq. 4 to evaluate (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Deserialize)]
pub enum Reading {
    /// p̄_W · [B + x·A·cos²(πx)]: the default until our data say otherwise (R5).
    #[default]
    #[serde(rename = "bracket-sq")]
    BracketSq,
    /// p̄_W · [B + x·A·cos(2πx)].
    #[serde(rename = "bracket-2x")]
    Bracket2x,
    /// p̄_W · B + x·A·cos²(πx) (E* = 1): negative for small x with Table 1 (R5).
    #[serde(rename = "literal")]
    Literal,
}

impl Reading {
    pub const ALL: [Reading; 3] = [Reading::BracketSq, Reading::Bracket2x, Reading::Literal];

    /// The name used in specs, on the command line and in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Reading::BracketSq => "bracket-sq",
            Reading::Bracket2x => "bracket-2x",
            Reading::Literal => "literal",
        }
    }
}

impl Reading {
    /// The factor s(x) that multiplies A under this reading, from Westergaard's `p_w` =
    /// p̄_W/E* at `x` = a/λ: every reading is p̄/E* = p̄_W/E*·B + s(x)·A (the table in the
    /// module documentation), the one definition that [`Wnl`] evaluates and the refit
    /// (`crate::fit`) regresses on.
    pub fn a_shape(self, x: f64, p_w: f64) -> f64 {
        match self {
            Reading::BracketSq => p_w * x * (PI * x).cos().powi(2),
            Reading::Bracket2x => p_w * x * (2.0 * PI * x).cos(),
            Reading::Literal => x * (PI * x).cos().powi(2),
        }
    }
}

impl fmt::Display for Reading {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A reading name that names no reading.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown reading `{0}`; allowed: bracket-sq, bracket-2x, literal")]
pub struct ReadingParseError(pub String);

impl FromStr for Reading {
    type Err = ReadingParseError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Reading::ALL
            .into_iter()
            .find(|r| r.name() == s)
            .ok_or_else(|| ReadingParseError(s.into()))
    }
}

/// The six coefficients of each correction polynomial, with the domain they were fitted on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients {
    /// a₀…a₅ of A(AR, τ_max).
    pub a: [f64; 6],
    /// b₀…b₅ of B(AR, τ_max).
    pub b: [f64; 6],
    /// Where the polynomials were fitted; evaluations outside it are extrapolations.
    pub domain: FitDomain,
}

impl Coefficients {
    /// The paper's Table 1 (docs/replication.md R5).
    pub const PAPER_TABLE1: Coefficients = Coefficients {
        a: [0.24536, -9.96905, 4.80482, -0.305098, -47.5605, -3.56199],
        b: [0.963506, 1.26005, -0.33278, -0.424387, 10.4263, -2.45931],
        domain: FitDomain::PAPER,
    };
}

/// One of the two correction polynomials of a coefficient set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Correction {
    /// A(AR, τ_max), coefficients a₀…a₅.
    A,
    /// B(AR, τ_max), coefficients b₀…b₅.
    B,
}

impl Correction {
    pub const BOTH: [Correction; 2] = [Correction::A, Correction::B];

    /// `A` or `B`.
    pub fn name(self) -> &'static str {
        match self {
            Correction::A => "A",
            Correction::B => "B",
        }
    }

    /// The coefficient letter, `a` or `b`.
    pub fn letter(self) -> &'static str {
        match self {
            Correction::A => "a",
            Correction::B => "b",
        }
    }

    /// This polynomial's six coefficients in `c`.
    pub fn of(self, c: &Coefficients) -> &[f64; 6] {
        match self {
            Correction::A => &c.a,
            Correction::B => &c.b,
        }
    }
}

/// The quadratic form c₀ + c₁ AR + c₂ τ + c₃ AR² + c₄ AR τ + c₅ τ² shared by A and B.
pub fn quadratic_surface(c: &[f64; 6], aspect_ratio: f64, tau_max_mpa: f64) -> f64 {
    let (r, t) = (aspect_ratio, tau_max_mpa);
    c[0] + c[1] * r + c[2] * t + c[3] * r * r + c[4] * r * t + c[5] * t * t
}

/// The monomials [1, AR, τ, AR², AR τ, τ²] of [`quadratic_surface`], for fitting.
pub fn quadratic_monomials(aspect_ratio: f64, tau_max_mpa: f64) -> [f64; 6] {
    let (r, t) = (aspect_ratio, tau_max_mpa);
    [1.0, r, t, r * r, r * t, t * t]
}

/// The WNL law at one (AR, τ_max), with one reading and one coefficient set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wnl {
    /// Δ/λ (dimensionless, > 0).
    pub aspect_ratio: f64,
    /// Interfacial shear strength τ_max in MPa (≥ 0), as the polynomials take it.
    pub tau_max_mpa: f64,
    pub reading: Reading,
    pub coefficients: Coefficients,
}

impl Wnl {
    pub fn new(
        aspect_ratio: f64,
        tau_max_mpa: f64,
        reading: Reading,
        coefficients: Coefficients,
    ) -> Self {
        Self {
            aspect_ratio,
            tau_max_mpa,
            reading,
            coefficients,
        }
    }

    /// The correction A(AR, τ_max).
    pub fn correction_a(&self) -> f64 {
        quadratic_surface(&self.coefficients.a, self.aspect_ratio, self.tau_max_mpa)
    }

    /// The correction B(AR, τ_max).
    pub fn correction_b(&self) -> f64 {
        quadratic_surface(&self.coefficients.b, self.aspect_ratio, self.tau_max_mpa)
    }

    /// True outside the coefficients' fit domain.
    pub fn is_extrapolated(&self) -> bool {
        !self
            .coefficients
            .domain
            .contains(self.aspect_ratio, self.tau_max_mpa)
    }
}

impl PressureLaw for Wnl {
    fn p_over_estar(&self, a_over_lambda: f64) -> f64 {
        let p_w = Westergaard::new(self.aspect_ratio).p_over_estar(a_over_lambda);
        p_w * self.correction_b() + self.reading.a_shape(a_over_lambda, p_w) * self.correction_a()
    }
}
