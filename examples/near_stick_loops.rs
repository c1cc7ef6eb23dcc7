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
//!   with its error bar (the distance of the finest mesh from it). The loops run on all cores.
//!
//! `cargo run --release --example near_stick_loops -- unloading-steps|meshes`

use rayon::prelude::*;
use std::ops::ControlFlow;
use wavy::accuracy::richardson;
use wavy::fe::{
    cycle_work_over_estar_lambda2, solve_cycle, Interface, Kinematics, LayerProblem, MeshLevel,
    SolveOptions, StepOptions,
};

/// The loop's work and the face's work of friction at its end, over E* λ².
#[derive(Clone, Copy)]
struct LoopEnergy {
    work: f64,
    face: f64,
}

/// One loop: AR 0.3 on the nearly incompressible layer one wavelength thick, μ 1, τ_max/E* `tau`,
/// elastic slip `elastic_slip_over_element` (0: exact stick), on `mesh`, unloading each loading
/// interval in `unloading_substeps` steps.
fn near_stick_loop(
    tau: f64,
    elastic_slip_over_element: f64,
    mesh: MeshLevel,
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
        until_a_over_lambda: 0.4,
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
        face: curve
            .unloading
            .last()
            .map_or(0.0, |p| p.friction_work_over_estar_lambda2),
    }
}

fn unloading_steps() {
    println!("| τ_max/E* | unloading steps per loading step | ∮ p̄ dd / (E* λ²) | face's work / (E* λ²) | face / loop − 1 |");
    println!("|---|---|---|---|---|");
    for tau in [0.05, 0.2] {
        for substeps in [1, 2, 4, 8] {
            let e = near_stick_loop(tau, 0.005, MeshLevel::Default, substeps);
            println!(
                "| {tau} | {substeps} | {:.5e} | {:.5e} | {:+.2} % |",
                e.work,
                e.face,
                100.0 * (e.face / e.work - 1.0)
            );
        }
    }
}

fn meshes() {
    const SHEAR_STRENGTHS: [f64; 4] = [0.05, 0.1, 0.15, 0.2];
    const ELEMENTS: [usize; 3] = [32, 48, 72];
    const RATIO: f64 = 1.5;
    let cases: Vec<(f64, usize)> = SHEAR_STRENGTHS
        .iter()
        .flat_map(|&t| ELEMENTS.iter().map(move |&m| (t, m)))
        .collect();
    let energies: Vec<LoopEnergy> = cases
        .par_iter()
        .map(|&(t, m)| near_stick_loop(t, 0.0, MeshLevel::along_face(m), 4))
        .collect();
    println!("| τ_max/E* | W (face's work) on 32 | on 48 | on 72 | observed order | W extrapolated ± error bar |");
    println!("|---|---|---|---|---|---|");
    for (tau, e) in SHEAR_STRENGTHS.iter().zip(energies.chunks(3)) {
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

fn main() {
    match std::env::args().nth(1).as_deref() {
        Some("unloading-steps") => unloading_steps(),
        Some("meshes") => meshes(),
        _ => {
            eprintln!("usage: near_stick_loops unloading-steps|meshes");
            std::process::exit(2);
        }
    }
}
