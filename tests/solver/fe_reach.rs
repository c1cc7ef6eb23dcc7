//! Acceptance: finite kinematics at the default mesh reaches a/λ ≥ 0.45 for AR = 0.18
//! (AR = 0.1 and 0.3 are exercised at the default mesh by tests/solver/fe_convergence.rs).
//! Reference for the sanity bounds: the linear Westergaard value π AR sin²(π a) at
//! a/λ = 0.45 is 0.5561; the finite-strain curve lies above it at this aspect ratio
//! (measured +12 %), and must stay below the full-contact linear load π AR = 0.5655
//! times 1.25.
use std::ops::ControlFlow;
use wavy::fe::*;

#[test]
fn ar_0_18_reaches_045_at_default_mesh() {
    let pb = wavy::defaults::layer_problem(0.18);
    let c = solve_curve(&pb, &SolveOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .expect("curve");
    let last = c.points.last().unwrap();
    assert!(last.a_over_lambda >= 0.45, "reached {}", last.a_over_lambda);
    let p = c.p_at(0.45).unwrap();
    assert!(
        p > 0.5561 && p < 1.25 * std::f64::consts::PI * 0.18,
        "p̄/E*(0.45) = {p}"
    );
}
