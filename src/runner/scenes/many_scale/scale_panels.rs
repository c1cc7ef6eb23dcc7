//! The many-scale scene's tables and panels: per profile its FE curves, the models' curves and
//! their errors against the FE (with the FE's own error estimate); the errors against K.

use super::{ManyScaleScene, Model, ScaleCase};
use crate::accuracy::contact_fraction::{contact_fraction_at, ModelErrors};
use crate::fe::CurvePoint;
use crate::models::ModelKind;
use crate::plot::{padded_range, LegendPosition, Panel, Series};
use crate::profile::Weierstrass;
use crate::runner::scenes::profile_comparison::fe_series;
use crate::runner::scenes::scene_output::Remarks;
use crate::runner::sweep::fe_cases::SolvedCases;
use crate::table::{Cell, Table};
use anyhow::Result;
use plotters::style::RGBColor;

/// One model's errors against one FE curve.
#[derive(Debug, Clone)]
pub(super) struct ErrorRecord {
    weierstrass: Weierstrass,
    tau: f64,
    model: Model,
    errors: Option<ModelErrors>,
    /// The FE curve's own RMS relative error, estimated.
    fe_error: Option<f64>,
}

/// The scene's two tables as they fill, and its error records for the last panel.
pub(super) struct Tables {
    curves: Table,
    errors: Table,
    pub records: Vec<ErrorRecord>,
}

impl Tables {
    pub fn new() -> Self {
        Tables {
            curves: Table::new(
                "",
                &[
                    "profile",
                    "scales",
                    "tau_max_mpa",
                    "source",
                    "p_over_estar",
                    "contact_fraction",
                    "patches",
                ],
            ),
            errors: Table::new(
                "errors",
                &[
                    "profile",
                    "gamma",
                    "dimension",
                    "scales",
                    "tau_max_mpa",
                    "model",
                    "points",
                    "max_rel_error",
                    "rms_rel_error",
                    "max_abs_error",
                    "fe_rms_error_estimate",
                    "fe_error_over_model_error",
                ],
            ),
            records: vec![],
        }
    }

    pub fn into_vec(self) -> Vec<Table> {
        vec![self.curves, self.errors]
    }

    /// One row of the curves table.
    fn push_point(
        &mut self,
        case: &ScaleCase,
        tau: f64,
        source: &str,
        (p, c): (f64, f64),
        patches: Cell,
    ) {
        self.curves.push(vec![
            case.name().into(),
            Cell::Num(case.weierstrass.scales as f64),
            tau.into(),
            source.into(),
            p.into(),
            c.into(),
            patches,
        ]);
    }

    fn push_curve(&mut self, case: &ScaleCase, tau: f64, source: &str, points: &[(f64, f64)]) {
        for &point in points {
            self.push_point(case, tau, source, point, Cell::Empty);
        }
    }

    fn push_fe_curve(&mut self, case: &ScaleCase, tau: f64, points: &[CurvePoint]) {
        for p in points {
            let patches = Cell::Num(p.patches as f64);
            self.push_point(
                case,
                tau,
                "fe",
                (p.p_over_estar, p.contact_fraction),
                patches,
            );
        }
    }

    fn push_errors(&mut self, case: &ScaleCase, record: ErrorRecord) {
        let w = &case.weierstrass;
        let e = record.errors;
        let ratio = record.fe_error.zip(e).map(|(f, m)| f / m.rms_rel);
        self.errors.push(vec![
            case.name().into(),
            Cell::Num(w.gamma as f64),
            w.dimension.into(),
            Cell::Num(w.scales as f64),
            record.tau.into(),
            record.model.name().into(),
            Cell::Num(e.map_or(0, |e| e.points) as f64),
            e.map(|e| e.max_rel).into(),
            e.map(|e| e.rms_rel).into(),
            e.map(|e| e.max_abs).into(),
            record.fe_error.into(),
            ratio.into(),
        ]);
        self.records.push(record);
    }
}

/// The model's curve at the mean pressures `loads`, where it has an answer.
fn model_curve(
    s: &ManyScaleScene,
    model: Model,
    case: &ScaleCase,
    tau: f64,
    loads: &[f64],
) -> Result<Vec<(f64, f64)>> {
    let recursion = |kind| -> Result<Vec<(f64, f64)>> {
        let mut line = vec![];
        for &p in loads {
            if let Some(c) = s.recursion_fraction(kind, &case.profile, tau, p)? {
                line.push((p, c));
            }
        }
        Ok(line)
    };
    match model {
        Model::RecursionWestergaard => recursion(ModelKind::Westergaard),
        Model::RecursionWnl => recursion(ModelKind::Wnl),
        Model::BemLinear => {
            let fractions = ManyScaleScene::bem_fractions(&case.profile, loads)?;
            Ok(loads.iter().copied().zip(fractions).collect())
        }
    }
}

/// The errors of a model's curve against the FE curve read at the model's loads, where the FE
/// contact fraction is at least `error_from_contact_fraction`.
fn errors_against(
    s: &ManyScaleScene,
    line: &[(f64, f64)],
    fe: &[CurvePoint],
) -> Option<ModelErrors> {
    ModelErrors::of_pairs(line.iter().filter_map(|&(p, c)| {
        let f = contact_fraction_at(fe, p)?;
        (f >= s.error_from_contact_fraction).then_some((c, f))
    }))
}

/// The estimate of the FE curve's RMS relative error from the same case on its
/// error-estimate mesh ([`crate::runner::scenes::profile_comparison::ComparisonSettings::fe_error_estimate`]).
fn fe_error_estimate(
    s: &ManyScaleScene,
    case: &ScaleCase,
    tau: f64,
    solved: &SolvedCases,
) -> Option<f64> {
    let fine = solved.outcome(&s.fe_case(case, tau, false))?;
    let coarse = solved.outcome(&s.fe_case(case, tau, true))?;
    s.settings()
        .fe_error_estimate(fine, coarse, case.profile.max_order())
}

/// The panel of one profile: its FE curve at each τ_max and each model's curve (a frictionless
/// model's once, with the frictionless FE); their points go into the curves table and their
/// errors against the FE into the errors table.
pub(super) fn profile_panel(
    s: &ManyScaleScene,
    case: &ScaleCase,
    solved: &SolvedCases,
    tables: &mut Tables,
    remarks: &mut Remarks,
) -> Result<Panel> {
    let name = case.name();
    let mut series = vec![];
    for (t, tau) in s.tau_max_mpa.iter().map(|t| t.get()).enumerate() {
        let fe = solved
            .outcome(&s.fe_case(case, tau, false))
            .expect("solved");
        remarks.stopped_curve(&format!("{name}, τ_max = {tau} MPa"), fe);
        tables.push_fe_curve(case, tau, &fe.points);
        series.push(fe_series(t, tau, &fe.points));
        let p_max = fe.points.last().map_or(0.0, |p| p.p_over_estar);
        let loads = s.settings().model_loads(p_max);
        let fe_error = fe_error_estimate(s, case, tau, solved);
        for model in Model::ALL
            .into_iter()
            .filter(|m| t == 0 || !m.frictionless())
        {
            let line = model_curve(s, model, case, tau, &loads)?;
            tables.push_curve(case, tau, model.name(), &line);
            let record = ErrorRecord {
                weierstrass: case.weierstrass,
                tau,
                model,
                errors: errors_against(s, &line, &fe.points),
                fe_error,
            };
            tables.push_errors(case, record);
            let label = match model.frictionless() {
                true => model.name().to_string(),
                false => format!("{}, τ_max = {tau} MPa", model.name()),
            };
            series.push(match model {
                Model::BemLinear => Series::markers(Some(label), model.color(), 3, line),
                _ => Series::dashed(Some(label), model.color(), 1 + t as u32, line),
            });
        }
    }
    let x_range = padded_range(series.iter().flat_map(|l| l.points.iter().map(|p| p.0)));
    Ok(Panel {
        title: format!("K = {}: {name}", case.weierstrass.scales),
        x_label: "p̄/E*".into(),
        y_label: "contact fraction".into(),
        x_range: (0.0, x_range.1),
        y_range: (0.0, (1.2 * s.until_contact_fraction).min(1.0)),
        series,
        notes: vec![],
        legend: Some(LegendPosition::UpperLeft),
        log_scale: (false, false),
    })
}

/// Whether `w` belongs to `family`: its parameters, or K = 1 of the same AR₀ (shared).
fn in_family(w: &Weierstrass, family: &super::Family) -> bool {
    w.aspect_ratio_0 == family.ar0
        && (w.scales == 1 || (w.gamma == family.gamma && w.dimension == family.dimension))
}

/// How family `i`'s lines are drawn: solid, dashed, then thin solid and thin dashed.
fn family_line(
    i: usize,
    label: Option<String>,
    color: RGBColor,
    points: Vec<(f64, f64)>,
) -> Series {
    let width = if i < 2 { 2 } else { 1 };
    match i % 2 {
        0 => Series::line(label, color, width, points),
        _ => Series::dashed(label, color, width, points),
    }
}

/// RMS relative error (%) against K, frictionless: each model against the FE and the FE's own
/// error estimate, a line per family (styled by [`family_line`]; the legend names the models by
/// the first family's lines, the families by their FE lines). The frictional rows are in the
/// errors table.
pub(super) fn error_panel(s: &ManyScaleScene, records: &[ErrorRecord]) -> Panel {
    let tau = s.tau_max_mpa[0].get();
    let mut series = vec![];
    for (i, family) in s.families.iter().enumerate() {
        let of = |pick: &dyn Fn(&ErrorRecord) -> Option<f64>, model: Model| {
            let mut line: Vec<(f64, f64)> = records
                .iter()
                .filter(|r| r.tau == tau && r.model == model && in_family(&r.weierstrass, family))
                .filter_map(|r| Some((r.weierstrass.scales as f64, 100.0 * pick(r)?)))
                .collect();
            line.sort_by(|a, b| a.0.total_cmp(&b.0));
            line
        };
        let label = |name: &str| (i == 0).then(|| name.to_string());
        for model in Model::ALL {
            let points = of(&|r| r.errors.map(|e| e.rms_rel), model);
            series.push(family_line(i, label(model.name()), model.color(), points));
        }
        let fe = of(&|r| r.fe_error, Model::RecursionWestergaard);
        let name = format!(
            "FE error estimate, AR₀ {}, γ {}, D {}",
            family.ar0, family.gamma, family.dimension
        );
        series.push(family_line(i, Some(name), RGBColor(0, 0, 0), fe));
    }
    let k_max = s.families.iter().map(|f| f.scales).max().unwrap_or(1) as f64;
    let y_max = padded_range(series.iter().flat_map(|l| l.points.iter().map(|p| p.1))).1;
    Panel {
        title: format!("RMS relative error against the FE, τ_max = {tau} MPa"),
        x_label: "scales K".into(),
        y_label: "RMS error of the contact fraction, %".into(),
        x_range: (0.8, k_max + 0.2),
        y_range: (0.0, 1.6 * y_max),
        series,
        notes: vec![],
        legend: Some(LegendPosition::UpperLeft),
        log_scale: (false, false),
    }
}
