//! The speed–accuracy figure: one panel per case, each tier's largest error against its wall
//! time per curve, on logarithmic axes.

use crate::accuracy::{self, Tier};
use crate::fe::Kinematics;
use crate::plot::{palette, LegendPosition, Panel, Series};
use crate::runner::scenes::speed_accuracy::tier_measurement::{CaseMeasurements, Measurement};
use plotters::style::RGBColor;

/// One panel per case: error against cost, each tier a marker, the finite-strain meshes joined,
/// the Pareto front dashed. Also returns, per case with tiers that have no curve, which.
pub(in crate::runner) fn figure_panels(
    tiers: &[Tier],
    cases: &[CaseMeasurements],
) -> (Vec<Panel>, Vec<String>) {
    let measured = cases.iter().flat_map(|c| &c.measurements);
    let with_errors: Vec<&Measurement> = measured.filter(|m| m.errors.is_some()).collect();
    let errors: Vec<f64> = with_errors.iter().map(|m| m.errors.unwrap().max).collect();
    let costs: Vec<f64> = with_errors.iter().map(|m| m.seconds_per_curve).collect();
    let ranges = (log_range(&errors), log_range(&costs));
    let families = Families::of(tiers);
    let mut panels = vec![];
    let mut failed_cases = vec![];
    for (k, c) in cases.iter().enumerate() {
        let failed: Vec<String> = (c.measurements.iter())
            .filter(|m| m.errors.is_none())
            .map(|m| m.tier.name())
            .collect();
        let (ar, tau) = (c.aspect_ratio, c.tau_max_mpa);
        if !failed.is_empty() {
            failed_cases.push(format!(
                "AR = {ar}, τ_max = {tau} MPa: {}",
                failed.join(", ")
            ));
        }
        panels.push(case_panel(c, k == 0, &families, ranges, &failed));
    }
    (panels, failed_cases)
}

/// The legend's names of the FE families, which list the meshes of the spec's tiers.
struct Families {
    /// The finite-strain meshes.
    finite: String,
    /// The Richardson pairs.
    richardson: String,
    /// The mesh-limit triples.
    limit: String,
}

impl Families {
    fn of(tiers: &[Tier]) -> Self {
        let finite_meshes: Vec<String> = tiers
            .iter()
            .filter_map(|t| match t {
                Tier::Fe {
                    kinematics: Kinematics::Finite,
                    elements_along_face,
                } => Some(elements_along_face.to_string()),
                _ => None,
            })
            .collect();
        let meshes_of = |t: &Tier| {
            let meshes: Vec<String> = t.fe_curves().iter().map(|c| c.1.to_string()).collect();
            meshes.join("+")
        };
        let richardson_pairs: Vec<String> = tiers
            .iter()
            .filter(|t| matches!(t, Tier::FeRichardson { .. }))
            .map(meshes_of)
            .collect();
        let limit_triples: Vec<String> = tiers
            .iter()
            .filter(|t| matches!(t, Tier::FeLimit { .. }))
            .map(meshes_of)
            .collect();
        Families {
            finite: format!("FE finite strain, mesh {}", finite_meshes.join(", ")),
            richardson: format!("FE Richardson, meshes {}", richardson_pairs.join(", ")),
            limit: format!("FE mesh limit, meshes {}", limit_triples.join(", ")),
        }
    }

    /// The legend name and colour of a tier's family.
    fn of_tier(&self, t: &Tier) -> (&str, RGBColor) {
        match t {
            Tier::Westergaard => ("Westergaard", palette::BLACK),
            Tier::Wnl(crate::models::CoefficientSet::PaperTable1) => {
                ("WNL, paper's Table 1", palette::ORANGE)
            }
            Tier::Wnl(_) => ("WNL, our refit", palette::GREEN),
            Tier::Fe {
                kinematics: Kinematics::Linear,
                ..
            } => ("FE linear", palette::PURPLE),
            Tier::Fe { .. } => (self.finite.as_str(), palette::BLUE),
            Tier::FeRichardson { .. } => (self.richardson.as_str(), palette::VERMILION),
            Tier::FeLimit { .. } => (self.limit.as_str(), palette::SKY),
        }
    }
}

/// The panel of one case on the shared `(x, y)` ranges; the first panel carries the legend.
/// `failed` names the tiers with no curve.
fn case_panel(
    c: &CaseMeasurements,
    first_panel: bool,
    families: &Families,
    (x_range, y_range): ((f64, f64), (f64, f64)),
    failed: &[String],
) -> Panel {
    let ms = &c.measurements;
    let front_points: Vec<(f64, f64)> = c
        .front
        .iter()
        .map(|&i| (ms[i].errors.unwrap().max, ms[i].seconds_per_curve))
        .collect();
    let mut series = vec![Series::dashed(
        first_panel.then(|| "Pareto front".into()),
        palette::GREY,
        1,
        front_points,
    )];
    let mut labels: Vec<&str> = vec![];
    for m in ms {
        let Some(e) = m.errors else { continue };
        let (label, color) = families.of_tier(&m.tier);
        let first = !labels.contains(&label);
        labels.push(label);
        series.push(Series::markers(
            (first_panel && first).then(|| label.to_string()),
            color,
            5,
            vec![(e.max, m.seconds_per_curve)],
        ));
    }
    let fe_path: Vec<(f64, f64)> = ms
        .iter()
        .filter(|m| m.tier.is_finite_fe())
        .filter_map(|m| Some((m.errors?.max, m.seconds_per_curve)))
        .collect();
    series.push(Series::line(None, palette::BLUE, 1, fe_path));
    let mut notes = vec![format!(
        "reference uncertain by ≤ {}",
        accuracy::measured::percent(c.reference_uncertainty)
    )];
    if !failed.is_empty() {
        notes.push(format!("no curve: {}", failed.join(", ")));
    }
    let (ar, tau) = (c.aspect_ratio, c.tau_max_mpa);
    Panel {
        title: format!("AR = {ar}, τ_max = {tau} MPa"),
        x_label: "largest relative error of p̄/E*".into(),
        y_label: "wall time per curve, s".into(),
        x_range,
        y_range,
        series,
        notes,
        log_scale: (true, true),
        legend: first_panel.then_some(LegendPosition::LowerLeft),
    }
}

/// Whole decades enclosing `values` (positive), for a logarithmic axis.
fn log_range(values: &[f64]) -> (f64, f64) {
    let (lo, hi) = values
        .iter()
        .filter(|v| **v > 0.0 && v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (0.1, 1.0);
    }
    (
        10f64.powf(lo.log10().floor()),
        10f64.powf(hi.log10().ceil().max(lo.log10().floor() + 1.0)),
    )
}
