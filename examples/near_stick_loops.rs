//! The hysteresis scene's AR 0.3 loops near full stick (μ 1, loaded to a/λ 0.4 and unloaded), two
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
//! `cargo run --release --example near_stick_loops -- unloading-steps|meshes [TAUS ELEMENTS [P]]`

use rayon::prelude::*;
use std::ops::ControlFlow;
use wavy::accuracy::richardson;
use wavy::fe::{
    cycle_friction_work_over_estar_lambda2, cycle_work_over_estar_lambda2, solve_cycle, Interface,
    Kinematics, LayerProblem, MeshLevel, SolveOptions, StepOptions,
};

/// The loop's work and the face's work of friction at its end, over E* λ².
#[derive(Clone, Copy)]
struct LoopEnergy {
    work: f64,
    face: f64,
}

/// One loop: AR 0.3 on the nearly incompressible layer one wavelength thick, μ 1, τ_max/E* `tau`,
/// elastic slip `elastic_slip_over_element` (0: exact stick), on `mesh`, loaded to a/λ 0.4 (or to
/// the mean pressure `until_p_over_estar`), unloading each loading interval in
/// `unloading_substeps` steps.
fn near_stick_loop(
    (tau, elastic_slip_over_element): (f64, f64),
    mesh: MeshLevel,
    until_p_over_estar: Option<f64>,
    unloading_substeps: usize,
) -> LoopEnergy {
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
    let curve =
        solve_cycle(&problem, &opts, &mut |_, _| ControlFlow::Continue(())).unwrap_or_else(|f| {
            panic!("τ_max/E* {tau}, {mesh:?}, {unloading_substeps} unloading steps: {f}")
        });
    LoopEnergy {
        work: cycle_work_over_estar_lambda2(&curve.points, &curve.unloading),
        face: cycle_friction_work_over_estar_lambda2(&curve.unloading),
    }
}

fn unloading_steps() {
    println!("| τ_max/E* | unloading steps per loading step | ∮ p̄ dd / (E* λ²) | face's work / (E* λ²) | face / loop − 1 |");
    println!("|---|---|---|---|---|");
    for tau in [0.05, 0.2] {
        for substeps in [1, 2, 4, 8] {
            let e = near_stick_loop((tau, 0.005), MeshLevel::Default, None, substeps);
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

/// A comma-separated list of numbers, or the usage error.
fn list<T: std::str::FromStr>(text: Option<&String>) -> Option<Vec<T>> {
    text.and_then(|t| t.split(',').map(|v| v.parse().ok()).collect())
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match (args.first().map(String::as_str), args.len()) {
        (Some("unloading-steps"), 1) => unloading_steps(),
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
    eprintln!("usage: near_stick_loops unloading-steps | meshes [TAU,… N1,N2,N3 [P_OVER_ESTAR]]");
    std::process::exit(2);
}
