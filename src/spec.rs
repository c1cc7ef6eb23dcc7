//! TOML experiment specs: the field types every scene section is made of, their physical
//! ranges, and the strict parse that reports file, field, line and column.
//!
//! Parsing is strict (`deny_unknown_fields`, typed values, physical ranges checked while
//! deserialising so that the TOML parser can point at the line and column). The list of
//! scenes, and with it the whole-file type `Spec`, is the registry in `runner::scenes`; each
//! scene's section type lives beside its runner and validates itself with a [`Validator`].
//!
//! This module reads no file: [`parse_document`] takes the text and the name to quote in errors.

use crate::accuracy::measured::{self, ChoiceError, Query, PHYSICS_COLUMNS};
use crate::defaults;
use crate::fe::{Kinematics, MeshLevel};
use crate::models::{CoefficientSet, ModelKind, Reading};
use crate::profile::Profile;

mod profile_field;
pub use profile_field::ProfileField;
use serde::de::{self, DeserializeOwned, Deserializer};
use serde::Deserialize;
use std::fmt;
use thiserror::Error;

/// A spec that could not be read, parsed or validated. Every message names the file and the
/// field, and for range errors the value and the allowed range.
#[derive(Debug, Error)]
pub enum SpecError {
    #[error("{origin}: cannot read the spec: {message}")]
    Read { origin: String, message: String },
    /// A data file named by a spec (measured points) that cannot be used.
    #[error("{origin}: cannot use the data file: {message}")]
    Data { origin: String, message: String },
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

/// The finite-element curves of a scene (docs/replication.md R6; defaults R7, in
/// `crate::defaults`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeSection {
    /// τ_max values (MPa) of the panels that get an FE curve; each must be one of the panels'.
    pub tau_max_mpa: Vec<Bounded<NonNegative>>,
    /// Plane-strain modulus of the FE model, MPa: the physics sees τ_max/E* (docs/replication.md R7; default 1 in `crate::defaults`).
    #[serde(default = "default_fe_estar_mpa")]
    pub estar_mpa: Bounded<Positive>,
    /// Layer thickness over wavelength h/λ (docs/replication.md R7; default 1 in `crate::defaults`).
    #[serde(default = "default_thickness_over_lambda")]
    pub thickness_over_lambda: Bounded<Positive>,
    /// Bulk over shear modulus κ/G (docs/replication.md R7; default 1000 in `crate::defaults`).
    #[serde(default = "default_kappa_over_g")]
    pub kappa_over_g: Bounded<Positive>,
    /// Friction coefficient μ of the Coulomb–Orowan law (docs/replication.md R7; default 1 in `crate::defaults`).
    #[serde(default = "default_friction_coefficient")]
    pub friction_coefficient: Bounded<NonNegative>,
    /// Penalty regularisation of stick: elastic slip at the friction threshold over the mean
    /// element length along the contact face (default 0.005, Abaqus's; 0 is exact stick).
    #[serde(default = "default_elastic_slip_over_element")]
    pub elastic_slip_over_element: Bounded<NonNegative>,
    /// `finite` (the paper's physics) or `linear` (small strain).
    #[serde(default)]
    pub kinematics: Kinematics,
    /// `coarse` (32×16), `default` (48×24), `fine` (72×36), or the number of elements along
    /// the contact face; absent: `default`, or the mesh `tolerance` needs.
    #[serde(default, deserialize_with = "mesh_from_name")]
    pub mesh: Option<MeshLevel>,
    /// Instead of `mesh`: a relative tolerance of p̄/E*; the curves use the coarsest
    /// finite-strain mesh whose measured error (expected/speed_accuracy.csv) meets it at every
    /// case of the section ([`FeSection::mesh_for`]).
    #[serde(default)]
    pub tolerance: Option<Bounded<Positive>>,
    /// Also solve each curve on the next coarser mesh and report the Richardson estimate of its
    /// relative error (a column `error_estimate` and a note per panel; order measured by the
    /// speed_accuracy scene). Adds the cost of the coarser curves.
    #[serde(default)]
    pub error_estimate: bool,
    /// Load until a/λ reaches this value, in (0, 0.5).
    pub until_a_over_lambda: Bounded<OpenHalfWidth>,
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
fn default_elastic_slip_over_element() -> Bounded<NonNegative> {
    Bounded::trusted(defaults::elastic_slip_over_element())
}
/// A [`MeshLevel`] from its name or element count (see [`MeshLevel::ALLOWED`]).
pub(crate) fn mesh_from_name<'de, D: Deserializer<'de>>(
    d: D,
) -> Result<Option<MeshLevel>, D::Error> {
    String::deserialize(d)?
        .parse::<MeshLevel>()
        .map(Some)
        .map_err(de::Error::custom)
}

impl FeSection {
    /// The mesh of the section's curves at these aspect ratios: `mesh` (`default` when absent),
    /// or with `tolerance` the finest of the meshes it chooses at each (AR, τ_max) of the
    /// section, so that every curve meets it.
    pub fn mesh_for(&self, aspect_ratios: &[f64]) -> Result<MeshLevel, ChoiceError> {
        let Some(tolerance) = self.tolerance.map(|t| t.get()) else {
            return Ok(self.mesh.unwrap_or_default());
        };
        let physics = [
            self.estar_mpa.get(),
            self.thickness_over_lambda.get(),
            self.kappa_over_g.get(),
            self.friction_coefficient.get(),
            self.elastic_slip_over_element.get(),
        ];
        let physics: Vec<(&str, f64)> = PHYSICS_COLUMNS.iter().copied().zip(physics).collect();
        let table = measured::committed()?;
        let mut finest: Option<MeshLevel> = None;
        for tau in self.tau_max_mpa.iter().map(|t| t.get()) {
            for &ar in aspect_ratios {
                let query = Query {
                    aspect_ratio: ar,
                    tau_max_mpa: tau,
                    a_over_lambda: (
                        self.until_a_over_lambda.get(),
                        self.until_a_over_lambda.get(),
                    ),
                    physics: &physics,
                };
                let choice = table.choose(tolerance, &query, |t| t.is_finite_fe())?;
                let mesh = choice.tier.mesh().expect("an FE tier has a mesh");
                if finest.is_none_or(|f| mesh.counts().0 > f.counts().0) {
                    finest = Some(mesh);
                }
            }
        }
        finest.ok_or(ChoiceError::NoTierMeets {
            tolerance,
            best: None,
        })
    }
}

/// Which model lines to draw and how to evaluate the WNL law.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSelection {
    /// Lines to draw: any of `westergaard`, `wnl`.
    pub draw: Vec<ModelKind>,
    /// Reading of the paper's Eq. 4 (docs/replication.md R5): `bracket-sq` (default), `bracket-2x`, `literal`.
    #[serde(default)]
    pub reading: Reading,
    /// WNL coefficient set, by name (default `paper-table1`).
    #[serde(default)]
    pub coefficients: CoefficientSet,
    /// A second WNL coefficient set (e.g. our refit of Table 1) drawn dashed and scored
    /// against the FE points beside the first; none by default.
    #[serde(default)]
    pub compare_coefficients: Option<CoefficientSet>,
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

/// Parses `text` as a `T`, strictly. `origin` names the file in error messages; a field
/// error names the field's dotted path.
pub fn parse_document<T: DeserializeOwned>(text: &str, origin: &str) -> Result<T, SpecError> {
    let de = toml::Deserializer::parse(text).map_err(|e| SpecError::Parse {
        origin: origin.into(),
        field: "(document)".into(),
        message: excerpt(e.to_string().trim_end()),
    })?;
    serde_path_to_error::deserialize(de).map_err(|e| {
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
            message: excerpt(e.into_inner().to_string().trim_end()),
        }
    })
}

/// Checks a parsed scene section against the rules serde cannot express (ranges of grids,
/// lists that must not be empty, cross-field rules), naming the file, field and value.
pub struct Validator<'a> {
    /// The spec's text (to turn spans into line and column).
    pub text: &'a str,
    /// The spec's name in messages.
    pub origin: &'a str,
}

impl Validator<'_> {
    pub fn invalid(
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

    pub fn grid(
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

    /// An FE section: its τ_max list non-empty, each one of `panels` (when given); `mesh` or
    /// `tolerance`, not both, and a tolerance the measurements can serve at `aspect_ratios`.
    pub fn fe_section(
        &self,
        field: &str,
        fe: &FeSection,
        panels: Option<&[f64]>,
        aspect_ratios: &[f64],
    ) -> Result<(), SpecError> {
        if let Some(t) = fe.tolerance {
            let tolerance = format!("{field}.tolerance");
            if let Some(mesh) = fe.mesh {
                return Err(self.invalid(
                    &tolerance,
                    None,
                    t.get().to_string(),
                    format!("absent when `mesh` is set (here {mesh:?}): set one of the two"),
                ));
            }
            if fe.kinematics != Kinematics::Finite {
                return Err(self.invalid(
                    &tolerance,
                    None,
                    t.get().to_string(),
                    "absent with linear kinematics (the measured errors are of the finite-strain solution)".into(),
                ));
            }
            if let Err(e) = fe.mesh_for(aspect_ratios) {
                return Err(self.invalid(&tolerance, None, t.get().to_string(), e.to_string()));
            }
        }
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
    pub fn at_least(
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

    /// The rigid surface of a single FE case whose section is `fe`: the sinusoid of
    /// `{prefix}.aspect_ratio` or the `{prefix}.profile` ([`ProfileField`]: harmonics
    /// `[[1, AR₁], [n, AR₂], …]`, docs/replication.md R13, or a Weierstrass profile, R14),
    /// exactly one of the two. A profile
    /// is refused with a `tolerance` (the measured errors are of single sinusoids) and where the
    /// solver cannot take it at the section's mesh (`fe::validate`: unresolved, too steep).
    pub fn fe_surface(
        &self,
        prefix: &str,
        fe: &FeSection,
        aspect_ratio: Option<f64>,
        profile: Option<&ProfileField>,
    ) -> Result<Profile, SpecError> {
        let field = format!("{prefix}.profile");
        let given = match (aspect_ratio, profile) {
            (Some(ar), None) => return Ok(Profile::sinusoid(ar)),
            (None, Some(given)) => given,
            (a, p) => {
                let given = match (a, p) {
                    (Some(_), Some(_)) => "both",
                    _ => "neither",
                };
                return Err(self.invalid(
                    &format!("{prefix}.aspect_ratio"),
                    None,
                    format!("{given} of aspect_ratio and profile"),
                    "exactly one: aspect_ratio = Δ/λ, or profile = [[1, AR₁], [n, AR₂], …] or \"weierstrass:AR0,gamma,D,K\"".into(),
                ));
            }
        };
        let text = given.quoted();
        let profile = given
            .profile()
            .map_err(|e| self.invalid(&field, None, text.clone(), e.to_string()))?;
        if let Some(t) = fe.tolerance.filter(|_| !profile.is_sinusoid()) {
            return Err(self.invalid(
                &format!("{prefix}.fe.tolerance"),
                None,
                t.get().to_string(),
                "absent with a profile (the measured errors are of single sinusoids): set `mesh`"
                    .into(),
            ));
        }
        let mesh = fe
            .mesh_for(&[profile.aspect_ratio])
            .map_err(|e| self.invalid(&field, None, text.clone(), e.to_string()))?;
        let problem = crate::fe::LayerProblem {
            finer_harmonics: profile.finer,
            ..defaults::layer_problem(profile.aspect_ratio)
        };
        let options = crate::fe::SolveOptions {
            mesh,
            ..Default::default()
        };
        crate::fe::validate(&problem, &options)
            .map_err(|e| self.invalid(&field, None, text, e.to_string()))?;
        Ok(profile)
    }

    pub fn non_empty(&self, field: &str, len: usize) -> Result<(), SpecError> {
        if len == 0 {
            return Err(self.invalid(field, None, "[]".into(), "at least one value".into()));
        }
        Ok(())
    }

    pub fn models(&self, field: &str, m: &ModelSelection) -> Result<(), SpecError> {
        self.non_empty(&format!("{field}.draw"), m.draw.len())
    }
}

/// The rigid surface of a validated single FE case ([`Validator::fe_surface`]): the sinusoid
/// of `aspect_ratio` or the `profile`.
///
/// # Panics
/// When neither is given or the profile is malformed: validation refuses such a spec.
pub fn validated_surface(aspect_ratio: Option<f64>, profile: Option<&ProfileField>) -> Profile {
    match (aspect_ratio, profile) {
        (Some(ar), _) => Profile::sinusoid(ar),
        (None, Some(given)) => given.profile().expect("validated"),
        (None, None) => unreachable!("validated: aspect_ratio or profile"),
    }
}

/// Longest line of a quoted spec excerpt in an error message, in characters.
const EXCERPT_LINE_CHARS: usize = 160;
/// Most lines of an error message.
const EXCERPT_LINES: usize = 12;

/// `message` with each line cut to [`EXCERPT_LINE_CHARS`] and at most [`EXCERPT_LINES`] lines:
/// the TOML parser quotes the offending line, which may be megabytes long (a 10⁶-element
/// array on one line).
fn excerpt(message: &str) -> String {
    let mut out: Vec<String> = message
        .lines()
        .take(EXCERPT_LINES)
        .map(|l| match l.char_indices().nth(EXCERPT_LINE_CHARS) {
            Some((cut, _)) => format!(
                "{} … ({} more characters)",
                &l[..cut],
                l[cut..].chars().count()
            ),
            None => l.to_string(),
        })
        .collect();
    let total = message.lines().count();
    if total > EXCERPT_LINES {
        out.push(format!("… ({} more lines)", total - EXCERPT_LINES));
    }
    out.join("\n")
}

/// 1-based line and column of a byte offset.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}
