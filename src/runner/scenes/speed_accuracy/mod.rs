//! The speed–accuracy trade: for each (AR, τ_max), every tier that answers p̄/E*(a/λ) —
//! Westergaard, WNL with a coefficient set, linear FE, finite-strain FE at several meshes, the
//! Richardson extrapolation of two of those meshes and the mesh limit of three — with its error
//! against a converged reference and its cost.
//!
//! The reference is the limit of the finite-strain curves on fine meshes (`reference_meshes`),
//! computed once by `wavy refine-reference` into the file `reference`
//! (`crate::runner::scenes::speed_accuracy::reference_curves`; docs/replication.md R11); the order of the FE error that error
//! estimates use is observed here on three meshes refined by a constant ratio (`order_meshes`).
//! The errors are computed here; the wall times come from `timings` (measured data, written by
//! `wavy time-tiers`: a figure that recomputed times would differ on every run).

pub(crate) mod case_reference;
pub(crate) mod figure;
pub mod reference_curves;
pub mod refine_reference;
pub(crate) mod tables;
pub(crate) mod tier_measurement;
pub mod tier_timings;
pub(crate) mod tier_values;
pub mod time_tiers;

use crate::accuracy::Tier;
use crate::fe::{Kinematics, MeshLevel};
use crate::runner::scenes::scene_output::{Layout, Remarks};
use crate::runner::scenes::speed_accuracy::case_reference::Reference;
use crate::runner::scenes::speed_accuracy::figure::figure_panels;
use crate::runner::scenes::speed_accuracy::reference_curves::ReferenceCurves;
use crate::runner::scenes::speed_accuracy::tables::{SceneColumns, Tables};
use crate::runner::scenes::speed_accuracy::tier_measurement::{
    error_time_trade, pareto_front, CaseMeasurements, Measurement,
};
use crate::runner::scenes::speed_accuracy::tier_timings::Timings;
use crate::runner::scenes::speed_accuracy::tier_values::{
    closed_form_values, extrapolated_values, fe_tier_values,
};
use crate::runner::scenes::{Scene, SceneContext, SceneResult};
use crate::runner::sweep::fe_cases::{FeCase, FeOutcome, FePhysics, SolvedCases};
use crate::runner::RunOptions;
use crate::spec::{Bounded, FeSection, Grid, Positive, SpecError, Validator};
use anyhow::{bail, Context, Result};
use serde::{de, Deserialize, Deserializer};

/// The `[speed_accuracy]` section.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedAccuracyScene {
    /// Aspect ratios Δ/λ of the measured cases (figure rows).
    pub aspect_ratios: Vec<Bounded<Positive>>,
    /// Where the errors are taken, a/λ.
    pub a_over_lambda: Grid,
    /// Edges of the a/λ bands whose largest errors are reported separately (increasing, from
    /// the first to the last value of `a_over_lambda`): the FE error is largest at small a/λ, and a
    /// tolerance asked at larger a/λ is judged by its own band.
    pub error_bands: Vec<f64>,
    /// The tiers measured, by name (`westergaard`, `wnl-<set>`, `fe-finite-N`, `fe-linear-N`,
    /// `fe-richardson-C-F`, `fe-limit-A-B-C`; an extrapolating tier's meshes are tiers too: its
    /// time is theirs).
    #[serde(deserialize_with = "tiers_from_names")]
    pub tiers: Vec<Tier>,
    /// Elements along the face of the finite-strain meshes whose limit is the reference, coarse
    /// to fine (at least three; `wavy refine-reference` solves them).
    pub reference_meshes: Vec<usize>,
    /// The reference curves, relative to the spec's folder (written by `wavy refine-reference`).
    pub reference: String,
    /// Three meshes, each the same ratio finer than the last, on which the order of the FE error
    /// is observed (the order error estimates use).
    pub order_meshes: [usize; 3],
    /// The measured wall times, relative to the spec's folder.
    pub timings: String,
    /// The cases' τ_max (MPa, figure columns), their physics (defaults of docs/replication.md
    /// R7) and the target a/λ of every FE curve. The meshes are the tiers'; `mesh` is not used.
    pub fe: FeSection,
}

fn tiers_from_names<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Tier>, D::Error> {
    Vec::<String>::deserialize(d)?
        .iter()
        .map(|s| s.parse::<Tier>().map_err(de::Error::custom))
        .collect()
}

impl SpeedAccuracyScene {
    /// The aspect ratios of the cases.
    pub(crate) fn ars(&self) -> Vec<f64> {
        self.aspect_ratios.iter().map(|a| a.get()).collect()
    }
    /// The physics of every case, in the order of `PHYSICS_COLUMNS` (the reference file's columns).
    pub fn physics(&self) -> [f64; 5] {
        FePhysics::from(&self.fe).by_column().map(|(_, v)| v)
    }

    /// The τ_max of the cases, MPa.
    pub(crate) fn taus(&self) -> Vec<f64> {
        self.fe.tau_max_mpa.iter().map(|t| t.get()).collect()
    }

    /// The refinement ratio ρ of the order meshes.
    fn refinement_ratio(&self) -> f64 {
        self.order_meshes[2] as f64 / self.order_meshes[1] as f64
    }

    /// The FE case of an FE tier (or a reference mesh) at (AR, τ_max in MPa).
    pub fn case(&self, kinematics: Kinematics, nx: usize, ar: f64, tau: f64) -> FeCase {
        let physics = FePhysics {
            kinematics,
            ..FePhysics::from(&self.fe)
        };
        let options = self.fe.options(&[ar], Some(MeshLevel::along_face(nx)));
        FeCase::new(&physics, ar, tau, options)
    }

    /// The FE curves of every case: the FE tiers, then the order's meshes, each once.
    fn curves(&self) -> Vec<(Kinematics, usize)> {
        let mut out: Vec<(Kinematics, usize)> = vec![];
        let tiers = self.tiers.iter().flat_map(|t| t.fe_curves());
        let order = self.order_meshes.map(|n| (Kinematics::Finite, n));
        for k in tiers.chain(order) {
            if !out.contains(&k) {
                out.push(k);
            }
        }
        out
    }
}

/// The checks of [`Scene::validate`] beyond the shared ones, one per field.
impl SpeedAccuracyScene {
    /// `error_bands`: increasing, from the first to the last value of `a_over_lambda`.
    fn check_error_bands(&self, v: &Validator) -> Result<(), SpecError> {
        let xs = self.a_over_lambda.values();
        let e = &self.error_bands;
        if !(e.len() >= 2
            && e.windows(2).all(|w| w[0] < w[1])
            && e[0] == xs[0]
            && e[e.len() - 1] == xs[xs.len() - 1])
        {
            return Err(v.invalid(
                "speed_accuracy.error_bands",
                None,
                format!("{e:?}"),
                format!(
                    "increasing band edges from {} to {} (the a_over_lambda grid's ends)",
                    xs[0],
                    xs[xs.len() - 1]
                ),
            ));
        }
        Ok(())
    }

    /// `tiers`: each once, and an extrapolating tier's meshes among them.
    fn check_tiers(&self, v: &Validator) -> Result<(), SpecError> {
        for (i, t) in self.tiers.iter().enumerate() {
            if self.tiers[..i].contains(t) {
                return Err(v.invalid(
                    &format!("speed_accuracy.tiers[{i}]"),
                    None,
                    t.name(),
                    "each tier once".into(),
                ));
            }
            // an extrapolating tier's timed tiers are its meshes
            let meshes = match t.is_extrapolated() {
                true => t.timed_tiers(),
                false => vec![],
            };
            if meshes.iter().any(|mesh| !self.tiers.contains(mesh)) {
                let names: Vec<String> = meshes.iter().map(Tier::name).collect();
                return Err(v.invalid(
                    &format!("speed_accuracy.tiers[{i}]"),
                    None,
                    t.name(),
                    format!(
                        "{} among the tiers too (an extrapolating tier's time is its meshes')",
                        names.join(" and ")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// `order_meshes`: three increasing element counts in range, refined by a constant ratio.
    fn check_order_meshes(&self, v: &Validator) -> Result<(), SpecError> {
        let range = MeshLevel::ELEMENTS_ALONG_FACE;
        let [coarsest, coarse, fine] = self.order_meshes;
        if !(coarsest < coarse
            && coarse < fine
            && range.contains(&coarsest)
            && range.contains(&fine)
            && coarsest * fine == coarse * coarse)
        {
            return Err(v.invalid(
                "speed_accuracy.order_meshes",
                None,
                format!("{:?}", self.order_meshes),
                format!(
                    "three increasing element counts in {}..={}, each the same ratio finer than the last (middle² = first × last)",
                    range.start(),
                    range.end()
                ),
            ));
        }
        Ok(())
    }

    /// `reference_meshes`: at least three increasing element counts in range.
    fn check_reference_meshes(&self, v: &Validator) -> Result<(), SpecError> {
        let range = MeshLevel::ELEMENTS_ALONG_FACE;
        let r = &self.reference_meshes;
        if !(r.len() >= 3
            && r.windows(2).all(|w| w[0] < w[1])
            && r.iter().all(|n| range.contains(n)))
        {
            return Err(v.invalid(
                "speed_accuracy.reference_meshes",
                None,
                format!("{r:?}"),
                format!(
                    "at least three increasing element counts in {}..={} (the limit fitted through them has three terms)",
                    range.start(),
                    range.end()
                ),
            ));
        }
        Ok(())
    }

    /// The FE section: no mesh or tolerance (the tiers name their meshes, the scene measures
    /// the errors a tolerance is judged by), finite kinematics (the reference's).
    fn check_fe_settings(&self, v: &Validator) -> Result<(), SpecError> {
        if let Some(m) = self.fe.mesh {
            return Err(v.invalid(
                "speed_accuracy.fe.mesh",
                None,
                format!("{m:?}"),
                "not set: the tiers name their meshes".into(),
            ));
        }
        if let Some(t) = self.fe.tolerance {
            return Err(v.invalid(
                "speed_accuracy.fe.tolerance",
                None,
                t.get().to_string(),
                "not set: this scene measures the errors a tolerance is judged by".into(),
            ));
        }
        if self.fe.kinematics != Kinematics::Finite {
            return Err(v.invalid(
                "speed_accuracy.fe.kinematics",
                None,
                self.fe.kinematics.name().into(),
                "finite (the reference is the finite-strain solution; linear FE is a tier)".into(),
            ));
        }
        Ok(())
    }
}

impl Scene for SpeedAccuracyScene {
    fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        v.non_empty("speed_accuracy.aspect_ratios", self.aspect_ratios.len())?;
        v.non_empty("speed_accuracy.tiers", self.tiers.len())?;
        v.fe_section("speed_accuracy.fe", &self.fe, None, &self.ars())?;
        let until = self.fe.until_a_over_lambda.get();
        v.grid(
            "speed_accuracy.a_over_lambda",
            &self.a_over_lambda,
            (0.0, until),
            false,
        )?;
        self.check_error_bands(v)?;
        self.check_tiers(v)?;
        self.check_order_meshes(v)?;
        self.check_reference_meshes(v)?;
        self.check_fe_settings(v)
    }

    fn fe_cases(&self, _opts: &RunOptions) -> Vec<FeCase> {
        let mut cases = vec![];
        for tau in self.taus() {
            for ar in self.ars() {
                for (k, nx) in self.curves() {
                    cases.push(self.case(k, nx, ar, tau));
                }
            }
        }
        cases
    }

    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        if ctx.opts.fe_mesh_override.is_some() {
            bail!("a mesh override does not apply to speed_accuracy: its tiers name their meshes");
        }
        let path = ctx.spec_dir.join(&self.timings);
        let timings = tier_timings::read(&path)
            .with_context(|| format!("speed_accuracy.timings: {}", path.display()))?;
        let path = ctx.spec_dir.join(&self.reference);
        let reference = reference_curves::read(&path)
            .with_context(|| format!("speed_accuracy.reference: {}", path.display()))?;
        let meshes = reference
            .meshes()
            .with_context(|| format!("speed_accuracy.reference: {}", path.display()))?;
        if meshes != self.reference_meshes {
            bail!(
                "speed_accuracy.reference: {} holds the limit of meshes {meshes:?}, the spec asks for {:?}: recompute it with `wavy refine-reference` (make reference)",
                path.display(),
                self.reference_meshes
            );
        }
        run(
            ctx.title,
            self,
            &timings,
            &self.timings,
            &reference,
            ctx.opts,
        )
    }
}

fn run(
    title: &str,
    s: &SpeedAccuracyScene,
    timings: &Timings,
    timings_name: &str,
    reference_curves: &ReferenceCurves,
    opts: &RunOptions,
) -> Result<SceneResult> {
    let (ars, taus) = (s.ars(), s.taus());
    let solved = SolvedCases::solve(s.fe_cases(opts), opts)?;
    let mut tables = Tables::new(SceneColumns {
        a_over_lambda: s.a_over_lambda.values(),
        error_bands: s.error_bands.clone(),
        order_meshes: s.order_meshes,
        reference_meshes: s.reference_meshes.clone(),
        physics: s.physics(),
    });
    let mut cases = vec![];
    for &ar in &ars {
        for &tau in &taus {
            let reference = reference(s, &solved, reference_curves, ar, tau)?;
            tables.push_reference(&reference, ar, tau);
            let mut measurements = vec![];
            for tier in &s.tiers {
                let m = measure(s, &solved, timings, timings_name, tier, ar, tau)?;
                let values = m.1.as_deref();
                tables.push_bands(tier, values, &reference.p_over_estar, ar, tau);
                measurements.push(m.0.with_errors(values, &reference.p_over_estar));
            }
            let front = pareto_front(&measurements);
            tables.push_measurements(&measurements, &front, ar, tau);
            tables.push_trade(error_time_trade(&measurements).as_ref(), ar, tau);
            cases.push(CaseMeasurements {
                aspect_ratio: ar,
                tau_max_mpa: tau,
                reference_uncertainty: reference.uncertainty,
                measurements,
                front,
            });
        }
    }
    let (panels, failed) = figure_panels(&s.tiers, &cases);
    let mut remarks = Remarks::with_footer(footer(s, timings, timings_name));
    if !failed.is_empty() {
        remarks.footer_and_note(format!(
            "tiers without a curve (they stop short of a/λ = {}): {}",
            s.fe.until_a_over_lambda.get(),
            failed.join("; ")
        ));
    }
    let layout = Layout {
        grid: (ars.len(), taus.len()),
        panel_px: (540, 380),
        margin_px: 150,
        font_px: 15,
    };
    Ok(remarks.finish(title, layout, panels, tables.into_vec()))
}

/// The reference of the case (AR, τ_max in MPa): the committed limit on the a/λ grid, the order
/// observed on the order meshes.
fn reference(
    s: &SpeedAccuracyScene,
    solved: &SolvedCases,
    reference_curves: &ReferenceCurves,
    ar: f64,
    tau: f64,
) -> Result<Reference> {
    let at = format!("AR = {ar}, τ_max = {tau} MPa");
    let curves = s.order_meshes.map(|nx| {
        let o = curve(s, solved, Kinematics::Finite, nx, ar, tau);
        (nx, o)
    });
    for (nx, o) in &curves {
        if let Some(f) = &o.failure {
            bail!("{at}: the observed order needs the finite-strain curve on mesh {nx}, which stopped: {f}");
        }
    }
    let limit = reference_curves.case(ar, tau, s.physics());
    Reference::of(
        curves.map(|(_, o)| o.points.as_slice()),
        s.order_meshes,
        s.refinement_ratio(),
        &s.a_over_lambda.values(),
        &limit,
        &at,
    )
}

/// The curve of an FE tier (or a reference mesh) at (AR, τ_max in MPa).
fn curve<'a>(
    s: &SpeedAccuracyScene,
    solved: &'a SolvedCases,
    kinematics: Kinematics,
    nx: usize,
    ar: f64,
    tau: f64,
) -> &'a FeOutcome {
    solved
        .outcome(&s.case(kinematics, nx, ar, tau))
        .expect("every curve of the scene is among its cases")
}

/// One tier at (AR, τ_max in MPa): its cost, and its p̄/E* on the a/λ grid (none when it has
/// no curve there: the measurement's status says why).
fn measure(
    s: &SpeedAccuracyScene,
    solved: &SolvedCases,
    timings: &Timings,
    timings_name: &str,
    tier: &Tier,
    ar: f64,
    tau: f64,
) -> Result<(Measurement, Option<Vec<f64>>)> {
    let xs = s.a_over_lambda.values();
    let at = format!("AR = {ar}, τ_max = {tau} MPa");
    let timing_of = |tier: &Tier| {
        timings.get(tier, ar, tau).with_context(|| {
            format!(
                "{timings_name} has no timing of tier {tier} at {at}: measure it with `wavy time-tiers` (make bench-tiers)"
            )
        })
    };
    // a Richardson tier costs its two curves
    let timed = tier
        .timed_tiers()
        .iter()
        .map(timing_of)
        .collect::<Result<Vec<_>>>()?;
    let seconds_per_curve: f64 = timed.iter().map(|t| t.median_seconds_per_curve).sum();
    let (values, status, fe) = match *tier {
        Tier::Fe {
            kinematics,
            elements_along_face: nx,
        } => fe_tier_values(
            &xs,
            curve(s, solved, kinematics, nx, ar, tau),
            nx,
            tier,
            &at,
        )?,
        Tier::FeRichardson { .. } | Tier::FeLimit { .. } => {
            let curves: Vec<(&FeOutcome, usize)> = (tier.fe_curves().into_iter())
                .map(|(kinematics, nx)| (curve(s, solved, kinematics, nx, ar, tau), nx))
                .collect();
            extrapolated_values(&xs, &curves, tier, &at)?
        }
        _ => closed_form_values(&xs, tier, ar, tau),
    };
    let seconds_per_point = tier
        .is_closed_form()
        .then(|| seconds_per_curve / timed[0].points_per_curve as f64);
    let m = Measurement {
        tier: *tier,
        errors: None,
        status,
        seconds_per_curve,
        seconds_per_point,
        fe,
    };
    Ok((m, values))
}

/// The footer: how the error and the wall time are measured.
fn footer(s: &SpeedAccuracyScene, timings: &Timings, timings_name: &str) -> Vec<String> {
    let xs = s.a_over_lambda.values();
    let meshes: Vec<String> = s.reference_meshes.iter().map(|n| n.to_string()).collect();
    let physics = FePhysics::from(&s.fe);
    let mut footer = vec![
        format!(
            "Error: largest over a/λ ∈ [{}, {}] against the limit p₀ + c₁/n + c₂/n² of FE meshes n = {}",
            xs[0],
            xs[xs.len() - 1],
            meshes.join(", "),
        ),
        format!(
            "({}); E* = {} MPa, κ/G = {}, h/λ = {}, μ = {}. FE markers right to left: finer meshes.",
            s.reference,
            physics.estar_mpa,
            physics.kappa_over_g,
            physics.thickness_over_lambda,
            physics.friction_coefficient
        ),
        format!(
            "Wall time per curve (closed forms: {} points; extrapolations: all their meshes) from {timings_name}:",
            xs.len()
        ),
    ];
    footer.extend(timings.describe());
    if s.tiers
        .iter()
        .any(|t| matches!(t, Tier::FeRichardson { .. }))
    {
        footer.push(format!(
            "fe-richardson-C-F: p_F + (p_F − p_C)/((F/C)^q − 1), q = {}, at each a/λ.",
            crate::accuracy::RICHARDSON_TIER_ORDER
        ));
    }
    if s.tiers.iter().any(|t| matches!(t, Tier::FeLimit { .. })) {
        footer.push(
            "fe-limit-A-B-C: the limit p₀ of p₀ + c₁/n + c₂/n² through meshes n = A, B, C, at each a/λ."
                .into(),
        );
    }
    footer
}
