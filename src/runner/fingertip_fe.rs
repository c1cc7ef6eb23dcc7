//! The fingertip parameters against direct finite elements (docs/replication.md R8, R9): is the
//! WNL law right where the paper applies it, AR = 0.08 and τ_max/E* = 0.1–0.71, outside the
//! domain its polynomials were fitted on (AR 0.1–0.3, τ_max ≤ 0.2 MPa at E* = 1 MPa)?
//!
//! One panel per E* (and one frictionless): p̄/E* against a/λ from our FE, Westergaard, the WNL
//! law as the paper uses it (τ_max in MPa) and the WNL law read as a law of τ_max/E* (the
//! polynomials evaluated at τ_max/E* × E*_fit). A table gives each law's largest and
//! root-mean-square relative error against the FE curve on a grid of a/λ.
//!
//! This module also holds what Fig. 5 (`fingertip_area`) shares with it: the FE table
//! [`FingertipFe`], the ridge geometry check, the τ_max/E* law, the words for an extrapolation,
//! and the inverse a(p̄) of an FE curve.

use super::fe_cases::{self, FeCase, FeOutcome, FePhysics};
use super::scenes::{Scene, SceneContext, SceneResult};
use super::RunOptions;
use crate::accuracy::measured::percent;
use crate::accuracy::relative_errors;
use crate::defaults;
use crate::fe::convergence::p_at;
use crate::fe::{CurvePoint, Kinematics, MeshLevel, SolveOptions};
use crate::models::{ModelKind, ModelLaw, PressureLaw};
use crate::numfmt::sig_digits;
use crate::plot::{palette, Figure, Panel, Series};
use crate::spec::{
    mesh_from_name, Bounded, Grid, ModelSelection, NonNegative, OpenHalfWidth, Positive,
    SpecError, Validator, A_OVER_LAMBDA_ALLOWED,
};
use crate::table::{Cell, Table};
use anyhow::Result;
use plotters::style::RGBColor;
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
    pub elastic_slip_over_element: Option<Bounded<Positive>>,
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
    let side = |x: f64, lo: f64, hi: f64| if x < lo { format!("< {lo}") } else { format!("> {hi}") };
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

/// Where a mean pressure falls on an FE curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum FeInverse {
    /// At or below the curve's last point: a/λ there.
    Within(f64),
    /// Above the curve's last point (a/λ = `last_a_over_lambda`): the FE says only that the
    /// contact is at least that wide.
    Beyond { last_a_over_lambda: f64 },
}

/// a/λ at which an FE curve carries p̄/E* = `p_over_estar` (≥ 0): linear in √p̄ between the
/// origin (no load, no contact) and the curve's points, whose p̄ must not decrease. Points that
/// repeat an edge position (within 10⁻⁶, as in [`p_at`]) are skipped. Above the last point the
/// answer is [`FeInverse::Beyond`], never an extrapolation.
pub(crate) fn fe_a_over_lambda_at(
    points: &[CurvePoint],
    p_over_estar: f64,
) -> Result<FeInverse, String> {
    let mut nodes = vec![(0.0, 0.0)];
    for p in points {
        let &(a, s) = nodes.last().expect("starts with the origin");
        if p.a_over_lambda <= a + 1e-6 {
            continue;
        }
        let root = p.p_over_estar.max(0.0).sqrt();
        if root < s {
            return Err(format!(
                "the FE curve's p̄/E* decreases to {} at a/λ = {}: no unique contact width",
                sig_digits(p.p_over_estar, 6),
                sig_digits(p.a_over_lambda, 4)
            ));
        }
        nodes.push((p.a_over_lambda, root));
    }
    let target = p_over_estar.max(0.0).sqrt();
    let &(last_a, last_s) = nodes.last().expect("starts with the origin");
    if target > last_s {
        return Ok(FeInverse::Beyond {
            last_a_over_lambda: last_a,
        });
    }
    let k = nodes
        .iter()
        .position(|&(_, s)| s >= target)
        .expect("target ≤ the last node's");
    if k == 0 {
        return Ok(FeInverse::Within(0.0));
    }
    let ((a0, s0), (a1, s1)) = (nodes[k - 1], nodes[k]);
    let t = if s1 > s0 {
        (target - s0) / (s1 - s0)
    } else {
        1.0
    };
    Ok(FeInverse::Within(a0 + t * (a1 - a0)))
}

/// `complete`, or `incomplete at a/λ = …: <reason>` for a curve that stopped short.
pub(crate) fn fe_status(fe: &FeOutcome) -> String {
    match &fe.failure {
        None => "complete".into(),
        Some(f) => format!("incomplete at a/λ = {}: {f}", sig_digits(last_a(fe), 4)),
    }
}

/// The a/λ of an FE curve's last point (0 for an empty curve).
pub(crate) fn last_a(fe: &FeOutcome) -> f64 {
    fe.points.last().map_or(0.0, |p| p.a_over_lambda)
}

/// The fingertip ridges against direct FE: one panel per E* (and a frictionless one).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FingertipFeScene {
    /// Ridge wavelength λ, mm.
    pub wavelength_mm: Bounded<Positive>,
    /// Ridge amplitude Δ, mm (AR = Δ/λ).
    pub amplitude_mm: Bounded<Positive>,
    /// Plane-strain moduli E*, MPa: one frictional FE curve and one panel each.
    pub estar_mpa: Vec<Bounded<Positive>>,
    /// Interfacial shear strength τ_max, MPa.
    pub tau_max_mpa: Bounded<NonNegative>,
    /// Also the frictionless FE curve (τ_max = 0, the same at every E*) in a panel of its own.
    pub frictionless: bool,
    /// E*_fit: the modulus of the FE sweep the WNL polynomials were fitted at, MPa (R9; default
    /// `crate::defaults::fe_estar_mpa`). The τ_max/E* law evaluates them at τ_max/E* × E*_fit.
    #[serde(default)]
    pub fit_estar_mpa: Option<Bounded<Positive>>,
    /// Where the lines are sampled and tabulated, a/λ.
    pub a_over_lambda: Grid,
    /// Where the errors against FE are taken, a/λ (the FE curve interpolated there, [`p_at`]).
    pub error_a_over_lambda: Grid,
    pub models: ModelSelection,
    pub fe: FingertipFe,
}

impl Scene for FingertipFeScene {
    /// The frictionless curve first (when asked), then one per E*, in the spec's order.
    fn fe_cases(&self, opts: &RunOptions) -> Vec<FeCase> {
        let ar = self.aspect_ratio();
        self.panels()
            .iter()
            .map(|p| self.fe.case(ar, p.tau_max_mpa, p.fe_estar_mpa, opts))
            .collect()
    }

    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        run(ctx.title, self, ctx.opts)
    }

    fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        ridge_aspect_ratio(
            v,
            "fingertip_fe",
            self.wavelength_mm.get(),
            self.amplitude_mm.get(),
        )?;
        v.non_empty("fingertip_fe.estar_mpa", self.estar_mpa.len())?;
        v.grid(
            "fingertip_fe.a_over_lambda",
            &self.a_over_lambda,
            A_OVER_LAMBDA_ALLOWED,
            true,
        )?;
        // relative errors need p̄ > 0 (a/λ > 0), and the FE curve must reach the grid's end
        let until = self.fe.until_a_over_lambda.get();
        v.grid(
            "fingertip_fe.error_a_over_lambda",
            &self.error_a_over_lambda,
            (0.0, until),
            false,
        )?;
        v.models("fingertip_fe.models", &self.models)
    }
}

/// One panel: a modulus (none: frictionless) and its FE curve's parameters.
struct PanelCase {
    estar_mpa: Option<f64>,
    tau_max_mpa: f64,
    /// The E* the FE case is built with (the frictionless curve is keyed at E*_fit).
    fe_estar_mpa: f64,
}

/// One line of a panel.
struct Line {
    key: &'static str,
    label: &'static str,
    law: ModelLaw,
    color: RGBColor,
    dashed: bool,
}

impl FingertipFeScene {
    fn aspect_ratio(&self) -> f64 {
        self.amplitude_mm.get() / self.wavelength_mm.get()
    }

    fn panels(&self) -> Vec<PanelCase> {
        let fit = fit_estar_mpa(self.fit_estar_mpa);
        let mut panels = vec![];
        if self.frictionless {
            panels.push(PanelCase {
                estar_mpa: None,
                tau_max_mpa: 0.0,
                fe_estar_mpa: fit,
            });
        }
        for e in self.estar_mpa.iter().map(|e| e.get()) {
            panels.push(PanelCase {
                estar_mpa: Some(e),
                tau_max_mpa: self.tau_max_mpa.get(),
                fe_estar_mpa: e,
            });
        }
        panels
    }

    /// The lines of a panel, in the order of `models.draw`; WNL gives two.
    fn lines(&self, panel: &PanelCase) -> Vec<Line> {
        let ar = self.aspect_ratio();
        let fit = fit_estar_mpa(self.fit_estar_mpa);
        let m = &self.models;
        let mut lines = vec![];
        for &kind in &m.draw {
            match kind {
                ModelKind::Westergaard => lines.push(Line {
                    key: "westergaard",
                    label: "Westergaard",
                    law: ModelLaw::new(kind, ar, 0.0, m.reading, m.coefficients),
                    color: palette::BLACK,
                    dashed: false,
                }),
                ModelKind::Wnl => {
                    lines.push(Line {
                        key: "wnl_tau_mpa",
                        label: "WNL, τ_max in MPa (paper)",
                        law: ModelLaw::new(
                            kind,
                            ar,
                            panel.tau_max_mpa,
                            m.reading,
                            m.coefficients,
                        ),
                        color: palette::VERMILION,
                        dashed: false,
                    });
                    lines.push(Line {
                        key: "wnl_tau_over_estar",
                        label: "WNL as a τ_max/E* law",
                        law: wnl_tau_over_estar(
                            m,
                            ar,
                            panel.tau_max_mpa,
                            panel.estar_mpa.unwrap_or(fit),
                            fit,
                        ),
                        color: palette::BLUE,
                        dashed: true,
                    });
                }
            }
        }
        lines
    }
}

/// The first a/λ of `xs` where `law` is not a physical pressure, in words.
fn unphysical(law: &ModelLaw, xs: &[f64]) -> Option<String> {
    xs.iter()
        .find_map(|&x| law.physical_p_over_estar(x).err())
        .map(|e| format!("unphysical: {e}"))
}

fn run(title: &str, s: &FingertipFeScene, opts: &RunOptions) -> Result<SceneResult> {
    let ar = s.aspect_ratio();
    let fit = fit_estar_mpa(s.fit_estar_mpa);
    let xs = s.a_over_lambda.values();
    let error_xs = s.error_a_over_lambda.values();
    let panels = s.panels();
    let outcomes = fe_cases::solve_all(&s.fe_cases(opts), opts)?;
    let key_lines = s.lines(&panels[0]);

    let mut header = vec![
        "estar_mpa",
        "tau_max_mpa",
        "tau_over_estar",
        "a_over_lambda",
        "p_over_estar_fe",
    ];
    let columns: Vec<String> = key_lines
        .iter()
        .map(|l| format!("p_over_estar_{}", l.key))
        .collect();
    header.extend(columns.iter().map(String::as_str));
    let flags: Vec<String> = key_lines
        .iter()
        .filter(|l| l.key != "westergaard")
        .map(|l| format!("{}_extrapolated", l.key))
        .collect();
    header.extend(flags.iter().map(String::as_str));
    header.push("fe_status");
    let mut curves = Table::new("", &header);
    let mut fe_points = Table::new(
        "fe_points",
        &[
            "estar_mpa",
            "tau_max_mpa",
            "a_over_lambda",
            "p_over_estar",
            "p_over_estar_reaction",
        ],
    );
    let mut errors = Table::new(
        "errors",
        &[
            "law",
            "estar_mpa",
            "tau_max_mpa",
            "tau_over_estar",
            "tau_in_polynomials_mpa",
            "extrapolated",
            "outside_fit",
            "points",
            "max_rel_error",
            "rms_rel_error",
            "law_status",
            "fe_status",
        ],
    );

    let mut figure_panels = vec![];
    let mut notes = vec![];
    let mut incomplete = vec![];
    // (reason, the lines at the panels it applies to)
    let mut outside: Vec<(String, Vec<String>)> = vec![];
    let mut wnl_lines = 0;
    for (panel, fe) in panels.iter().zip(&outcomes) {
        let estar_cell: Cell = panel.estar_mpa.into();
        let ratio = panel.estar_mpa.map(|e| panel.tau_max_mpa / e);
        let ratio_cell: Cell = ratio.unwrap_or(0.0).into();
        let status = fe_status(fe);
        let name = match (panel.estar_mpa, ratio) {
            (Some(e), Some(r)) => format!(
                "E* = {e} MPa, τ_max = {} MPa (τ_max/E* = {})",
                panel.tau_max_mpa,
                sig_digits(r, 2)
            ),
            _ => "frictionless (any E*)".into(),
        };
        let short = panel
            .estar_mpa
            .map_or("frictionless".into(), |e| format!("E* = {e} MPa"));
        if let Some(f) = &fe.failure {
            incomplete.push(format!(
                "FE curve {name} stopped at a/λ = {}: {f}",
                sig_digits(last_a(fe), 4)
            ));
        }
        for p in &fe.points {
            fe_points.push(vec![
                estar_cell.clone(),
                panel.tau_max_mpa.into(),
                p.a_over_lambda.into(),
                p.p_over_estar.into(),
                p.p_over_estar_reaction.into(),
            ]);
        }
        let lines = s.lines(panel);
        for &x in &xs {
            let mut row = vec![
                estar_cell.clone(),
                panel.tau_max_mpa.into(),
                ratio_cell.clone(),
                x.into(),
                p_at(&fe.points, x).into(),
            ];
            row.extend(lines.iter().map(|l| Cell::Num(l.law.p_over_estar(x))));
            row.extend(
                lines
                    .iter()
                    .filter(|l| l.key != "westergaard")
                    .map(|l| Cell::from(l.law.is_extrapolated())),
            );
            row.push(status.clone().into());
            curves.push(row);
        }

        // errors on the grid where the FE curve reaches (all of it for a complete curve)
        let reference: Vec<(f64, f64)> = error_xs
            .iter()
            .filter_map(|&x| Some((x, p_at(&fe.points, x)?)))
            .collect();
        let mut panel_notes = vec![];
        for l in &lines {
            let values: Vec<f64> = reference
                .iter()
                .map(|&(x, _)| l.law.p_over_estar(x))
                .collect();
            let fe_values: Vec<f64> = reference.iter().map(|r| r.1).collect();
            let e = (!values.is_empty()).then(|| relative_errors(&values, &fe_values));
            let why = outside_fit(&l.law);
            if l.key != "westergaard" {
                wnl_lines += 1;
            }
            for w in &why {
                match outside.iter_mut().find(|(r, _)| r == w) {
                    Some((_, at)) => at.push(format!("{} at {short}", l.label)),
                    None => outside.push((w.clone(), vec![format!("{} at {short}", l.label)])),
                }
            }
            let law_status = unphysical(&l.law, &xs).unwrap_or_else(|| "physical".into());
            if law_status != "physical" {
                panel_notes.push(format!("{}: p̄/E* < 0 (unphysical)", l.label));
                notes.push(format!("{} at {name}: {law_status}", l.label));
            }
            if let Some(e) = e {
                panel_notes.push(format!(
                    "{}: max {}, RMS {}",
                    l.label,
                    percent(e.max),
                    percent(e.rms)
                ));
            }
            let tau_poly: Cell = match l.law {
                ModelLaw::Wnl(w) => w.tau_max_mpa.into(),
                ModelLaw::Westergaard(_) => Cell::Empty,
            };
            errors.push(vec![
                l.key.into(),
                estar_cell.clone(),
                panel.tau_max_mpa.into(),
                ratio_cell.clone(),
                tau_poly,
                l.law.is_extrapolated().into(),
                why.join(", ").into(),
                (reference.len() as f64).into(),
                e.map(|e| e.max).into(),
                e.map(|e| e.rms).into(),
                law_status.into(),
                status.clone().into(),
            ]);
        }
        if fe.failure.is_some() {
            panel_notes.push(format!(
                "FE INCOMPLETE: stopped at a/λ = {}",
                sig_digits(last_a(fe), 3)
            ));
        }

        let mut series = vec![Series::markers(
            Some("FE (this project)".into()),
            palette::GREY,
            3,
            fe.points
                .iter()
                .map(|p| (p.a_over_lambda, p.p_over_estar))
                .collect(),
        )];
        for l in &lines {
            let pts = xs.iter().map(|&x| (x, l.law.p_over_estar(x))).collect();
            let label = Some(if l.law.is_extrapolated() {
                format!("{}, extrapolated", l.label)
            } else {
                l.label.to_string()
            });
            series.push(if l.dashed {
                Series::dashed(label, l.color, 2, pts)
            } else {
                Series::line(label, l.color, 2, pts)
            });
        }
        figure_panels.push(Panel::mean_pressure(
            name,
            "a/λ",
            (xs[0], xs[xs.len() - 1]),
            series,
            panel_notes,
        ));
    }

    let (e0, e1) = (error_xs[0], error_xs[error_xs.len() - 1]);
    let mut footer = vec![
        format!(
            "Ridges λ = {} mm, Δ = {} mm (AR = {}). WNL: reading `{}`, coefficients `{}`.",
            s.wavelength_mm.get(),
            s.amplitude_mm.get(),
            sig_digits(ar, 3),
            s.models.reading,
            s.models.coefficients,
        ),
        format!(
            "Errors: relative, of p̄/E* against the FE curve interpolated at {} points a/λ ∈ [{e0}, {e1}].",
            error_xs.len()
        ),
        format!(
            "WNL as a τ_max/E* law: the polynomials at τ = (τ_max/E*) × E*_fit, E*_fit = {fit} MPa (the fitted FE sweep's, R9); the paper's use: τ = {} MPa.",
            s.tau_max_mpa.get()
        ),
    ];
    if let Some(case) = s.fe_cases(opts).first() {
        let (nx, ny) = case.options.mesh.counts();
        let physics = s.fe.physics(fit);
        footer.push(format!(
            "FE (ours): {:?} kinematics, neo-Hookean κ/G = {}, h/λ = {}, μ = {}, mesh {nx}×{ny}, loaded to a/λ = {}.",
            physics.kinematics,
            physics.kappa_over_g,
            physics.thickness_over_lambda,
            physics.friction_coefficient,
            s.fe.until_a_over_lambda.get()
        ));
    }
    if !outside.is_empty() {
        let reasons: Vec<String> = outside
            .iter()
            .map(|(why, at)| {
                if at.len() == wnl_lines {
                    format!("{why}: every WNL line")
                } else {
                    format!("{why}: {}", at.join(", "))
                }
            })
            .collect();
        footer.push("EXTRAPOLATED (outside the fit domain of the polynomials):".into());
        footer.extend(reasons.iter().map(|r| format!("    {r}.")));
        notes.push(format!(
            "EXTRAPOLATED (outside the fit domain) — {}.",
            reasons.join("; ")
        ));
    }
    if !incomplete.is_empty() {
        footer.push(format!(
            "INCOMPLETE FE curves ({}): see the panels and fe_status in the CSVs.",
            incomplete.len()
        ));
    }
    let cols = 2;
    let rows = figure_panels.len().div_ceil(cols);
    let figure = Figure {
        width: 560 * cols as u32,
        height: 430 * rows as u32 + 40 * footer.len() as u32 + 60,
        caption: title.into(),
        grid: (rows, cols),
        panels: figure_panels,
        footer,
        font_px: 15,
    };
    Ok(SceneResult {
        tables: vec![curves, errors, fe_points],
        figure,
        notes,
        incomplete,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(a: f64, p: f64) -> CurvePoint {
        CurvePoint {
            a_over_lambda: a,
            p_over_estar: p,
            p_over_estar_reaction: p,
            slab_displacement_over_lambda: 0.0,
            newton_iterations: 1,
            active_nodes: 1,
        }
    }

    #[test]
    fn fe_inverse_interpolates_and_never_extrapolates() {
        let pts = [point(0.1, 0.01), point(0.2, 0.04), point(0.2, 0.04), point(0.3, 0.09)];
        // p = x² exactly: linear in √p reproduces it
        for (p, a) in [(0.0, 0.0), (0.0025, 0.05), (0.01, 0.1), (0.0625, 0.25), (0.09, 0.3)] {
            match fe_a_over_lambda_at(&pts, p) {
                Ok(FeInverse::Within(x)) => assert!((x - a).abs() < 1e-12, "{p}: {x} ≠ {a}"),
                other => panic!("{p}: {other:?}"),
            }
        }
        assert_eq!(
            fe_a_over_lambda_at(&pts, 0.1),
            Ok(FeInverse::Beyond {
                last_a_over_lambda: 0.3
            })
        );
        let turning = [point(0.1, 0.02), point(0.2, 0.01)];
        assert!(fe_a_over_lambda_at(&turning, 0.005).is_err());
    }
}
