//! The Newton work of the 18 Fig. 3 curves (AR ∈ {0.1, 0.18, 0.3} × τ_max ∈ {0, 0.01,
//! 0.05, 0.1, 0.15, 0.2} MPa, E* = 1 MPa, default mesh, to a/λ = 0.45, the figure's
//! physics): per curve the tangent assemblies and factorisations of every attempt, and
//! their totals, the counts the README's "Frictional speed" section compares solver
//! changes by (deterministic, unlike wall times on a noisy machine).
//!
//! Run: `cargo run --release --example fig3_work [-- --no-branch-switch] [-- --points FILE]`.
//! `--no-branch-switch` turns the semismooth choice of the friction branches off
//! (`SolveOptions::semismooth_friction`); `--points FILE` writes every point
//! (`AR τ a/λ p̄/E*`, 13 significant digits) to compare two builds' curves.
use rayon::prelude::*;
use wavy::fe::{solve_curve, SolveOptions};
#[path = "../benches/common/mod.rs"]
mod common;
use common::finite_layer_problem;

const ASPECT_RATIOS: [f64; 3] = [0.1, 0.18, 0.3];
const TAU_MAX_OVER_ESTAR: [f64; 6] = [0.0, 0.01, 0.05, 0.1, 0.15, 0.2];

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
    let cases: Vec<(f64, f64)> = ASPECT_RATIOS
        .iter()
        .flat_map(|&ar| TAU_MAX_OVER_ESTAR.iter().map(move |&tau| (ar, tau)))
        .collect();
    let opts = SolveOptions {
        semismooth_friction,
        ..Default::default()
    };
    let curves: Vec<_> = cases
        .par_iter()
        .map(|&(ar, tau)| {
            solve_curve(&finite_layer_problem(ar, tau), &opts, &mut |_| {})
                .unwrap_or_else(|f| panic!("AR {ar}, τ_max/E* {tau}: {}", f.error))
        })
        .collect();
    println!("| AR | τ_max (MPa) | tangent assemblies | factorisations |");
    println!("|---|---|---|---|");
    let (mut assemblies, mut factorisations) = (0, 0);
    let mut points = String::new();
    for (&(ar, tau), c) in cases.iter().zip(&curves) {
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
    println!("| all 18 | | {assemblies} | {factorisations} |");
    if let Some(path) = points_file {
        std::fs::write(&path, points).unwrap_or_else(|e| panic!("{path}: {e}"));
    }
}
