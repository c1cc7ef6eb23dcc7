//! Closed-form contact laws p̄/E*(a/λ) for a rigid sinusoid on a soft solid, their inverse, and
//! the superposition of two of them for a two-scale profile (`superposition`, R13), or of many,
//! scale by scale, for a Weierstrass profile (`superposition::recursion`, R14).
//!
//! Everything here is dimensionless: the contact half-width enters as `a_over_lambda`
//! (a/λ ∈ [0, ½], ½ = full contact), the mean pressure as `p_over_estar` (p̄/E*), the
//! waviness as the aspect ratio AR = Δ/λ. The one dimensional input is the interfacial
//! shear strength τ_max, in MPa, because the paper's correction polynomials take it so
//! (docs/replication.md R5, R9).

pub mod coefficient_sets;
pub mod domain;
pub mod inverse;
pub mod spence;
pub mod superposition;
pub mod westergaard;
pub mod wnl;

pub use coefficient_sets::CoefficientSet;
pub use domain::FitDomain;
pub use inverse::{a_over_lambda_at, InverseError};
pub use superposition::{
    contact_fraction_limit, order_ratios, profile_contact, recursive_contact, superposed_contact,
    BigWaveDistribution, CrestContact, CrestState, FinerScale, SuperposedContact,
    SuperpositionError,
};
pub use westergaard::Westergaard;
pub use wnl::{Coefficients, Reading, Wnl};

/// A mean-pressure law p̄/E* as a function of the contact half-width a/λ.
pub trait PressureLaw {
    /// Mean pressure over the plane-strain modulus, p̄/E*, at contact half-width `a_over_lambda`,
    /// unchecked (see [`PressureLaw::physical_p_over_estar`]).
    fn p_over_estar(&self, a_over_lambda: f64) -> f64;

    /// p̄/E* when it is a physical answer: finite and not negative. A law evaluated where it
    /// overflows (an enormous aspect ratio or shear strength) or where its correction
    /// polynomials drive it below zero (the `literal` reading at small a/λ, WNL far outside
    /// its fit domain) gives an error naming the point, never a number.
    fn physical_p_over_estar(&self, a_over_lambda: f64) -> Result<f64, UnphysicalPressure> {
        let p = self.p_over_estar(a_over_lambda);
        if !p.is_finite() {
            Err(UnphysicalPressure::NotFinite {
                a_over_lambda,
                p_over_estar: p,
            })
        } else if p < 0.0 {
            Err(UnphysicalPressure::Negative {
                a_over_lambda,
                p_over_estar: p,
            })
        } else {
            Ok(p)
        }
    }

    /// p̄/E* at full contact (a/λ = ½).
    fn full_contact_p_over_estar(&self) -> f64 {
        self.p_over_estar(0.5)
    }
}

/// Why a law's value is not a physical mean pressure.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum UnphysicalPressure {
    #[error("p̄/E* = {p_over_estar} at a/λ = {a_over_lambda}: not a finite number (the law overflows for these inputs)")]
    NotFinite {
        a_over_lambda: f64,
        p_over_estar: f64,
    },
    #[error("p̄/E* = {p_over_estar:.6e} < 0 at a/λ = {a_over_lambda}: a negative mean pressure is unphysical (the law is used where it does not hold)")]
    Negative {
        a_over_lambda: f64,
        p_over_estar: f64,
    },
}

/// A model law by name (`westergaard`, `wnl`), as specs and the command line select it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModelKind {
    Westergaard,
    Wnl,
}

impl ModelKind {
    /// Every law, in the order they are listed in messages.
    pub const ALL: [ModelKind; 2] = [ModelKind::Westergaard, ModelKind::Wnl];

    /// The name used in specs, column names and legends.
    pub fn key(self) -> &'static str {
        match self {
            ModelKind::Westergaard => "westergaard",
            ModelKind::Wnl => "wnl",
        }
    }
}

/// A model name that is neither `westergaard` nor `wnl`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown model `{0}`; allowed: westergaard, wnl")]
pub struct ModelKindParseError(pub String);

impl std::str::FromStr for ModelKind {
    type Err = ModelKindParseError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ModelKind::ALL
            .into_iter()
            .find(|k| k.key() == s)
            .ok_or_else(|| ModelKindParseError(s.into()))
    }
}

/// The model laws the pipeline can draw, selectable by name in specs and on the command line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ModelLaw {
    Westergaard(Westergaard),
    Wnl(Wnl),
}

impl PressureLaw for ModelLaw {
    fn p_over_estar(&self, a_over_lambda: f64) -> f64 {
        match self {
            ModelLaw::Westergaard(m) => m.p_over_estar(a_over_lambda),
            ModelLaw::Wnl(m) => m.p_over_estar(a_over_lambda),
        }
    }
}

impl ModelLaw {
    /// The law `kind` at one (AR, τ_max in MPa); `reading` and `coefficients` serve WNL only.
    pub fn new(
        kind: ModelKind,
        aspect_ratio: f64,
        tau_max_mpa: f64,
        reading: Reading,
        coefficients: CoefficientSet,
    ) -> Self {
        match kind {
            ModelKind::Westergaard => ModelLaw::Westergaard(Westergaard::new(aspect_ratio)),
            ModelKind::Wnl => ModelLaw::Wnl(Wnl::new(
                aspect_ratio,
                tau_max_mpa,
                reading,
                coefficients.coefficients(),
            )),
        }
    }

    /// The law in words, for messages: `Westergaard` or `WNL (reading, coefficients)`.
    pub fn describe(&self) -> String {
        match self {
            ModelLaw::Westergaard(_) => "Westergaard".into(),
            ModelLaw::Wnl(m) => format!(
                "WNL (reading {}, A = {:.4}, B = {:.4})",
                m.reading,
                m.correction_a(),
                m.correction_b()
            ),
        }
    }

    /// True when the law is evaluated outside the domain its coefficients were fitted on.
    /// Westergaard has no fitted part and never extrapolates.
    pub fn is_extrapolated(&self) -> bool {
        match self {
            ModelLaw::Westergaard(_) => false,
            ModelLaw::Wnl(m) => m.is_extrapolated(),
        }
    }
}
