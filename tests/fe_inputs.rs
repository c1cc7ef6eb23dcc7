//! Input validation: errors name the field, the value and the allowed range.
use wavy::fe::*;

fn err(pb: LayerProblem, opts: SolveOptions) -> SolveError {
    solve_curve(&pb, &opts, &mut |_| {})
        .expect_err("invalid input")
        .error
}

#[test]
fn invalid_inputs_are_rejected_with_field_names() {
    let ok = LayerProblem::default();
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
