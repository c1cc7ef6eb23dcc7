//! Paper Fig. 5 (docs/replication.md R8): total contact area of a fingertip against normal load, ridges as a
//! sinusoid of wavelength λ and amplitude Δ.
//!
//! The nominal contact is a disc of area A_exp, radius R = √(A_exp/π); N = 2R/λ ridges cross
//! it (not rounded: an effective count). A load F gives the mean pressure p̄ = F/(πR²) (R8),
//! the model gives the half-width a from p̄/E*, and the area is A_total = 2a·N·2R. Above the
//! model's full-contact pressure every ridge is in full contact, a = λ/2: the scene records
//! that state as `full`, it does not clamp the inverse.

use super::scenes::{Scene, SceneContext, SceneResult};
use super::{measured, model_laws};
use crate::models::{a_over_lambda_at, InverseError, ModelKind, PressureLaw};
use crate::plot::{padded_range, palette, Figure, LegendPosition, Panel, Series};
use crate::spec::{
    Bounded, Grid, Location, ModelSelection, NonNegative, Positive, SpecError, Validator,
};
use crate::table::{Cell, Table};
use anyhow::Result;
use serde::Deserialize;
use std::f64::consts::PI;
use std::path::Path;

/// Paper Fig. 5 (R8): fingerprint ridges as a sinusoid, total contact area against load.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FingertipAreaScene {
    /// Ridge wavelength λ, mm.
    pub wavelength_mm: Bounded<Positive>,
    /// Ridge amplitude Δ, mm.
    pub amplitude_mm: Bounded<Positive>,
    /// Nominal (apparent) circular contact area A_exp, mm²; R = √(A_exp/π).
    pub nominal_area_mm2: Bounded<Positive>,
    /// Plane-strain modulus of the central line, MPa.
    pub estar_mpa: Bounded<Positive>,
    /// Plane-strain modulus range [low, high] drawn as a band, MPa.
    pub estar_band_mpa: [Bounded<Positive>; 2],
    /// Interfacial shear strength τ_max, MPa.
    pub tau_max_mpa: Bounded<NonNegative>,
    /// Normal load grid, N.
    pub load_n: Grid,
    pub models: ModelSelection,
    /// Measured points, relative to the spec's folder (schema: `experiments/data/README.md`).
    /// A missing file is reported in the figure and the run's output, never replaced.
    pub measured_data: Option<String>,
}

impl Scene for FingertipAreaScene {
    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        run(ctx.title, self, ctx.spec_dir)
    }

    fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        v.grid(
            "fingertip_area.load_n",
            &self.load_n,
            (0.0, f64::INFINITY),
            true,
        )?;
        v.models("fingertip_area.models", &self.models)?;
        let [lo, hi] = self.estar_band_mpa.map(Bounded::get);
        let e = self.estar_mpa.get();
        if !(lo < e && e < hi) {
            return Err(SpecError::Invalid {
                origin: v.origin.into(),
                field: "fingertip_area.estar_band_mpa".into(),
                location: Location(None),
                value: format!("[{lo}, {hi}]"),
                allowed: format!("[low, high] with low < estar_mpa = {e} < high"),
            });
        }
        let ar = self.amplitude_mm.get() / self.wavelength_mm.get();
        if ar >= 0.5 {
            return Err(SpecError::Invalid {
                origin: v.origin.into(),
                field: "fingertip_area.amplitude_mm".into(),
                location: Location(None),
                value: self.amplitude_mm.get().to_string(),
                allowed: format!("< wavelength_mm / 2 = {}", self.wavelength_mm.get() / 2.0),
            });
        }
        Ok(())
    }
}

/// Outcome of one load on one model.
enum Area {
    Partial { a_over_lambda: f64, area_mm2: f64 },
    Full { area_mm2: f64 },
    Undefined(InverseError),
}

fn run(title: &str, s: &FingertipAreaScene, spec_dir: &Path) -> Result<SceneResult> {
    let lambda_mm = s.wavelength_mm.get();
    let ar = s.amplitude_mm.get() / lambda_mm;
    let radius_mm = (s.nominal_area_mm2.get() / PI).sqrt();
    let ridges = 2.0 * radius_mm / lambda_mm;
    let full_area_mm2 = lambda_mm * ridges * 2.0 * radius_mm;
    let tau = s.tau_max_mpa.get();
    let loads = s.load_n.values();
    let [e_lo, e_hi] = s.estar_band_mpa.map(|v| v.get());
    let e_mid = s.estar_mpa.get();

    let laws = model_laws(&s.models, ar, tau);
    let area_at = |law: &dyn PressureLaw, estar_mpa: f64, load_n: f64| -> (f64, Area) {
        let p_over_estar = load_n / (PI * radius_mm * radius_mm) / estar_mpa;
        let area = match a_over_lambda_at(law, p_over_estar) {
            Ok(x) => Area::Partial {
                a_over_lambda: x,
                area_mm2: 2.0 * x * lambda_mm * ridges * 2.0 * radius_mm,
            },
            Err(InverseError::AboveFullContact { .. }) => Area::Full {
                area_mm2: full_area_mm2,
            },
            Err(e) => Area::Undefined(e),
        };
        (p_over_estar, area)
    };

    let mut table = Table::new(
        "",
        &[
            "model",
            "estar_mpa",
            "load_n",
            "p_over_estar",
            "a_over_lambda",
            "area_mm2",
            "state",
            "extrapolated",
        ],
    );
    let mut series = vec![];
    let mut notes = vec![];
    for (name, law) in &laws {
        let (label, color) = match name {
            ModelKind::Westergaard => ("Westergaard".to_string(), palette::BLACK),
            ModelKind::Wnl => (format!("WNL ({})", s.models.reading), palette::VERMILION),
        };
        let extrapolated = law.is_extrapolated();
        let mut curves = vec![];
        for estar in [e_lo, e_mid, e_hi] {
            let mut pts = vec![];
            for &f in &loads {
                let (p, area) = area_at(law, estar, f);
                let (x, a, state): (Cell, Cell, String) = match &area {
                    Area::Partial {
                        a_over_lambda,
                        area_mm2,
                    } => {
                        pts.push((f, *area_mm2));
                        (
                            (*a_over_lambda).into(),
                            (*area_mm2).into(),
                            "partial".into(),
                        )
                    }
                    Area::Full { area_mm2 } => {
                        pts.push((f, *area_mm2));
                        (0.5.into(), (*area_mm2).into(), "full".into())
                    }
                    Area::Undefined(e) => {
                        let note =
                            format!("{label}, E* = {estar} MPa, F = {f} N: no contact area: {e}");
                        if !notes.contains(&note) && notes.len() < 20 {
                            notes.push(note);
                        }
                        (Cell::Empty, Cell::Empty, "undefined".into())
                    }
                };
                table.push(vec![
                    name.key().into(),
                    estar.into(),
                    f.into(),
                    p.into(),
                    x,
                    a,
                    state.into(),
                    extrapolated.into(),
                ]);
            }
            curves.push(pts);
        }
        let suffix = if extrapolated { ", extrapolated" } else { "" };
        // Lower modulus → more area: the range runs between the E*-high and E*-low curves.
        // WNL's range is shaded; Westergaard's is drawn as two dashed edges so both stay visible.
        let range_label = Some(format!("{label}, E* ∈ [{e_lo}, {e_hi}] MPa"));
        match name {
            ModelKind::Wnl => series.push(Series::band(
                range_label,
                color,
                curves[2].clone(),
                curves[0].clone(),
            )),
            ModelKind::Westergaard => {
                series.push(Series::dashed(range_label, color, 1, curves[0].clone()));
                series.push(Series::dashed(None, color, 1, curves[2].clone()));
            }
        }
        series.push(Series::line(
            Some(format!("{label}, E* = {e_mid} MPa{suffix}")),
            color,
            3,
            curves[1].clone(),
        ));
    }
    series.push(Series::dashed(
        Some(format!("full contact, {full_area_mm2:.0} mm²")),
        palette::GREY,
        1,
        vec![
            (loads[0], full_area_mm2),
            (loads[loads.len() - 1], full_area_mm2),
        ],
    ));

    let mut footer = vec![
        format!(
            "Ridges λ = {lambda_mm} mm, Δ = {} mm (AR = {ar:.3}); A_exp = {} mm², R = {radius_mm:.3} mm, N = 2R/λ = {ridges:.2}.",
            s.amplitude_mm.get(),
            s.nominal_area_mm2.get()
        ),
        format!("Mean pressure p̄ = F/(πR²); area 2a·N·2R; τ_max = {tau} MPa enters the WNL polynomials in MPa."),
    ];
    if laws.iter().any(|(_, l)| l.is_extrapolated()) {
        let note = format!(
            "WNL is evaluated outside its fit domain (AR = {ar:.3}): an extrapolation, as in the paper."
        );
        footer.push(note.clone());
        notes.push(note);
    }
    match &s.measured_data {
        Some(rel) => {
            let path = spec_dir.join(rel);
            let data = measured::read(&path).map_err(|e| SpecError::Data {
                origin: path.display().to_string(),
                message: format!("{e:#}"),
            })?;
            match data {
                Some(m) => {
                    let who = m.provenance("digitised_by").unwrap_or_default();
                    series.push(Series::markers(
                        Some(format!(
                            "measured ({}, digitised by {who})",
                            m.provenance("source_figure").unwrap_or_default()
                        )),
                        palette::BLACK,
                        5,
                        m.points.clone(),
                    ));
                    footer.push(format!(
                        "Measured: {} ({}); digitised by {who}, {}.",
                        m.provenance("source").unwrap_or_default(),
                        m.provenance("source_figure").unwrap_or_default(),
                        m.provenance("method").unwrap_or_default()
                    ));
                }
                None => {
                    let note = format!(
                        "Measured points of Warman & Ennos (2009) NOT SHOWN: no data file {rel} beside the spec (schema: experiments/data/README.md)."
                    );
                    footer.push(note.clone());
                    footer.push(
                        "No digitised copy is available to us; the points are never invented or simulated."
                            .into(),
                    );
                    notes.push(note);
                }
            }
        }
        None => {
            let note = "No measured data file is named in the spec: model lines only.".to_string();
            footer.push(note.clone());
            notes.push(note);
        }
    }

    let y = padded_range(
        series
            .iter()
            .flat_map(|s| s.points.iter().chain(&s.upper).map(|p| p.1)),
    );
    let panel = Panel {
        title: "Total contact area against normal load".into(),
        x_label: "normal load F (N)".into(),
        y_label: "contact area (mm²)".into(),
        x_range: (loads[0], loads[loads.len() - 1]),
        y_range: (0.0, y.1),
        series,
        notes: vec![],
        log_scale: (false, false),
        legend: Some(LegendPosition::LowerRight),
    };
    let figure = Figure {
        width: 1100,
        height: 820,
        caption: title.into(),
        grid: (1, 1),
        panels: vec![panel],
        footer,
        font_px: 18,
    };
    Ok(SceneResult {
        tables: vec![table],
        figure,
        notes,
        incomplete: vec![],
    })
}
