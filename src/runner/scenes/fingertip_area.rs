//! Paper Fig. 5 (docs/replication.md R8): total contact area of a fingertip against normal load, ridges as a
//! sinusoid of wavelength λ and amplitude Δ.
//!
//! The nominal contact is a disc of area A_exp, radius R = √(A_exp/π); N = 2R/λ ridges cross
//! it (not rounded: an effective count). A load F gives the mean pressure p̄ = F/(πR²) (R8),
//! the model gives the half-width a from p̄/E*, and the area is A_total = 2a·N·2R. Above the
//! model's full-contact pressure every ridge is in full contact, a = λ/2: the scene records
//! that state as `full`, it does not clamp the inverse.

use crate::accuracy::measured::percent;
use crate::models::{a_over_lambda_at, InverseError, ModelKind, ModelLaw, PressureLaw};
use crate::numfmt::sig_digits;
use crate::plot::{padded_range, palette, LegendPosition, Panel, Series};
use crate::runner::measured_points;
use crate::runner::scenes::fe_inverse::{fe_a_over_lambda_at, FeInverse};
use crate::runner::scenes::fingertip_ridges::{ridge_aspect_ratio, FingertipFe};
use crate::runner::scenes::scene_output::{Layout, Remarks};
use crate::runner::scenes::wnl_beyond_fit::{fit_estar_mpa, outside_fit};
use crate::runner::scenes::{Scene, SceneContext, SceneResult};
use crate::runner::sweep::fe_cases::{self, FeCase, FeOutcome};
use crate::runner::{model_laws, RunOptions};
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
    /// E*_fit: the modulus of the FE sweep the WNL polynomials were fitted at, MPa (R9; default
    /// `crate::defaults::fe_estar_mpa`): the figure states τ_max/E* against the fitted range.
    #[serde(default)]
    pub fit_estar_mpa: Option<Bounded<Positive>>,
    /// Direct finite-element curves at E* low, central and high (`fingertip_fe`'s table): a
    /// third band; absent: model lines only.
    pub fe: Option<FingertipFe>,
}

impl Scene for FingertipAreaScene {
    /// One curve per modulus: E* low, central, high.
    fn fe_cases(&self, opts: &RunOptions) -> Vec<FeCase> {
        let Some(fe) = &self.fe else { return vec![] };
        let ar = self.amplitude_mm.get() / self.wavelength_mm.get();
        self.moduli()
            .map(|e| fe.case(ar, self.tau_max_mpa.get(), e, opts))
            .to_vec()
    }

    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        run(ctx.title, self, ctx.spec_dir, ctx.opts)
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
        ridge_aspect_ratio(
            v,
            "fingertip_area",
            self.wavelength_mm.get(),
            self.amplitude_mm.get(),
        )?;
        Ok(())
    }
}

impl FingertipAreaScene {
    /// E* low, central, high, MPa.
    fn moduli(&self) -> [f64; 3] {
        let [lo, hi] = self.estar_band_mpa.map(Bounded::get);
        [lo, self.estar_mpa.get(), hi]
    }
}

/// The disc of nominal contact and the ridges across it (R8).
struct Contact {
    wavelength_mm: f64,
    aspect_ratio: f64,
    /// R = √(A_exp/π), mm.
    radius_mm: f64,
    /// N = 2R/λ, not rounded.
    ridges: f64,
    /// Every ridge in full contact (a = λ/2), mm².
    full_area_mm2: f64,
}

impl Contact {
    fn of(s: &FingertipAreaScene) -> Self {
        let wavelength_mm = s.wavelength_mm.get();
        let radius_mm = (s.nominal_area_mm2.get() / PI).sqrt();
        let ridges = 2.0 * radius_mm / wavelength_mm;
        Contact {
            wavelength_mm,
            aspect_ratio: s.amplitude_mm.get() / wavelength_mm,
            radius_mm,
            ridges,
            full_area_mm2: wavelength_mm * ridges * 2.0 * radius_mm,
        }
    }

    /// A_total = 2a·N·2R at contact half-width a/λ, mm².
    fn area_mm2(&self, a_over_lambda: f64) -> f64 {
        2.0 * a_over_lambda * self.wavelength_mm * self.ridges * 2.0 * self.radius_mm
    }

    /// p̄/E* under a load F (N) at modulus E* (MPa): p̄ = F/(πR²).
    fn p_over_estar(&self, load_n: f64, estar_mpa: f64) -> f64 {
        load_n / (PI * self.radius_mm * self.radius_mm) / estar_mpa
    }

    /// Outcome of a load on a model law.
    fn area(&self, law: &dyn PressureLaw, p_over_estar: f64) -> Area {
        match a_over_lambda_at(law, p_over_estar) {
            Ok(x) => Area::Partial {
                a_over_lambda: x,
                area_mm2: self.area_mm2(x),
            },
            Err(InverseError::AboveFullContact { .. }) => Area::Full {
                area_mm2: self.full_area_mm2,
            },
            Err(e) => Area::Undefined(e),
        }
    }
}

/// Outcome of one load on one model.
enum Area {
    Partial { a_over_lambda: f64, area_mm2: f64 },
    Full { area_mm2: f64 },
    Undefined(InverseError),
}

const HEADER: [&str; 8] = [
    "model",
    "estar_mpa",
    "load_n",
    "p_over_estar",
    "a_over_lambda",
    "area_mm2",
    "state",
    "extrapolated",
];

fn run(
    title: &str,
    s: &FingertipAreaScene,
    spec_dir: &Path,
    opts: &RunOptions,
) -> Result<SceneResult> {
    let contact = Contact::of(s);
    let tau = s.tau_max_mpa.get();
    let loads = s.load_n.values();
    let laws = model_laws(&s.models, contact.aspect_ratio, tau);
    let mut table = Table::new("", &HEADER);
    let mut remarks = Remarks::default();
    let mut series = vec![];
    for (kind, law) in &laws {
        series.extend(model_series(
            s,
            &contact,
            *kind,
            law,
            &mut table,
            &mut remarks.notes,
        ));
    }
    let mut fe_footer = vec![];
    if let Some(fe) = &s.fe {
        let (fe_series, footer) = fe_series(s, &contact, fe, opts, &mut table, &mut remarks)?;
        series.extend(fe_series);
        fe_footer = footer;
    }
    let full = contact.full_area_mm2;
    series.push(Series::dashed(
        Some(format!("full contact, {full:.0} mm²")),
        palette::GREY,
        1,
        vec![(loads[0], full), (loads[loads.len() - 1], full)],
    ));
    remarks.footer = vec![
        format!(
            "Ridges λ = {} mm, Δ = {} mm (AR = {:.3}); A_exp = {} mm², R = {:.3} mm, N = 2R/λ = {:.2}.",
            contact.wavelength_mm,
            s.amplitude_mm.get(),
            contact.aspect_ratio,
            s.nominal_area_mm2.get(),
            contact.radius_mm,
            contact.ridges
        ),
        format!("Mean pressure p̄ = F/(πR²); area 2a·N·2R; τ_max = {tau} MPa enters the WNL polynomials in MPa."),
    ];
    remarks.footer.extend(fe_footer);
    let panel_title = extrapolation_title(s, &laws, &mut remarks);
    series.extend(measured_series(s, spec_dir, &mut remarks)?);
    let y = padded_range(
        series
            .iter()
            .flat_map(|s| s.points.iter().chain(&s.upper).map(|p| p.1)),
    );
    let panel = Panel {
        title: panel_title,
        x_label: "normal load F (N)".into(),
        y_label: "contact area (mm²)".into(),
        x_range: (loads[0], loads[loads.len() - 1]),
        y_range: (0.0, y.1),
        series,
        notes: vec![],
        log_scale: (false, false),
        legend: Some(LegendPosition::LowerRight),
    };
    let layout = Layout {
        grid: (1, 1),
        panel_px: (1240, 820),
        margin_px: 0,
        font_px: 18,
    };
    Ok(remarks.finish(title, layout, vec![panel], vec![table]))
}

/// A model's area at E* low, central and high: its rows of `table`, and its series (a band or
/// two dashed edges, and the central line). Loads with no contact area add a note (at most 20).
fn model_series(
    s: &FingertipAreaScene,
    contact: &Contact,
    kind: ModelKind,
    law: &ModelLaw,
    table: &mut Table,
    notes: &mut Vec<String>,
) -> Vec<Series> {
    let (label, color) = match kind {
        ModelKind::Westergaard => ("Westergaard".to_string(), palette::BLACK),
        ModelKind::Wnl => (format!("WNL ({})", s.models.reading), palette::VERMILION),
    };
    let extrapolated = law.is_extrapolated();
    let mut curves = vec![];
    for estar in s.moduli() {
        let mut pts = vec![];
        for f in s.load_n.values() {
            let p = contact.p_over_estar(f, estar);
            let (x, a, state): (Cell, Cell, &str) = match contact.area(law, p) {
                Area::Partial {
                    a_over_lambda,
                    area_mm2,
                } => {
                    pts.push((f, area_mm2));
                    (a_over_lambda.into(), area_mm2.into(), "partial")
                }
                Area::Full { area_mm2 } => {
                    pts.push((f, area_mm2));
                    (0.5.into(), area_mm2.into(), "full")
                }
                Area::Undefined(e) => {
                    let note =
                        format!("{label}, E* = {estar} MPa, F = {f} N: no contact area: {e}");
                    if !notes.contains(&note) && notes.len() < 20 {
                        notes.push(note);
                    }
                    (Cell::Empty, Cell::Empty, "undefined")
                }
            };
            table.push(vec![
                kind.key().into(),
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
    let [e_lo, e_mid, e_hi] = s.moduli();
    let suffix = if extrapolated { ", EXTRAPOLATED" } else { "" };
    // Lower modulus → more area: the range runs between the E*-high and E*-low curves.
    // WNL's range is shaded; Westergaard's is drawn as two dashed edges so both stay visible.
    let range_label = Some(format!("{label}, E* ∈ [{e_lo}, {e_hi}] MPa{suffix}"));
    let mut series = match kind {
        ModelKind::Wnl => vec![Series::band(
            range_label,
            color,
            curves[2].clone(),
            curves[0].clone(),
        )],
        ModelKind::Westergaard => vec![
            Series::dashed(range_label, color, 1, curves[0].clone()),
            Series::dashed(None, color, 1, curves[2].clone()),
        ],
    };
    series.push(Series::line(
        Some(format!("{label}, E* = {e_mid} MPa{suffix}")),
        color,
        3,
        curves[1].clone(),
    ));
    series
}

/// The direct FE curves at E* low, central and high: their rows of `table`, their series (a
/// band, the stiff edge, the central line, the ends of curves short of the last load) and their
/// footer lines.
fn fe_series(
    s: &FingertipAreaScene,
    contact: &Contact,
    fe_table: &FingertipFe,
    opts: &RunOptions,
    table: &mut Table,
    remarks: &mut Remarks,
) -> Result<(Vec<Series>, Vec<String>)> {
    let tau = s.tau_max_mpa.get();
    let outcomes = fe_cases::solve_all(&s.fe_cases(opts), opts)?;
    let mut footer = vec![];
    let mut curves = vec![];
    let mut beyond = vec![];
    for (&estar, fe) in s.moduli().iter().zip(&outcomes) {
        let label = format!("E* = {estar} MPa, τ_max = {tau} MPa");
        remarks.stopped_curve(&label, fe);
        if fe.failure.is_some() {
            footer.push(format!(
                "FE at E* = {estar} MPa INCOMPLETE: {}.",
                fe.status()
            ));
        }
        let curve = fe_area_curve(s, contact, estar, fe, &label, table)?;
        if curve.0.len() < s.load_n.values().len() {
            beyond.push(format!(
                "F > {} N at E* = {estar} MPa",
                sig_digits(curve.0.last().map_or(0.0, |p| p.0), 3)
            ));
        }
        curves.push(curve);
    }
    let series = fe_band_series(s, &curves);
    let reached = curves.iter().map(|c| c.1).fold(f64::INFINITY, f64::min);
    footer.insert(
        0,
        format!(
            "Direct FE (ours): the same ridges, τ_max = {tau} MPa, loaded to a/λ = {}; every curve reaches a/λ ≥ {} (○: its last point).",
            fe_table.until_a_over_lambda.get(),
            sig_digits(reached, 4)
        ),
    );
    if !beyond.is_empty() {
        footer.push(format!(
            "Beyond it ({}) the FE area is {}–100 % of full contact: not drawn (CSV state beyond_fe).",
            beyond.join(", "),
            percent(2.0 * reached)
        ));
    }
    Ok((series, footer))
}

/// The FE curve at `estar` as (load N, area mm²) points up to the last load it reaches, with
/// the last a/λ it reached; one row of `table` per load (empty cells where the curve does not
/// reach it).
fn fe_area_curve(
    s: &FingertipAreaScene,
    contact: &Contact,
    estar: f64,
    fe: &FeOutcome,
    label: &str,
    table: &mut Table,
) -> Result<(Vec<(f64, f64)>, f64)> {
    let mut pts = vec![];
    for f in s.load_n.values() {
        let p = contact.p_over_estar(f, estar);
        let inverse = fe_a_over_lambda_at(&fe.points, p)
            .map_err(|e| anyhow::anyhow!("FE curve {label}: {e}"))?;
        let (x, a, state): (Cell, Cell, &str) = match inverse {
            FeInverse::Within(x) => {
                pts.push((f, contact.area_mm2(x)));
                (x.into(), contact.area_mm2(x).into(), "partial")
            }
            FeInverse::Beyond { .. } if fe.failure.is_some() => {
                (Cell::Empty, Cell::Empty, "fe_incomplete")
            }
            FeInverse::Beyond { .. } => (Cell::Empty, Cell::Empty, "beyond_fe"),
        };
        table.push(vec![
            "fe".into(),
            estar.into(),
            f.into(),
            p.into(),
            x,
            a,
            state.into(),
            false.into(),
        ]);
    }
    Ok((pts, fe.last_a_over_lambda()))
}

/// The series of the FE curves at E* low, central and high (`curves`, from
/// [`fe_area_curve`]): the band runs where both its edges are computed; the stiff edge and the
/// central line go on to their own last points, and a curve short of the last load ends in a
/// marker.
fn fe_band_series(s: &FingertipAreaScene, curves: &[(Vec<(f64, f64)>, f64)]) -> Vec<Series> {
    let [e_lo, e_mid, e_hi] = s.moduli();
    let n = curves[0].0.len().min(curves[2].0.len());
    let mut series = vec![
        Series::band(
            Some(format!("direct FE (ours), E* ∈ [{e_lo}, {e_hi}] MPa")),
            palette::GREEN,
            curves[2].0[..n].to_vec(),
            curves[0].0[..n].to_vec(),
        ),
        Series::dashed(None, palette::GREEN, 1, curves[2].0.clone()),
        Series::line(
            Some(format!("direct FE (ours), E* = {e_mid} MPa")),
            palette::GREEN,
            3,
            curves[1].0.clone(),
        ),
    ];
    let loads = s.load_n.values().len();
    let ends: Vec<(f64, f64)> = curves
        .iter()
        .filter(|c| c.0.len() < loads)
        .filter_map(|c| c.0.last().copied())
        .collect();
    if !ends.is_empty() {
        series.push(Series::markers(
            Some("end of an FE curve (last load on it)".into()),
            palette::GREEN,
            6,
            ends,
        ));
    }
    series
}

/// The panel's title, which says where the WNL law is extrapolated (as in the paper); each
/// extrapolation also goes to the footer and the notes.
fn extrapolation_title(
    s: &FingertipAreaScene,
    laws: &[(ModelKind, ModelLaw)],
    remarks: &mut Remarks,
) -> String {
    let tau = s.tau_max_mpa.get();
    let [e_lo, _, e_hi] = s.moduli();
    let fit = fit_estar_mpa(s.fit_estar_mpa);
    let mut panel_title = "Total contact area against normal load".to_string();
    for (_, law) in laws {
        let why = outside_fit(law).join(", ");
        let ModelLaw::Wnl(m) = law else { continue };
        if why.is_empty() {
            continue;
        }
        let fitted = m.coefficients.domain.tau_max_mpa_max;
        let ratios = format!(
            "τ_max/E* = {}–{}",
            sig_digits(tau / e_hi, 2),
            sig_digits(tau / e_lo, 2)
        );
        panel_title = format!(
            "{panel_title}: WNL EXTRAPOLATED ({why}; {ratios}, fit ≤ {})",
            sig_digits(fitted / fit, 2)
        );
        remarks.footer_and_note(format!(
            "WNL EXTRAPOLATED, as in the paper: {why} (fit AR {}–{}); {ratios} (fit: τ_max ≤ {fitted} MPa at E* = {fit} MPa).",
            m.coefficients.domain.aspect_ratio_min,
            m.coefficients.domain.aspect_ratio_max,
        ));
    }
    panel_title
}

/// The measured points, when the spec names a data file that exists; what is missing is said
/// in the footer and the notes.
fn measured_series(
    s: &FingertipAreaScene,
    spec_dir: &Path,
    remarks: &mut Remarks,
) -> Result<Option<Series>> {
    let Some(rel) = &s.measured_data else {
        remarks.footer_and_note(
            "No measured data file is named in the spec: model lines only.".into(),
        );
        return Ok(None);
    };
    let path = spec_dir.join(rel);
    let data = measured_points::read(&path).map_err(|e| SpecError::Data {
        origin: path.display().to_string(),
        message: format!("{e:#}"),
    })?;
    let Some(m) = data else {
        let note = format!(
            "Measured points of Warman & Ennos (2009) NOT SHOWN: no data file {rel} beside the spec (schema: experiments/data/README.md)."
        );
        remarks.footer.push(note.clone());
        remarks.footer.push(
            "No digitised copy is available to us; the points are never invented or simulated."
                .into(),
        );
        remarks.notes.push(note);
        return Ok(None);
    };
    let who = m.provenance("digitised_by").unwrap_or_default();
    remarks.footer.push(format!(
        "Measured: {} ({}); digitised by {who}, {}.",
        m.provenance("source").unwrap_or_default(),
        m.provenance("source_figure").unwrap_or_default(),
        m.provenance("method").unwrap_or_default()
    ));
    Ok(Some(Series::markers(
        Some(format!(
            "measured ({}, digitised by {who})",
            m.provenance("source_figure").unwrap_or_default()
        )),
        palette::BLACK,
        5,
        m.points.clone(),
    )))
}
