//! Linear kinematics vs Westergaard's half-space solution
//! `p̄/E* = π (Δ/λ) sin²(π a/λ)` (K. L. Johnson, Contact Mechanics, 1985, §13.2; the
//! layer of thickness λ bonded to a rigid slab differs from the half-space by
//! `O(e^{−4π}) ≈ 4·10⁻⁶` for the first harmonic).
use std::f64::consts::PI;
use std::ops::ControlFlow;
use wavy::fe::*;

fn westergaard(ar: f64, a: f64) -> f64 {
    PI * ar * (PI * a).sin().powi(2)
}

fn max_error(kappa_over_g: f64) -> (f64, usize) {
    let ar = 0.01;
    let pb = LayerProblem {
        kappa_over_g,
        kinematics: Kinematics::Linear,
        ..wavy::defaults::layer_problem(ar)
    };
    let curve = solve_curve(&pb, &SolveOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .expect("linear curve");
    let mut worst = 0.0_f64;
    let mut count = 0;
    for p in curve
        .points
        .iter()
        .filter(|p| (0.1..=0.45).contains(&p.a_over_lambda))
    {
        worst = worst.max((p.p_over_estar / westergaard(ar, p.a_over_lambda) - 1.0).abs());
        count += 1;
    }
    (worst, count)
}

/// Requirement (i) asks for a max relative error ≤ 1 % on a/λ ∈ [0.1, 0.45], default mesh.
/// Measured: 0.048 %; asserted ≤ 0.15 %, about three times that. The edge rule is calibrated on
/// this problem (AR 0.01, linear; other meshes and gradings too), so this checks the calibration
/// on the default mesh rather than the solver independently.
#[test]
fn linear_matches_westergaard_within_0_15_percent() {
    let (worst, count) = max_error(1000.0);
    eprintln!(
        "linear, AR 0.01, default mesh: max relative error vs Westergaard {:.3} % over {count} points",
        100.0 * worst
    );
    assert!(count >= 20, "only {count} points in range");
    assert!(worst <= 0.0015, "max relative error {worst}");
}
