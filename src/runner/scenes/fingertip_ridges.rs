//! The fingertip ridges as both fingertip scenes (`fingertip_fe`, `fingertip_area`) state them:
//! the check of their aspect ratio, and their finite-element curves (the `fe` table).

use crate::defaults;
use crate::fe::{Kinematics, MeshLevel, SolveOptions};
use crate::runner::sweep::fe_cases::{FeCase, FePhysics};
use crate::runner::RunOptions;
use crate::spec::{
    mesh_from_name, Bounded, NonNegative, OpenHalfWidth, Positive, SpecError, Validator,
};
use serde::Deserialize;

/// The finite-element curves of the fingertip scenes (`[fingertip_fe.fe]`,
/// `[fingertip_area.fe]`): one per modulus E* at the ridges' AR and τ_max. The parameters left
/// out take their defaults (docs/replication.md R7, `crate::defaults`); two scenes with the same
/// table share their cached curves.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FingertipFe {
    /// Load until a/λ reaches this value, in (0, 0.5). A target in the last element of the face
    /// ends the curve when the valley node touches (the contact closes).
    pub until_a_over_lambda: Bounded<OpenHalfWidth>,
    /// `coarse` (32×16), `default` (48×24), `fine` (72×36), or the number of elements along the
    /// contact face; absent: `default`.
    #[serde(default, deserialize_with = "mesh_from_name")]
    pub mesh: Option<MeshLevel>,
    /// h/λ (R7; default in `crate::defaults`).
    #[serde(default)]
    pub thickness_over_lambda: Option<Bounded<Positive>>,
    /// κ/G (R7; default in `crate::defaults`).
    #[serde(default)]
    pub kappa_over_g: Option<Bounded<Positive>>,
    /// μ of the Coulomb–Orowan law (R7; default in `crate::defaults`).
    #[serde(default)]
    pub friction_coefficient: Option<Bounded<NonNegative>>,
    /// Elastic slip at the friction threshold over the mean face element length (R3; default in
    /// `crate::defaults`).
    #[serde(default)]
    pub elastic_slip_over_element: Option<Bounded<NonNegative>>,
    /// `finite` (the paper's physics) or `linear`.
    #[serde(default)]
    pub kinematics: Kinematics,
}

impl FingertipFe {
    /// The physical parameters of the curve at modulus `estar_mpa`.
    pub fn physics(&self, estar_mpa: f64) -> FePhysics {
        FePhysics {
            estar_mpa,
            thickness_over_lambda: self
                .thickness_over_lambda
                .map_or_else(defaults::thickness_over_lambda, Bounded::get),
            kappa_over_g: self
                .kappa_over_g
                .map_or_else(defaults::kappa_over_g, Bounded::get),
            friction_coefficient: self
                .friction_coefficient
                .map_or_else(defaults::friction_coefficient, Bounded::get),
            elastic_slip_over_element: self
                .elastic_slip_over_element
                .map_or_else(defaults::elastic_slip_over_element, Bounded::get),
            kinematics: self.kinematics,
        }
    }

    /// The curve at (AR, τ_max in MPa, E* in MPa), at the run's mesh override if it has one.
    pub fn case(
        &self,
        aspect_ratio: f64,
        tau_max_mpa: f64,
        estar_mpa: f64,
        opts: &RunOptions,
    ) -> FeCase {
        let options = SolveOptions {
            until_a_over_lambda: self.until_a_over_lambda.get(),
            mesh: opts
                .fe_mesh_override
                .unwrap_or(self.mesh.unwrap_or_default()),
            ..SolveOptions::default()
        };
        FeCase::new(&self.physics(estar_mpa), aspect_ratio, tau_max_mpa, options)
    }
}

/// The ridges' aspect ratio Δ/λ, refused unless below ½ (the indenter's peak-to-valley 2Δ
/// must fit in a wavelength's half-period geometry).
pub(crate) fn ridge_aspect_ratio(
    v: &Validator,
    scene: &str,
    wavelength_mm: f64,
    amplitude_mm: f64,
) -> Result<f64, SpecError> {
    let ar = amplitude_mm / wavelength_mm;
    if ar >= 0.5 {
        return Err(v.invalid(
            &format!("{scene}.amplitude_mm"),
            None,
            amplitude_mm.to_string(),
            format!("< wavelength_mm / 2 = {}", wavelength_mm / 2.0),
        ));
    }
    Ok(ar)
}
