//! Paper Fig. 3: p̄/E* against a/λ, one panel per (AR, τ_max): model lines, and finite-element
//! points with the mean squared error of each model against them where the spec asks for FE.

use crate::models::{ModelKind, ModelLaw, PressureLaw};
use crate::numfmt::sig_digits;
use crate::plot::{palette, Panel, Series};
use crate::runner::scenes::scene_output::{incomplete_panel_note, Layout, Remarks};
use crate::runner::scenes::{Scene, SceneContext, SceneResult};
use crate::runner::sweep::fe_cases::{self, FeCase, FeOutcome, SolvedCases};
use crate::runner::{model_laws, RunOptions};
use crate::spec::{
    Bounded, FeSection, Grid, ModelSelection, NonNegative, Positive, SpecError, Validator,
    A_OVER_LAMBDA_ALLOWED,
};
use crate::table::{Cell, Table};
use anyhow::{Context, Result};
use serde::Deserialize;

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

impl Scene for FeVsModelScene {
    /// One case per (τ_max, AR) of the FE section, τ_max outer; with `error_estimate`, then
    /// each of them on the next coarser mesh.
    fn fe_cases(&self, opts: &RunOptions) -> Vec<FeCase> {
        let Some(fe) = &self.fe else { return vec![] };
        let ars: Vec<f64> = self.aspect_ratios.iter().map(|a| a.get()).collect();
        let cases = fe_cases::section_cases(fe, &ars, opts);
        fe_cases::with_coarser_cases(cases, fe.error_estimate)
    }

    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        run(ctx.title, self, ctx.opts)
    }

    fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        v.non_empty("fe_vs_model.aspect_ratios", self.aspect_ratios.len())?;
        v.non_empty("fe_vs_model.tau_max_mpa", self.tau_max_mpa.len())?;
        v.grid(
            "fe_vs_model.a_over_lambda",
            &self.a_over_lambda,
            A_OVER_LAMBDA_ALLOWED,
            true,
        )?;
        v.models("fe_vs_model.models", &self.models)?;
        if let Some(fe) = &self.fe {
            let panels: Vec<f64> = self.tau_max_mpa.iter().map(|t| t.get()).collect();
            let ars: Vec<f64> = self.aspect_ratios.iter().map(|a| a.get()).collect();
            v.fe_section("fe_vs_model.fe", fe, Some(&panels), &ars)?;
        }
        Ok(())
    }
}

/// Mean squared error and largest absolute deviation of `law` against FE points, in p̄/E*.
fn errors(law: &ModelLaw, fe: &FeOutcome) -> (f64, f64) {
    let n = fe.points.len().max(1) as f64;
    let (sum, max) = fe.points.iter().fold((0.0, 0.0_f64), |(sum, max), p| {
        let d = law.p_over_estar(p.a_over_lambda) - p.p_over_estar;
        (sum + d * d, max.max(d.abs()))
    });
    (sum / n, max)
}

fn run(title: &str, s: &FeVsModelScene, opts: &RunOptions) -> Result<SceneResult> {
    let ars: Vec<f64> = s.aspect_ratios.iter().map(|v| v.get()).collect();
    let taus: Vec<f64> = s.tau_max_mpa.iter().map(|v| v.get()).collect();
    let solved = SolvedCases::solve(s.fe_cases(opts), opts)?;
    // the section's own curves come first; the error estimates' coarser curves after them
    let n_main =
        s.fe.as_ref()
            .map_or(0, |fe| fe.tau_max_mpa.len() * ars.len());
    let main = &solved.cases[..n_main];
    let estimates = ErrorEstimates::of(s, &solved, main)?;
    let mut tables = Tables::new(s, estimates.is_some());
    let mut remarks = Remarks::with_footer(vec![format!(
        "WNL: reading `{}` of Eq. 4, coefficients `{}`; Westergaard: linear, frictionless half-space.",
        s.models.reading, s.models.coefficients
    )]);
    let mut panels = vec![];
    let mut extrapolated_panels = vec![];
    // Rows: τ_max; columns: AR.
    for &tau in &taus {
        for &ar in &ars {
            let laws = PanelLaws::new(s, ar, tau)?;
            if laws.extrapolated {
                extrapolated_panels.push(format!("AR = {ar}, τ_max = {tau} MPa"));
            }
            tables.push_lines(s, &laws, ar, tau);
            let mut notes = vec![];
            let at = main
                .iter()
                .position(|c| c.problem.aspect_ratio == ar && c.tau_max_mpa == tau);
            let fe = at.map(|k| &solved.outcomes[k]);
            if let (Some(k), Some(fe)) = (at, fe) {
                let estimate = estimates.as_ref().map(|e| e.of_case(k));
                tables.push_fe_points(ar, tau, fe, estimate);
                notes.extend(estimate.map(|e| e.panel_note(fe)));
                notes.extend(tables.push_mse(s, &laws, ar, tau, fe));
                notes.extend(incomplete_panel_note(fe));
                remarks.stopped_curve(&format!("AR = {ar}, τ_max = {tau} MPa"), fe);
            }
            panels.push(figure_panel(s, &laws, fe, ar, tau, notes));
        }
    }
    if let (Some(fe), Some(case)) = (&s.fe, main.first()) {
        let (nx, ny) = case.options.mesh.counts();
        remarks.footer.push(format!(
            "FE (ours): {:?} kinematics, neo-Hookean κ/G = {}, h/λ = {}, E* = {} MPa, mesh {nx}×{ny}; FE curves for τ_max ∈ {:?} MPa.",
            case.problem.kinematics,
            fe.kappa_over_g.get(),
            fe.thickness_over_lambda.get(),
            fe.estar_mpa.get(),
            fe.tau_max_mpa.iter().map(|t| t.get()).collect::<Vec<_>>()
        ));
    }
    remarks.count_incomplete(
        "each stops short of its target a/λ; see the panels and fe_status in the MSE table",
    );
    if !extrapolated_panels.is_empty() {
        remarks.footer_and_note(format!(
            "WNL evaluated outside its fit domain in: {}",
            extrapolated_panels.join("; ")
        ));
    }
    let layout = Layout {
        grid: (taus.len(), ars.len()),
        panel_px: (420, 330),
        margin_px: 140,
        font_px: 16,
    };
    Ok(remarks.finish(title, layout, panels, tables.into_vec(s.fe.is_some())))
}

/// The laws of one panel: the drawn models and the comparison WNL line, if any.
struct PanelLaws {
    laws: Vec<(ModelKind, ModelLaw)>,
    compare: Option<ModelLaw>,
    /// Some drawn law is evaluated outside its fit domain.
    extrapolated: bool,
}

impl PanelLaws {
    /// The laws at (AR, τ_max in MPa); a negative or non-finite value on the a/λ grid is an
    /// error, never a drawn line.
    fn new(s: &FeVsModelScene, ar: f64, tau: f64) -> Result<Self> {
        let laws = model_laws(&s.models, ar, tau);
        let compare = s
            .models
            .compare_coefficients
            .map(|c| ModelLaw::new(ModelKind::Wnl, ar, tau, s.models.reading, c));
        for law in laws.iter().map(|(_, l)| l).chain(&compare) {
            for x in s.a_over_lambda.values() {
                law.physical_p_over_estar(x).with_context(|| {
                    format!("panel AR = {ar}, τ_max = {tau} MPa, {}", law.describe())
                })?;
            }
        }
        let extrapolated = laws.iter().any(|(_, l)| l.is_extrapolated());
        Ok(PanelLaws {
            laws,
            compare,
            extrapolated,
        })
    }
}

/// The Richardson error estimates of the section's curves, from each curve and the same case
/// on the next coarser mesh (`error_estimate` of the FE section).
struct ErrorEstimates {
    /// Per curve of the section, per point: the estimate (none without a coarser curve).
    per_case: Vec<Option<Vec<Option<f64>>>>,
    /// The panel note gives the largest estimate from this a/λ on, where the committed
    /// speed–accuracy errors start (the relative estimate grows without bound as a/λ → 0).
    note_from_a_over_lambda: f64,
}

/// The estimates of one curve (none: no coarser curve).
#[derive(Clone, Copy)]
struct CaseEstimates<'a> {
    per_point: Option<&'a [Option<f64>]>,
    note_from_a_over_lambda: f64,
}

impl ErrorEstimates {
    /// The estimates of the section's curves `main`; none unless the section asks for them.
    fn of(s: &FeVsModelScene, solved: &SolvedCases, main: &[FeCase]) -> Result<Option<Self>> {
        if !s.fe.as_ref().is_some_and(|fe| fe.error_estimate) {
            return Ok(None);
        }
        let measured = crate::accuracy::measured::committed()?;
        let order = measured.fe_order()?;
        let note_from_a_over_lambda = measured
            .cases
            .iter()
            .map(|c| c.a_over_lambda.0)
            .fold(f64::INFINITY, f64::min);
        let per_case = fe_cases::coarser_cases(main)
            .iter()
            .zip(&solved.outcomes)
            .map(|(c, fine)| {
                let (coarse_case, ratio) = c.as_ref()?;
                let coarse = solved.outcome(coarse_case)?;
                Some(crate::accuracy::error_estimates(
                    &fine.points,
                    &coarse.points,
                    *ratio,
                    order,
                ))
            })
            .collect();
        Ok(Some(ErrorEstimates {
            per_case,
            note_from_a_over_lambda,
        }))
    }

    /// The estimates of the `k`-th curve of the section.
    fn of_case(&self, k: usize) -> CaseEstimates<'_> {
        CaseEstimates {
            per_point: self.per_case[k].as_deref(),
            note_from_a_over_lambda: self.note_from_a_over_lambda,
        }
    }
}

impl CaseEstimates<'_> {
    /// The panel note: the largest estimate over the range the speed–accuracy errors are
    /// measured on.
    fn panel_note(&self, fe: &FeOutcome) -> String {
        let largest = self.per_point.and_then(|e| {
            fe.points
                .iter()
                .zip(e)
                .filter(|(p, _)| p.a_over_lambda >= self.note_from_a_over_lambda)
                .filter_map(|(_, e)| *e)
                .reduce(f64::max)
        });
        match largest {
            Some(e) => format!(
                "FE error ≤ {} (Richardson)",
                crate::accuracy::measured::percent(e)
            ),
            None => "FE error: no estimate (coarser curve missing)".into(),
        }
    }
}

/// The scene's tables: the lines on the a/λ grid, the FE points, each law's error per panel.
struct Tables {
    lines: Table,
    fe_points: Table,
    mse: Table,
    with_estimates: bool,
}

impl Tables {
    fn new(s: &FeVsModelScene, with_estimates: bool) -> Self {
        let mut header = vec!["aspect_ratio", "tau_max_mpa", "a_over_lambda"];
        let columns: Vec<String> = s
            .models
            .draw
            .iter()
            .map(|&m| format!("p_over_estar_{}", m.key()))
            .collect();
        header.extend(columns.iter().map(String::as_str));
        let compare_column = compare_key(s).map(|k| format!("p_over_estar_{k}"));
        if let Some(c) = &compare_column {
            header.push(c);
        }
        header.push("wnl_extrapolated");
        let mut fe_points_header = vec![
            "aspect_ratio",
            "tau_max_mpa",
            "a_over_lambda",
            "p_over_estar",
            "p_over_estar_reaction",
            "stick_half_width_over_lambda",
            "stick_fraction",
        ];
        if with_estimates {
            fe_points_header.push("error_estimate");
        }
        let mut mse_header = vec![
            "aspect_ratio".to_string(),
            "tau_max_mpa".into(),
            "fe_points".into(),
        ];
        let keys = s.models.draw.iter().map(|m| m.key().to_string());
        for key in keys.chain(compare_key(s)) {
            mse_header.push(format!("mse_{key}"));
            mse_header.push(format!("max_abs_dev_{key}"));
        }
        mse_header.push("fe_status".into());
        Tables {
            lines: Table::new("", &header),
            fe_points: Table::new("fe_points", &fe_points_header),
            mse: Table::new(
                "mse",
                &mse_header.iter().map(String::as_str).collect::<Vec<_>>(),
            ),
            with_estimates,
        }
    }

    /// The panel's laws on the a/λ grid.
    fn push_lines(&mut self, s: &FeVsModelScene, laws: &PanelLaws, ar: f64, tau: f64) {
        for x in s.a_over_lambda.values() {
            let mut row: Vec<Cell> = vec![ar.into(), tau.into(), x.into()];
            row.extend(laws.laws.iter().map(|(_, l)| Cell::Num(l.p_over_estar(x))));
            if let Some(law) = &laws.compare {
                row.push(law.p_over_estar(x).into());
            }
            row.push(laws.extrapolated.into());
            self.lines.push(row);
        }
    }

    /// The panel's FE points, with their error estimates when the section asks for them.
    fn push_fe_points(
        &mut self,
        ar: f64,
        tau: f64,
        fe: &FeOutcome,
        estimate: Option<CaseEstimates>,
    ) {
        for (i, p) in fe.points.iter().enumerate() {
            let mut row: Vec<Cell> = vec![
                ar.into(),
                tau.into(),
                p.a_over_lambda.into(),
                p.p_over_estar.into(),
                p.p_over_estar_reaction.into(),
                p.stick_half_width_over_lambda.into(),
                p.stick_fraction.into(),
            ];
            if self.with_estimates {
                let e = estimate.and_then(|e| e.per_point).and_then(|e| e[i]);
                row.push(e.into());
            }
            self.fe_points.push(row);
        }
    }

    /// Each law's error against the panel's FE points; returns the panel notes of the WNL
    /// lines' mean squared errors.
    fn push_mse(
        &mut self,
        s: &FeVsModelScene,
        laws: &PanelLaws,
        ar: f64,
        tau: f64,
        fe: &FeOutcome,
    ) -> Vec<String> {
        let mut notes = vec![];
        let mut row: Vec<Cell> = vec![ar.into(), tau.into(), (fe.points.len() as f64).into()];
        for (name, law) in &laws.laws {
            let (m, d) = errors(law, fe);
            row.extend([m.into(), d.into()]);
            if *name == ModelKind::Wnl {
                notes.push(format!("MSE(WNL) = {}", sig_digits(m, 2)));
            }
        }
        if let Some(law) = &laws.compare {
            let (m, d) = errors(law, fe);
            row.extend([m.into(), d.into()]);
            notes.push(format!(
                "MSE(WNL, {}) = {}",
                s.models.compare_coefficients.map_or("", |c| c.name()),
                sig_digits(m, 2)
            ));
        }
        let status = match &fe.failure {
            None => "complete".to_string(),
            Some(f) => format!("incomplete: {f}"),
        };
        row.push(status.into());
        self.mse.push(row);
        notes
    }

    /// The tables written: the FE tables only when the scene has FE curves.
    fn into_vec(self, with_fe: bool) -> Vec<Table> {
        match with_fe {
            true => vec![self.lines, self.fe_points, self.mse],
            false => vec![self.lines],
        }
    }
}

/// The key of the WNL line with the comparison coefficient set, e.g. `wnl_ours_bracket_sq`.
fn compare_key(s: &FeVsModelScene) -> Option<String> {
    s.models
        .compare_coefficients
        .as_ref()
        .map(|c| format!("wnl_{}", c.name().replace('-', "_")))
}

/// One panel: the FE points (if any), the model lines, the comparison line.
fn figure_panel(
    s: &FeVsModelScene,
    laws: &PanelLaws,
    fe: Option<&FeOutcome>,
    ar: f64,
    tau: f64,
    mut notes: Vec<String>,
) -> Panel {
    let xs = s.a_over_lambda.values();
    let mut series: Vec<Series> = vec![];
    if let Some(fe) = fe {
        let pts = fe
            .points
            .iter()
            .map(|p| (p.a_over_lambda, p.p_over_estar))
            .collect();
        series.push(Series::markers(
            Some("FE (this project)".into()),
            palette::GREY,
            3,
            pts,
        ));
    }
    series.extend(laws.laws.iter().map(|(name, law)| {
        let pts = xs.iter().map(|&x| (x, law.p_over_estar(x))).collect();
        let (label, color) = match name {
            ModelKind::Westergaard => ("Westergaard".to_string(), palette::BLACK),
            ModelKind::Wnl => (
                format!("WNL ({}, {})", s.models.reading, s.models.coefficients),
                palette::VERMILION,
            ),
        };
        Series::line(Some(label), color, 2, pts)
    }));
    if let (Some(law), Some(name)) = (&laws.compare, &s.models.compare_coefficients) {
        let pts = xs.iter().map(|&x| (x, law.p_over_estar(x))).collect();
        series.push(Series::dashed(
            Some(format!("WNL ({}, {name})", s.models.reading)),
            palette::BLUE,
            2,
            pts,
        ));
    }
    if laws.extrapolated {
        notes.push("WNL extrapolated".into());
    }
    Panel::mean_pressure(
        format!("AR = {ar}, τ_max = {tau} MPa"),
        "a/λ",
        (xs[0], xs[xs.len() - 1]),
        series,
        notes,
    )
}
