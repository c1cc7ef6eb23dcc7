//! The Newton work of the Fig. 3 curves: the finite-element cases of
//! `experiments/fig3_fe_vs_model.toml` (3 aspect ratios × 6 shear strengths, the spec's
//! physics and mesh, built by the runner as for the figure), per curve the tangent
//! assemblies and factorisations of every attempt, and their totals: the counts
//! docs/performance.md compares solver changes by (deterministic, unlike wall times on a
//! noisy machine).
//!
//! Run: `cargo run --release --example fig3_work [-- --no-branch-switch] [-- --points FILE]`.
//! `--no-branch-switch` turns the semismooth choice of the friction branches off
//! (`NewtonOptions::semismooth_friction`); `--points FILE` writes every point
//! (`AR τ a/λ p̄/E*`, 13 significant digits) to compare two builds' curves.
use rayon::prelude::*;
use std::ops::ControlFlow;
use std::path::Path;
use wavy::fe::{solve_curve, NewtonOptions, SolveOptions};
use wavy::runner::{load_spec, RunOptions};

const SPEC: &str = "experiments/fig3_fe_vs_model.toml";

fn main() {
    let mut semismooth_friction = true;
    let mut points_file = None;
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        match flag.as_str() {
            "--no-branch-switch" => semismooth_friction = false,
            "--points" => points_file = Some(it.next().expect("--points FILE")),
            other => panic!("unknown flag {other} (--no-branch-switch, --points FILE)"),
        }
    }
    let spec = load_spec(Path::new(SPEC)).unwrap_or_else(|e| panic!("{SPEC}: {e:#}"));
    let cases = spec.scene().fe_cases(&RunOptions::default());
    let curves: Vec<_> = cases
        .par_iter()
        .map(|case| {
            let opts = SolveOptions {
                newton: NewtonOptions {
                    semismooth_friction,
                    ..case.options.newton
                },
                ..case.options
            };
            solve_curve(&case.problem, &opts, &mut |_| ControlFlow::Continue(())).unwrap_or_else(
                |f| {
                    let ar = case.problem.aspect_ratio;
                    panic!("AR {ar}, τ_max {} MPa: {}", case.tau_max_mpa, f.error)
                },
            )
        })
        .collect();
    println!("| AR | τ_max (MPa) | tangent assemblies | factorisations |");
    println!("|---|---|---|---|");
    let (mut assemblies, mut factorisations) = (0, 0);
    let mut points = String::new();
    for (case, c) in cases.iter().zip(&curves) {
        let (ar, tau) = (case.problem.aspect_ratio, case.tau_max_mpa);
        println!(
            "| {ar} | {tau} | {} | {} |",
            c.work.tangent_assemblies, c.work.factorisations
        );
        assemblies += c.work.tangent_assemblies;
        factorisations += c.work.factorisations;
        for p in &c.points {
            points += &format!(
                "{ar} {tau} {:.12e} {:.12e}\n",
                p.a_over_lambda, p.p_over_estar
            );
        }
    }
    println!(
        "| all {} | | {assemblies} | {factorisations} |",
        cases.len()
    );
    if let Some(path) = points_file {
        std::fs::write(&path, points).unwrap_or_else(|e| panic!("{path}: {e}"));
    }
}
