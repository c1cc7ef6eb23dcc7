//! Paper Fig. 3: p̄/E* against a/λ, one panel per (AR, τ_max): model lines, and finite-element
//! points with the mean squared error of each model against them where the spec asks for FE.

use super::fe_cases::{self, FeCase, FeOutcome};
use super::scenes::{Scene, SceneContext, SceneResult};
use super::{model_laws, RunOptions};
use crate::models::{ModelKind, ModelLaw, PressureLaw};
use crate::plot::{palette, Figure, Panel, Series};
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
    let xs = s.a_over_lambda.values();
    let ars: Vec<f64> = s.aspect_ratios.iter().map(|v| v.get()).collect();
    let taus: Vec<f64> = s.tau_max_mpa.iter().map(|v| v.get()).collect();

    let all_cases = s.fe_cases(opts);
    let all_outcomes = fe_cases::solve_all(&all_cases, opts)?;
    // the section's own curves come first; the error estimates' coarser curves after them
    let n_main = s
        .fe
        .as_ref()
        .map_or(0, |fe| fe.tau_max_mpa.len() * ars.len());
    let (cases, outcomes) = (&all_cases[..n_main], &all_outcomes[..n_main]);
    // The error note of a panel starts where the committed speed–accuracy errors do (the
    // relative error estimate grows without bound as a/λ → 0).
    let mut error_note_from_a_over_lambda = 0.0;
    let estimates: Vec<Option<Vec<Option<f64>>>> = match &s.fe {
        Some(fe) if fe.error_estimate => {
            let measured = crate::accuracy::measured::committed()?;
            let order = measured.fe_order()?;
            error_note_from_a_over_lambda = measured
                .cases
                .iter()
                .map(|c| c.a_over_lambda.0)
                .fold(f64::INFINITY, f64::min);
            let coarse = fe_cases::coarser_cases(cases);
            coarse
                .iter()
                .zip(outcomes)
                .map(|(c, fine)| {
                    let (coarse_case, ratio) = c.as_ref()?;
                    let (_, coarse) = all_cases.iter().zip(&all_outcomes).find(|(k, _)| {
                        k.problem == coarse_case.problem && k.options == coarse_case.options
                    })?;
                    Some(crate::accuracy::error_estimates(
                        &fine.points,
                        &coarse.points,
                        *ratio,
                        order,
                    ))
                })
                .collect()
        }
        _ => vec![None; n_main],
    };
    let estimate_at = |ar: f64, tau: f64| -> Option<&Vec<Option<f64>>> {
        cases
            .iter()
            .zip(&estimates)
            .find(|(c, _)| c.problem.aspect_ratio == ar && c.tau_max_mpa == tau)
            .and_then(|(_, e)| e.as_ref())
    };
    let fe_at = |ar: f64, tau: f64| -> Option<&FeOutcome> {
        cases
            .iter()
            .zip(outcomes)
            .find(|(c, _)| c.problem.aspect_ratio == ar && c.tau_max_mpa == tau)
            .map(|(_, r)| r)
    };

    let mut header = vec!["aspect_ratio", "tau_max_mpa", "a_over_lambda"];
    let columns: Vec<String> = s
        .models
        .draw
        .iter()
        .map(|&m| format!("p_over_estar_{}", m.key()))
        .collect();
    header.extend(columns.iter().map(String::as_str));
    // the WNL line with the comparison coefficient set, e.g. `wnl_ours_bracket_sq`
    let compare_key = s
        .models
        .compare_coefficients
        .as_ref()
        .map(|c| format!("wnl_{}", c.name().replace('-', "_")));
    let compare_column = compare_key.as_ref().map(|k| format!("p_over_estar_{k}"));
    if let Some(c) = &compare_column {
        header.push(c);
    }
    header.push("wnl_extrapolated");
    let mut table = Table::new("", &header);
    let with_estimates = s.fe.as_ref().is_some_and(|fe| fe.error_estimate);
    let mut fe_points_header = vec![
        "aspect_ratio",
        "tau_max_mpa",
        "a_over_lambda",
        "p_over_estar",
        "p_over_estar_reaction",
    ];
    if with_estimates {
        fe_points_header.push("error_estimate");
    }
    let mut fe_points = Table::new("fe_points", &fe_points_header);
    let mut mse_header = vec![
        "aspect_ratio".to_string(),
        "tau_max_mpa".into(),
        "fe_points".into(),
    ];
    for &m in &s.models.draw {
        mse_header.push(format!("mse_{}", m.key()));
        mse_header.push(format!("max_abs_dev_{}", m.key()));
    }
    if let Some(key) = &compare_key {
        mse_header.push(format!("mse_{key}"));
        mse_header.push(format!("max_abs_dev_{key}"));
    }
    mse_header.push("fe_status".into());
    let mut mse = Table::new(
        "mse",
        &mse_header.iter().map(String::as_str).collect::<Vec<_>>(),
    );

    let mut panels = vec![];
    let mut extrapolated_panels = vec![];
    let mut notes = vec![];
    let mut incomplete = vec![];
    // Rows: τ_max; columns: AR.
    for &tau in &taus {
        for &ar in &ars {
            let laws = model_laws(&s.models, ar, tau);
            let compare = s
                .models
                .compare_coefficients
                .map(|c| ModelLaw::new(ModelKind::Wnl, ar, tau, s.models.reading, c));
            let extrapolated = laws.iter().any(|(_, l)| l.is_extrapolated());
            if extrapolated {
                extrapolated_panels.push(format!("AR = {ar}, τ_max = {tau} MPa"));
            }
            // a negative or non-finite model value is an error, never a drawn line
            let drawn = laws.iter().map(|(_, l)| l).chain(&compare);
            for law in drawn {
                for &x in &xs {
                    law.physical_p_over_estar(x).with_context(|| {
                        format!("panel AR = {ar}, τ_max = {tau} MPa, {}", law.describe())
                    })?;
                }
            }
            for &x in &xs {
                let mut row: Vec<Cell> = vec![ar.into(), tau.into(), x.into()];
                row.extend(laws.iter().map(|(_, l)| Cell::Num(l.p_over_estar(x))));
                if let Some(law) = &compare {
                    row.push(law.p_over_estar(x).into());
                }
                row.push(extrapolated.into());
                table.push(row);
            }
            let mut series: Vec<Series> = vec![];
            let mut panel_notes = vec![];
            let fe = fe_at(ar, tau);
            if let Some(fe) = fe {
                let estimates = estimate_at(ar, tau);
                for (i, p) in fe.points.iter().enumerate() {
                    let mut row: Vec<Cell> = vec![
                        ar.into(),
                        tau.into(),
                        p.a_over_lambda.into(),
                        p.p_over_estar.into(),
                        p.p_over_estar_reaction.into(),
                    ];
                    if with_estimates {
                        row.push(estimates.and_then(|e| e[i]).into());
                    }
                    fe_points.push(row);
                }
                if with_estimates {
                    // the largest estimate over the range the speed–accuracy errors are
                    // measured on (the relative error grows without bound as a/λ → 0)
                    let largest = estimates.and_then(|e| {
                        fe.points
                            .iter()
                            .zip(e)
                            .filter(|(p, _)| p.a_over_lambda >= error_note_from_a_over_lambda)
                            .filter_map(|(_, e)| *e)
                            .reduce(f64::max)
                    });
                    panel_notes.push(match largest {
                        Some(e) => format!(
                            "FE error ≤ {} (Richardson)",
                            crate::accuracy::measured::percent(e)
                        ),
                        None => "FE error: no estimate (coarser curve missing)".into(),
                    });
                }
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
                let mut row: Vec<Cell> =
                    vec![ar.into(), tau.into(), (fe.points.len() as f64).into()];
                for (name, law) in &laws {
                    let (m, d) = errors(law, fe);
                    row.push(m.into());
                    row.push(d.into());
                    if *name == ModelKind::Wnl {
                        panel_notes.push(format!("MSE(WNL) = {}", crate::numfmt::sig_digits(m, 2)));
                    }
                }
                if let Some(law) = &compare {
                    let (m, d) = errors(law, fe);
                    row.push(m.into());
                    row.push(d.into());
                    panel_notes.push(format!(
                        "MSE(WNL, {}) = {}",
                        s.models.compare_coefficients.map_or("", |c| c.name()),
                        crate::numfmt::sig_digits(m, 2)
                    ));
                }
                let status = match &fe.failure {
                    None => "complete".to_string(),
                    Some(f) => {
                        let reached = fe.points.last().map_or(0.0, |p| p.a_over_lambda);
                        panel_notes.push(format!("FE INCOMPLETE: stopped at a/λ = {reached:.3}"));
                        incomplete.push(format!(
                            "FE curve AR = {ar}, τ_max = {tau} MPa stopped at a/λ = {reached:.4}: {f}"
                        ));
                        format!("incomplete: {f}")
                    }
                };
                row.push(status.into());
                mse.push(row);
            }
            series.extend(laws.iter().map(|(name, law)| {
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
            if let (Some(law), Some(name)) = (&compare, &s.models.compare_coefficients) {
                let pts = xs.iter().map(|&x| (x, law.p_over_estar(x))).collect();
                series.push(Series::dashed(
                    Some(format!("WNL ({}, {name})", s.models.reading)),
                    palette::BLUE,
                    2,
                    pts,
                ));
            }
            if extrapolated {
                panel_notes.push("WNL extrapolated".into());
            }
            panels.push(Panel::mean_pressure(
                format!("AR = {ar}, τ_max = {tau} MPa"),
                "a/λ",
                (xs[0], xs[xs.len() - 1]),
                series,
                panel_notes,
            ));
        }
    }

    let mut footer = vec![format!(
        "WNL: reading `{}` of Eq. 4, coefficients `{}`; Westergaard: linear, frictionless half-space.",
        s.models.reading, s.models.coefficients
    )];
    if let (Some(fe), Some(case)) = (&s.fe, cases.first()) {
        let (nx, ny) = case.options.mesh.counts();
        footer.push(format!(
            "FE (ours): {:?} kinematics, neo-Hookean κ/G = {}, h/λ = {}, E* = {} MPa, mesh {nx}×{ny}; FE curves for τ_max ∈ {:?} MPa.",
            case.problem.kinematics,
            fe.kappa_over_g.get(),
            fe.thickness_over_lambda.get(),
            fe.estar_mpa.get(),
            fe.tau_max_mpa.iter().map(|t| t.get()).collect::<Vec<_>>()
        ));
    }
    if !incomplete.is_empty() {
        footer.push(format!(
            "INCOMPLETE FE curves ({}): each stops short of its target a/λ; see the panels and fe_status in the MSE table.",
            incomplete.len()
        ));
    }
    if !extrapolated_panels.is_empty() {
        let note = format!(
            "WNL evaluated outside its fit domain in: {}",
            extrapolated_panels.join("; ")
        );
        footer.push(note.clone());
        notes.push(note);
    }
    let figure = Figure {
        width: 420 * ars.len() as u32,
        height: 330 * taus.len() as u32 + 140,
        caption: title.into(),
        grid: (taus.len(), ars.len()),
        panels,
        footer,
        font_px: 16,
    };
    let mut tables = vec![table];
    if s.fe.is_some() {
        tables.push(fe_points);
        tables.push(mse);
    }
    Ok(SceneResult {
        tables,
        figure,
        notes,
        incomplete,
    })
}
