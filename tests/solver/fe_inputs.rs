//! Input validation: errors name the field, the value and the allowed range.
use std::ops::ControlFlow;
use wavy::fe::*;

fn err(pb: LayerProblem, opts: SolveOptions) -> SolveError {
    solve_curve(&pb, &opts, &mut |_| ControlFlow::Continue(()))
        .expect_err("invalid input")
        .error
}

#[test]
fn invalid_inputs_are_rejected_with_field_names() {
    let ok = wavy::defaults::layer_problem(0.1);
    let o = SolveOptions::default();
    let cases = [
        (
            LayerProblem {
                aspect_ratio: 0.0,
                ..ok
            },
            o,
            "aspect_ratio",
        ),
        (
            LayerProblem {
                thickness_over_lambda: -1.0,
                ..ok
            },
            o,
            "thickness_over_lambda",
        ),
        (
            LayerProblem {
                kappa_over_g: f64::NAN,
                ..ok
            },
            o,
            "kappa_over_g",
        ),
        (
            ok,
            SolveOptions {
                until_a_over_lambda: 0.5,
                ..o
            },
            "until_a_over_lambda",
        ),
        (
            ok,
            SolveOptions {
                until_a_over_lambda: 0.0,
                ..o
            },
            "until_a_over_lambda",
        ),
    ];
    for (pb, opts, field) in cases {
        match err(pb, opts) {
            SolveError::InvalidInput { field: f, .. } => assert_eq!(f, field),
            e => panic!("unexpected {e}"),
        }
    }
    let msg = err(
        LayerProblem {
            aspect_ratio: -0.2,
            ..ok
        },
        o,
    )
    .to_string();
    assert!(
        msg.contains("aspect_ratio") && msg.contains("-0.2") && msg.contains("> 0"),
        "{msg}"
    );
}

#[test]
fn estar_matches_closed_form() {
    // κ/G = 1000: E = 9κG/(3κ+G), ν = (3κ−2G)/(2(3κ+G)), E* = E/(1−ν²) ≈ 3.996 G
    let e = estar_over_g(1000.0);
    assert!((e - 3.996).abs() < 1e-3, "{e}");
    // incompressible limit E* → 4G
    assert!((estar_over_g(1e12) - 4.0).abs() < 1e-9);
}

/// τ_max = 0 (or μ = 0) is frictionless: the interface law says so and no friction machinery
/// (history, non-symmetric tangent) is built, so the curve is bitwise the frictionless one.
#[test]
fn zero_shear_strength_builds_no_friction() {
    assert_eq!(
        Interface::coulomb_orowan(1.0, 0.0, 0.005),
        Interface::Frictionless
    );
    assert_eq!(
        Interface::coulomb_orowan(0.0, 0.1, 0.005),
        Interface::Frictionless
    );
    let opts = SolveOptions {
        mesh: MeshLevel::Elements { nx: 16, ny: 8 },
        until_a_over_lambda: 0.3,
        ..Default::default()
    };
    let pb = |interface| LayerProblem {
        interface,
        ..wavy::defaults::layer_problem(0.1)
    };
    let m = build_model(&pb(Interface::coulomb_orowan(1.0, 0.0, 0.005)), &opts);
    assert!(m.is_potential() && m.elastic_slip_limit().is_none());
    assert!(m.initial_state().slip.is_empty());
    let a = solve_curve(
        &pb(Interface::coulomb_orowan(1.0, 0.0, 0.005)),
        &opts,
        &mut |_| ControlFlow::Continue(()),
    );
    let b = solve_curve(&pb(Interface::Frictionless), &opts, &mut |_| {
        ControlFlow::Continue(())
    });
    assert_eq!(a.unwrap().points, b.unwrap().points);
}

#[test]
fn invalid_friction_inputs_name_the_field() {
    for (law, field) in [
        (
            CoulombOrowan {
                friction_coefficient: -1.0,
                tau_max_over_estar: 0.1,
                elastic_slip_over_element: 0.005,
            },
            "friction_coefficient",
        ),
        (
            CoulombOrowan {
                friction_coefficient: 1.0,
                tau_max_over_estar: f64::NAN,
                elastic_slip_over_element: 0.005,
            },
            "tau_max_over_estar",
        ),
        (
            CoulombOrowan {
                friction_coefficient: 1.0,
                tau_max_over_estar: 0.1,
                elastic_slip_over_element: -0.005,
            },
            "elastic_slip_over_element",
        ),
    ] {
        let pb = LayerProblem {
            interface: Interface::CoulombOrowan(law),
            ..wavy::defaults::layer_problem(0.1)
        };
        match err(pb, SolveOptions::default()) {
            SolveError::InvalidInput { field: f, .. } => assert_eq!(f, field),
            e => panic!("unexpected {e}"),
        }
    }
}

/// A step callback's `Break` ends the solve as an ordinary return: `SolveError::Stopped` with the
/// points converged so far, the last one the callback saw included; on loading and on unloading.
#[test]
fn a_callback_that_breaks_stops_the_solve_with_its_points() {
    let pb = LayerProblem {
        interface: Interface::coulomb_orowan(
            1.0,
            0.05,
            wavy::defaults::elastic_slip_over_element(),
        ),
        ..wavy::defaults::layer_problem(0.3)
    };
    let opts = SolveOptions {
        mesh: MeshLevel::along_face(16),
        until_a_over_lambda: 0.3,
        ..SolveOptions::default()
    };
    let mut seen = 0;
    let f = solve_curve(&pb, &opts, &mut |_| {
        seen += 1;
        if seen == 3 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    })
    .expect_err("the callback stops it");
    assert_eq!(f.error, SolveError::Stopped { points: 3 });
    assert_eq!(f.points.len(), 3);
    let full = solve_cycle(&pb, &opts, &mut |_, _| ControlFlow::Continue(())).expect("cycle");
    let loading = full.points.len();
    let mut seen = 0;
    let f = solve_cycle(&pb, &opts, &mut |direction, _| {
        seen += 1;
        match direction {
            LoadDirection::Unloading if seen == loading + 2 => ControlFlow::Break(()),
            _ => ControlFlow::Continue(()),
        }
    })
    .expect_err("the callback stops the unloading");
    assert_eq!(
        f.error,
        SolveError::Stopped {
            points: loading + 2
        }
    );
    assert_eq!((f.points.len(), f.unloading.len()), (loading, 2));
}
