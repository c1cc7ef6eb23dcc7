//! Tests of the superposition model; tolerances sit near what was measured (noted per test).

use super::*;
use crate::models::{Coefficients, Reading, Westergaard, Wnl};

/// ∫₀^L g by composite Gauss–Legendre (`panels` × 20 points).
fn quad(length: f64, panels: usize, g: impl Fn(f64) -> f64) -> f64 {
    let (nodes, weights) = gauss_legendre(20);
    let h = length / panels as f64;
    (0..panels)
        .map(|i| {
            nodes
                .iter()
                .zip(&weights)
                .map(|(z, w)| 0.5 * h * w * g(h * (i as f64 + 0.5 * (z + 1.0))))
                .sum::<f64>()
        })
        .sum()
}

/// p(a₁ − ε), written from the edge distance ε itself (independent of `pressure_at`).
fn pressure_from_edge(d: &BigWaveDistribution, eps: f64) -> f64 {
    let (a, s, p) = (d.half_width, d.s, d.p_mean);
    let x = a - eps;
    let gap = 2.0 * (0.5 * PI * (2.0 * a - eps)).cos() * (0.5 * PI * eps).sin();
    2.0 * p * (PI * x).cos() * (gap * (s + (PI * x).sin())).sqrt() / (s * s)
}

/// ∫ p over [x1, x2] ⊂ [0, ½] by quadrature of the pointwise pressure: plain on the part
/// inside [0, a₁ − ε₀], x = a₁ − t² near the edge (removes the square root).
fn quad_load(d: &BigWaveDistribution, x1: f64, x2: f64) -> f64 {
    let a = d.half_width;
    if x1 >= a {
        return 0.0;
    }
    let split = x1.max(a - 0.25 * (a - x1));
    let inner = if split > x1 {
        quad(split.min(x2) - x1, 8, |t| d.pressure_at(x1 + t))
    } else {
        0.0
    };
    if x2 <= split {
        return inner;
    }
    // [split, min(x2, a)] as ε = a − x ∈ [a − min(x2, a), a − split], ε = t².
    let (e_lo, e_hi) = (a - x2.min(a), a - split);
    let (t_lo, t_hi) = (e_lo.sqrt(), e_hi.sqrt());
    inner
        + quad(t_hi - t_lo, 8, |t| {
            let t = t_lo + t;
            pressure_from_edge(d, t * t) * 2.0 * t
        })
}

fn westergaard_pair(ar1: f64, ar2: f64) -> (Westergaard, Westergaard) {
    (Westergaard::new(ar1), Westergaard::new(ar2))
}

#[test]
fn distribution_integrates_to_the_mean_pressure() {
    let mut worst_closed: f64 = 0.0;
    let mut worst_quad: f64 = 0.0;
    for &a in &[1e-3, 0.05, 0.2, 0.3, 0.45, 0.499] {
        let d = BigWaveDistribution::new(a, 0.37).unwrap();
        let closed = 2.0 * d.load(0.0, 0.5);
        let by_quadrature = 2.0 * quad_load(&d, 0.0, 0.5);
        worst_closed = worst_closed.max((closed / 0.37 - 1.0).abs());
        worst_quad = worst_quad.max((by_quadrature / 0.37 - 1.0).abs());
    }
    // measured: closed form 0, quadrature 2.2e-16
    assert!(worst_closed < 1e-15 && worst_quad < 1e-14);
}

#[test]
fn crest_means_match_quadrature_and_average_to_the_mean_pressure() {
    let mut worst_quad: f64 = 0.0;
    let mut worst_sum: f64 = 0.0;
    for &a in &[0.03, 0.21, 0.33, 0.49] {
        let d = BigWaveDistribution::new(a, 0.2).unwrap();
        for &n in &[2u32, 3, 7, 8, 101, 1000] {
            let means = d.crest_mean_pressures(n);
            let sum: f64 = means.iter().sum::<f64>() / n as f64;
            worst_sum = worst_sum.max((sum / 0.2 - 1.0).abs());
            if n > 101 {
                continue;
            }
            for (j, &p) in means.iter().enumerate() {
                // crest at |x| = k/n; period mapped into [0, ½] by evenness and periodicity
                let k = (j as u32).min(n - j as u32) as f64;
                let h = 0.5 / n as f64;
                let reference = if k == 0.0 {
                    2.0 * quad_load(&d, 0.0, h)
                } else if 2.0 * k == n as f64 {
                    2.0 * quad_load(&d, 0.5 - h, 0.5)
                } else {
                    quad_load(&d, k / n as f64 - h, k / n as f64 + h)
                } * n as f64;
                if reference == 0.0 {
                    assert_eq!(p, 0.0);
                } else {
                    worst_quad = worst_quad.max((p / reference - 1.0).abs());
                }
            }
        }
    }
    // measured: 8.7e-15 against quadrature, 1.2e-15 on the mean
    assert!(worst_quad < 1e-13 && worst_sum < 1e-14);
}

#[test]
fn a_crest_barely_touched_keeps_its_relative_accuracy() {
    // the period [1/(2n), 3/(2n)] of crest 1 overlaps the contact by δ only
    let n = 10u32;
    let mut worst: f64 = 0.0;
    for &delta in &[1e-3, 1e-6, 1e-9, 1e-12] {
        let a = 0.05 + delta;
        let d = BigWaveDistribution::new(a, 0.1).unwrap();
        let delta = a - 0.05; // exact (Sterbenz)
        let p1 = d.crest_mean_pressures(n)[1];
        let t = delta.sqrt();
        let reference = n as f64 * quad(t, 4, |t| pressure_from_edge(&d, t * t) * 2.0 * t);
        worst = worst.max((p1 / reference - 1.0).abs());
    }
    // measured: ≤ 4.4e-16 down to p₁ ≈ 5e-17 (a difference of loads would keep no digit)
    assert!(worst < 1e-14);
}

#[test]
fn contact_fraction_tends_to_the_integral_limit() {
    let wnl = |ar| Wnl::new(ar, 0.1, Reading::BracketSq, Coefficients::PAPER_TABLE1);
    let (w_big, w_small) = westergaard_pair(0.1, 0.02);
    let (n_big, n_small) = (wnl(0.2), wnl(0.1));
    let cases: [(&dyn PressureLaw, &dyn PressureLaw, f64); 3] = [
        (&w_big, &w_small, 0.1),
        (&w_big, &Westergaard::new(0.2), 0.1),
        (&n_big, &n_small, 0.25),
    ];
    // measured: 0 < F − F∞ ≤ 0.90 n^(−5/4) over n = 50 … 3200 (positive: f is concave in p
    // near the edge, so f(mean p) ≥ mean f(p))
    for (big, small, p) in cases {
        let limit = contact_fraction_limit(big, small, p).unwrap();
        for n in [50u32, 100, 200, 400, 800, 1600, 3200] {
            let f = superposed_contact(big, small, n, p)
                .unwrap()
                .contact_fraction;
            let scaled = (f - limit) * (n as f64).powf(1.25);
            assert!(scaled > 0.0 && scaled < 1.0, "n {n}: F {f}, F∞ {limit}");
        }
    }
}

#[test]
fn contact_fraction_is_monotone_in_the_mean_pressure() {
    let wnl = |ar| Wnl::new(ar, 0.1, Reading::BracketSq, Coefficients::PAPER_TABLE1);
    let (w_big, w_small) = westergaard_pair(0.1, 0.03);
    let (n_big, n_small) = (wnl(0.2), wnl(0.1));
    let cases: [(&dyn PressureLaw, &dyn PressureLaw); 3] =
        [(&w_big, &w_small), (&n_big, &n_small), (&w_big, &n_small)];
    for (big, small) in cases {
        for n in [2u32, 5, 16] {
            let full = big.full_contact_p_over_estar();
            let mut last = (0.0, 0.0);
            for i in 1..100 {
                let p = full * i as f64 / 100.0;
                let c = superposed_contact(big, small, n, p).unwrap();
                let now = (c.big_half_width_over_lambda, c.contact_fraction);
                assert!(
                    now.0 > last.0 && now.1 >= last.1,
                    "n {n}, p̄ {p}: {last:?} → {now:?}"
                );
                assert!(c.contact_fraction <= 1.0 && c.crests.len() == n as usize);
                last = now;
            }
        }
    }
}

#[test]
fn vanishing_small_aspect_ratio_counts_whole_touched_periods() {
    let big = Westergaard::new(0.1);
    for (n, p) in [(10u32, 0.1), (7, 0.05), (8, 0.3), (40, 0.2)] {
        let a1 = superposed_contact(&big, &big, n, p)
            .unwrap()
            .big_half_width_over_lambda;
        let means = BigWaveDistribution::new(a1, p)
            .unwrap()
            .crest_mean_pressures(n);
        let p_min = means
            .iter()
            .copied()
            .filter(|&q| q > 0.0)
            .fold(f64::MAX, f64::min);
        let m = ((n as f64 * a1 + 0.5).ceil() - 1.0) as u32;
        let touched = (2 * m + 1).min(n);
        assert_eq!(means.iter().filter(|&&q| q > 0.0).count(), touched as usize);
        let limit = touched as f64 / n as f64;
        assert!(2.0 * a1 <= limit && limit < 2.0 * a1 + 2.0 / n as f64);
        // below πAR₂ = p_min every touched crest is in full contact: the limit, exactly
        for shrink in [0.999, 1e-3] {
            let small = Westergaard::new(shrink * p_min / PI);
            let f = superposed_contact(&big, &small, n, p)
                .unwrap()
                .contact_fraction;
            assert!((f - limit).abs() <= 1e-15, "n {n}: {f} vs {limit}");
        }
        // just above it the least-loaded crests (a pair, or one at the valley) are partial
        let small = Westergaard::new(p_min / (0.9 * PI));
        let c = superposed_contact(&big, &small, n, p).unwrap();
        let partial = c
            .crests
            .iter()
            .filter(|c| c.state == CrestState::Partial)
            .count();
        let deficit = partial as f64 * (1.0 - 2.0 / PI * 0.9f64.sqrt().asin()) / n as f64;
        assert!((limit - c.contact_fraction - deficit).abs() < 1e-14);
    }
}

#[test]
fn infinite_order_approaches_twice_the_big_half_width_quadratically_in_ar2() {
    // 2a₁ − F∞ ≈ (3/4)(π AR₂/K)², K = 2p̄ cos(πa₁) √(π sin 2πa₁)/sin²(πa₁)
    let (big, p) = (Westergaard::new(0.1), 0.1);
    let a1 = superposed_contact(&big, &big, 2, p)
        .unwrap()
        .big_half_width_over_lambda;
    let s = (PI * a1).sin();
    let k = 2.0 * p * (PI * a1).cos() * (PI * (2.0 * PI * a1).sin()).sqrt() / (s * s);
    // measured: ratio − 1 = −2.77e-3, −2.80e-5, −2.80e-7 at AR₂ = 1e-2, 1e-3, 1e-4 (−28 AR₂²)
    for ar2 in [1e-2, 1e-3, 1e-4] {
        let f = contact_fraction_limit(&big, &Westergaard::new(ar2), p).unwrap();
        let ratio = (2.0 * a1 - f) / (0.75 * (PI * ar2 / k).powi(2));
        assert!(
            (ratio - 1.0).abs() < 30.0 * ar2 * ar2 + 1e-8,
            "AR₂ {ar2}: {ratio}"
        );
    }
}

#[test]
fn limit_quadrature_is_converged() {
    let wnl = |ar| Wnl::new(ar, 0.05, Reading::Bracket2x, Coefficients::PAPER_TABLE1);
    let (w_big, w_small) = westergaard_pair(0.1, 0.02);
    let (n_big, n_small) = (wnl(0.15), wnl(0.12));
    let cases: [(&dyn PressureLaw, &dyn PressureLaw, f64); 3] = [
        (&w_big, &w_small, 0.1),
        (&w_big, &w_small, 0.005),
        (&n_big, &n_small, 0.3),
    ];
    // measured: 8 vs 32 panels ≤ 5.6e-17 absolute, 2 vs 32 ≤ 1.7e-16
    for (big, small, p) in cases {
        let reference = contact_fraction_limit_with(big, small, p, 32).unwrap();
        for panels in [2, LIMIT_PANELS] {
            let value = contact_fraction_limit_with(big, small, p, panels).unwrap();
            assert!(
                (value - reference).abs() < 1e-15,
                "{panels} panels: {value} vs {reference}"
            );
        }
    }
}

#[test]
fn inputs_outside_the_model_are_named_errors() {
    use SuperpositionError as E;
    let w = Westergaard::new(0.1);
    let literal = Wnl::new(0.1, 0.0, Reading::Literal, Coefficients::PAPER_TABLE1);
    let full = w.full_contact_p_over_estar();
    for p in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            superposed_contact(&w, &w, 4, p),
            Err(E::Pressure { .. })
        ));
        assert!(matches!(
            contact_fraction_limit(&w, &w, p),
            Err(E::Pressure { .. })
        ));
    }
    for p in [full, 2.0 * full] {
        let e = superposed_contact(&w, &w, 4, p).unwrap_err();
        assert!(matches!(e, E::BigFullContact { .. }), "{e}");
    }
    for order in [0, 1, MAX_ORDER + 1] {
        let e = superposed_contact(&w, &w, order, 0.1).unwrap_err();
        assert_eq!(e, E::Order { order });
        assert!(e.to_string().contains(&order.to_string()));
    }
    let e = superposed_contact(&literal, &w, 4, 0.1).unwrap_err();
    assert!(
        matches!(
            e,
            E::BigInverse {
                source: InverseError::NegativeModel { .. },
                ..
            }
        ),
        "{e}"
    );
    for e in [
        superposed_contact(&w, &literal, 4, 0.1).unwrap_err(),
        contact_fraction_limit(&w, &literal, 0.1).unwrap_err(),
    ] {
        assert!(
            matches!(
                e,
                E::SmallLaw {
                    source: InverseError::NegativeModel { .. }
                }
            ),
            "{e}"
        );
    }
    for (a, p) in [
        (0.0, 0.1),
        (0.5, 0.1),
        (f64::NAN, 0.1),
        (0.2, 0.0),
        (0.2, f64::NAN),
    ] {
        assert!(BigWaveDistribution::new(a, p).is_err(), "a₁ {a}, p̄ {p}");
    }
}

#[test]
fn crests_report_positions_states_and_widths() {
    let (big, small) = westergaard_pair(0.1, 0.02);
    let c = superposed_contact(&big, &small, 9, 0.1).unwrap();
    let full = small.full_contact_p_over_estar();
    for (j, crest) in c.crests.iter().enumerate() {
        assert_eq!(crest.x_over_lambda, j as f64 / 9.0);
        let expected = match crest.state {
            CrestState::Free => (crest.p_over_estar == 0.0, 0.0),
            CrestState::Full => (crest.p_over_estar >= full, 0.5),
            CrestState::Partial => {
                let a = (crest.p_over_estar / full).sqrt().asin() / PI;
                (crest.p_over_estar > 0.0 && crest.p_over_estar < full, a)
            }
        };
        assert!(expected.0, "crest {j}: {crest:?}");
        assert!(
            (crest.half_width_over_wavelength - expected.1).abs() < 1e-12,
            "{crest:?}"
        );
    }
    let states: Vec<CrestState> = c.crests.iter().map(|c| c.state).collect();
    assert!(states.contains(&CrestState::Full) && states.contains(&CrestState::Partial));
    assert!(states.contains(&CrestState::Free));
}
