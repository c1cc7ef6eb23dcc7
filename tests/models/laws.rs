//! The analytic models against numbers computed by hand from docs/replication.md R4/R5 (Table 1).

use std::f64::consts::PI;
use wavy::models::{
    a_over_lambda_at, Coefficients, InverseError, ModelLaw, PressureLaw, Reading, Westergaard, Wnl,
};

fn wnl(ar: f64, tau: f64, reading: Reading) -> Wnl {
    Wnl::new(ar, tau, reading, Coefficients::PAPER_TABLE1)
}

fn assert_rel(found: f64, expected: f64, rel: f64) {
    assert!(
        (found - expected).abs() <= rel * expected.abs(),
        "found {found:e}, expected {expected:e} (relative tolerance {rel:e})"
    );
}

#[test]
fn westergaard_full_contact_pressure_is_pi_estar_delta_over_lambda() {
    // R4: p* = π E* Δ/λ; with p̄/E* the E* drops out.
    for ar in [0.001, 0.1, 0.18, 0.3] {
        let w = Westergaard::new(ar);
        assert_rel(w.p_over_estar(0.5), PI * ar, 1e-15);
        assert_rel(w.full_contact_p_over_estar(), PI * ar, 1e-15);
    }
    // At a/λ = 1/4, sin²(π/4) = 1/2: p̄/E* = π·AR/2.
    assert_rel(
        Westergaard::new(0.1).p_over_estar(0.25),
        PI * 0.1 / 2.0,
        1e-15,
    );
}

#[test]
fn wnl_by_hand_at_ar_0_1_tau_0() {
    // A = a0 + a1·0.1 + a3·0.01 = 0.24536 − 0.996905 − 0.00305098 = −0.75459598
    // B = b0 + b1·0.1 + b3·0.01 = 0.963506 + 0.126005 − 0.00424387 = 1.08526713
    let (a, b) = (-0.75459598, 1.08526713);
    let m = wnl(0.1, 0.0, Reading::BracketSq);
    assert_rel(m.correction_a(), a, 1e-14);
    assert_rel(m.correction_b(), b, 1e-14);
    // At x = 1/4: p_W = π·0.1·sin²(π/4) = 0.05π; cos²(π/4) = 1/2; cos(π/2) = 0.
    let p_w = 0.05 * PI;
    assert_rel(m.p_over_estar(0.25), p_w * (b + 0.25 * a * 0.5), 1e-14);
    assert_rel(
        wnl(0.1, 0.0, Reading::Bracket2x).p_over_estar(0.25),
        p_w * b,
        1e-12,
    );
    assert_rel(
        wnl(0.1, 0.0, Reading::Literal).p_over_estar(0.25),
        p_w * b + 0.25 * a * 0.5,
        1e-14,
    );
}

#[test]
fn wnl_by_hand_at_ar_0_3_tau_0_2() {
    // A = 0.24536 − 9.96905·0.3 + 4.80482·0.2 − 0.305098·0.09 − 47.5605·0.06 − 3.56199·0.04
    //   = 0.24536 − 2.990715 + 0.960964 − 0.02745882 − 2.85363 − 0.1424796 = −4.80795942
    // B = 0.963506 + 1.26005·0.3 − 0.33278·0.2 − 0.424387·0.09 + 10.4263·0.06 − 2.45931·0.04
    //   = 0.963506 + 0.378015 − 0.066556 − 0.03819483 + 0.625578 − 0.0983724 = 1.76397577
    let (a, b) = (-4.80795942, 1.76397577);
    let m = wnl(0.3, 0.2, Reading::BracketSq);
    assert_rel(m.correction_a(), a, 1e-13);
    assert_rel(m.correction_b(), b, 1e-13);
    // At x = 0.1: p_W = 0.3π sin²(0.1π), bracket-sq factor B + 0.1·A·cos²(0.1π).
    let (s, c) = ((0.1 * PI).sin(), (0.1 * PI).cos());
    assert_rel(
        m.p_over_estar(0.1),
        0.3 * PI * s * s * (b + 0.1 * a * c * c),
        1e-13,
    );
    assert!(!m.is_extrapolated());
}

#[test]
fn full_contact_values_of_the_bracketed_readings() {
    // R5: bracket-sq returns to B·p*, bracket-2x rises to (B − A/2)·p*, about 2.7·p* at AR = 0.3, τ = 0:
    // A = 0.24536 − 2.990715 − 0.02745882 = −2.77281382, B = 0.963506 + 0.378015 − 0.03819483 = 1.30332617.
    let (a, b) = (-2.77281382, 1.30332617);
    let p_star = PI * 0.3;
    assert_rel(
        wnl(0.3, 0.0, Reading::BracketSq).p_over_estar(0.5),
        b * p_star,
        1e-13,
    );
    let two_x = wnl(0.3, 0.0, Reading::Bracket2x).p_over_estar(0.5);
    assert_rel(two_x, (b - a / 2.0) * p_star, 1e-13);
    assert!((two_x / p_star - 2.69).abs() < 0.01);
}

#[test]
fn inverse_of_forward_is_the_identity_to_1e_12() {
    let mut laws: Vec<ModelLaw> = vec![];
    for ar in [0.1, 0.18, 0.3] {
        laws.push(ModelLaw::Westergaard(Westergaard::new(ar)));
        for tau in [0.0, 0.05, 0.1, 0.2] {
            for reading in [Reading::BracketSq, Reading::Bracket2x] {
                laws.push(ModelLaw::Wnl(wnl(ar, tau, reading)));
            }
        }
    }
    let mut worst: f64 = 0.0;
    for law in &laws {
        for i in 1..=49 {
            let x = i as f64 / 100.0;
            let back = a_over_lambda_at(law, law.p_over_estar(x))
                .unwrap_or_else(|e| panic!("{law:?} at {x}: {e}"));
            worst = worst.max((back - x).abs() / x);
        }
    }
    assert!(
        worst <= 1e-12,
        "worst relative error of inverse∘forward: {worst:e}"
    );
}

#[test]
fn inverse_refuses_pressures_outside_the_physical_range() {
    let w = Westergaard::new(0.1);
    let full = PI * 0.1;
    assert_eq!(a_over_lambda_at(&w, full).unwrap(), 0.5);
    assert_eq!(a_over_lambda_at(&w, 0.0).unwrap(), 0.0);
    match a_over_lambda_at(&w, full * 1.001) {
        Err(InverseError::AboveFullContact {
            full_contact_p_over_estar,
            ..
        }) => assert_rel(full_contact_p_over_estar, full, 1e-15),
        other => panic!("expected AboveFullContact, got {other:?}"),
    }
    assert!(matches!(
        a_over_lambda_at(&w, -1e-9),
        Err(InverseError::NegativeOrNotFinite { .. })
    ));
    assert!(matches!(
        a_over_lambda_at(&w, f64::NAN),
        Err(InverseError::NegativeOrNotFinite { .. })
    ));
}

#[test]
fn literal_reading_is_negative_and_has_no_inverse() {
    // R5: with every Table 1 value A < 0, so p = p_W·B + x·A·cos²(πx) < 0 for small x.
    let m = wnl(0.1, 0.0, Reading::Literal);
    assert!(m.p_over_estar(0.05) < 0.0);
    match a_over_lambda_at(&m, 0.01) {
        Err(InverseError::NegativeModel {
            a_over_lambda,
            p_over_estar,
        }) => {
            assert!(a_over_lambda > 0.0 && a_over_lambda < 0.2 && p_over_estar < 0.0)
        }
        other => panic!("expected NegativeModel, got {other:?}"),
    }
}

#[test]
fn non_monotonic_extrapolation_is_detected_not_inverted() {
    // Far outside the fit domain (AR = 0.02, τ_max = 0.5 MPa) bracket-sq turns back near a/λ ≈ 0.40:
    // p̄(a) = p̄ then has two roots for pressures just below the local maximum.
    let m = wnl(0.02, 0.5, Reading::BracketSq);
    assert!(m.is_extrapolated());
    assert!(
        m.p_over_estar(0.45) < m.p_over_estar(0.40),
        "the law must turn back between 0.40 and 0.45"
    );
    match a_over_lambda_at(&m, 0.01) {
        Err(InverseError::NonMonotonic { a_over_lambda, .. }) => {
            assert!((0.35..0.45).contains(&a_over_lambda))
        }
        other => panic!("expected NonMonotonic, got {other:?}"),
    }
    // bracket-2x turns back at AR = 0.05 already inside the τ range of the fit.
    assert!(matches!(
        a_over_lambda_at(&wnl(0.05, 0.2, Reading::Bracket2x), 0.01),
        Err(InverseError::NonMonotonic { .. })
    ));
}

#[test]
fn extrapolation_is_flagged_outside_the_fit_domain_only() {
    assert!(!wnl(0.1, 0.0, Reading::BracketSq).is_extrapolated());
    assert!(!wnl(0.3, 0.2, Reading::BracketSq).is_extrapolated());
    assert!(!wnl(0.18, 0.05, Reading::BracketSq).is_extrapolated());
    assert!(wnl(0.08, 0.05, Reading::BracketSq).is_extrapolated()); // fingertip AR (R8)
    assert!(wnl(0.31, 0.0, Reading::BracketSq).is_extrapolated());
    assert!(wnl(0.2, 0.21, Reading::BracketSq).is_extrapolated());
    assert!(!ModelLaw::Westergaard(Westergaard::new(0.01)).is_extrapolated());
}
