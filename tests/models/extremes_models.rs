//! The closed-form laws at their extremes, property-based: a/λ from 0 to ½ (both ends
//! included), AR from 1e-12 to 10, τ_max from 0 to 100 MPa, every reading, coefficient set and
//! model. Each evaluation is a finite, non-negative p̄/E* or a typed error, never NaN, ±inf or a
//! silent negative; wherever the law is invertible, inverse ∘ forward is the identity.
//!
//! Case counts: `WAVY_FUZZ_CASES` (default 10 000 per property; `make fuzz` sets 1 000 000).

use proptest::prelude::*;
use wavy::models::{
    a_over_lambda_at, inverse::check_invertible, CoefficientSet, InverseError, ModelKind, ModelLaw,
    PressureLaw, Reading, UnphysicalPressure,
};

fn cases() -> u32 {
    std::env::var("WAVY_FUZZ_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(10_000)
}

/// A fixed seed (reproducible runs) unless `WAVY_FUZZ_SEED` names another.
fn seed() -> proptest::test_runner::RngSeed {
    proptest::test_runner::RngSeed::Fixed(
        std::env::var("WAVY_FUZZ_SEED")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(0x5eed),
    )
}

/// AR log-uniform on [1e-12, 10].
fn aspect_ratio() -> impl Strategy<Value = f64> {
    (-12.0..=1.0f64).prop_map(|e| 10f64.powf(e))
}

/// τ_max on [0, 100] MPa: zero, log-uniform small values, and uniform large ones.
fn tau_max_mpa() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        (-6.0..=0.0f64).prop_map(|e| 10f64.powf(e)),
        0.0..=100.0f64,
    ]
}

/// a/λ on [0, ½], with both ends and their neighbours.
fn a_over_lambda() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(0.5),
        Just(f64::MIN_POSITIVE),
        Just(0.5 - f64::EPSILON),
        0.0..=0.5f64,
    ]
}

fn law() -> impl Strategy<Value = ModelLaw> {
    (
        prop::sample::select(ModelKind::ALL.to_vec()),
        aspect_ratio(),
        tau_max_mpa(),
        prop::sample::select(Reading::ALL.to_vec()),
        prop::sample::select(CoefficientSet::ALL.to_vec()),
    )
        .prop_map(|(kind, ar, tau, reading, set)| ModelLaw::new(kind, ar, tau, reading, set))
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: cases(),
        failure_persistence: None,
        rng_seed: seed(),
        ..ProptestConfig::default()
    })]

    #[test]
    fn a_value_is_finite_and_non_negative_or_a_typed_error(law in law(), x in a_over_lambda()) {
        match law.physical_p_over_estar(x) {
            Ok(p) => {
                prop_assert!(p.is_finite() && p >= 0.0, "{p} at {x} for {law:?}");
                prop_assert_eq!(p.to_bits(), law.p_over_estar(x).to_bits());
            }
            Err(UnphysicalPressure::NotFinite { p_over_estar, .. }) => {
                prop_assert!(!p_over_estar.is_finite());
            }
            Err(UnphysicalPressure::Negative { p_over_estar, .. }) => {
                prop_assert!(p_over_estar < 0.0);
            }
        }
    }

    #[test]
    fn inverse_of_forward_is_the_identity_where_the_law_is_monotonic(
        law in law(),
        x in a_over_lambda(),
    ) {
        let Ok(p) = law.physical_p_over_estar(x) else { return Ok(()) };
        match a_over_lambda_at(&law, p) {
            Ok(a) => {
                prop_assert!(a.is_finite() && (0.0..=0.5).contains(&a), "a = {a}");
                // p̄(a) = p̄ to round-off of the law's scale
                let scale = law.full_contact_p_over_estar().abs().max(f64::MIN_POSITIVE);
                let back = law.p_over_estar(a);
                prop_assert!(
                    (back - p).abs() <= 1e-12 * scale,
                    "p̄(a⁻¹(p̄)) = {back} vs {p} (a = {a}, x = {x}) for {law:?}"
                );
            }
            // a law that is negative, not finite or turns back somewhere has no inverse: typed
            Err(e) => {
                prop_assert!(check_invertible(&law).is_err(), "{e} but the law checks as invertible: {law:?}");
                prop_assert!(matches!(
                    e,
                    InverseError::NotFinite { .. }
                        | InverseError::NegativeModel { .. }
                        | InverseError::NonMonotonic { .. }
                ), "{e}");
            }
        }
    }

    #[test]
    fn inverse_never_answers_outside_its_range(law in law(), p in prop_oneof![
        Just(-0.0), Just(f64::NAN), Just(f64::INFINITY), Just(-1e-300), 0.0..10.0f64, 1e10..1e300f64
    ]) {
        match a_over_lambda_at(&law, p) {
            Ok(a) => prop_assert!(a.is_finite() && (0.0..=0.5).contains(&a)),
            Err(InverseError::NegativeOrNotFinite { .. }) => prop_assert!(!(p.is_finite() && p >= 0.0)),
            Err(InverseError::AboveFullContact { full_contact_p_over_estar, .. }) => {
                prop_assert!(p > full_contact_p_over_estar)
            }
            Err(_) => prop_assert!(check_invertible(&law).is_err()),
        }
    }
}

/// The inputs of the original defect reports: overflow is `NotFinite`, never "negative … NaN".
#[test]
fn overflow_is_reported_as_such() {
    let huge = ModelLaw::new(
        ModelKind::Wnl,
        0.1,
        1e300,
        Reading::BracketSq,
        CoefficientSet::PaperTable1,
    );
    assert!(matches!(
        a_over_lambda_at(&huge, 0.1),
        Err(InverseError::NotFinite { .. })
    ));
    let w = ModelLaw::new(
        ModelKind::Westergaard,
        1e308,
        0.0,
        Reading::BracketSq,
        CoefficientSet::PaperTable1,
    );
    assert!(matches!(
        w.physical_p_over_estar(0.25),
        Err(UnphysicalPressure::NotFinite { .. })
    ));
    let literal = ModelLaw::new(
        ModelKind::Wnl,
        0.2,
        0.1,
        Reading::Literal,
        CoefficientSet::PaperTable1,
    );
    assert!(matches!(
        literal.physical_p_over_estar(0.02),
        Err(UnphysicalPressure::Negative { .. })
    ));
    println!("{} cases per property", cases());
}
