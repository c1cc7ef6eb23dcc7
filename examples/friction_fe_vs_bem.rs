//! The finite elements against the frictional boundary elements on the same load path (issue 43,
//! docs/verification.md, "The finite elements against it"): a compressible layer bonded to a
//! rigid base, linear kinematics, exact stick, loaded to a/λ 0.3 through the FE's own load steps
//! (one per contact-face node event) and unloaded through them. The boundary elements are driven
//! through the FE's mean pressures, increment for increment, so that both solve the same
//! backward-Euler problem of friction and what differs is the discretisation of space; a second
//! boundary-element loading in many small steps gives the path's own step error. μ 0 is the
//! frictionless baseline of the same comparison. One markdown table row per case and mesh.
//!
//! `cargo run --release --example friction_fe_vs_bem [-- H N1,N2,.. [KAPPA_OVER_G]]`: the layer
//! thickness h/λ (default 0.25), the FE meshes (face elements, default 48,96,192) and the layer's
//! κ/G (default 2.1667, ν 0.3). The cases run on all
//! cores; about 16 minutes on two at the defaults.

use rayon::prelude::*;
use std::ops::ControlFlow;
use wavy::bem::frictional_contact::{FrictionalProblem, InterfaceLaw, NormalCoupling};
use wavy::bem::frictional_curve::{follow_pressures, outermost_edge, FrictionalCurve};
use wavy::bem::ElasticBody;
use wavy::fe::{
    cycle_friction_work_over_estar_lambda2, solve_cycle, CurvePoint, Interface, Kinematics,
    LayerProblem, LoadDirection, MeshLevel, SolveOptions,
};
use wavy::profile::Profile;

/// One frictional case: the indenter's aspect ratio, the layer's κ/G, μ and τ_max/E*.
#[derive(Clone, Copy)]
struct Case {
    ar: f64,
    kappa_over_g: f64,
    mu: f64,
    tau_max_over_estar: f64,
}

/// Grid points per wavelength of the boundary elements (a/λ 0.03 spans 123 of them).
const GRID: usize = 4096;
/// The boundary elements' tolerance (as `wavy solve --solver bem`).
const TOL: f64 = 1e-10;
/// Even load steps of the boundary elements' own reference path.
const FINE_STEPS: usize = 320;
/// Where the comparison starts: below it the contact spans few face elements.
const FROM_A: f64 = 0.03;

/// What one mesh of one case measured against the boundary elements on its load path.
struct Comparison {
    points: usize,
    /// The FE's last mean pressure (p̄/E*).
    p_over_estar: f64,
    /// Largest |a_FE/a_BEM − 1| over the points from [`FROM_A`].
    a_error: f64,
    /// Largest |c_FE − c_BEM| in units of the face element at the contact edge.
    stick_error_elements: f64,
    /// The face's work of friction over the loop, FE and BEM (E* λ²).
    dissipation_fe: f64,
    dissipation_bem: f64,
    /// c/a of both at the last loading point.
    stick_ratio_fe: f64,
    stick_ratio_bem: f64,
}

/// The FE's loop: its loading points and its unloading points.
fn fe_loop(
    case: Case,
    thickness: f64,
    nx: usize,
) -> Result<(Vec<CurvePoint>, Vec<CurvePoint>), String> {
    let problem = LayerProblem {
        thickness_over_lambda: thickness,
        kappa_over_g: case.kappa_over_g,
        kinematics: Kinematics::Linear,
        interface: Interface::coulomb_orowan(case.mu, case.tau_max_over_estar, 0.0),
        ..wavy::defaults::layer_problem(case.ar)
    };
    let opts = SolveOptions {
        mesh: MeshLevel::Elements {
            nx,
            // as many across h as along the face's half wavelength per λ, at most the default's
            // nx/2 (a layer one wavelength thick)
            ny: ((nx as f64 * thickness).round() as usize).clamp(4, nx / 2),
        },
        until_a_over_lambda: 0.3,
        ..Default::default()
    };
    let curve = solve_cycle(&problem, &opts, &mut |_: LoadDirection, _: &CurvePoint| {
        ControlFlow::Continue(())
    })
    .map_err(|failure| format!("FE: {}", failure.error))?;
    Ok((curve.points, curve.unloading))
}

/// The boundary elements on the same layer and law through `loading` then `unloading` (p̄/E*).
fn bem_curve(
    case: Case,
    thickness: f64,
    profile: &Profile,
    loading: &[f64],
    unloading: &[f64],
) -> Result<FrictionalCurve, String> {
    let poisson = wavy::fe::poisson_ratio(case.kappa_over_g);
    let problem = FrictionalProblem {
        profile,
        body: ElasticBody::Layer { thickness, poisson },
        poisson,
        law: InterfaceLaw {
            friction_coefficient: case.mu,
            tau_max_over_estar: case.tau_max_over_estar,
        },
        coupling: NormalCoupling::Full,
        points_per_wavelength: GRID,
        tol: TOL,
    };
    follow_pressures(&problem, loading, unloading).map_err(|e| format!("BEM: {e}"))
}

fn compare(case: Case, thickness: f64, nx: usize) -> Result<Comparison, String> {
    let (fe, fe_unloading) = fe_loop(case, thickness, nx)?;
    let profile = Profile::sinusoid(case.ar);
    let pressures: Vec<f64> = fe.iter().map(|p| p.p_over_estar).collect();
    let unloading_pressures: Vec<f64> = fe_unloading
        .iter()
        .map(|p| p.p_over_estar)
        .filter(|&p| p > 0.0)
        .collect();
    let curve = bem_curve(case, thickness, &profile, &pressures, &unloading_pressures)?;
    let bem = &curve.loading;
    let mut a_error = 0.0f64;
    let mut stick_error_elements = 0.0f64;
    for (i, (f, b)) in fe.iter().zip(bem).enumerate().skip(1) {
        if f.a_over_lambda < FROM_A {
            continue;
        }
        let a_bem = outermost_edge(b);
        a_error = a_error.max((f.a_over_lambda / a_bem - 1.0).abs());
        let element = f.a_over_lambda - fe[i - 1].a_over_lambda;
        let dc = (f.stick_half_width_over_lambda - b.stick_half_width_over_lambda).abs();
        stick_error_elements = stick_error_elements.max(dc / element);
    }
    let (last_fe, last_bem) = (fe.last().unwrap(), bem.last().unwrap());
    Ok(Comparison {
        points: fe.len(),
        p_over_estar: last_fe.p_over_estar,
        dissipation_fe: cycle_friction_work_over_estar_lambda2(&fe_unloading),
        dissipation_bem: curve.face_dissipation_over_estar_lambda2(),
        a_error,
        stick_error_elements,
        stick_ratio_fe: last_fe.stick_half_width_over_lambda / last_fe.a_over_lambda,
        stick_ratio_bem: last_bem.stick_half_width_over_lambda / outermost_edge(last_bem),
    })
}

/// The boundary elements' c/a at the end of `steps` even steps of `√p̄` (about even steps of a
/// on a crest) up to `p_over_estar`: the load path's own step error, against the FE's path.
fn stick_ratio_in_steps(
    case: Case,
    thickness: f64,
    p_over_estar: f64,
    steps: usize,
) -> Result<f64, String> {
    let profile = Profile::sinusoid(case.ar);
    let pressures: Vec<f64> = (1..=steps)
        .map(|j| p_over_estar * (j as f64 / steps as f64).powi(2))
        .collect();
    let curve = bem_curve(case, thickness, &profile, &pressures, &[])?;
    let last = curve.loading.last().unwrap();
    Ok(last.stick_half_width_over_lambda / outermost_edge(last))
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let thickness: f64 = args.first().map_or(0.25, |s| s.parse().expect("h/λ"));
    let meshes: Vec<usize> = args.get(1).map_or(vec![48, 96, 192], |s| {
        s.split(',').map(|m| m.parse().expect("mesh")).collect()
    });
    let kappa_over_g: f64 = args.get(2).map_or(2.1667, |s| s.parse().expect("κ/G"));
    let mut cases = vec![];
    for ar in [0.001, 0.01] {
        let case = |mu, tau_max_over_estar| Case {
            ar,
            kappa_over_g,
            mu,
            tau_max_over_estar,
        };
        cases.push(case(0.0, 0.0));
        for mu in [0.2, 0.5, 1.0] {
            // no Orowan cap (1000 E*), and one below μ p over most of the contact at a/λ 0.3
            // (the peak pressure is about 7 AR E*)
            for tau in [1e3, 0.1 * ar] {
                cases.push(case(mu, tau));
            }
        }
    }
    let runs: Vec<(Case, usize)> = cases
        .iter()
        .flat_map(|&c| meshes.iter().map(move |&m| (c, m)))
        .collect();
    let results: Vec<Result<Comparison, String>> = runs
        .par_iter()
        .map(|&(c, m)| compare(c, thickness, m))
        .collect();
    let fine: Vec<String> = cases
        .par_iter()
        .enumerate()
        .map(|(k, &c)| {
            // to the last load of the finest mesh that completed
            let ran = &results[k * meshes.len()..(k + 1) * meshes.len()];
            match (c.mu > 0.0, ran.iter().rev().find_map(|r| r.as_ref().ok())) {
                (true, Some(last)) => {
                    stick_ratio_in_steps(c, thickness, last.p_over_estar, FINE_STEPS)
                        .map_or_else(|e| e, |r| format!("{r:.4}"))
                }
                _ => "–".into(),
            }
        })
        .collect();
    println!("h/λ {thickness}, κ/G {kappa_over_g} (ν {:.3}), linear kinematics, exact stick, to a/λ 0.3; BEM N {GRID} on the FE's load path", wavy::fe::poisson_ratio(kappa_over_g));
    println!();
    println!("| AR | μ | τ_max/E* | mesh | points | max \\|a_FE/a_BEM − 1\\| (a/λ ≥ {FROM_A}) | max \\|c_FE − c_BEM\\| (edge elements) | c/a FE | c/a BEM | c/a BEM, {FINE_STEPS} steps | loop's face work FE / BEM − 1 |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for (((c, m), r), k) in runs.iter().zip(&results).zip(0..) {
        let r = match r {
            Ok(r) => r,
            Err(e) => {
                println!(
                    "| {} | {} | {} | {m} | failed: {e} |||||||",
                    c.ar, c.mu, c.tau_max_over_estar
                );
                continue;
            }
        };
        let frictional = |text: String| if c.mu > 0.0 { text } else { "–".into() };
        println!(
            "| {} | {} | {} | {m} | {} | {:.2e} | {} | {} | {} | {} | {} |",
            c.ar,
            c.mu,
            c.tau_max_over_estar,
            r.points,
            r.a_error,
            frictional(format!("{:.2}", r.stick_error_elements)),
            frictional(format!("{:.4}", r.stick_ratio_fe)),
            frictional(format!("{:.4}", r.stick_ratio_bem)),
            frictional(fine[k / meshes.len()].clone()),
            frictional(format!(
                "{:+.2} %",
                100.0 * (r.dissipation_fe / r.dissipation_bem - 1.0)
            )),
        );
    }
}
