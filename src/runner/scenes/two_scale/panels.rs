//! The two-scale scene's panels and tables: per profile its FE curves, the models' curves and
//! their errors against the FE (with the FE's own error estimate), and the contact maps.

use super::{Model, TwoScaleScene};
use crate::accuracy::contact_fraction::ModelErrors;
use crate::numfmt::sig_digits;
use crate::plot::{padded_range, LegendPosition, Panel, Series};
use crate::profile::Profile;
use crate::runner::scenes::profile_comparison::fe_series;
use crate::runner::scenes::scene_output::Remarks;
use crate::runner::sweep::fe_cases::{FeCase, FeOutcome, SolvedCases};
use crate::table::{Cell, Table};
use anyhow::Result;
use plotters::style::RGBColor;

/// The panel of profile `i`: its FE curve at each τ_max and each model's curve, whose points go
/// into the curves table and whose errors against the FE into the errors table.
pub(super) fn profile_panel(
    s: &TwoScaleScene,
    i: usize,
    cases: &[FeCase],
    solved: &SolvedCases,
    (curves, errors): (&mut Table, &mut Table),
    remarks: &mut Remarks,
) -> Result<Panel> {
    let profile = s.profile(i);
    let name = profile.to_string();
    let mut series = vec![];
    for (t, tau) in s.tau_max_mpa.iter().map(|t| t.get()).enumerate() {
        let case = &cases[t * s.profiles.len() + i];
        let fe = solved.outcome(case).expect("solved");
        remarks.stopped_curve(&format!("{name}, τ_max = {tau} MPa"), fe);
        let fe_error = fe_error_estimate(s, i, case, solved);
        for p in &fe.points {
            curves.push(vec![
                name.clone().into(),
                tau.into(),
                "fe".into(),
                p.p_over_estar.into(),
                p.contact_fraction.into(),
                Cell::Num(p.patches as f64),
            ]);
        }
        series.push(fe_series(t, tau, &fe.points));
        let p_max = fe.points.last().map_or(0.0, |p| p.p_over_estar);
        for model in Model::ALL {
            let drawn = !model.frictionless() || t == 0;
            let mut line = vec![];
            for p in s.settings().model_loads(p_max) {
                if let Some(c) = s.model_fraction(model, &profile, tau, p)? {
                    line.push((p, c));
                    curves.push(vec![
                        name.clone().into(),
                        tau.into(),
                        model.name().into(),
                        p.into(),
                        c.into(),
                        Cell::Empty,
                    ]);
                }
            }
            if drawn {
                let label = if model.frictionless() {
                    model.name().to_string()
                } else {
                    format!("{}, τ_max = {tau} MPa", model.name())
                };
                series.push(Series::dashed(
                    Some(label),
                    model.color(),
                    1 + t as u32,
                    line,
                ));
            }
            let mut row = error_row(s, &name, tau, model, &profile, fe)?;
            let model_error = match row[5] {
                Cell::Num(e) => Some(e),
                _ => None,
            };
            row.push(fe_error.into());
            row.push(fe_error.zip(model_error).map(|(f, m)| f / m).into());
            errors.push(row);
        }
    }
    let x_range = padded_range(series.iter().flat_map(|l| l.points.iter().map(|p| p.0)));
    Ok(Panel {
        title: format!("profile {name}"),
        x_label: "p̄/E*".into(),
        y_label: "contact fraction".into(),
        x_range: (0.0, x_range.1),
        y_range: (0.0, 1.0),
        series,
        notes: vec![],
        legend: Some(LegendPosition::LowerRight),
        log_scale: (false, false),
    })
}

/// The estimate of the FE curve's relative error from the same case on `error_estimate_mesh`
/// ([`crate::runner::scenes::profile_comparison::ComparisonSettings::fe_error_estimate`]).
fn fe_error_estimate(
    s: &TwoScaleScene,
    i: usize,
    case: &FeCase,
    solved: &SolvedCases,
) -> Option<f64> {
    let fine = solved.outcome(case)?;
    let coarse = solved.outcome(&s.coarse_case(i, case))?;
    s.settings()
        .fe_error_estimate(fine, coarse, s.profile(i).max_order())
}

/// The errors of `model` against the FE curve at its points with a contact fraction of at
/// least `error_from_contact_fraction` (where the model has an answer).
fn error_row(
    s: &TwoScaleScene,
    name: &str,
    tau: f64,
    model: Model,
    profile: &Profile,
    fe: &FeOutcome,
) -> Result<Vec<Cell>> {
    let e = ModelErrors::against(&fe.points, s.error_from_contact_fraction, |p| {
        s.model_fraction(model, profile, tau, p)
    })?;
    Ok(vec![
        name.into(),
        tau.into(),
        model.name().into(),
        Cell::Num(e.map_or(0, |e| e.points) as f64),
        e.map(|e| e.max_rel).into(),
        e.map(|e| e.rms_rel).into(),
        e.map(|e| e.max_abs).into(),
    ])
}

/// Where the contact patches lie (x/λ in the half wavelength) against p̄/E*: one segment per
/// patch per load event.
pub(super) fn contact_map(name: &str, fe: &FeOutcome) -> Panel {
    let mut series = vec![];
    let p_max = fe.points.last().map_or(1.0, |p| p.p_over_estar);
    for (p, patches) in fe.points.iter().zip(&fe.patch_edges) {
        for e in patches {
            series.push(Series::line(
                None,
                RGBColor(0, 0, 0),
                2,
                vec![(e[0], p.p_over_estar), (e[1], p.p_over_estar)],
            ));
        }
    }
    let most = fe.points.iter().map(|p| p.patches).max().unwrap_or(0);
    Panel {
        title: format!("contact patches, {name}, frictionless"),
        x_label: "x/λ".into(),
        y_label: "p̄/E*".into(),
        x_range: (0.0, 0.5),
        y_range: (0.0, p_max * 1.02),
        series,
        notes: vec![format!(
            "up to {most} patches; p̄/E* up to {}",
            sig_digits(p_max, 3)
        )],
        legend: None,
        log_scale: (false, false),
    }
}
