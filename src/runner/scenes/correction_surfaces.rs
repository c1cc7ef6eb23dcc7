//! Paper Fig. 2: the correction surfaces A(AR, τ_max) and B(AR, τ_max), as families of lines
//! a reader can read values off, with the finite-element aspect ratios emphasised.

use crate::models::wnl::{quadratic_surface, Correction};
use crate::models::{CoefficientSet, Coefficients};
use crate::plot::{padded_range, palette, LegendPosition, Panel, Series};
use crate::runner::scenes::scene_output::{Layout, Remarks};
use crate::runner::scenes::{Scene, SceneContext, SceneResult};
use crate::spec::{Bounded, Grid, NonNegative, Positive, SpecError, Validator};
use crate::table::Table;
use anyhow::Result;
use serde::Deserialize;

/// Paper Fig. 2: A and B over an (AR, τ_max) grid.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CorrectionSurfacesScene {
    /// Coefficient set, by name (default `paper-table1`).
    #[serde(default)]
    pub coefficients: CoefficientSet,
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

impl Scene for CorrectionSurfacesScene {
    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        run(ctx.title, self)
    }

    fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        v.grid(
            "correction_surfaces.aspect_ratio",
            &self.aspect_ratio,
            (0.0, f64::INFINITY),
            false,
        )?;
        v.grid(
            "correction_surfaces.tau_max_mpa",
            &self.tau_max_mpa,
            (0.0, f64::INFINITY),
            true,
        )?;
        v.non_empty(
            "correction_surfaces.line_aspect_ratios",
            self.line_aspect_ratios.len(),
        )?;
        v.non_empty(
            "correction_surfaces.line_tau_max_mpa",
            self.line_tau_max_mpa.len(),
        )
    }
}

fn run(title: &str, s: &CorrectionSurfacesScene) -> Result<SceneResult> {
    let c = s.coefficients.coefficients();
    let (table, any_extrapolated) = surfaces_table(s, &c);
    let mut panels = vec![];
    for correction in Correction::BOTH {
        panels.extend(correction_panels(s, correction, &c));
    }
    let d = c.domain;
    let mut remarks = Remarks::with_footer(vec![format!(
        "Coefficients: {}. Fit domain AR ∈ [{}, {}], τ_max ∈ [{}, {}] MPa; τ_max enters in MPa, as in the paper.",
        s.coefficients, d.aspect_ratio_min, d.aspect_ratio_max, d.tau_max_mpa_min, d.tau_max_mpa_max
    )]);
    if any_extrapolated {
        remarks.footer_and_note(
            "Part of the grid lies outside the fit domain: those values are extrapolations \
             (column `extrapolated` of the CSV)."
                .into(),
        );
    }
    let layout = Layout {
        grid: (2, 2),
        panel_px: (700, 550),
        margin_px: 0,
        font_px: 18,
    };
    Ok(remarks.finish(title, layout, panels, vec![table]))
}

/// A and B on the (AR, τ_max) grid; also whether any grid point lies outside the fit domain.
fn surfaces_table(s: &CorrectionSurfacesScene, c: &Coefficients) -> (Table, bool) {
    let mut table = Table::new(
        "",
        &[
            "aspect_ratio",
            "tau_max_mpa",
            "correction_a",
            "correction_b",
            "extrapolated",
        ],
    );
    let mut any_extrapolated = false;
    for ar in s.aspect_ratio.values() {
        for tau in s.tau_max_mpa.values() {
            let extrapolated = !c.domain.contains(ar, tau);
            any_extrapolated |= extrapolated;
            table.push(vec![
                ar.into(),
                tau.into(),
                quadratic_surface(Correction::A.of(c), ar, tau).into(),
                quadratic_surface(Correction::B.of(c), ar, tau).into(),
                extrapolated.into(),
            ]);
        }
    }
    (table, any_extrapolated)
}

/// One line per aspect ratio of `line_aspect_ratios` against τ_max: those of `marked` (the FE
/// aspect ratios) solid and thick, the others dashed.
fn against_tau(s: &CorrectionSurfacesScene, coeffs: &[f64; 6], marked: &[f64]) -> Vec<Series> {
    let taus = s.tau_max_mpa.values();
    let is_marked = |ar: f64| {
        marked
            .iter()
            .any(|m| (m - ar).abs() <= 1e-12 * m.abs().max(1.0))
    };
    let mut series = vec![];
    for (k, ar) in s.line_aspect_ratios.iter().map(|v| v.get()).enumerate() {
        let pts: Vec<(f64, f64)> = taus
            .iter()
            .map(|&t| (t, quadratic_surface(coeffs, ar, t)))
            .collect();
        let color = palette::CYCLE[k % palette::CYCLE.len()];
        let label = Some(format!(
            "AR = {ar}{}",
            if is_marked(ar) { " (FE)" } else { "" }
        ));
        series.push(if is_marked(ar) {
            Series::line(label, color, 3, pts)
        } else {
            Series::dashed(label, color, 1, pts)
        });
    }
    series
}

/// One line per shear strength of `line_tau_max_mpa` against the aspect ratio.
fn against_ar(s: &CorrectionSurfacesScene, coeffs: &[f64; 6]) -> Vec<Series> {
    let ars = s.aspect_ratio.values();
    let mut series = vec![];
    for (k, tau) in s.line_tau_max_mpa.iter().map(|v| v.get()).enumerate() {
        let pts: Vec<(f64, f64)> = ars
            .iter()
            .map(|&r| (r, quadratic_surface(coeffs, r, tau)))
            .collect();
        let color = palette::CYCLE[k % palette::CYCLE.len()];
        series.push(Series::line(
            Some(format!("τ_max = {tau} MPa")),
            color,
            2,
            pts,
        ));
    }
    series
}

/// The two panels of one correction: against τ_max, one line per aspect ratio (the FE ones
/// solid and thick); against AR, one line per τ_max with the FE aspect ratios as guides.
fn correction_panels(
    s: &CorrectionSurfacesScene,
    correction: Correction,
    c: &Coefficients,
) -> [Panel; 2] {
    let ars = s.aspect_ratio.values();
    let taus = s.tau_max_mpa.values();
    let marked: Vec<f64> = s.marked_aspect_ratios.iter().map(|v| v.get()).collect();
    let (name, coeffs) = (correction.name(), correction.of(c));
    let vs_tau = against_tau(s, coeffs, &marked);
    let mut vs_ar = against_ar(s, coeffs);
    let all = |series: &[Series]| {
        series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .collect::<Vec<_>>()
    };
    let y_tau = padded_range(all(&vs_tau));
    let y_ar = padded_range(all(&vs_ar));
    for (i, &m) in marked.iter().enumerate() {
        let label = (i == 0).then(|| "FE aspect ratios".to_string());
        vs_ar.push(Series::dashed(
            label,
            palette::GREY,
            1,
            vec![(m, y_ar.0), (m, y_ar.1)],
        ));
    }
    [
        Panel {
            title: format!("{name}(AR, τ_max) against τ_max"),
            x_label: "τ_max (MPa)".into(),
            y_label: name.into(),
            x_range: (taus[0], taus[taus.len() - 1]),
            y_range: y_tau,
            series: vs_tau,
            notes: vec![],
            log_scale: (false, false),
            legend: Some(LegendPosition::LowerLeft),
        },
        Panel {
            title: format!("{name}(AR, τ_max) against AR"),
            x_label: "AR = Δ/λ".into(),
            y_label: name.into(),
            x_range: (ars[0], ars[ars.len() - 1]),
            y_range: y_ar,
            series: vs_ar,
            notes: vec![],
            log_scale: (false, false),
            legend: Some(LegendPosition::LowerLeft),
        },
    ]
}
