//! The hysteresis scene's figure: a p̄–a loop panel per aspect ratio, the dissipation against
//! τ_max/E*, the p̄–δ loops of the largest aspect ratio, the confinement loops, and the footer
//! that says what the loops are and how large the mesh error of W is.

use super::{
    branch_points, Confinement, Dissipation, HysteresisScene, LoopSeries, SolvedLoop, CLOSURE_RTOL,
};
use crate::fe::LoadDirection;
use crate::plot::{padded_range, palette, LegendPosition, Panel, Series};
use crate::runner::sweep::fe_cases::surface_label;
use anyhow::Result;
use plotters::style::RGBColor;

/// A loop as two series: loading solid (with `label`), unloading dashed.
fn loop_series(
    label: Option<String>,
    color: RGBColor,
    branches: [(LoadDirection, Vec<(f64, f64)>); 2],
) -> Vec<Series> {
    branches
        .into_iter()
        .map(|(dir, pts)| match dir {
            LoadDirection::Loading => Series::line(label.clone(), color, 2, pts),
            LoadDirection::Unloading => Series::dashed(None, color, 2, pts),
        })
        .collect()
}

/// The colour of a shear strength, the same in every panel.
fn color_of_tau(s: &HysteresisScene, tau: f64) -> RGBColor {
    let i =
        s.fe.tau_max_mpa
            .iter()
            .position(|t| t.get() == tau)
            .unwrap_or(0);
    palette::CYCLE[i % palette::CYCLE.len()]
}

/// A loop's dissipation in a legend.
fn work_label(d: &Option<Dissipation>) -> String {
    match d {
        None => "incomplete".to_string(),
        Some(d) if d.work.abs() <= CLOSURE_RTOL * d.loading_work => "W ≈ 0 (closes)".into(),
        Some(d) => format!(
            "W/W_load = {}",
            crate::accuracy::measured::percent(d.work / d.loading_work)
        ),
    }
}

/// The panels: a p̄–a loop panel per aspect ratio, the dissipation against τ_max/E*, the p̄–δ
/// loops of the largest aspect ratio, and the confinement loops.
pub(super) fn figure_panels(s: &HysteresisScene, results: &[SolvedLoop]) -> Vec<Panel> {
    let estar = s.fe.estar_mpa.get();
    let main: Vec<&SolvedLoop> = results
        .iter()
        .filter(|(l, _, _)| l.series == LoopSeries::AspectRatio)
        .collect();
    let at_ar = |ar: f64| {
        main.iter()
            .filter(move |(l, _, _)| l.case.problem.aspect_ratio == ar)
    };
    let mut panels = vec![];
    for ar in s.aspect_ratios.iter().map(|a| a.get()) {
        let mut series = vec![];
        for (l, o, d) in at_ar(ar) {
            let tau = l.case.tau_max_mpa;
            let label = format!("τ_max/E* = {}: {}", tau / estar, work_label(d));
            series.extend(loop_series(
                Some(label),
                color_of_tau(s, tau),
                branch_points(o, |p| p.a_over_lambda),
            ));
        }
        panels.push(loop_panel(format!("AR = {ar}: p̄–a loops"), "a/λ", series));
    }
    panels.push(dissipation_panel(s, &main));
    // the p̄–δ loops of the largest aspect ratio: their area is W
    let ar_max = s
        .aspect_ratios
        .iter()
        .map(|a| a.get())
        .fold(0.0_f64, f64::max);
    let mut series = vec![];
    // colours as in the p̄–a panels: no second legend
    for (l, o, _) in at_ar(ar_max) {
        series.extend(loop_series(
            None,
            color_of_tau(s, l.case.tau_max_mpa),
            branch_points(o, |p| p.slab_displacement_over_lambda),
        ));
    }
    panels.push(Panel {
        legend: None,
        ..loop_panel(
            format!("AR = {ar_max}: p̄–δ loops (area = W; colours as above)"),
            "δ/λ",
            series,
        )
    });
    if let Some(c) = &s.confinement {
        panels.push(confinement_panel(c, estar, results));
    }
    panels
}

/// The dissipation against τ_max/E*, one line per aspect ratio.
fn dissipation_panel(s: &HysteresisScene, main: &[&SolvedLoop]) -> Panel {
    let estar = s.fe.estar_mpa.get();
    let mut series = vec![];
    for (i, ar) in s.aspect_ratios.iter().map(|a| a.get()).enumerate() {
        let pts: Vec<(f64, f64)> = main
            .iter()
            .filter(|(l, _, _)| l.case.problem.aspect_ratio == ar)
            .filter_map(|(l, _, d)| Some((l.case.tau_max_mpa / estar, d.as_ref()?.work)))
            .collect();
        let color = palette::CYCLE[i % palette::CYCLE.len()];
        series.push(Series::line(
            Some(format!("AR = {ar}")),
            color,
            2,
            pts.clone(),
        ));
        series.push(Series::markers(None, color, 4, pts));
    }
    let x_max =
        s.fe.tau_max_mpa
            .iter()
            .fold(0.0_f64, |m, t| m.max(t.get() / estar));
    Panel {
        title: "Dissipated energy per cycle".into(),
        x_label: "τ_max/E*".into(),
        y_label: "W/(E* λ²)".into(),
        x_range: (0.0, x_max.max(f64::MIN_POSITIVE)),
        y_range: padded_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.1))),
        series,
        notes: vec![],
        log_scale: (false, false),
        legend: Some(LegendPosition::UpperRight),
    }
}

/// The confinement series: p̄–δ loops per layer thickness.
fn confinement_panel(c: &Confinement, estar_mpa: f64, results: &[SolvedLoop]) -> Panel {
    let mut series = vec![];
    let conf = results
        .iter()
        .filter(|(l, _, _)| l.series == LoopSeries::Confinement);
    for (i, (l, o, d)) in conf.enumerate() {
        series.extend(loop_series(
            Some(format!(
                "h/λ = {}: {}",
                l.case.problem.thickness_over_lambda,
                work_label(d)
            )),
            palette::CYCLE[i % palette::CYCLE.len()],
            branch_points(o, |p| p.slab_displacement_over_lambda),
        ));
    }
    loop_panel(
        format!(
            "Confinement: {}, τ_max/E* = {}, to p̄/E* = {}",
            surface_label(&c.surface()),
            c.tau_max_mpa.get() / estar_mpa,
            c.until_p_over_estar.get()
        ),
        "δ/λ",
        series,
    )
}

/// The footer: what the loops are, what W is, and the mesh error of W when estimated.
pub(super) fn footer(
    s: &HysteresisScene,
    results: &[SolvedLoop],
    order: Option<f64>,
) -> Result<Vec<String>> {
    let main: Vec<&SolvedLoop> = results
        .iter()
        .filter(|(l, _, _)| l.series == LoopSeries::AspectRatio)
        .collect();
    let case = &main
        .first()
        .map(|(l, _, _)| &l.case)
        .ok_or_else(|| anyhow::anyhow!("the scene has no loop"))?;
    let (nx, ny) = case.options.mesh.counts();
    let mut footer = vec![
        format!(
            "Solid: loading to a/λ = {}; dashed: unloading to zero load (slip history carried through). Finite strain, neo-Hookean κ/G = {}, h/λ = {} (but in the confinement panel), E* = {} MPa, μ = {}, mesh {nx}×{ny}.",
            s.fe.until_a_over_lambda.get(),
            s.fe.kappa_over_g.get(),
            s.fe.thickness_over_lambda.get(),
            s.fe.estar_mpa.get(),
            s.fe.friction_coefficient.get()
        ),
        format!(
            "W = ∮ p̄ dδ/(E* λ²), the energy dissipated per cycle, per wavelength and unit ridge length. Checked on every loop: frictionless loops close and no loop creates energy, within {CLOSURE_RTOL:e} of the loading work W_load."
        ),
    ];
    if let Some(order) = order {
        let largest = main
            .iter()
            .filter_map(|(_, _, d)| {
                let d = d.as_ref()?;
                Some((d.coarse?.1 - d.work).abs() / d.loading_work)
            })
            .fold(0.0_f64, f64::max);
        footer.push(format!(
            "Mesh error of W (Richardson from the next coarser mesh, order {order:.2}): at most {} of the loading work over the aspect-ratio loops; per loop in the dissipation table.",
            crate::accuracy::measured::percent(largest)
        ));
    }
    Ok(footer)
}

fn loop_panel(title: String, x_label: &str, series: Vec<Series>) -> Panel {
    let x = padded_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.0)));
    Panel {
        // the loops rise to the upper right: the lower right is free
        legend: Some(LegendPosition::LowerRight),
        ..Panel::mean_pressure(title, x_label, x, series, vec![])
    }
}
