//! The finite-element solver at the extremes of its inputs: every curve reaches its target
//! a/λ or ends in a typed error with the points it converged; never a curve that stops short
//! and calls itself complete (issue #9). What each case reached is printed
//! (`cargo test --release --test fe_extremes -- --nocapture`) and quoted in the README.

use wavy::defaults::layer_problem;
use wavy::fe::*;

/// Solves and checks the outcome; returns how far the curve got and the error, if any.
fn outcome(label: &str, pb: &LayerProblem, opts: &SolveOptions) -> (f64, Option<SolveError>) {
    match solve_curve(pb, opts, &mut |_| {}) {
        Ok(c) => {
            let a = c
                .points
                .last()
                .expect("a complete curve has points")
                .a_over_lambda;
            assert!(
                a >= opts.until_a_over_lambda,
                "{label}: Ok at a/λ = {a} < target {}",
                opts.until_a_over_lambda
            );
            assert!(c.points.iter().all(|p| p.p_over_estar.is_finite()
                && p.p_over_estar >= 0.0
                && p.a_over_lambda.is_finite()));
            println!("{label}: reached a/λ = {a:.4} ({} points)", c.points.len());
            (a, None)
        }
        Err(f) => {
            let a = f.points.last().map_or(0.0, |p| p.a_over_lambda);
            assert!(
                a < opts.until_a_over_lambda,
                "{label}: failed after reaching the target"
            );
            assert!(
                !matches!(f.error, SolveError::InvalidInput { .. }),
                "{label}: {}",
                f.error
            );
            println!("{label}: stopped at a/λ = {a:.4}: {}", f.error);
            (a, Some(f.error))
        }
    }
}

fn opts(mesh: MeshLevel, until: f64) -> SolveOptions {
    SolveOptions {
        mesh,
        until_a_over_lambda: until,
        ..SolveOptions::default()
    }
}

fn elements(nx: usize) -> MeshLevel {
    format!("{nx}").parse().unwrap()
}

#[test]
fn large_aspect_ratios_reach_their_target_or_say_where_they_stop() {
    // AR 0.3 resolves a/λ ≥ 0.48 at the default mesh (the valley element is reachable)
    let (a, e) = outcome(
        "AR 0.3, default mesh, to 0.48",
        &layer_problem(0.3),
        &opts(MeshLevel::Default, 0.48),
    );
    assert!(e.is_none() && a >= 0.48);
    // beyond the paper's range: as far as they go (README, "Reliability")
    for ar in [0.4, 0.5] {
        outcome(
            &format!("AR {ar}, coarse mesh"),
            &layer_problem(ar),
            &opts(MeshLevel::Coarse, 0.45),
        );
    }
}

#[test]
fn material_and_geometry_extremes_reach_their_target_or_stop_typed() {
    let mut cases = 0;
    for kappa_over_g in [1e4, 1e6] {
        let pb = LayerProblem {
            kappa_over_g,
            ..layer_problem(0.1)
        };
        outcome(
            &format!("κ/G = {kappa_over_g:e}, coarse"),
            &pb,
            &opts(MeshLevel::Coarse, 0.45),
        );
        cases += 1;
    }
    for thickness_over_lambda in [0.1, 10.0] {
        let pb = LayerProblem {
            thickness_over_lambda,
            ..layer_problem(0.1)
        };
        outcome(
            &format!("h/λ = {thickness_over_lambda}, coarse"),
            &pb,
            &opts(MeshLevel::Coarse, 0.45),
        );
        cases += 1;
    }
    // τ_max = 0.1 MPa against E* from 10⁻³ to 10³ MPa: τ_max/E* from 100 to 10⁻⁴
    for estar_mpa in [1e-3, 1.0, 1e3] {
        let pb = LayerProblem {
            interface: Interface::coulomb_orowan(1.0, 0.1 / estar_mpa, 0.005),
            ..layer_problem(0.1)
        };
        outcome(
            &format!("E* = {estar_mpa:e} MPa, τ_max = 0.1 MPa, coarse"),
            &pb,
            &opts(MeshLevel::Coarse, 0.45),
        );
        cases += 1;
    }
    println!("{cases} cases");
}

#[test]
fn coarse_meshes_reach_their_target_or_say_the_mesh_is_too_coarse() {
    let mut reached = 0;
    for nx in [4, 5, 6, 8, 12, 16, 24] {
        for ar in [0.1, 0.3] {
            let (a, e) = outcome(
                &format!("AR {ar}, {nx} elements"),
                &layer_problem(ar),
                &opts(elements(nx), 0.45),
            );
            match e {
                None => reached += 1,
                // the only acceptable reasons on a coarse mesh: the last element ends short
                // of the target, or Newton gives up on the coarse geometry
                Some(SolveError::TargetBeyondMesh { a_over_lambda, .. }) => {
                    assert_eq!(a_over_lambda, a)
                }
                Some(_) => {}
            }
        }
    }
    // Since the valley node may be the last event, 8 elements reach 0.45 at AR 0.1 (issue #9:
    // the curve used to stop at 0.371 and call itself complete).
    let (a, e) = outcome(
        "AR 0.1, 8 elements",
        &layer_problem(0.1),
        &opts(elements(8), 0.45),
    );
    assert!(e.is_none() && a >= 0.45, "{a} {e:?}");
    // and a target beyond the last element is an error that says so
    let (_, e) = outcome(
        "AR 0.1, 8 elements, to 0.49",
        &layer_problem(0.1),
        &opts(elements(8), 0.49),
    );
    assert!(
        matches!(e, Some(SolveError::TargetBeyondMesh { .. })),
        "{e:?}"
    );
    println!("{reached} of 14 coarse-mesh curves reached a/λ = 0.45");
}
