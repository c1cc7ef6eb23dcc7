//! Global vertical equilibrium: `p̄` from the contact forces over the deformed interface
//! must equal `p̄` from the slab reaction to 1e-6 relative (requirement (vi)). Exact
//! identity at equilibrium (translation invariance of the energy), so the tolerance
//! only absorbs the Newton residual.
use wavy::fe::*;

fn check(kin: Kinematics, ar: f64) {
    let pb = LayerProblem {
        kinematics: kin,
        ..wavy::defaults::layer_problem(ar)
    };
    let opts = SolveOptions {
        mesh: MeshLevel::Coarse,
        until_a_over_lambda: 0.3,
        ..Default::default()
    };
    let mut seen = 0;
    let mut worst = 0.0_f64;
    let curve = solve_curve(&pb, &opts, &mut |_| {
        seen += 1;
        std::ops::ControlFlow::Continue(())
    })
    .expect("curve");
    assert_eq!(seen, curve.points.len(), "on_step called once per point");
    assert!(curve.points.len() >= 5);
    for p in &curve.points {
        let rel = (p.p_over_estar - p.p_over_estar_reaction).abs() / p.p_over_estar_reaction.abs();
        assert!(
            rel <= 1e-6,
            "{kin:?} a {}: traction {} vs reaction {}",
            p.a_over_lambda,
            p.p_over_estar,
            p.p_over_estar_reaction
        );
        assert!(p.p_over_estar > 0.0);
        worst = worst.max(rel);
    }
    eprintln!("{kin:?}, AR {ar}: max |traction − reaction|/reaction {worst:.2e}");
    // monotone loading: a, p̄ and d increase
    for w in curve.points.windows(2) {
        assert!(w[1].a_over_lambda > w[0].a_over_lambda);
        assert!(w[1].p_over_estar > w[0].p_over_estar);
        assert!(w[1].slab_displacement_over_lambda > w[0].slab_displacement_over_lambda);
    }
    // the deformed state: contact pressure is non-negative, zero on free nodes
    let fs = &curve.final_state;
    assert_eq!(fs.bottom.len(), fs.contact_pressure_over_estar.len());
    assert!(fs.contact_pressure_over_estar.iter().all(|&p| p >= -1e-9));
}

#[test]
fn traction_and_reaction_agree_finite() {
    check(Kinematics::Finite, 0.1);
}

#[test]
fn traction_and_reaction_agree_linear() {
    check(Kinematics::Linear, 0.05);
}
