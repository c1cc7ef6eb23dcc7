//! The fingertip parameters against direct finite elements (docs/replication.md R8, R9): is the
//! WNL law right where the paper applies it, AR = 0.08 and τ_max/E* = 0.1–0.71, outside the
//! domain its polynomials were fitted on (AR 0.1–0.3, τ_max ≤ 0.2 MPa at E* = 1 MPa)?
//!
//! One panel per E* (and one frictionless): p̄/E* against a/λ from our FE, Westergaard, the WNL
//! law as the paper uses it (τ_max in MPa) and the WNL law read as a law of τ_max/E* (the
//! polynomials evaluated at τ_max/E* × E*_fit). A table gives each law's largest and
//! root-mean-square relative error against the FE curve on a grid of a/λ.

use crate::accuracy::measured::percent;
use crate::accuracy::{relative_errors, ErrorSummary};
use crate::fe::convergence::p_at;
use crate::models::{ModelKind, ModelLaw, PressureLaw};
use crate::numfmt::sig_digits;
use crate::plot::{palette, Panel, Series};
use crate::runner::scenes::fingertip_ridges::{ridge_aspect_ratio, FingertipFe};
use crate::runner::scenes::scene_output::{incomplete_panel_note, Layout, Remarks};
use crate::runner::scenes::wnl_beyond_fit::{fit_estar_mpa, outside_fit, wnl_tau_over_estar};
use crate::runner::scenes::{Scene, SceneContext, SceneResult};
use crate::runner::sweep::fe_cases::{self, FeCase, FeOutcome};
use crate::runner::RunOptions;
use crate::spec::{
    Bounded, Grid, ModelSelection, NonNegative, Positive, SpecError, Validator,
    A_OVER_LAMBDA_ALLOWED,
};
use crate::table::{Cell, Table};
use anyhow::Result;
use plotters::style::RGBColor;
use serde::Deserialize;

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

impl PanelCase {
    /// τ_max/E* (none for the frictionless panel).
    fn tau_over_estar(&self) -> Option<f64> {
        self.estar_mpa.map(|e| self.tau_max_mpa / e)
    }

    /// The panel's title, which also names its FE curve.
    fn name(&self) -> String {
        match (self.estar_mpa, self.tau_over_estar()) {
            (Some(e), Some(r)) => format!(
                "E* = {e} MPa, τ_max = {} MPa (τ_max/E* = {})",
                self.tau_max_mpa,
                sig_digits(r, 2)
            ),
            _ => "frictionless (any E*)".into(),
        }
    }

    /// The panel's name in a list: its modulus.
    fn short_name(&self) -> String {
        self.estar_mpa
            .map_or("frictionless".into(), |e| format!("E* = {e} MPa"))
    }
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
                        law: ModelLaw::new(kind, ar, panel.tau_max_mpa, m.reading, m.coefficients),
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
    let xs = s.a_over_lambda.values();
    let error_xs = s.error_a_over_lambda.values();
    let panels = s.panels();
    let outcomes = fe_cases::solve_all(&s.fe_cases(opts), opts)?;
    let mut tables = Tables::new(&s.lines(&panels[0]));
    let mut remarks = Remarks::default();
    let mut outside = OutsideFit::default();
    let mut figure_panels = vec![];
    for (panel, fe) in panels.iter().zip(&outcomes) {
        let lines = s.lines(panel);
        let reference: Vec<(f64, f64)> = error_xs
            .iter()
            .filter_map(|&x| Some((x, p_at(&fe.points, x)?)))
            .collect();
        let judged: Vec<Judged> = lines.iter().map(|l| judge(l, &reference, &xs)).collect();
        remarks.stopped_curve(&panel.name(), fe);
        for (l, j) in lines.iter().zip(&judged) {
            outside.add(l, &j.outside_fit, &panel.short_name());
            if j.law_status != "physical" {
                let note = format!("{} at {}: {}", l.label, panel.name(), j.law_status);
                remarks.notes.push(note);
            }
        }
        tables.push_panel(panel, fe, &lines, &judged, &xs, reference.len());
        figure_panels.push(figure_panel(panel, fe, &lines, &judged, &xs));
    }
    remarks.footer = footer(s, opts);
    outside.remark(&mut remarks);
    remarks.count_incomplete("see the panels and fe_status in the CSVs");
    let rows = figure_panels.len().div_ceil(2);
    let layout = Layout {
        grid: (rows, 2),
        panel_px: (560, 430),
        margin_px: 40 * remarks.footer.len() as u32 + 60,
        font_px: 15,
    };
    Ok(remarks.finish(title, layout, figure_panels, tables.into_vec()))
}

/// One line of a panel judged against the panel's FE curve.
struct Judged {
    /// Relative errors on the error grid where the FE curve reaches (none if it reaches none).
    errors: Option<ErrorSummary>,
    /// Where the law leaves its fit domain, in words ([`outside_fit`]).
    outside_fit: Vec<String>,
    /// `physical`, or the first a/λ where the law is not a physical pressure.
    law_status: String,
}

/// `line` against the FE curve's (a/λ, p̄/E*) `reference`; `xs` the a/λ it is drawn at.
fn judge(line: &Line, reference: &[(f64, f64)], xs: &[f64]) -> Judged {
    let values: Vec<f64> = reference
        .iter()
        .map(|&(x, _)| line.law.p_over_estar(x))
        .collect();
    let fe_values: Vec<f64> = reference.iter().map(|r| r.1).collect();
    Judged {
        errors: (!values.is_empty()).then(|| relative_errors(&values, &fe_values)),
        outside_fit: outside_fit(&line.law),
        law_status: unphysical(&line.law, xs).unwrap_or_else(|| "physical".into()),
    }
}

/// The scene's three tables: the lines on the a/λ grid, each line's errors, the FE points.
struct Tables {
    curves: Table,
    errors: Table,
    fe_points: Table,
}

impl Tables {
    /// Empty tables whose line columns are those of `key_lines` (every panel draws the same).
    fn new(key_lines: &[Line]) -> Self {
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
        Tables {
            curves: Table::new("", &header),
            errors: Table::new("errors", &ERRORS_HEADER),
            fe_points: Table::new("fe_points", &FE_POINTS_HEADER),
        }
    }

    /// The rows of one panel: its FE points, its lines on `xs`, and each line's errors over
    /// `points` points of the error grid.
    fn push_panel(
        &mut self,
        panel: &PanelCase,
        fe: &FeOutcome,
        lines: &[Line],
        judged: &[Judged],
        xs: &[f64],
        points: usize,
    ) {
        let estar: Cell = panel.estar_mpa.into();
        let ratio: Cell = panel.tau_over_estar().unwrap_or(0.0).into();
        let status = fe.status();
        for p in &fe.points {
            self.fe_points.push(vec![
                estar.clone(),
                panel.tau_max_mpa.into(),
                p.a_over_lambda.into(),
                p.p_over_estar.into(),
                p.p_over_estar_reaction.into(),
            ]);
        }
        for &x in xs {
            let mut row = vec![
                estar.clone(),
                panel.tau_max_mpa.into(),
                ratio.clone(),
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
            self.curves.push(row);
        }
        for (l, j) in lines.iter().zip(judged) {
            let tau_in_polynomials: Cell = match l.law {
                ModelLaw::Wnl(w) => w.tau_max_mpa.into(),
                ModelLaw::Westergaard(_) => Cell::Empty,
            };
            self.errors.push(vec![
                l.key.into(),
                estar.clone(),
                panel.tau_max_mpa.into(),
                ratio.clone(),
                tau_in_polynomials,
                l.law.is_extrapolated().into(),
                j.outside_fit.join(", ").into(),
                (points as f64).into(),
                j.errors.map(|e| e.max).into(),
                j.errors.map(|e| e.rms).into(),
                j.law_status.clone().into(),
                status.clone().into(),
            ]);
        }
    }

    fn into_vec(self) -> Vec<Table> {
        vec![self.curves, self.errors, self.fe_points]
    }
}

const ERRORS_HEADER: [&str; 12] = [
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
];

const FE_POINTS_HEADER: [&str; 5] = [
    "estar_mpa",
    "tau_max_mpa",
    "a_over_lambda",
    "p_over_estar",
    "p_over_estar_reaction",
];

/// One panel: the FE points, then each line on `xs`; the notes give each line's errors.
fn figure_panel(
    panel: &PanelCase,
    fe: &FeOutcome,
    lines: &[Line],
    judged: &[Judged],
    xs: &[f64],
) -> Panel {
    let mut notes = vec![];
    for (l, j) in lines.iter().zip(judged) {
        if j.law_status != "physical" {
            notes.push(format!("{}: p̄/E* < 0 (unphysical)", l.label));
        }
        if let Some(e) = j.errors {
            notes.push(format!(
                "{}: max {}, RMS {}",
                l.label,
                percent(e.max),
                percent(e.rms)
            ));
        }
    }
    notes.extend(incomplete_panel_note(fe));
    let mut series = vec![Series::markers(
        Some("FE (this project)".into()),
        palette::GREY,
        3,
        fe.points
            .iter()
            .map(|p| (p.a_over_lambda, p.p_over_estar))
            .collect(),
    )];
    for l in lines {
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
    Panel::mean_pressure(
        panel.name(),
        "a/λ",
        (xs[0], xs[xs.len() - 1]),
        series,
        notes,
    )
}

/// The footer before any warning: the ridges and laws, the errors, the τ_max/E* law, the FE.
fn footer(s: &FingertipFeScene, opts: &RunOptions) -> Vec<String> {
    let fit = fit_estar_mpa(s.fit_estar_mpa);
    let error_xs = s.error_a_over_lambda.values();
    let (e0, e1) = (error_xs[0], error_xs[error_xs.len() - 1]);
    let mut footer = vec![
        format!(
            "Ridges λ = {} mm, Δ = {} mm (AR = {}). WNL: reading `{}`, coefficients `{}`.",
            s.wavelength_mm.get(),
            s.amplitude_mm.get(),
            sig_digits(s.aspect_ratio(), 3),
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
    footer
}

/// The lines drawn outside the fit domain of the polynomials, by reason.
#[derive(Default)]
struct OutsideFit {
    /// (reason, the lines at the panels it applies to), in order of first appearance.
    reasons: Vec<(String, Vec<String>)>,
    /// WNL lines over all panels: a reason that applies to every one says so.
    wnl_lines: usize,
}

impl OutsideFit {
    /// `line` of the panel `short`, outside its fit domain for each of `why`.
    fn add(&mut self, line: &Line, why: &[String], short: &str) {
        if line.key != "westergaard" {
            self.wnl_lines += 1;
        }
        for w in why {
            let at = format!("{} at {short}", line.label);
            match self.reasons.iter_mut().find(|(r, _)| r == w) {
                Some((_, lines)) => lines.push(at),
                None => self.reasons.push((w.clone(), vec![at])),
            }
        }
    }

    /// The EXTRAPOLATED lines of the footer and the run's note (none inside the fit domain).
    fn remark(&self, remarks: &mut Remarks) {
        if self.reasons.is_empty() {
            return;
        }
        let reasons: Vec<String> = self
            .reasons
            .iter()
            .map(|(why, at)| {
                if at.len() == self.wnl_lines {
                    format!("{why}: every WNL line")
                } else {
                    format!("{why}: {}", at.join(", "))
                }
            })
            .collect();
        remarks
            .footer
            .push("EXTRAPOLATED (outside the fit domain of the polynomials):".into());
        remarks
            .footer
            .extend(reasons.iter().map(|r| format!("    {r}.")));
        remarks.notes.push(format!(
            "EXTRAPOLATED (outside the fit domain) — {}.",
            reasons.join("; ")
        ));
    }
}
