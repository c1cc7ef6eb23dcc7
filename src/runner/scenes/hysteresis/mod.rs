//! Beyond the paper: loading–unloading cycles of the finite-strain frictional model, and the
//! energy each dissipates (docs/replication.md R12).
//!
//! Every case loads to its target and unloads back to zero load with the slip history carried
//! through (`fe::solve_cycle`). The dissipated energy per cycle, per unit length of ridge and
//! per wavelength, is `W = ∮ p̄ dδ` over `E* λ²` (`fe::cycle_work_over_estar_lambda2`), δ the
//! slab's approach. Two checks run on every result, and a violation fails the run: a
//! frictionless loop closes, `|W| ≤ CLOSURE_RTOL · W_load`, and no loop creates energy,
//! `W ≥ −CLOSURE_RTOL · W_load` (`W_load = ∫ p̄ dδ` along loading).

mod loop_panels;

use crate::accuracy::richardson;
use crate::fe::{cycle_work_over_estar_lambda2, CurvePoint, Interface, LoadDirection};
use crate::profile::Profile;
use crate::runner::scenes::scene_output::{Layout, Remarks};
use crate::runner::scenes::{Scene, SceneContext, SceneResult};
use crate::runner::sweep::fe_cases::{
    self, surface_label, FeCase, FeOutcome, FePhysics, SolvedCases,
};
use crate::runner::RunOptions;
use crate::spec::{Bounded, FeSection, NonNegative, Positive, SpecError, Validator};
use crate::table::{Cell, Table};
use anyhow::{bail, Result};
use serde::Deserialize;

/// Largest `|W| / W_load` of a loop that closes: the unloading branch revisits the loading
/// branch's loads, so a reversible loop differs from zero only by the solver's tolerance
/// (residual 10⁻¹⁰ of the largest nodal force; tests/solver/fe_hysteresis.rs pins the closure far
/// below this bound). The same bound is the round-off allowance of "no loop creates energy".
pub const CLOSURE_RTOL: f64 = 1e-6;

/// Loading–unloading cycles: p̄–a loops per aspect ratio and shear strength, their
/// dissipated energy, and a confinement series (layer thickness) at one case.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HysteresisScene {
    /// Aspect ratios Δ/λ: one loop panel each, one dissipation line each.
    pub aspect_ratios: Vec<Bounded<Positive>>,
    /// The finite-element physics, the loops' shear strengths (`tau_max_mpa`, at `estar_mpa`)
    /// and the load target (`until_a_over_lambda`); with `error_estimate`, every loop is also
    /// solved on the next coarser mesh for a Richardson estimate of its dissipation.
    pub fe: FeSection,
    /// Loops at several layer thicknesses (absent: none).
    pub confinement: Option<Confinement>,
}

/// The confinement series: one case at several layer thicknesses, loaded to a mean pressure
/// (a thin, nearly incompressible layer stiffens sharply, so a common contact width is out of
/// reach of the thinnest).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Confinement {
    /// Aspect ratio Δ/λ of a sinusoid; or, instead, `profile`.
    pub aspect_ratio: Option<Bounded<Positive>>,
    /// A profile of cosine harmonics `[[1, AR₁], [n, AR₂], …]` (docs/replication.md R13) or the
    /// command line's text for one (`"weierstrass:AR0,gamma,D,K"`, R14), instead of
    /// `aspect_ratio`.
    pub profile: Option<crate::spec::ProfileField>,
    /// Shear strength, MPa (at the FE section's `estar_mpa`).
    pub tau_max_mpa: Bounded<NonNegative>,
    /// Layer thicknesses h/λ.
    pub thickness_over_lambda: Vec<Bounded<Positive>>,
    /// Load until p̄/E* is this (`fe::SolveOptions::until_p_over_estar`); the FE section's
    /// `until_a_over_lambda` caps a/λ on the way.
    pub until_p_over_estar: Bounded<Positive>,
}

impl Confinement {
    /// The rigid surface: the sinusoid of `aspect_ratio` or the `profile` (validated: exactly
    /// one of them).
    fn surface(&self) -> Profile {
        crate::spec::validated_surface(self.aspect_ratio.map(|a| a.get()), self.profile.as_ref())
    }
}

/// The two series of loops of the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum LoopSeries {
    /// Over aspect ratio and shear strength, at the FE section's layer thickness.
    AspectRatio,
    /// Over layer thickness, at one case.
    Confinement,
}

impl LoopSeries {
    /// The name in the CSV tables.
    fn name(self) -> &'static str {
        match self {
            LoopSeries::AspectRatio => "aspect_ratio",
            LoopSeries::Confinement => "confinement",
        }
    }
}

/// One loop of the scene: its case and which series it belongs to.
struct Loop {
    case: FeCase,
    series: LoopSeries,
}

impl HysteresisScene {
    fn loops(&self, opts: &RunOptions) -> Vec<Loop> {
        let ars: Vec<f64> = self.aspect_ratios.iter().map(|a| a.get()).collect();
        let mut loops: Vec<Loop> = fe_cases::section_cases(&self.fe, &ars, opts)
            .into_iter()
            .map(|c| Loop {
                case: c.with_unloading(),
                series: LoopSeries::AspectRatio,
            })
            .collect();
        if let Some(c) = &self.confinement {
            let surface = c.surface();
            let mut options = self
                .fe
                .options(&[surface.aspect_ratio], opts.fe_mesh_override);
            options.until_p_over_estar = Some(c.until_p_over_estar.get());
            for h in &c.thickness_over_lambda {
                let physics = FePhysics {
                    thickness_over_lambda: h.get(),
                    ..FePhysics::from(&self.fe)
                };
                let case = FeCase::for_profile(&physics, &surface, c.tau_max_mpa.get(), options);
                loops.push(Loop {
                    case: case.with_unloading(),
                    series: LoopSeries::Confinement,
                });
            }
        }
        loops
    }
}

impl Scene for HysteresisScene {
    /// Every loop; with `error_estimate`, then each on the next coarser mesh.
    fn fe_cases(&self, opts: &RunOptions) -> Vec<FeCase> {
        let cases = self.loops(opts).into_iter().map(|l| l.case).collect();
        fe_cases::with_coarser_cases(cases, self.fe.error_estimate)
    }

    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        run(ctx.title, self, ctx.opts)
    }

    fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        v.non_empty("hysteresis.aspect_ratios", self.aspect_ratios.len())?;
        let ars: Vec<f64> = self.aspect_ratios.iter().map(|a| a.get()).collect();
        v.fe_section("hysteresis.fe", &self.fe, None, &ars)?;
        if let Some(c) = &self.confinement {
            v.fe_surface(
                "hysteresis.confinement",
                &self.fe,
                c.aspect_ratio.map(|a| a.get()),
                c.profile.as_ref(),
            )?;
            v.non_empty(
                "hysteresis.confinement.thickness_over_lambda",
                c.thickness_over_lambda.len(),
            )?;
        }
        Ok(())
    }
}

/// The dissipation of one loop, with the loading work and the mesh-convergence estimate.
struct Dissipation {
    loading_work: f64,
    work: f64,
    /// The work of friction at the face over the loop ([`CurvePoint::friction_work_over_estar_lambda2`]
    /// at its last point): the dissipation measured at the face, the energy audit of `work`.
    face_work: f64,
    /// W on the next coarser mesh, and the Richardson extrapolation of the two.
    coarse: Option<(f64, f64)>,
}

fn loading_work(points: &[CurvePoint]) -> f64 {
    cycle_work_over_estar_lambda2(points, &[])
}

fn run(title: &str, s: &HysteresisScene, opts: &RunOptions) -> Result<SceneResult> {
    let loops = s.loops(opts);
    let solved = SolvedCases::solve(s.fe_cases(opts), opts)?;
    let order = match s.fe.error_estimate {
        true => Some(crate::accuracy::measured::committed()?.fe_order()?),
        false => None,
    };
    let estar = s.fe.estar_mpa.get();
    let mut tables = Tables::new(order.is_some());
    let mut incomplete = vec![];
    let mut results: Vec<SolvedLoop> = vec![];
    for l in &loops {
        let c = &l.case;
        let o = solved.outcome(c).expect("every loop was solved");
        let (surface, h) = (
            surface_label(&c.problem.profile()),
            c.problem.thickness_over_lambda,
        );
        let label = format!("{surface}, τ_max/E* = {}, h/λ = {h}", c.tau_max_mpa / estar);
        tables.push_points(l, o, estar);
        let d = match &o.failure {
            Some(f) => {
                let (branch, reached) = match o.unloading.last() {
                    Some(p) => ("unloading", p.p_over_estar),
                    None => ("loading", o.points.last().map_or(0.0, |p| p.p_over_estar)),
                };
                incomplete.push(format!(
                    "loop {label} stopped while {branch} at p̄/E* = {reached:.4}: {f}"
                ));
                tables.push_dissipation(l, o, estar, Err(format!("incomplete ({branch}): {f}")));
                None
            }
            None => {
                let d = dissipation(c, o, &solved, order, &label)?;
                tables.push_dissipation(l, o, estar, Ok(&d));
                Some(d)
            }
        };
        results.push((l, o, d));
    }
    let panels = loop_panels::figure_panels(s, &results);
    let mut remarks = Remarks::with_footer(loop_panels::footer(s, &results, order)?);
    remarks.incomplete = incomplete;
    remarks.count_incomplete(
        "labelled `incomplete`, drawn as far as they got; see the status column of the dissipation table",
    );
    let rows = panels.len().div_ceil(3);
    let layout = Layout {
        grid: (rows, 3),
        panel_px: (430, 430),
        margin_px: 150,
        font_px: 15,
    };
    // incomplete loops are reported by the run itself (`SceneResult::incomplete`), not as notes
    let tables = vec![tables.points, tables.dissipation];
    Ok(remarks.finish(title, layout, panels, tables))
}

/// The dissipation of the complete loop `o` of case `c`, checked (a frictionless loop closes,
/// no loop creates energy), with its Richardson estimate when `order` is given.
fn dissipation(
    c: &FeCase,
    o: &FeOutcome,
    solved: &SolvedCases,
    order: Option<f64>,
    label: &str,
) -> Result<Dissipation> {
    let w_load = loading_work(&o.points);
    let w = cycle_work_over_estar_lambda2(&o.points, &o.unloading);
    let reversible = c.problem.interface == Interface::Frictionless;
    if reversible && w.abs() > CLOSURE_RTOL * w_load {
        bail!("the frictionless loop {label} does not close: dissipated W/(E*λ²) = {w:.3e}, beyond {CLOSURE_RTOL:e} of the loading work {w_load:.4e}");
    }
    if w < -CLOSURE_RTOL * w_load {
        bail!("the loop {label} creates energy: W/(E*λ²) = {w:.3e} < 0 beyond {CLOSURE_RTOL:e} of the loading work {w_load:.4e}");
    }
    // W on the next coarser mesh, and the Richardson extrapolation from the two
    let coarse = order.and_then(|order| {
        let (coarse_case, ratio) = fe_cases::coarser_cases(std::slice::from_ref(c))
            .pop()
            .flatten()?;
        let co = solved.outcome(&coarse_case)?;
        if co.failure.is_some() {
            return None;
        }
        let wc = cycle_work_over_estar_lambda2(&co.points, &co.unloading);
        Some((wc, richardson(wc, w, ratio, order)))
    });
    let face_work = crate::fe::cycle_friction_work_over_estar_lambda2(&o.unloading);
    Ok(Dissipation {
        loading_work: w_load,
        work: w,
        face_work,
        coarse,
    })
}

/// The scene's two tables: every point of every loop, and each loop's dissipation.
struct Tables {
    points: Table,
    dissipation: Table,
    /// The dissipation table has the mesh-convergence columns.
    with_estimates: bool,
}

impl Tables {
    fn new(with_estimates: bool) -> Self {
        let mut dissipation_header = vec![
            "series",
            "aspect_ratio",
            "profile",
            "tau_max_over_estar",
            "thickness_over_lambda",
            "peak_a_over_lambda",
            "peak_p_over_estar",
            "loading_work_over_estar_lambda2",
            "dissipation_over_estar_lambda2",
            "dissipated_fraction",
            "face_friction_work_over_estar_lambda2",
        ];
        if with_estimates {
            dissipation_header.extend([
                "dissipation_coarse_mesh",
                "dissipation_richardson",
                "dissipation_error_estimate",
            ]);
        }
        dissipation_header.push("status");
        Tables {
            points: Table::new("", &POINTS_HEADER),
            dissipation: Table::new("dissipation", &dissipation_header),
            with_estimates,
        }
    }

    /// Every point of the loop `o`, loading then unloading.
    fn push_points(&mut self, l: &Loop, o: &FeOutcome, estar_mpa: f64) {
        let c = &l.case;
        for (branch, pts) in [
            (LoadDirection::Loading, &o.points),
            (LoadDirection::Unloading, &o.unloading),
        ] {
            for p in pts {
                self.points.push(vec![
                    l.series.name().into(),
                    c.problem.aspect_ratio.into(),
                    c.problem.profile().to_string().into(),
                    (c.tau_max_mpa / estar_mpa).into(),
                    c.problem.thickness_over_lambda.into(),
                    branch.name().into(),
                    p.a_over_lambda.into(),
                    p.p_over_estar.into(),
                    p.slab_displacement_over_lambda.into(),
                ]);
            }
        }
    }

    /// The loop's dissipation, or (`Err`) the status of a loop that stopped short.
    fn push_dissipation(
        &mut self,
        l: &Loop,
        o: &FeOutcome,
        estar_mpa: f64,
        d: Result<&Dissipation, String>,
    ) {
        let c = &l.case;
        let peak = o.points.last();
        let mut row: Vec<Cell> = vec![
            l.series.name().into(),
            c.problem.aspect_ratio.into(),
            c.problem.profile().to_string().into(),
            (c.tau_max_mpa / estar_mpa).into(),
            c.problem.thickness_over_lambda.into(),
            peak.map(|p| p.a_over_lambda).into(),
            peak.map(|p| p.p_over_estar).into(),
        ];
        let empty = || [Cell::Empty, Cell::Empty, Cell::Empty];
        match d {
            Err(status) => {
                row.extend(empty());
                row.push(Cell::Empty);
                if self.with_estimates {
                    row.extend(empty());
                }
                row.push(status.into());
            }
            Ok(d) => {
                let (w_load, w) = (d.loading_work, d.work);
                row.extend([w_load.into(), w.into(), (w / w_load).into()]);
                row.push(d.face_work.into());
                if self.with_estimates {
                    match d.coarse {
                        Some((wc, limit)) => {
                            row.extend([wc.into(), limit.into(), (limit - w).abs().into()])
                        }
                        None => row.extend(empty()),
                    }
                }
                row.push("complete".into());
            }
        }
        self.dissipation.push(row);
    }
}

const POINTS_HEADER: [&str; 9] = [
    "series",
    "aspect_ratio",
    "profile",
    "tau_max_over_estar",
    "thickness_over_lambda",
    "branch",
    "a_over_lambda",
    "p_over_estar",
    "slab_displacement_over_lambda",
];

/// `(x, y)` of the points of both branches of `o`, loading then unloading.
fn branch_points(
    o: &FeOutcome,
    x: impl Fn(&CurvePoint) -> f64,
) -> [(LoadDirection, Vec<(f64, f64)>); 2] {
    let xy = |pts: &[CurvePoint]| pts.iter().map(|p| (x(p), p.p_over_estar)).collect();
    [
        (LoadDirection::Loading, xy(&o.points)),
        (LoadDirection::Unloading, xy(&o.unloading)),
    ]
}

/// One loop as solved: its case, its curve, its dissipation (none: it stopped short).
type SolvedLoop<'a> = (&'a Loop, &'a FeOutcome, Option<Dissipation>);
