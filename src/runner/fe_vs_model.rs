//! Paper Fig. 3: p̄/E* against a/λ, one panel per (AR, τ_max): model lines, and finite-element
//! points with the mean squared error of each model against them where the spec asks for FE.

use super::fe_cases::{FeCase, FeOutcome};
use super::{model_key, model_laws, padded_range, sweep, RunOptions};
use crate::models::{ModelLaw, PressureLaw};
use crate::plot::{palette, Figure, LegendPosition, Panel, Series};
use crate::spec::{FeVsModelScene, ModelName};
use crate::table::{Cell, Table};
use anyhow::Result;

/// The FE cases of a scene, in (τ_max, AR) order, with their panel coordinates.
fn fe_cases(s: &FeVsModelScene, opts: &RunOptions) -> Vec<FeCase> {
    let Some(fe) = &s.fe else { return vec![] };
    let mut cases = vec![];
    for tau in fe.tau_max_mpa.iter().map(|t| t.get()) {
        for ar in s.aspect_ratios.iter().map(|a| a.get()) {
            let mut case = FeCase::from_section(fe, ar, tau);
            if let Some(mesh) = opts.fe_mesh_override {
                case.options.mesh = mesh;
            }
            cases.push(case);
        }
    }
    cases
}

pub(super) fn compute_share(s: &FeVsModelScene, opts: &RunOptions) -> Result<(usize, usize)> {
    let r = sweep::run(&fe_cases(s, opts), &opts.sweep, FeCase::solve)?;
    Ok((r.computed, r.from_cache))
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

pub(super) fn run(
    title: &str,
    s: &FeVsModelScene,
    opts: &RunOptions,
) -> Result<(Vec<Table>, Figure, Vec<String>)> {
    let xs = s.a_over_lambda.values();
    let ars: Vec<f64> = s.aspect_ratios.iter().map(|v| v.get()).collect();
    let taus: Vec<f64> = s.tau_max_mpa.iter().map(|v| v.get()).collect();

    let cases = fe_cases(s, opts);
    let unsharded = RunOptions {
        sweep: sweep::SweepOptions {
            shard: None,
            ..opts.sweep.clone()
        },
        ..opts.clone()
    };
    let swept = sweep::run(&cases, &unsharded.sweep, FeCase::solve)?;
    let fe_at = |ar: f64, tau: f64| -> Option<&FeOutcome> {
        cases
            .iter()
            .zip(&swept.results)
            .find(|(c, _)| c.problem.aspect_ratio == ar && c.tau_max_mpa == tau)
            .and_then(|(_, r)| r.as_ref())
    };

    let mut header = vec!["aspect_ratio", "tau_max_mpa", "a_over_lambda"];
    let columns: Vec<String> = s
        .models
        .draw
        .iter()
        .map(|&m| format!("p_over_estar_{}", model_key(m)))
        .collect();
    header.extend(columns.iter().map(String::as_str));
    header.push("wnl_extrapolated");
    let mut table = Table::new("", &header);
    let mut fe_points = Table::new(
        "fe_points",
        &[
            "aspect_ratio",
            "tau_max_mpa",
            "a_over_lambda",
            "p_over_estar",
            "p_over_estar_reaction",
        ],
    );
    let mut mse_header = vec![
        "aspect_ratio".to_string(),
        "tau_max_mpa".into(),
        "fe_points".into(),
    ];
    for &m in &s.models.draw {
        mse_header.push(format!("mse_{}", model_key(m)));
        mse_header.push(format!("max_abs_dev_{}", model_key(m)));
    }
    mse_header.push("fe_status".into());
    let mut mse = Table::new(
        "mse",
        &mse_header.iter().map(String::as_str).collect::<Vec<_>>(),
    );

    let mut panels = vec![];
    let mut extrapolated_panels = vec![];
    let mut notes = vec![];
    // Rows: τ_max; columns: AR.
    for &tau in &taus {
        for &ar in &ars {
            let laws = model_laws(&s.models, ar, tau);
            let extrapolated = laws.iter().any(|(_, l)| l.is_extrapolated());
            if extrapolated {
                extrapolated_panels.push(format!("AR = {ar}, τ_max = {tau} MPa"));
            }
            for &x in &xs {
                let mut row: Vec<Cell> = vec![ar.into(), tau.into(), x.into()];
                row.extend(laws.iter().map(|(_, l)| Cell::Num(l.p_over_estar(x))));
                row.push(extrapolated.into());
                table.push(row);
            }
            let mut series: Vec<Series> = vec![];
            let mut panel_notes = vec![];
            let fe = fe_at(ar, tau);
            if let Some(fe) = fe {
                for p in &fe.points {
                    fe_points.push(vec![
                        ar.into(),
                        tau.into(),
                        p.a_over_lambda.into(),
                        p.p_over_estar.into(),
                        p.p_over_estar_reaction.into(),
                    ]);
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
                    if *name == ModelName::Wnl {
                        panel_notes.push(format!("MSE(WNL) = {}", crate::numfmt::sig_digits(m, 2)));
                    }
                }
                let status = match &fe.failure {
                    None => "complete".to_string(),
                    Some(f) => {
                        let reached = fe.points.last().map_or(0.0, |p| p.a_over_lambda);
                        panel_notes.push(format!("FE stopped at a/λ = {reached:.3}"));
                        notes.push(format!(
                            "FE curve AR = {ar}, τ_max = {tau} MPa stopped at a/λ = {reached:.4}: {f}"
                        ));
                        format!("stopped: {f}")
                    }
                };
                row.push(status.into());
                mse.push(row);
            }
            series.extend(laws.iter().map(|(name, law)| {
                let pts = xs.iter().map(|&x| (x, law.p_over_estar(x))).collect();
                let (label, color) = match name {
                    ModelName::Westergaard => ("Westergaard".to_string(), palette::BLACK),
                    ModelName::Wnl => (format!("WNL ({})", s.models.reading), palette::VERMILION),
                };
                Series::line(Some(label), color, 2, pts)
            }));
            let y = padded_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
            if extrapolated {
                panel_notes.push("WNL extrapolated".into());
            }
            panels.push(Panel {
                title: format!("AR = {ar}, τ_max = {tau} MPa"),
                x_label: "a/λ".into(),
                y_label: "p̄/E*".into(),
                x_range: (xs[0], xs[xs.len() - 1]),
                y_range: y,
                series,
                notes: panel_notes,
                legend: Some(LegendPosition::UpperLeft),
            });
        }
    }

    let mut footer = vec![format!(
        "WNL: reading `{}` of Eq. 4, coefficients `{}`; Westergaard: linear, frictionless half-space.",
        s.models.reading, s.models.coefficients
    )];
    if let (Some(fe), Some(case)) = (&s.fe, cases.first()) {
        let (nx, ny) = case.options.mesh.counts();
        footer.push(format!(
            "FE (ours): {:?} kinematics, neo-Hookean κ/G = {}, h/λ = {}, E* = {} MPa, mesh {nx}×{ny}; FE only for τ_max ∈ {:?} MPa.",
            case.problem.kinematics,
            fe.kappa_over_g.get(),
            fe.thickness_over_lambda.get(),
            fe.estar_mpa.get(),
            fe.tau_max_mpa.iter().map(|t| t.get()).collect::<Vec<_>>()
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
    Ok((tables, figure, notes))
}
