//! The WNL law beyond the sweep its polynomials were fitted on (docs/replication.md R9): read as
//! a law of τ_max/E*, and where it leaves its fit domain, in words.

use crate::defaults;
use crate::models::{ModelKind, ModelLaw};
use crate::numfmt::sig_digits;
use crate::spec::{Bounded, ModelSelection, Positive};

/// E*_fit, the modulus of the FE sweep the WNL polynomials were fitted at, MPa: the spec's
/// `fit_estar_mpa`, or the FE sweep's default (R7, R9).
pub(crate) fn fit_estar_mpa(field: Option<Bounded<Positive>>) -> f64 {
    field.map_or_else(defaults::fe_estar_mpa, Bounded::get)
}

/// The WNL law read as a law of the physical group τ_max/E*: the polynomials evaluated at
/// τ_eff = (τ_max/E*) × E*_fit, the τ_max that gives the same τ_max/E* in the fitted sweep
/// (docs/replication.md R9). At E* = E*_fit it is the paper's law.
pub(crate) fn wnl_tau_over_estar(
    models: &ModelSelection,
    aspect_ratio: f64,
    tau_max_mpa: f64,
    estar_mpa: f64,
    fit_estar_mpa: f64,
) -> ModelLaw {
    ModelLaw::new(
        ModelKind::Wnl,
        aspect_ratio,
        tau_max_mpa / estar_mpa * fit_estar_mpa,
        models.reading,
        models.coefficients,
    )
}

/// Where a law leaves its fit domain, in words (`AR 0.08 < 0.1`, `τ 0.714 MPa > 0.2 MPa`), one
/// per coordinate; empty inside it and for Westergaard.
pub(crate) fn outside_fit(law: &ModelLaw) -> Vec<String> {
    let ModelLaw::Wnl(m) = law else {
        return vec![];
    };
    if !m.is_extrapolated() {
        return vec![];
    }
    let d = m.coefficients.domain;
    let side = |x: f64, lo: f64, hi: f64| {
        if x < lo {
            format!("< {lo}")
        } else {
            format!("> {hi}")
        }
    };
    let mut why = vec![];
    if !(d.aspect_ratio_min..=d.aspect_ratio_max).contains(&m.aspect_ratio) {
        why.push(format!(
            "AR {} {}",
            sig_digits(m.aspect_ratio, 3),
            side(m.aspect_ratio, d.aspect_ratio_min, d.aspect_ratio_max)
        ));
    }
    if !(d.tau_max_mpa_min..=d.tau_max_mpa_max).contains(&m.tau_max_mpa) {
        why.push(format!(
            "τ {} MPa {} MPa",
            sig_digits(m.tau_max_mpa, 3),
            side(m.tau_max_mpa, d.tau_max_mpa_min, d.tau_max_mpa_max)
        ));
    }
    why
}
