//! `wavy eval` without its arguments: a closed-form law at (AR, τ_max), forward (a/λ → p̄/E*)
//! or inverse (p̄/E* → a/λ), or the recursive superposition of one law per harmonic of a profile
//! (p̄/E* → contact fraction, docs/replication.md R14), every input checked with the command
//! line's messages. The Python bindings call the same functions.

use crate::models::{
    a_over_lambda_at, profile_contact, CoefficientSet, InverseError, ModelKind, ModelLaw,
    PressureLaw, Reading, SuperpositionError,
};
use crate::profile::Profile;
use crate::runner::requests::input_checks::{
    a_over_lambda_in_range, non_negative, out_of_range, positive, InputError,
};
use crate::runner::requests::request_error::{full_message, RequestError};

/// One law at one (AR, τ_max in MPa), with the command line's names and units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawRequest {
    pub model: ModelKind,
    /// Aspect ratio Δ/λ (> 0).
    pub ar: f64,
    /// Interfacial shear strength τ_max in MPa (≥ 0; unused by Westergaard but checked).
    pub tau_max_mpa: f64,
    /// Reading of Eq. 4 (WNL only).
    pub reading: Reading,
    /// Coefficient set (WNL only).
    pub coefficients: CoefficientSet,
}

/// One evaluated point: a/λ, p̄/E*, and whether (AR, τ_max) lies outside the fit domain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawRow {
    pub a_over_lambda: f64,
    pub p_over_estar: f64,
    pub extrapolated: bool,
}

impl LawRequest {
    /// The law, once `--ar` and `--tau-max-mpa` are in range.
    pub fn law(&self) -> Result<ModelLaw, InputError> {
        positive("--ar", self.ar)?;
        non_negative("--tau-max-mpa", self.tau_max_mpa)?;
        Ok(ModelLaw::new(
            self.model,
            self.ar,
            self.tau_max_mpa,
            self.reading,
            self.coefficients,
        ))
    }

    /// The reading and coefficient-set names of the output (empty for Westergaard).
    pub fn reading_and_coefficients(&self) -> (&'static str, &'static str) {
        match self.model {
            ModelKind::Westergaard => ("", ""),
            ModelKind::Wnl => (self.reading.name(), self.coefficients.name()),
        }
    }

    /// The inputs that produced a value, as command-line flags, for messages.
    fn inputs(&self) -> String {
        let (reading, coefficients) = self.reading_and_coefficients();
        match self.model {
            ModelKind::Westergaard => format!("--model westergaard --ar {:?}", self.ar),
            ModelKind::Wnl => format!(
                "--model wnl --reading {reading} --coefficients {coefficients} --ar {:?} --tau-max-mpa {:?}",
                self.ar, self.tau_max_mpa
            ),
        }
    }

    /// p̄/E* at every a/λ of `xs` (each in [0, 0.5]), in order; the first bad input or
    /// unphysical value is the error.
    pub fn forward(&self, xs: &[f64]) -> Result<Vec<LawRow>, RequestError> {
        let law = self.law()?;
        let mut rows = Vec::with_capacity(xs.len());
        for &x in xs {
            a_over_lambda_in_range("--a-over-lambda", x)?;
            let p = law
                .physical_p_over_estar(x)
                .map_err(|source| RequestError::Unphysical {
                    inputs: format!("{} --a-over-lambda {x:?}", self.inputs()),
                    source,
                })?;
            rows.push(LawRow {
                a_over_lambda: x,
                p_over_estar: p,
                extrapolated: law.is_extrapolated(),
            });
        }
        Ok(rows)
    }

    /// a/λ at every p̄/E* of `ps` (each in [0, the full-contact pressure]), in order.
    pub fn inverse(&self, ps: &[f64]) -> Result<Vec<LawRow>, RequestError> {
        let law = self.law()?;
        let mut rows = Vec::with_capacity(ps.len());
        for &p in ps {
            let x = a_over_lambda_at(&law, p).map_err(|e| self.inverse_error(&law, p, e))?;
            rows.push(LawRow {
                a_over_lambda: x,
                p_over_estar: p,
                extrapolated: law.is_extrapolated(),
            });
        }
        Ok(rows)
    }

    /// An inverse that failed at `p`: a value out of range or not invertible (input errors),
    /// or a computation that failed.
    fn inverse_error(&self, law: &ModelLaw, p: f64, e: InverseError) -> RequestError {
        let full = law.full_contact_p_over_estar();
        match e {
            InverseError::NegativeOrNotFinite { .. } => {
                out_of_range("--p-over-estar", p, ">= 0").into()
            }
            // a computation that failed, not a bad value
            InverseError::NotFinite { .. } => RequestError::Inverse {
                inputs: format!("{} --p-over-estar {p}", self.inputs()),
                source: e,
            },
            InverseError::AboveFullContact { .. } => out_of_range(
                "--p-over-estar",
                p,
                format!("[0, {full}] (the full-contact pressure of this model)"),
            )
            .into(),
            other => InputError::NotInvertible {
                flag: "--p-over-estar".into(),
                value: p.to_string(),
                reason: other.to_string(),
            }
            .into(),
        }
    }
}

/// The recursive superposition (R14) of a profile: the law `model` at each harmonic's own aspect
/// ratio and the same τ_max, the harmonics' orders each a multiple of the one before.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileRequest {
    pub model: ModelKind,
    pub profile: Profile,
    /// Interfacial shear strength τ_max in MPa (≥ 0; unused by Westergaard but checked).
    pub tau_max_mpa: f64,
    /// Reading of Eq. 4 (WNL only).
    pub reading: Reading,
    /// Coefficient set (WNL only).
    pub coefficients: CoefficientSet,
}

/// One point of the recursion: p̄/E*, the contact fraction, and whether any scale's
/// (AR_k, τ_max) lies outside the fit domain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileRow {
    pub p_over_estar: f64,
    pub contact_fraction: f64,
    pub extrapolated: bool,
}

impl ProfileRequest {
    /// The contact fraction at every p̄/E* of `ps` (each in (0, the big wave's full-contact
    /// pressure)), in order; the first bad input or failed inversion is the error.
    pub fn contact_fractions(&self, ps: &[f64]) -> Result<Vec<ProfileRow>, RequestError> {
        non_negative("--tau-max-mpa", self.tau_max_mpa)?;
        let law_at = |ar| {
            ModelLaw::new(
                self.model,
                ar,
                self.tau_max_mpa,
                self.reading,
                self.coefficients,
            )
        };
        let extrapolated = self
            .profile
            .harmonics()
            .any(|h| law_at(h.aspect_ratio).is_extrapolated());
        ps.iter()
            .map(|&p| {
                let c = profile_contact(&self.profile, law_at, p).map_err(|e| self.error(p, e))?;
                Ok(ProfileRow {
                    p_over_estar: p,
                    contact_fraction: c.contact_fraction,
                    extrapolated,
                })
            })
            .collect()
    }

    /// A recursion that failed at `p`: a pressure out of range (an input error) or a law that
    /// could not be inverted (a failed computation, naming the inputs).
    fn error(&self, p: f64, e: SuperpositionError) -> RequestError {
        match e {
            SuperpositionError::Pressure { .. } => out_of_range("--p-over-estar", p, "> 0").into(),
            SuperpositionError::NotNested { .. } => InputError::Refused {
                flag: "--profile".into(),
                value: self.profile.to_string(),
                reason: e.to_string(),
            }
            .into(),
            SuperpositionError::BigFullContact {
                full_contact_p_over_estar,
                ..
            } => out_of_range(
                "--p-over-estar",
                p,
                format!(
                    "(0, {full_contact_p_over_estar}) (below the big wave's full-contact pressure)"
                ),
            )
            .into(),
            other => RequestError::Failed(format!(
                "the recursive superposition of --profile {} with --model {} at --p-over-estar {p}: {}",
                self.profile,
                self.model.key(),
                full_message(&other)
            )),
        }
    }
}
