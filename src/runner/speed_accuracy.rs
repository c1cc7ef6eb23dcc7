//! The speed–accuracy trade: for each (AR, τ_max), every tier that answers p̄/E*(a/λ) —
//! Westergaard, WNL with a coefficient set, linear FE, finite-strain FE at several meshes — with
//! its error against a converged reference and its cost.
//!
//! The reference is the Richardson extrapolation of the two finest finite-strain meshes
//! (`reference_meshes`, refined by ρ = fine/coarse), with the order observed on those two and
//! the mesh ρ times coarser (docs/replication.md R11). The errors are computed here; the wall
//! times come from `timings` (measured data, written by `wavy time-tiers`: a figure that
//! recomputed times would differ on every run).

use super::fe_cases::{FeCase, FeOutcome, FePhysics, SolvedCases};
use super::richardson_reference::Reference;
use super::scene_output::{Layout, Remarks};
use super::speed_accuracy_figure::figure_panels;
use super::tier_measurement::{pareto_front, CaseMeasurements, FeCost, Measurement};
use super::scenes::{Scene, SceneContext, SceneResult};
use super::tier_timings::{self, Timings};
use super::RunOptions;
use crate::accuracy::measured::PHYSICS_COLUMNS;
use crate::accuracy::{relative_errors, Tier};
use crate::fe::{convergence, Kinematics, MeshLevel};
use crate::models::PressureLaw;
use crate::spec::{Bounded, FeSection, Grid, Positive, SpecError, Validator};
use crate::table::{Cell, Table};
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
    /// The tiers measured, by name (`westergaard`, `wnl-<set>`, `fe-finite-N`, `fe-linear-N`).
    #[serde(deserialize_with = "tiers_from_names")]
    pub tiers: Vec<Tier>,
    /// Elements along the face of the two finest finite-strain meshes, coarse then fine: the
    /// Richardson reference.
    pub reference_meshes: [usize; 2],
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
    fn ars(&self) -> Vec<f64> {
        self.aspect_ratios.iter().map(|a| a.get()).collect()
    }
    fn taus(&self) -> Vec<f64> {
        self.fe.tau_max_mpa.iter().map(|t| t.get()).collect()
    }

    /// The three meshes of the observed order, coarse to fine (ratio ρ each).
    pub fn order_meshes(&self) -> [usize; 3] {
        let [coarse, fine] = self.reference_meshes;
        [coarse * coarse / fine, coarse, fine]
    }

    /// The refinement ratio ρ = fine/coarse of the reference meshes.
    fn refinement_ratio(&self) -> f64 {
        self.reference_meshes[1] as f64 / self.reference_meshes[0] as f64
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
        let tiers = self.tiers.iter().filter_map(|t| match *t {
            Tier::Fe {
                kinematics,
                elements_along_face,
            } => Some((kinematics, elements_along_face)),
            _ => None,
        });
        let order = self.order_meshes().map(|n| (Kinematics::Finite, n));
        for k in tiers.chain(order) {
            if !out.contains(&k) {
                out.push(k);
            }
        }
        out
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
        for (i, t) in self.tiers.iter().enumerate() {
            if self.tiers[..i].contains(t) {
                return Err(v.invalid(
                    &format!("speed_accuracy.tiers[{i}]"),
                    None,
                    t.name(),
                    "each tier once".into(),
                ));
            }
        }
        let [coarse, fine] = self.reference_meshes;
        let [coarsest, ..] = self.order_meshes();
        let range = MeshLevel::ELEMENTS_ALONG_FACE;
        if !(fine > coarse
            && range.contains(&coarse)
            && range.contains(&fine)
            && coarsest * fine == coarse * coarse
            && coarsest >= 4)
        {
            return Err(v.invalid(
                "speed_accuracy.reference_meshes",
                None,
                format!("{:?}", self.reference_meshes),
                format!(
                    "[coarse, fine] element counts with fine > coarse, in {}..={}, and coarse²/fine a whole number ≥ 4 (the third mesh of the observed order)",
                    range.start(),
                    range.end()
                ),
            ));
        }
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
        run(ctx.title, self, &timings, &self.timings, ctx.opts)
    }
}

fn run(
    title: &str,
    s: &SpeedAccuracyScene,
    timings: &Timings,
    timings_name: &str,
    opts: &RunOptions,
) -> Result<SceneResult> {
    let (ars, taus) = (s.ars(), s.taus());
    let solved = SolvedCases::solve(s.fe_cases(opts), opts)?;
    let mut tables = Tables::new();
    let mut cases = vec![];
    for &ar in &ars {
        for &tau in &taus {
            let reference = reference(s, &solved, ar, tau)?;
            tables.push_reference(s, &reference, ar, tau);
            let mut measurements = vec![];
            for tier in &s.tiers {
                let m = measure(s, &solved, timings, timings_name, tier, ar, tau)?;
                let values = m.1.as_deref();
                tables.push_bands(s, tier, values, &reference.p_over_estar, ar, tau);
                measurements.push(m.0.with_errors(values, &reference.p_over_estar));
            }
            let front = pareto_front(&measurements);
            tables.push_measurements(&measurements, &front, ar, tau);
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

/// The reference of the case (AR, τ_max in MPa): Richardson on the two finest meshes, the order
/// observed with the third.
fn reference(s: &SpeedAccuracyScene, solved: &SolvedCases, ar: f64, tau: f64) -> Result<Reference> {
    let at = format!("AR = {ar}, τ_max = {tau} MPa");
    let curves = s.order_meshes().map(|nx| {
        let o = curve(s, solved, Kinematics::Finite, nx, ar, tau);
        (nx, o)
    });
    for (nx, o) in &curves {
        if let Some(f) = &o.failure {
            bail!("{at}: the reference needs the finite-strain curve on mesh {nx}, which stopped: {f}");
        }
    }
    Reference::of(
        curves.map(|(_, o)| o.points.as_slice()),
        s.order_meshes(),
        s.refinement_ratio(),
        &s.a_over_lambda.values(),
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
    let timing = timings.get(tier, ar, tau).with_context(|| {
        format!(
            "{timings_name} has no timing of tier {tier} at {at}: measure it with `wavy time-tiers` (make bench-tiers)"
        )
    })?;
    let (values, status, fe) = match *tier {
        Tier::Fe {
            kinematics,
            elements_along_face: nx,
        } => {
            let o = curve(s, solved, kinematics, nx, ar, tau);
            let (mx, my) = MeshLevel::along_face(nx).counts();
            let cost = FeCost {
                dofs: 2 * (mx + 1) * (my + 1),
                load_steps: o.points.len(),
                newton_iterations: o.points.iter().map(|p| p.newton_iterations).sum(),
            };
            match &o.failure {
                Some(f) => {
                    let reached = o.last_a_over_lambda();
                    (None, format!("stops at a/λ = {reached:.3}: {f}"), Some(cost))
                }
                None => {
                    let v: Option<Vec<f64>> =
                        xs.iter().map(|&x| convergence::p_at(&o.points, x)).collect();
                    let v = v.with_context(|| {
                        format!("{at}: the curve of {tier} does not cover the a/λ grid")
                    })?;
                    (Some(v), "ok".into(), Some(cost))
                }
            }
        }
        _ => {
            let law = tier.law(ar, tau).expect("a closed-form tier has a law");
            match xs
                .iter()
                .map(|&x| law.physical_p_over_estar(x))
                .collect::<Result<Vec<f64>, _>>()
            {
                Ok(v) => (Some(v), "ok".into(), None),
                Err(e) => (None, format!("unphysical: {e}"), None),
            }
        }
    };
    let seconds_per_point = tier
        .is_closed_form()
        .then(|| timing.median_seconds_per_curve / timing.points_per_curve as f64);
    let m = Measurement {
        tier: *tier,
        errors: None,
        status,
        seconds_per_curve: timing.median_seconds_per_curve,
        seconds_per_point,
        fe,
    };
    Ok((m, values))
}

/// The scene's three tables: each tier's measurement, the reference of each case, and each
/// tier's largest error per a/λ band.
struct Tables {
    main: Table,
    reference: Table,
    bands: Table,
}

impl Tables {
    fn new() -> Self {
        let mut reference_header = vec!["aspect_ratio", "tau_max_mpa"];
        reference_header.extend(PHYSICS_COLUMNS);
        reference_header.extend([
            "a_over_lambda_min",
            "a_over_lambda_max",
            "order_meshes",
            "observed_order",
            "order_used",
            "reference_error_estimate",
            "reference_uncertainty",
        ]);
        Tables {
            main: Table::new("", &MAIN_HEADER),
            reference: Table::new("reference", &reference_header),
            bands: Table::new("bands", &BANDS_HEADER),
        }
    }

    fn push_reference(&mut self, s: &SpeedAccuracyScene, r: &Reference, ar: f64, tau: f64) {
        let xs = s.a_over_lambda.values();
        let [order_mesh, coarse, fine] = s.order_meshes();
        let mut row: Vec<Cell> = vec![ar.into(), tau.into()];
        row.extend(FePhysics::from(&s.fe).by_column().map(|(_, v)| v.into()));
        row.extend([
            xs[0].into(),
            xs[xs.len() - 1].into(),
            format!("{order_mesh} {coarse} {fine}").into(),
            r.observed_order.into(),
            r.order_used.into(),
            r.error_estimate.into(),
            r.uncertainty.into(),
        ]);
        self.reference.push(row);
    }

    /// The largest error of `tier`'s `values` against `reference` in each a/λ band.
    fn push_bands(
        &mut self,
        s: &SpeedAccuracyScene,
        tier: &Tier,
        values: Option<&[f64]>,
        reference: &[f64],
        ar: f64,
        tau: f64,
    ) {
        let xs = s.a_over_lambda.values();
        for band in s.error_bands.windows(2) {
            let in_band: Vec<usize> = (0..xs.len())
                .filter(|&i| band[0] <= xs[i] && xs[i] <= band[1])
                .collect();
            let error = values.map(|v| {
                let pick = |w: &[f64]| in_band.iter().map(|&i| w[i]).collect::<Vec<_>>();
                relative_errors(&pick(v), &pick(reference)).max
            });
            self.bands.push(vec![
                tier.name().into(),
                ar.into(),
                tau.into(),
                band[0].into(),
                band[1].into(),
                error.into(),
            ]);
        }
    }

    fn push_measurements(&mut self, ms: &[Measurement], front: &[usize], ar: f64, tau: f64) {
        for (i, m) in ms.iter().enumerate() {
            self.main.push(vec![
                m.tier.name().into(),
                ar.into(),
                tau.into(),
                m.status.clone().into(),
                m.errors.map(|e| e.max).into(),
                m.errors.map(|e| e.rms).into(),
                m.seconds_per_curve.into(),
                m.seconds_per_point.into(),
                m.fe.as_ref().map(|f| f.dofs as f64).into(),
                m.fe.as_ref().map(|f| f.load_steps as f64).into(),
                m.fe.as_ref().map(|f| f.newton_iterations as f64).into(),
                front.contains(&i).into(),
            ]);
        }
    }

    fn into_vec(self) -> Vec<Table> {
        vec![self.main, self.reference, self.bands]
    }
}

const MAIN_HEADER: [&str; 12] = [
    "tier",
    "aspect_ratio",
    "tau_max_mpa",
    "status",
    "max_rel_error",
    "rms_rel_error",
    "seconds_per_curve",
    "seconds_per_point",
    "dofs",
    "load_steps",
    "newton_iterations",
    "pareto",
];

const BANDS_HEADER: [&str; 6] = [
    "tier",
    "aspect_ratio",
    "tau_max_mpa",
    "a_over_lambda_from",
    "a_over_lambda_to",
    "max_rel_error",
];

/// The footer: how the error and the wall time are measured.
fn footer(s: &SpeedAccuracyScene, timings: &Timings, timings_name: &str) -> Vec<String> {
    let xs = s.a_over_lambda.values();
    let [order_mesh, coarse, fine] = s.order_meshes();
    let physics = FePhysics::from(&s.fe);
    let mut footer = vec![
        format!(
            "Error: largest over a/λ ∈ [{}, {}] against the Richardson extrapolation of FE meshes {coarse} and {fine}",
            xs[0],
            xs[xs.len() - 1],
        ),
        format!(
            "(order observed with mesh {order_mesh}); E* = {} MPa, κ/G = {}, h/λ = {}, μ = {}. FE markers right to left: finer meshes.",
            physics.estar_mpa,
            physics.kappa_over_g,
            physics.thickness_over_lambda,
            physics.friction_coefficient
        ),
        format!(
            "Wall time per curve (closed forms: {} points) from {timings_name}:",
            xs.len()
        ),
    ];
    footer.extend(timings.describe());
    footer
}

