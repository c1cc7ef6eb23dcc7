//! TOML experiment specs: one file, one scene, every input that scene needs.
//!
//! Parsing is strict (`deny_unknown_fields`, typed values, physical ranges checked while
//! deserialising so that the TOML parser can point at the line and column). A spec holds
//! exactly one scene table:
//!
//! - `[correction_surfaces]`: the surfaces A(AR, τ_max), B(AR, τ_max) (paper Fig. 2);
//! - `[fe_vs_model]`: p̄/E* against a/λ per (AR, τ_max) panel (paper Fig. 3);
//! - `[fingertip_area]`: total contact area against load for fingerprint ridges (paper Fig. 5, R8);
//! - `[deformed_mesh]`: the deformed FE mesh and its contact pressure at the end of loading;
//! - `[table1_refit]`: the WNL coefficients (paper Table 1) fitted to our FE curves.
//!
//! This module reads no file: [`Spec::parse`] takes the text and the name to quote in errors.

use crate::defaults;
use crate::models::Reading;
use serde::de::{self, Deserializer};
use serde::Deserialize;
use std::fmt;
use thiserror::Error;

/// A spec that could not be read, parsed or validated. Every message names the file and the
/// field, and for range errors the value and the allowed range.
#[derive(Debug, Error)]
pub enum SpecError {
    #[error("{origin}: cannot read the spec: {message}")]
    Read { origin: String, message: String },
    #[error("{origin}: field `{field}`: {message}")]
    Parse {
        origin: String,
        field: String,
        message: String,
    },
    #[error(
        "{origin}: field `{field}`{location}: value {value} is out of range; allowed: {allowed}"
    )]
    Invalid {
        origin: String,
        field: String,
        location: Location,
        value: String,
        allowed: String,
    },
}

/// Where a value sits in its file, when known.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Location(pub Option<(usize, usize)>);

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some((line, column)) => write!(f, " (line {line}, column {column})"),
            None => Ok(()),
        }
    }
}

/// A whole spec file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// Figure title.
    pub title: String,
    /// How `wavy check` compares a recomputation with `expected/`.
    pub check: CheckTolerance,
    pub correction_surfaces: Option<CorrectionSurfacesScene>,
    pub fe_vs_model: Option<FeVsModelScene>,
    pub fingertip_area: Option<FingertipAreaScene>,
    pub deformed_mesh: Option<DeformedMeshScene>,
    pub table1_refit: Option<Table1RefitScene>,
}

/// Paper Table 1 re-derived: the twelve WNL coefficients fitted by least squares in p̄/E* to our
/// FE curves, once per reading of Eq. 4 (R5), beside the paper's.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Table1RefitScene {
    /// Aspect ratios Δ/λ of the FE curves (at least three: the polynomials are quadratic).
    pub aspect_ratios: Vec<Bounded<Positive>>,
    /// τ_max grid (MPa) on which the fitted A and B are drawn against the paper's.
    pub tau_max_mpa: Grid,
    /// The FE curves; `fe.tau_max_mpa` (at least three values) are the fitted shear strengths.
    pub fe: FeSection,
}

/// The deformed finite-element mesh and its contact pressure at the end of loading.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DeformedMeshScene {
    /// Aspect ratio Δ/λ.
    pub aspect_ratio: Bounded<Positive>,
    /// The FE model; `tau_max_mpa` must hold exactly one value.
    pub fe: FeSection,
}

/// Tolerances of `wavy check`: a number passes when |new − expected| ≤ abs_tol + rel_tol·|expected|.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckTolerance {
    /// Relative tolerance; at least 1e-5, because `expected/` stores 6 significant digits
    /// (rounding alone moves a number by up to 5e-6 relative).
    pub rel_tol: Bounded<CheckRelTol>,
    /// Absolute tolerance (≥ 0), in the unit of each column.
    pub abs_tol: Bounded<NonNegative>,
}

/// The scene of a spec, once exactly one scene table has been found.
#[derive(Debug, Clone, Copy)]
pub enum Scene<'a> {
    CorrectionSurfaces(&'a CorrectionSurfacesScene),
    FeVsModel(&'a FeVsModelScene),
    FingertipArea(&'a FingertipAreaScene),
    DeformedMesh(&'a DeformedMeshScene),
    Table1Refit(&'a Table1RefitScene),
}

/// Paper Fig. 2: A and B over an (AR, τ_max) grid.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CorrectionSurfacesScene {
    /// Coefficient set, by name (`paper-table1`).
    #[serde(default = "default_coefficients")]
    pub coefficients: String,
    /// AR grid of the tabulated surfaces (dimensionless Δ/λ).
    pub aspect_ratio: Grid,
    /// τ_max grid of the tabulated surfaces, MPa.
    pub tau_max_mpa: Grid,
    /// Aspect ratios drawn as lines against τ_max.
    pub line_aspect_ratios: Vec<Bounded<Positive>>,
    /// τ_max values (MPa) drawn as lines against AR.
    pub line_tau_max_mpa: Vec<Bounded<NonNegative>>,
    /// Aspect ratios of the finite-element sweep, emphasised in the figure.
    pub marked_aspect_ratios: Vec<Bounded<Positive>>,
}

/// Paper Fig. 3: one panel per (AR, τ_max), p̄/E* against a/λ.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeVsModelScene {
    /// Panel rows' aspect ratios Δ/λ.
    pub aspect_ratios: Vec<Bounded<Positive>>,
    /// Panel columns' interfacial shear strengths, MPa.
    pub tau_max_mpa: Vec<Bounded<NonNegative>>,
    /// Where the model lines are sampled, a/λ.
    pub a_over_lambda: Grid,
    pub models: ModelSelection,
    /// Finite-element curves; absent: model lines only.
    pub fe: Option<FeSection>,
}

/// The finite-element curves of a `[fe_vs_model]` scene (REPLICATION.md R6; defaults R7).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeSection {
    /// τ_max values (MPa) of the panels that get an FE curve; each must be one of the panels'.
    pub tau_max_mpa: Vec<Bounded<NonNegative>>,
    /// Plane-strain modulus of the FE model, MPa: the physics sees τ_max/E* (R7 default 1).
    #[serde(default = "default_fe_estar_mpa")]
    pub estar_mpa: Bounded<Positive>,
    /// Layer thickness over wavelength h/λ (R7 default 1).
    #[serde(default = "default_thickness_over_lambda")]
    pub thickness_over_lambda: Bounded<Positive>,
    /// Bulk over shear modulus κ/G (R7 default 1000).
    #[serde(default = "default_kappa_over_g")]
    pub kappa_over_g: Bounded<Positive>,
    /// Friction coefficient μ of the Coulomb–Orowan law (R7 default 1).
    #[serde(default = "default_friction_coefficient")]
    pub friction_coefficient: Bounded<NonNegative>,
    /// Penalty regularisation of stick: elastic slip at the friction threshold over the mean
    /// element length along the contact face (default 0.005, Abaqus's).
    #[serde(default = "default_elastic_slip_over_element")]
    pub elastic_slip_over_element: Bounded<Positive>,
    /// `finite` (the paper's physics) or `linear` (small strain).
    #[serde(default)]
    pub kinematics: KinematicsName,
    /// `coarse`, `default`, `fine`, or the number of elements along the contact face.
    #[serde(default = "default_mesh")]
    pub mesh: MeshName,
    /// Load until a/λ reaches this value, in (0, 0.5).
    pub until_a_over_lambda: Bounded<OpenHalfWidth>,
}

/// Kinematics by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum KinematicsName {
    #[default]
    Finite,
    Linear,
}

/// A mesh resolution by name (`coarse`, `default`, `fine`) or element count along the face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeshName(pub crate::fe::MeshLevel);

impl<'de> Deserialize<'de> for MeshName {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse::<crate::cli::MeshArg>()
            .map(|m| MeshName(m.0))
            .map_err(|e| de::Error::custom(e.replace("--mesh = ", "value ")))
    }
}

fn default_fe_estar_mpa() -> Bounded<Positive> {
    Bounded::trusted(defaults::fe_estar_mpa())
}
fn default_thickness_over_lambda() -> Bounded<Positive> {
    Bounded::trusted(defaults::thickness_over_lambda())
}
fn default_kappa_over_g() -> Bounded<Positive> {
    Bounded::trusted(defaults::kappa_over_g())
}
fn default_friction_coefficient() -> Bounded<NonNegative> {
    Bounded::trusted(defaults::friction_coefficient())
}
fn default_elastic_slip_over_element() -> Bounded<Positive> {
    Bounded::trusted(defaults::elastic_slip_over_element())
}
fn default_mesh() -> MeshName {
    MeshName(crate::fe::MeshLevel::Default)
}

/// Paper Fig. 5 (R8): fingerprint ridges as a sinusoid, total contact area against load.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FingertipAreaScene {
    /// Ridge wavelength λ, mm.
    pub wavelength_mm: Bounded<Positive>,
    /// Ridge amplitude Δ, mm.
    pub amplitude_mm: Bounded<Positive>,
    /// Nominal (apparent) circular contact area A_exp, mm²; R = √(A_exp/π).
    pub nominal_area_mm2: Bounded<Positive>,
    /// Plane-strain modulus of the central line, MPa.
    pub estar_mpa: Bounded<Positive>,
    /// Plane-strain modulus range [low, high] drawn as a band, MPa.
    pub estar_band_mpa: [Bounded<Positive>; 2],
    /// Interfacial shear strength τ_max, MPa.
    pub tau_max_mpa: Bounded<NonNegative>,
    /// Normal load grid, N.
    pub load_n: Grid,
    pub models: ModelSelection,
    /// Measured points, relative to the spec's folder (schema: `experiments/data/README.md`).
    /// A missing file is reported in the figure and the run's output, never replaced.
    pub measured_data: Option<String>,
}

/// Which model lines to draw and how to evaluate the WNL law.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSelection {
    /// Lines to draw: any of `westergaard`, `wnl`.
    pub draw: Vec<ModelName>,
    /// Reading of the paper's Eq. 4 (R5): `bracket-sq` (default), `bracket-2x`, `literal`.
    #[serde(default)]
    pub reading: Reading,
    /// WNL coefficient set, by name (`paper-table1`).
    #[serde(default = "default_coefficients")]
    pub coefficients: String,
    /// A second WNL coefficient set (e.g. our refit of Table 1) drawn dashed and scored
    /// against the FE points beside the first; none by default.
    #[serde(default)]
    pub compare_coefficients: Option<String>,
}

/// A model line by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModelName {
    Westergaard,
    Wnl,
}

/// `count` evenly spaced values from `min` to `max`, both included.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Grid {
    pub min: toml::Spanned<f64>,
    pub max: toml::Spanned<f64>,
    pub count: toml::Spanned<usize>,
}

impl Grid {
    /// The grid's values; `min + i·(max − min)/(count − 1)`, the last one exactly `max`.
    pub fn values(&self) -> Vec<f64> {
        let (lo, hi, n) = (
            *self.min.get_ref(),
            *self.max.get_ref(),
            *self.count.get_ref(),
        );
        (0..n)
            .map(|i| {
                if i + 1 == n {
                    hi
                } else {
                    lo + (hi - lo) * i as f64 / (n - 1) as f64
                }
            })
            .collect()
    }
}

fn default_coefficients() -> String {
    "paper-table1".into()
}

/// A range rule for [`Bounded`]: its allowed range as text and the test.
pub trait Range {
    const ALLOWED: &'static str;
    fn contains(x: f64) -> bool;
}

/// A number checked against its [`Range`] while deserialising, so that the parser reports
/// the offending line and column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounded<R: Range> {
    value: f64,
    _range: std::marker::PhantomData<R>,
}

impl<R: Range> Bounded<R> {
    pub fn get(self) -> f64 {
        self.value
    }

    /// A value known to be in range (a default from `defaults`); panics otherwise.
    fn trusted(value: f64) -> Self {
        assert!(R::contains(value), "default {value} outside {}", R::ALLOWED);
        Self {
            value,
            _range: std::marker::PhantomData,
        }
    }
}

impl<'de, R: Range> Deserialize<'de> for Bounded<R> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let value = f64::deserialize(d)?;
        if R::contains(value) {
            Ok(Self {
                value,
                _range: std::marker::PhantomData,
            })
        } else {
            Err(de::Error::custom(format!(
                "value {value} is out of range; allowed: {}",
                R::ALLOWED
            )))
        }
    }
}

macro_rules! range {
    ($(#[$doc:meta])* $name:ident, $allowed:expr, |$x:ident| $test:expr) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct $name;
        impl Range for $name {
            const ALLOWED: &'static str = $allowed;
            fn contains($x: f64) -> bool {
                $x.is_finite() && $test
            }
        }
    };
}

range!(/// x > 0.
    Positive, "> 0", |x| x > 0.0);
range!(/// x ≥ 0.
    NonNegative, ">= 0", |x| x >= 0.0);
range!(/// 0 < x < ½: a contact half-width short of full contact.
    OpenHalfWidth, "(0, 0.5)", |x| x > 0.0 && x < 0.5);
range!(/// A relative tolerance that 6-digit golden numbers can meet.
    CheckRelTol, "[1e-5, 1]", |x| (1e-5..=1.0).contains(&x));

/// Allowed range of a contact half-width a/λ.
pub const A_OVER_LAMBDA_ALLOWED: (f64, f64) = (0.0, 0.5);

impl Spec {
    /// Parses and validates a spec. `origin` names the file in error messages.
    pub fn parse(text: &str, origin: &str) -> Result<Spec, SpecError> {
        let de = toml::Deserializer::parse(text).map_err(|e| SpecError::Parse {
            origin: origin.into(),
            field: "(document)".into(),
            message: e.to_string().trim_end().into(),
        })?;
        let spec: Spec = serde_path_to_error::deserialize(de).map_err(|e| {
            // toml::Spanned wraps its value in a private field; the user's field is its parent.
            let path = e
                .path()
                .to_string()
                .replace(".$__serde_spanned_private_value", "");
            let field = if path == "." {
                "(top level)".to_string()
            } else {
                path
            };
            SpecError::Parse {
                origin: origin.into(),
                field,
                message: e.into_inner().to_string().trim_end().into(),
            }
        })?;
        spec.validate(text, origin)?;
        Ok(spec)
    }

    /// The one scene of this spec.
    pub fn scene(&self) -> Scene<'_> {
        if let Some(s) = &self.correction_surfaces {
            Scene::CorrectionSurfaces(s)
        } else if let Some(s) = &self.fe_vs_model {
            Scene::FeVsModel(s)
        } else if let Some(s) = &self.fingertip_area {
            Scene::FingertipArea(s)
        } else if let Some(s) = &self.deformed_mesh {
            Scene::DeformedMesh(s)
        } else if let Some(s) = &self.table1_refit {
            Scene::Table1Refit(s)
        } else {
            unreachable!("Spec::parse admits exactly one scene table")
        }
    }

    fn validate(&self, text: &str, origin: &str) -> Result<(), SpecError> {
        let v = Validator { text, origin };
        let scenes = [
            self.correction_surfaces.is_some(),
            self.fe_vs_model.is_some(),
            self.fingertip_area.is_some(),
            self.deformed_mesh.is_some(),
            self.table1_refit.is_some(),
        ];
        let n = scenes.iter().filter(|&&s| s).count();
        if n != 1 {
            return Err(SpecError::Invalid {
                origin: origin.into(),
                field: "(scene table)".into(),
                location: Location(None),
                value: format!("{n} scene tables"),
                allowed: "exactly one of [correction_surfaces], [fe_vs_model], [fingertip_area], [deformed_mesh], [table1_refit]"
                    .into(),
            });
        }
        if let Some(s) = &self.correction_surfaces {
            v.grid(
                "correction_surfaces.aspect_ratio",
                &s.aspect_ratio,
                (0.0, f64::INFINITY),
                false,
            )?;
            v.grid(
                "correction_surfaces.tau_max_mpa",
                &s.tau_max_mpa,
                (0.0, f64::INFINITY),
                true,
            )?;
            v.coefficients("correction_surfaces.coefficients", &s.coefficients)?;
            v.non_empty(
                "correction_surfaces.line_aspect_ratios",
                s.line_aspect_ratios.len(),
            )?;
            v.non_empty(
                "correction_surfaces.line_tau_max_mpa",
                s.line_tau_max_mpa.len(),
            )?;
        }
        if let Some(s) = &self.fe_vs_model {
            v.non_empty("fe_vs_model.aspect_ratios", s.aspect_ratios.len())?;
            v.non_empty("fe_vs_model.tau_max_mpa", s.tau_max_mpa.len())?;
            v.grid(
                "fe_vs_model.a_over_lambda",
                &s.a_over_lambda,
                A_OVER_LAMBDA_ALLOWED,
                true,
            )?;
            v.models("fe_vs_model.models", &s.models)?;
            if let Some(fe) = &s.fe {
                let panels: Vec<f64> = s.tau_max_mpa.iter().map(|t| t.get()).collect();
                v.fe_section("fe_vs_model.fe", fe, Some(&panels))?;
            }
        }
        if let Some(s) = &self.table1_refit {
            v.at_least(
                "table1_refit.aspect_ratios",
                s.aspect_ratios.iter().map(|a| a.get()),
                3,
            )?;
            v.fe_section("table1_refit.fe", &s.fe, None)?;
            v.at_least(
                "table1_refit.fe.tau_max_mpa",
                s.fe.tau_max_mpa.iter().map(|t| t.get()),
                3,
            )?;
            v.grid(
                "table1_refit.tau_max_mpa",
                &s.tau_max_mpa,
                (0.0, f64::INFINITY),
                true,
            )?;
        }
        if let Some(s) = &self.deformed_mesh {
            v.fe_section("deformed_mesh.fe", &s.fe, None)?;
            if s.fe.tau_max_mpa.len() != 1 {
                return Err(v.invalid(
                    "deformed_mesh.fe.tau_max_mpa",
                    None,
                    format!("{} values", s.fe.tau_max_mpa.len()),
                    "exactly one value".into(),
                ));
            }
        }
        if let Some(s) = &self.fingertip_area {
            v.grid(
                "fingertip_area.load_n",
                &s.load_n,
                (0.0, f64::INFINITY),
                true,
            )?;
            v.models("fingertip_area.models", &s.models)?;
            let [lo, hi] = s.estar_band_mpa.map(Bounded::get);
            let e = s.estar_mpa.get();
            if !(lo < e && e < hi) {
                return Err(SpecError::Invalid {
                    origin: origin.into(),
                    field: "fingertip_area.estar_band_mpa".into(),
                    location: Location(None),
                    value: format!("[{lo}, {hi}]"),
                    allowed: format!("[low, high] with low < estar_mpa = {e} < high"),
                });
            }
            let ar = s.amplitude_mm.get() / s.wavelength_mm.get();
            if ar >= 0.5 {
                return Err(SpecError::Invalid {
                    origin: origin.into(),
                    field: "fingertip_area.amplitude_mm".into(),
                    location: Location(None),
                    value: s.amplitude_mm.get().to_string(),
                    allowed: format!("< wavelength_mm / 2 = {}", s.wavelength_mm.get() / 2.0),
                });
            }
        }
        Ok(())
    }
}

struct Validator<'a> {
    text: &'a str,
    origin: &'a str,
}

impl Validator<'_> {
    fn invalid(
        &self,
        field: &str,
        span: Option<std::ops::Range<usize>>,
        value: String,
        allowed: String,
    ) -> SpecError {
        SpecError::Invalid {
            origin: self.origin.into(),
            field: field.into(),
            location: Location(span.map(|s| line_column(self.text, s.start))),
            value,
            allowed,
        }
    }

    fn grid(
        &self,
        field: &str,
        g: &Grid,
        bounds: (f64, f64),
        closed_low: bool,
    ) -> Result<(), SpecError> {
        let (lo, hi) = bounds;
        let low_text = if closed_low {
            format!("[{lo}")
        } else {
            format!("({lo}")
        };
        let allowed = format!("{low_text}, {hi}]");
        let in_range =
            |x: f64| x.is_finite() && (if closed_low { x >= lo } else { x > lo }) && x <= hi;
        for (name, s) in [("min", &g.min), ("max", &g.max)] {
            if !in_range(*s.get_ref()) {
                return Err(self.invalid(
                    &format!("{field}.{name}"),
                    Some(s.span()),
                    s.get_ref().to_string(),
                    allowed,
                ));
            }
        }
        if g.max.get_ref() <= g.min.get_ref() {
            return Err(self.invalid(
                &format!("{field}.max"),
                Some(g.max.span()),
                g.max.get_ref().to_string(),
                format!("> min = {}", g.min.get_ref()),
            ));
        }
        let n = *g.count.get_ref();
        if !(2..=100_000).contains(&n) {
            return Err(self.invalid(
                &format!("{field}.count"),
                Some(g.count.span()),
                n.to_string(),
                "[2, 100000]".into(),
            ));
        }
        Ok(())
    }

    /// The τ_max list of an FE section: non-empty, and each one of `panels` (when given).
    fn fe_section(
        &self,
        field: &str,
        fe: &FeSection,
        panels: Option<&[f64]>,
    ) -> Result<(), SpecError> {
        let field = format!("{field}.tau_max_mpa");
        self.non_empty(&field, fe.tau_max_mpa.len())?;
        for (i, t) in fe.tau_max_mpa.iter().map(|t| t.get()).enumerate() {
            if let Some(panels) = panels.filter(|p| !p.contains(&t)) {
                return Err(self.invalid(
                    &format!("{field}[{i}]"),
                    None,
                    t.to_string(),
                    format!("one of the panels' tau_max_mpa {panels:?}"),
                ));
            }
        }
        Ok(())
    }

    /// At least `n` distinct values (a quadratic polynomial in a variable needs three).
    fn at_least(
        &self,
        field: &str,
        values: impl Iterator<Item = f64>,
        n: usize,
    ) -> Result<(), SpecError> {
        let mut v: Vec<f64> = values.collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        if v.len() < n {
            return Err(self.invalid(
                field,
                None,
                format!("{v:?}"),
                format!("at least {n} distinct values"),
            ));
        }
        Ok(())
    }

    fn non_empty(&self, field: &str, len: usize) -> Result<(), SpecError> {
        if len == 0 {
            return Err(self.invalid(field, None, "[]".into(), "at least one value".into()));
        }
        Ok(())
    }

    fn coefficients(&self, field: &str, name: &str) -> Result<(), SpecError> {
        if crate::coefficient_sets::by_name(name).is_none() {
            return Err(self.invalid(
                field,
                None,
                format!("\"{name}\""),
                crate::coefficient_sets::NAMES.join(", "),
            ));
        }
        Ok(())
    }

    fn models(&self, field: &str, m: &ModelSelection) -> Result<(), SpecError> {
        self.non_empty(&format!("{field}.draw"), m.draw.len())?;
        self.coefficients(&format!("{field}.coefficients"), &m.coefficients)?;
        if let Some(c) = &m.compare_coefficients {
            self.coefficients(&format!("{field}.compare_coefficients"), c)?;
        }
        Ok(())
    }
}

/// 1-based line and column of a byte offset.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}
