//! Scene `two_scale` (beyond the paper, docs/replication.md R13): two-scale wavy surfaces by
//! direct finite elements, against the paper's proposal of superposing single-scale solutions
//! (`crate::models::superposition`) and against the big wave's WNL law alone.
//!
//! Per profile (the big wave and one finer harmonic) and τ_max: the FE curve of the contact
//! fraction against p̄/E* (node events, `crate::fe::stepping::node_events`), the superposition with
//! Westergaard's law and with the WNL law for both scales, and the WNL law of the big wave alone
//! (`2a₁/λ`); a table of each model's error against the FE; two contact maps (where the patches
//! lie as the load grows).

use crate::accuracy::contact_fraction::contact_fraction_error_estimate;
use crate::fe::{Grading, MeshLevel, SolveOptions};
use crate::models::superposition::{superposed_contact, SuperpositionError};
use crate::models::{a_over_lambda_at, CoefficientSet, InverseError, ModelKind, ModelLaw, Reading};
use crate::numfmt::sig_digits;
use crate::plot::{padded_range, LegendPosition, Panel, Series};
use crate::profile::Profile;
use crate::runner::scenes::scene_output::{Layout, Remarks};
use crate::runner::scenes::{Scene, SceneContext, SceneResult};
use crate::runner::sweep::fe_cases::{FeCase, FeOutcome, FePhysics, SolvedCases};
use crate::runner::RunOptions;
use crate::spec::{Bounded, NonNegative, SpecError, Validator};
use crate::table::{Cell, Table};
use anyhow::Result;
use plotters::style::RGBColor;

/// The `[two_scale]` section.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TwoScaleScene {
    /// Two-scale profiles, each `[[1, AR₁], [n, AR₂]]`: (order, aspect ratio) pairs as
    /// `wavy solve --profile` takes them (docs/replication.md R13).
    pub profiles: Vec<Vec<(u32, f64)>>,
    /// τ_max values, MPa, at the default E* (1 MPa): τ_max/E*.
    pub tau_max_mpa: Vec<Bounded<NonNegative>>,
    /// Elements along the contact face.
    pub mesh: usize,
    /// Face spacing at the valley over that at the peak (1: uniform, the small waves lie
    /// everywhere).
    pub peak_ratio: f64,
    /// Load until the FE contact fraction reaches this, in (0, 1).
    pub until_contact_fraction: f64,
    /// Mean pressures at which each model curve is evaluated.
    pub model_points: usize,
    /// FE contact fractions below this are left out of the relative errors (a relative error of
    /// a vanishing contact says little).
    pub error_from_contact_fraction: f64,
    /// Elements along the face of the coarser mesh on which each case is solved again for its FE
    /// error estimate (fewer than `mesh`).
    pub error_estimate_mesh: usize,
    /// Order of the FE contact fraction's error in the element size, with which each case's FE
    /// error is estimated from the same case on `error_estimate_mesh` (`crate::accuracy::contact_fraction`; the order
    /// observed by mesh convergence: docs/results.md, two-scale surfaces).
    pub fe_error_order: f64,
    /// The profiles (indices into `profiles`, frictionless) whose contact maps are drawn.
    pub contact_maps: Vec<usize>,
    /// Reading of the paper's Eq. 4 for WNL (default `bracket-sq`).
    #[serde(default)]
    pub reading: Reading,
    /// WNL coefficient set (default `paper-table1`).
    #[serde(default)]
    pub coefficients: CoefficientSet,
}

/// A model compared with the FE.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Model {
    /// The superposition (R13) with Westergaard's law for both scales (frictionless).
    SuperpositionWestergaard,
    /// The superposition with the WNL law for both scales.
    SuperpositionWnl,
    /// The big wave's WNL law alone: `2a₁/λ`.
    BigWaveWnl,
}

impl Model {
    const ALL: [Model; 3] = [
        Model::SuperpositionWestergaard,
        Model::SuperpositionWnl,
        Model::BigWaveWnl,
    ];

    /// The name in the tables.
    fn name(self) -> &'static str {
        match self {
            Model::SuperpositionWestergaard => "superposition-westergaard",
            Model::SuperpositionWnl => "superposition-wnl",
            Model::BigWaveWnl => "big-wave-wnl",
        }
    }

    fn color(self) -> RGBColor {
        match self {
            Model::SuperpositionWestergaard => RGBColor(31, 119, 180),
            Model::SuperpositionWnl => RGBColor(44, 160, 44),
            Model::BigWaveWnl => RGBColor(127, 127, 127),
        }
    }

    /// Whether its curve does not depend on τ_max (drawn once).
    fn frictionless(self) -> bool {
        self == Model::SuperpositionWestergaard
    }
}

/// FE curve colours per τ_max (black, red, …).
const FE_COLORS: [RGBColor; 3] = [
    RGBColor(0, 0, 0),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
];

impl TwoScaleScene {
    fn profile(&self, i: usize) -> Profile {
        Profile::from_pairs(&self.profiles[i]).expect("validated")
    }

    fn options(&self) -> SolveOptions {
        SolveOptions {
            mesh: MeshLevel::along_face(self.mesh),
            grading: Grading {
                peak_ratio: self.peak_ratio,
                ..Grading::default()
            },
            until_contact_fraction: Some(self.until_contact_fraction),
            ..SolveOptions::default()
        }
    }

    /// The FE cases ([`Self::cases`]) and, after them, each on `error_estimate_mesh`, for the FE
    /// error estimates.
    fn all_cases(&self) -> Vec<FeCase> {
        let cases = self.cases();
        let coarse: Vec<FeCase> = cases.iter().map(|c| self.coarse_case(c)).collect();
        cases.into_iter().chain(coarse).collect()
    }

    /// `case` on `error_estimate_mesh`.
    fn coarse_case(&self, case: &FeCase) -> FeCase {
        let mut coarse = case.clone();
        coarse.options.mesh = MeshLevel::along_face(self.error_estimate_mesh);
        coarse
    }

    /// One FE case per (τ_max, profile), τ_max outer.
    fn cases(&self) -> Vec<FeCase> {
        let mut cases = vec![];
        for tau in self.tau_max_mpa.iter().map(|t| t.get()) {
            for i in 0..self.profiles.len() {
                let profile = self.profile(i);
                cases.push(FeCase::for_profile(
                    &FePhysics::default(),
                    &profile,
                    tau,
                    self.options(),
                ));
            }
        }
        cases
    }

    fn wnl(&self, aspect_ratio: f64, tau_max_mpa: f64) -> ModelLaw {
        ModelLaw::new(
            ModelKind::Wnl,
            aspect_ratio,
            tau_max_mpa,
            self.reading,
            self.coefficients,
        )
    }

    /// The contact fraction of `model` for `profile` at τ_max and p̄/E*; `None` at or beyond
    /// the big wave's full contact, where the model has no answer (any other failure is an
    /// error).
    fn model_fraction(
        &self,
        model: Model,
        profile: &Profile,
        tau: f64,
        p: f64,
    ) -> Result<Option<f64>> {
        let fine = profile.finer.iter().next().expect("two-scale");
        let big_ar = profile.aspect_ratio;
        let westergaard = |ar| {
            ModelLaw::new(
                ModelKind::Westergaard,
                ar,
                0.0,
                self.reading,
                self.coefficients,
            )
        };
        let superposed = |big: &ModelLaw, small: &ModelLaw| match superposed_contact(
            big, small, fine.order, p,
        ) {
            Ok(c) => Ok(Some(c.contact_fraction)),
            Err(SuperpositionError::BigFullContact { .. })
            | Err(SuperpositionError::BigInverse {
                source: InverseError::AboveFullContact { .. },
                ..
            }) => Ok(None),
            Err(e) => Err(e.into()),
        };
        match model {
            Model::SuperpositionWestergaard => {
                superposed(&westergaard(big_ar), &westergaard(fine.aspect_ratio))
            }
            Model::SuperpositionWnl => {
                superposed(&self.wnl(big_ar, tau), &self.wnl(fine.aspect_ratio, tau))
            }
            Model::BigWaveWnl => match a_over_lambda_at(&self.wnl(big_ar, tau), p) {
                Ok(a) => Ok(Some(2.0 * a)),
                Err(InverseError::AboveFullContact { .. }) => Ok(None),
                Err(e) => Err(e.into()),
            },
        }
    }
}

impl Scene for TwoScaleScene {
    fn fe_cases(&self, _opts: &RunOptions) -> Vec<FeCase> {
        self.all_cases()
    }

    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        run(ctx.title, self, ctx.opts)
    }

    fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        v.non_empty("two_scale.profiles", self.profiles.len())?;
        v.non_empty("two_scale.tau_max_mpa", self.tau_max_mpa.len())?;
        let field = "two_scale.profiles";
        for p in &self.profiles {
            let text = format!("{p:?}");
            let profile = Profile::from_pairs(p)
                .map_err(|e| v.invalid(field, None, text.clone(), e.to_string()))?;
            if p.len() != 2 {
                return Err(v.invalid(
                    field,
                    None,
                    text,
                    "two harmonics: [[1, AR₁], [n, AR₂]]".into(),
                ));
            }
            let problem = crate::fe::LayerProblem {
                finer_harmonics: profile.finer,
                ..crate::defaults::layer_problem(profile.aspect_ratio)
            };
            let coarse = SolveOptions {
                mesh: MeshLevel::along_face(self.error_estimate_mesh),
                ..self.options()
            };
            for opts in [self.options(), coarse] {
                crate::fe::validate(&problem, &opts)
                    .map_err(|e| v.invalid(field, None, text.clone(), e.to_string()))?;
            }
        }
        let c = self.until_contact_fraction;
        if !(c > 0.0 && c < 1.0) {
            return Err(v.invalid(
                "two_scale.until_contact_fraction",
                None,
                c.to_string(),
                "(0, 1)".into(),
            ));
        }
        let order = self.fe_error_order;
        if !(order.is_finite() && order > 0.0) {
            return Err(v.invalid(
                "two_scale.fe_error_order",
                None,
                order.to_string(),
                "> 0".into(),
            ));
        }
        if self.error_estimate_mesh >= self.mesh {
            return Err(v.invalid(
                "two_scale.error_estimate_mesh",
                None,
                self.error_estimate_mesh.to_string(),
                format!("fewer elements than mesh = {}", self.mesh),
            ));
        }
        if self.model_points < 2 {
            return Err(v.invalid(
                "two_scale.model_points",
                None,
                self.model_points.to_string(),
                ">= 2".into(),
            ));
        }
        if let Some(&i) = self
            .contact_maps
            .iter()
            .find(|&&i| i >= self.profiles.len())
        {
            return Err(v.invalid(
                "two_scale.contact_maps",
                None,
                i.to_string(),
                "indices into profiles".into(),
            ));
        }
        // a contact map draws the profile's curve at the first τ_max, which must be frictionless
        let first_tau = self.tau_max_mpa[0].get();
        if !self.contact_maps.is_empty() && first_tau != 0.0 {
            return Err(v.invalid(
                "two_scale.tau_max_mpa",
                None,
                format!("{first_tau} first"),
                "0 first when contact_maps are drawn (the maps show the frictionless curves)"
                    .into(),
            ));
        }
        Ok(())
    }
}

fn run(title: &str, s: &TwoScaleScene, opts: &RunOptions) -> Result<SceneResult> {
    let cases = s.cases();
    let solved = SolvedCases::solve(s.all_cases(), opts)?;
    let mut curves = Table::new(
        "",
        &[
            "profile",
            "tau_max_mpa",
            "source",
            "p_over_estar",
            "contact_fraction",
            "patches",
        ],
    );
    let mut errors = Table::new(
        "errors",
        &[
            "profile",
            "tau_max_mpa",
            "model",
            "fe_points",
            "max_rel_error",
            "rms_rel_error",
            "max_abs_error",
            "fe_rms_error_estimate",
            "fe_error_over_model_error",
        ],
    );
    let mut remarks = Remarks::with_footer(vec![format!(
        "FE: finite strain, neo-Hookean, h/λ = 1, mesh {} elements along the face (peak ratio {}), node events; E* = 1 MPa; its error estimated against mesh {} at order {}. Models: docs/replication.md R13.",
        s.mesh, s.peak_ratio, s.error_estimate_mesh, s.fe_error_order
    )]);
    let mut panels = vec![];
    for i in 0..s.profiles.len() {
        let tables = (&mut curves, &mut errors);
        panels.push(profile_panel(s, i, &cases, &solved, tables, &mut remarks)?);
    }
    for &i in &s.contact_maps {
        let case = &cases[i];
        let fe = solved.outcome(case).expect("solved");
        panels.push(contact_map(&s.profile(i).to_string(), fe));
    }
    remarks.count_incomplete("their curves end where the solver stopped; see the run's notes");
    let n = panels.len();
    let cols = 3;
    let layout = Layout {
        grid: (n.div_ceil(cols), cols),
        panel_px: (520, 420),
        margin_px: 120,
        font_px: 14,
    };
    Ok(remarks.finish(title, layout, panels, vec![curves, errors]))
}

/// The panel of profile `i`: its FE curve at each τ_max and each model's curve, whose points go
/// into the curves table and whose errors against the FE into the errors table.
fn profile_panel(
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
        let fe_error = fe_error_estimate(s, case, solved);
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
        series.push(Series::line(
            Some(format!("FE, τ_max = {tau} MPa")),
            FE_COLORS[t % FE_COLORS.len()],
            2,
            fe.points
                .iter()
                .map(|p| (p.p_over_estar, p.contact_fraction))
                .collect(),
        ));
        let p_max = fe.points.last().map_or(0.0, |p| p.p_over_estar);
        for model in Model::ALL {
            let drawn = !model.frictionless() || t == 0;
            let mut line = vec![];
            for k in 1..=s.model_points {
                let p = p_max * k as f64 / s.model_points as f64;
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

/// The estimate of the FE curve's relative error (root mean square over its points with a
/// contact fraction of at least `error_from_contact_fraction`,
/// [`contact_fraction_error_estimate`]) from the same case on `error_estimate_mesh`, over the
/// load range both reach (a coarse curve may stop short); `None` when the curve is incomplete or
/// they share no point.
fn fe_error_estimate(s: &TwoScaleScene, case: &FeCase, solved: &SolvedCases) -> Option<f64> {
    let ratio = s.mesh as f64 / s.error_estimate_mesh as f64;
    let fine = solved.outcome(case)?;
    let coarse = solved.outcome(&s.coarse_case(case))?;
    if fine.failure.is_some() {
        return None;
    }
    contact_fraction_error_estimate(
        &fine.points,
        &coarse.points,
        ratio,
        s.fe_error_order,
        s.error_from_contact_fraction,
    )
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
    let (mut count, mut max_rel, mut sum_sq, mut max_abs) = (0usize, 0.0_f64, 0.0, 0.0_f64);
    for p in fe
        .points
        .iter()
        .filter(|p| p.contact_fraction >= s.error_from_contact_fraction)
    {
        if let Some(c) = s.model_fraction(model, profile, tau, p.p_over_estar)? {
            let rel = c / p.contact_fraction - 1.0;
            count += 1;
            max_rel = max_rel.max(rel.abs());
            sum_sq += rel * rel;
            max_abs = max_abs.max((c - p.contact_fraction).abs());
        }
    }
    let rms = (count > 0).then(|| (sum_sq / count as f64).sqrt());
    Ok(vec![
        name.into(),
        tau.into(),
        model.name().into(),
        Cell::Num(count as f64),
        (count > 0).then_some(max_rel).into(),
        rms.into(),
        (count > 0).then_some(max_abs).into(),
    ])
}

/// Where the contact patches lie (x/λ in the half wavelength) against p̄/E*: one segment per
/// patch per load event.
fn contact_map(name: &str, fe: &FeOutcome) -> Panel {
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
