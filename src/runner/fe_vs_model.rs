//! Paper Fig. 3: p̄/E* against a/λ, one panel per (AR, τ_max), model lines (and finite-element
//! points where the spec asks for them).

use super::{model_key, model_laws, padded_range};
use crate::models::PressureLaw;
use crate::plot::{palette, Figure, LegendPosition, Panel, Series};
use crate::spec::{FeVsModelScene, ModelName};
use crate::table::{Cell, Table};
use anyhow::Result;

pub(super) fn run(title: &str, s: &FeVsModelScene) -> Result<(Vec<Table>, Figure, Vec<String>)> {
    let xs = s.a_over_lambda.values();
    let ars: Vec<f64> = s.aspect_ratios.iter().map(|v| v.get()).collect();
    let taus: Vec<f64> = s.tau_max_mpa.iter().map(|v| v.get()).collect();

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

    let mut panels = vec![];
    let mut extrapolated_panels = vec![];
    // Rows: τ_max; columns: AR (the paper's panels vary AR across and τ_max down).
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
            let series: Vec<Series> = laws
                .iter()
                .map(|(name, law)| {
                    let pts = xs.iter().map(|&x| (x, law.p_over_estar(x))).collect();
                    let (label, color) = match name {
                        ModelName::Westergaard => ("Westergaard".to_string(), palette::BLACK),
                        ModelName::Wnl => {
                            (format!("WNL ({})", s.models.reading), palette::VERMILION)
                        }
                    };
                    Series::line(Some(label), color, 2, pts)
                })
                .collect();
            let y = padded_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
            let mut notes = vec![];
            if extrapolated {
                notes.push("WNL extrapolated".into());
            }
            panels.push(Panel {
                title: format!("AR = {ar}, τ_max = {tau} MPa"),
                x_label: "a/λ".into(),
                y_label: "p̄/E*".into(),
                x_range: (xs[0], xs[xs.len() - 1]),
                y_range: y,
                series,
                notes,
                legend: Some(LegendPosition::UpperLeft),
            });
        }
    }

    let mut footer = vec![format!(
        "WNL: reading `{}` of Eq. 4, coefficients `{}`; Westergaard: linear, frictionless half-space.",
        s.models.reading, s.models.coefficients
    )];
    let mut notes = vec![];
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
        height: 330 * taus.len() as u32 + 120,
        caption: title.into(),
        grid: (taus.len(), ars.len()),
        panels,
        footer,
        font_px: 16,
    };
    Ok((vec![table], figure, notes))
}
