//! The hysteresis scene's AR 0.3 loops near full stick (μ 1, loaded to a/λ 0.4 and unloaded), three
//! studies, one markdown table each:
//!
//! - `unloading-steps` (docs/verification.md, "The energy audit"): the default mesh and penalty
//!   law, τ_max/E* 0.05 and 0.2, unloaded with 1, 2, 4 and 8 unloading steps per loading step; per
//!   loop the loop's work ∮ p̄ dd (trapezoid rule, what the scene reports), the face's work of
//!   friction, and their difference. About 1½ minutes on one core.
//! - `meshes` (docs/results.md, "Near full stick"): exact stick, τ_max/E* 0.05, 0.1, 0.15 and 0.2,
//!   on 32, 48 and 72 face elements, four unloading steps per loading step (so that the load
//!   steps' error stays below the mesh's); per τ_max/E* the loop's work and the face's work per
//!   mesh, the order observed on the three meshes, and the Richardson limit of the loop's work
//!   with its error bar (the distance of the finest mesh from it). The loops run on all cores;
//!   about 5 minutes on two. `meshes TAUS ELEMENTS` takes other comma-separated shear strengths
//!   and three meshes, each 1.5 times the one before (e.g. `meshes 0.1,0.2 48,72,108`), and a
//!   mean pressure to load to instead of a/λ 0.4 (`meshes 0.2 48,72,108 1`).
//!
//! - `quadrature` (docs/verification.md, "The energy audit"): the default mesh and penalty law,
//!   τ_max/E* 0.05, 0.1 and 0.2, one loop unloaded in eight steps per loading step; the loop's work
//!   under other quadratures of the unloading branch (the trapezoid rule on 1, 2, 4 and 8 steps and
//!   its limit, Simpson's rule on two steps, the end-corrected trapezoid rule on one step with the
//!   fine steps' one-sided slopes), and the unloading Newton iterations with one and two steps.
//!   About a minute on two cores.
//!
//! `cargo run --release --example near_stick_loops -- unloading-steps|quadrature|meshes [TAUS ELEMENTS [P]]`

use rayon::prelude::*;
use std::ops::ControlFlow;
use wavy::accuracy::richardson;
use wavy::fe::{
    cycle_friction_work_over_estar_lambda2, cycle_work_over_estar_lambda2, solve_cycle, Curve,
    CurvePoint, Interface, Kinematics, LayerProblem, MeshLevel, SolveOptions, StepOptions,
};

/// The loop's work and the face's work of friction at its end, over E* λ².
#[derive(Clone, Copy)]
struct LoopEnergy {
    work: f64,
    face: f64,
}

/// One loop's energies ([`near_stick_curve`]).
fn near_stick_loop(
    law: (f64, f64),
    mesh: MeshLevel,
    until_p_over_estar: Option<f64>,
    unloading_substeps: usize,
) -> LoopEnergy {
    let curve = near_stick_curve(law, mesh, until_p_over_estar, unloading_substeps);
    LoopEnergy {
        work: cycle_work_over_estar_lambda2(&curve.points, &curve.unloading),
        face: cycle_friction_work_over_estar_lambda2(&curve.unloading),
    }
}

/// One loop: AR 0.3 on the nearly incompressible layer one wavelength thick, μ 1, τ_max/E* `tau`,
/// elastic slip `elastic_slip_over_element` (0: exact stick), on `mesh`, loaded to a/λ 0.4 (or to
/// the mean pressure `until_p_over_estar`), unloading each loading interval in
/// `unloading_substeps` steps.
fn near_stick_curve(
    (tau, elastic_slip_over_element): (f64, f64),
    mesh: MeshLevel,
    until_p_over_estar: Option<f64>,
    unloading_substeps: usize,
) -> Curve {
    let problem = LayerProblem {
        aspect_ratio: 0.3,
        finer_harmonics: wavy::profile::FinerHarmonics::NONE,
        thickness_over_lambda: 1.0,
        kappa_over_g: 1000.0,
        kinematics: Kinematics::Finite,
        interface: Interface::coulomb_orowan(1.0, tau, elastic_slip_over_element),
    };
    let opts = SolveOptions {
        mesh,
        until_a_over_lambda: match until_p_over_estar {
            None => 0.4,
            Some(_) => SolveOptions::default().until_a_over_lambda,
        },
        until_p_over_estar,
        steps: StepOptions {
            unloading_substeps,
            ..StepOptions::default()
        },
        ..SolveOptions::default()
    };
    solve_cycle(&problem, &opts, &mut |_, _| ControlFlow::Continue(())).unwrap_or_else(|f| {
        panic!("τ_max/E* {tau}, {mesh:?}, {unloading_substeps} unloading steps: {f}")
    })
}

fn unloading_steps() {
    let penalty = wavy::defaults::elastic_slip_over_element();
    println!("| τ_max/E* | unloading steps per loading step | ∮ p̄ dd / (E* λ²) | face's work / (E* λ²) | face / loop − 1 |");
    println!("|---|---|---|---|---|");
    for tau in [0.05, 0.2] {
        for substeps in [1, 2, 4, 8] {
            let e = near_stick_loop((tau, penalty), MeshLevel::Default, None, substeps);
            println!(
                "| {tau} | {substeps} | {:.5e} | {:.5e} | {:+.2} % |",
                e.work,
                e.face,
                100.0 * (e.face / e.work - 1.0)
            );
        }
    }
}

fn meshes(shear_strengths: &[f64], elements: &[usize], until_p_over_estar: Option<f64>) {
    const RATIO: f64 = 1.5;
    let cases: Vec<(f64, usize)> = shear_strengths
        .iter()
        .flat_map(|&t| elements.iter().map(move |&m| (t, m)))
        .collect();
    let energies: Vec<LoopEnergy> = cases
        .par_iter()
        .map(|&(t, m)| near_stick_loop((t, 0.0), MeshLevel::along_face(m), until_p_over_estar, 4))
        .collect();
    println!(
        "| τ_max/E* | W (face's work) on {} | on {} | on {} | observed order | W extrapolated ± error bar |",
        elements[0], elements[1], elements[2]
    );
    println!("|---|---|---|---|---|---|");
    for (tau, e) in shear_strengths.iter().zip(energies.chunks(3)) {
        let w: Vec<f64> = e.iter().map(|x| x.work).collect();
        let order = ((w[1] - w[0]) / (w[2] - w[1])).abs().ln() / RATIO.ln();
        let limit = richardson(w[1], w[2], RATIO, order);
        let cells: Vec<String> = e
            .iter()
            .map(|x| format!("{:.4e} ({:.4e})", x.work, x.face))
            .collect();
        println!(
            "| {tau} | {} | {order:.2} | {limit:.4e} ± {:.1e} |",
            cells.join(" | "),
            (limit - w[2]).abs()
        );
    }
}

/// Unloading steps per loading step of the fine loop of [`quadrature`].
const FINE_SUBSTEPS: usize = 8;

/// `(d/λ, p̄/E*)` of each point.
fn d_p(points: &[CurvePoint]) -> Vec<(f64, f64)> {
    (points.iter())
        .map(|q| (q.slab_displacement_over_lambda, q.p_over_estar))
        .collect()
}

/// The slope `dp/dd` at `pts[0]` of the parabola through `pts[0..3]`.
fn one_sided_slope(pts: [(f64, f64); 3]) -> f64 {
    let [(x0, y0), (x1, y1), (x2, y2)] = pts;
    y0 * (2.0 * x0 - x1 - x2) / ((x0 - x1) * (x0 - x2))
        + y1 * (x0 - x2) / ((x1 - x0) * (x1 - x2))
        + y2 * (x0 - x1) / ((x2 - x0) * (x2 - x1))
}

/// The unloading branch's integral over its coarse intervals (one per loading interval, the
/// `FINE_SUBSTEPS` fine steps of each), by two rules: Simpson's rule on the coarse interval's
/// midpoint (what two unloading steps per loading step give), and the Hermite (end-corrected
/// trapezoid) rule on the coarse points, `h (p₀ + p₁)/2 + h²/12 (p₀' − p₁')`, with the one-sided
/// slopes of each end read off the fine points inside the interval (what slopes from the
/// solver's tangent would give).
struct UnloadingRules {
    simpson: f64,
    hermite: f64,
}

fn unloading_rules(fine: &[(f64, f64)]) -> UnloadingRules {
    let n = FINE_SUBSTEPS;
    let (mut simpson, mut hermite) = (0.0, 0.0);
    for w in fine.chunks(n).zip(fine.chunks(n).skip(1)) {
        let (c, next) = w;
        let (p0, pm, p1) = (c[0], c[n / 2], next[0]);
        let h = p1.0 - p0.0;
        simpson += h / 6.0 * (p0.1 + 4.0 * pm.1 + p1.1);
        let slope0 = one_sided_slope([c[0], c[1], c[2]]);
        let slope1 = one_sided_slope([next[0], c[n - 1], c[n - 2]]);
        hermite += h * (p0.1 + p1.1) / 2.0 + h * h / 12.0 * (slope0 - slope1);
    }
    UnloadingRules { simpson, hermite }
}

/// What the loop's work `∮ p̄ dd` would be under other quadratures of the unloading branch, on the
/// scene's loops (default mesh, penalty law), from one loop unloaded in `FINE_SUBSTEPS` steps per
/// loading step: the trapezoid rule on 1, 2, 4 and 8 steps (the unloading branch does not move
/// with them, docs/verification.md), their second-order Richardson limit from 4 and 8, Simpson's
/// rule on two steps and the Hermite rule on one; and the unloading Newton iterations of the loop
/// solved with one and with two unloading steps per loading step.
fn quadrature() {
    let taus = [0.05, 0.1, 0.2];
    let penalty = wavy::defaults::elastic_slip_over_element();
    let runs: Vec<(f64, usize)> = (taus.iter())
        .flat_map(|&t| [1, 2, FINE_SUBSTEPS].map(|m| (t, m)))
        .collect();
    let curves: Vec<Curve> = runs
        .par_iter()
        .map(|&(t, m)| near_stick_curve((t, penalty), MeshLevel::Default, None, m))
        .collect();
    println!("| τ_max/E* | trapezoid, 1 / 2 / 4 / 8 steps | limit | Simpson, 2 steps | Hermite, 1 step | W / limit − 1: trapezoid 1 step, Simpson 2, Hermite 1 | unloading Newton iterations, 1 / 2 steps |");
    println!("|---|---|---|---|---|---|---|");
    for (tau, c) in taus.iter().zip(curves.chunks(3)) {
        let iterations =
            |curve: &Curve| -> usize { curve.unloading.iter().map(|q| q.newton_iterations).sum() };
        let fine = &c[2];
        // the trapezoid rule as the scene takes it, on every (8/m)-th unloading point
        let w = [1, 2, 4, 8].map(|m| {
            let every = FINE_SUBSTEPS / m;
            let coarse: Vec<CurvePoint> = fine.unloading[every - 1..]
                .iter()
                .step_by(every)
                .copied()
                .collect();
            cycle_work_over_estar_lambda2(&fine.points, &coarse)
        });
        let limit = richardson(w[2], w[3], 2.0, 2.0);
        let load_work = cycle_work_over_estar_lambda2(&fine.points, &[]);
        let loading = d_p(&fine.points);
        let branch = [&loading[loading.len() - 1..], &d_p(&fine.unloading)].concat();
        let rules = unloading_rules(&branch);
        let simpson = load_work + rules.simpson;
        let hermite = load_work + rules.hermite;
        let rel = |x: f64| 100.0 * (x / limit - 1.0);
        println!(
            "| {tau} | {:.4e} / {:.4e} / {:.4e} / {:.4e} | {limit:.4e} | {simpson:.4e} | {hermite:.4e} | {:+.2} % / {:+.2} % / {:+.2} % | {} / {} |",
            w[0],
            w[1],
            w[2],
            w[3],
            rel(w[0]),
            rel(simpson),
            rel(hermite),
            iterations(&c[0]),
            iterations(&c[1]),
        );
    }
}

/// A comma-separated list of numbers, or the usage error.
fn list<T: std::str::FromStr>(text: Option<&String>) -> Option<Vec<T>> {
    text.and_then(|t| t.split(',').map(|v| v.parse().ok()).collect())
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match (args.first().map(String::as_str), args.len()) {
        (Some("unloading-steps"), 1) => unloading_steps(),
        (Some("quadrature"), 1) => quadrature(),
        (Some("meshes"), 1) => meshes(&[0.05, 0.1, 0.15, 0.2], &[32, 48, 72], None),
        (Some("meshes"), 3 | 4) => {
            let until_p = args.get(3).map(|p| p.parse::<f64>().ok());
            match (
                list::<f64>(args.get(1)),
                list::<usize>(args.get(2)),
                until_p,
            ) {
                (Some(taus), Some(elements), None | Some(Some(_))) if elements.len() == 3 => {
                    meshes(&taus, &elements, until_p.flatten())
                }
                _ => usage(),
            }
        }
        _ => usage(),
    }
}

fn usage() {
    eprintln!(
        "usage: near_stick_loops unloading-steps | quadrature | meshes [TAU,… N1,N2,N3 [P_OVER_ESTAR]]"
    );
    std::process::exit(2);
}
