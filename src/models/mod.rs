//! Closed-form contact laws p̄/E*(a/λ) for a rigid sinusoid on a soft solid, and their inverse.
//!
//! Everything here is dimensionless: the contact half-width enters as `a_over_lambda`
//! (a/λ ∈ [0, ½], ½ = full contact), the mean pressure as `p_over_estar` (p̄/E*), the
//! waviness as the aspect ratio AR = Δ/λ. The one dimensional input is the interfacial
//! shear strength τ_max, in MPa, because the paper's correction polynomials take it so
//! (REPLICATION.md R5, R9).

pub mod domain;
pub mod inverse;
pub mod westergaard;
pub mod wnl;

pub use domain::FitDomain;
pub use inverse::{a_over_lambda_at, InverseError};
pub use westergaard::Westergaard;
pub use wnl::{Coefficients, Reading, Wnl};

/// A mean-pressure law p̄/E* as a function of the contact half-width a/λ.
pub trait PressureLaw {
    /// Mean pressure over the plane-strain modulus, p̄/E*, at contact half-width `a_over_lambda`.
    fn p_over_estar(&self, a_over_lambda: f64) -> f64;

    /// p̄/E* at full contact (a/λ = ½).
    fn full_contact_p_over_estar(&self) -> f64 {
        self.p_over_estar(0.5)
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
    /// True when the law is evaluated outside the domain its coefficients were fitted on.
    /// Westergaard has no fitted part and never extrapolates.
    pub fn is_extrapolated(&self) -> bool {
        match self {
            ModelLaw::Westergaard(_) => false,
            ModelLaw::Wnl(m) => m.is_extrapolated(),
        }
    }
}
