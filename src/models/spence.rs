//! Spence's limit: the central stick zone of a frictional Hertzian (parabolic) contact under
//! monotonic normal loading (D. A. Spence, J. Elasticity 5, 297–319, 1975), in Goodman's
//! approximation. Independent of both solvers: docs/verification.md ("Spence's stick zone")
//! derives it.
//!
//! Loading is self-similar: the fields at contact half-width `a` are those at any other scaled
//! by `a`, so the stick ratio `c/a` depends on μ and Dundurs' β alone. A point inside the stick
//! zone has never moved sideways since it stuck, so `∂u_x/∂x = 0` there; with Johnson's eq.
//! 2.25 this reads `H q = −β p` on `|x| < c`, while `q = μ p sign(x)` slips outward on
//! `c < |x| < a` (the compressible solid is drawn inwards). With the pressure Hertzian
//! (Goodman: the shear's effect on it dropped), the traction in the stick zone is bounded at
//! both fronts only when
//!
//! ```text
//! β E(k) = μ [K(k′) − E(k′)],    k = c/a,  k′ = √(1 − k²)
//! ```
//!
//! (`K`, `E` the complete elliptic integrals of modulus `k`). The left side falls from `βπ/2`
//! at `k = 0` to `β` at `k = 1`, the right side from `+∞` to 0, so every `μ > 0` and `β ≠ 0`
//! has one root: there is always a central stick zone, and it fills the contact as `β/μ → 0`.

/// `K(k)` and `E(k)`, the complete elliptic integrals of the first and second kind of modulus
/// `k ∈ [0, 1)`, by the arithmetic–geometric mean (to rounding).
pub fn complete_elliptic(k: f64) -> (f64, f64) {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    let mut sum = 0.5 * k * k;
    let mut weight = 0.5;
    for _ in 0..64 {
        let c = 0.5 * (a - b);
        if c.abs() <= f64::EPSILON * a {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
        weight *= 2.0;
        sum += weight * c * c;
    }
    let big_k = std::f64::consts::FRAC_PI_2 / a;
    (big_k, big_k * (1.0 - sum))
}

/// The stick ratio `c/a` of Spence's self-similar loading in Goodman's approximation (module
/// doc), for the friction coefficient `mu` (≥ 0) and Dundurs' `beta` (its sign only orients the
/// shear): 1 when `β = 0` (nothing slips), 0 when `μ = 0` (nothing sticks), else the root of
/// `|β| E(k) = μ [K(k′) − E(k′)]` by bisection, to rounding.
pub fn stick_ratio(mu: f64, beta: f64) -> f64 {
    let beta = beta.abs();
    if beta == 0.0 {
        return 1.0;
    }
    if mu == 0.0 {
        return 0.0;
    }
    let excess = |k: f64| {
        let (_, e) = complete_elliptic(k);
        let (kp_k, kp_e) = complete_elliptic((1.0 - k * k).sqrt());
        beta * e - mu * (kp_k - kp_e)
    };
    // excess → −∞ as k → 0 and = β > 0 at k = 1
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if excess(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Midpoint-rule quadrature of a smooth integrand on `[0, π/2]`.
    fn quad(f: impl Fn(f64) -> f64) -> f64 {
        let n = 20_000;
        let h = std::f64::consts::FRAC_PI_2 / n as f64;
        (0..n).map(|i| f((i as f64 + 0.5) * h)).sum::<f64>() * h
    }

    /// The AGM values against the defining integrals, and the tabulated `K(1/√2) = 1.854075`,
    /// `E(1/√2) = 1.350644` (Abramowitz & Stegun, Table 17.1, m = ½).
    #[test]
    fn elliptic_integrals_match_their_definitions() {
        for k in [0.0, 0.1, 0.5, 0.9, 0.99] {
            let (big_k, big_e) = complete_elliptic(k);
            let want_k = quad(|t| 1.0 / (1.0 - k * k * t.sin().powi(2)).sqrt());
            let want_e = quad(|t| (1.0 - k * k * t.sin().powi(2)).sqrt());
            assert!(
                (big_k - want_k).abs() < 1e-8,
                "K({k}) = {big_k} vs {want_k}"
            );
            assert!(
                (big_e - want_e).abs() < 1e-8,
                "E({k}) = {big_e} vs {want_e}"
            );
        }
        let (big_k, big_e) = complete_elliptic(0.5f64.sqrt());
        assert!((big_k - 1.854075).abs() < 1e-6 && (big_e - 1.350644).abs() < 1e-6);
    }

    /// The two integrals of the bounded-traction condition (docs/verification.md) by direct
    /// quadrature: `∫₀ᵏ √((1 − t²)/(k² − t²)) dt = E(k)` and
    /// `∫ₖ¹ √((1 − s²)/(s² − k²)) ds = K(k′) − E(k′)`, each after the substitution that
    /// removes its end singularity.
    #[test]
    fn the_condition_integrals_are_elliptic() {
        for k in [0.2, 0.5, 0.8] {
            let kp = (1.0f64 - k * k).sqrt();
            // t = k sin θ
            let inner = quad(|t| (1.0 - k * k * t.sin().powi(2)).sqrt());
            // s² = k² + k′² sin²θ
            let outer = quad(|t| {
                let s = (k * k + kp * kp * t.sin().powi(2)).sqrt();
                kp * kp * t.cos().powi(2) / s
            });
            let (_, e) = complete_elliptic(k);
            let (kk, ke) = complete_elliptic(kp);
            assert!((inner - e).abs() < 1e-8, "k = {k}: {inner} vs E = {e}");
            assert!(
                (outer - (kk - ke)).abs() < 1e-8,
                "k = {k}: {outer} vs {}",
                kk - ke
            );
        }
    }

    /// The root satisfies the condition, the limits hold, and more friction sticks more.
    #[test]
    fn the_stick_ratio_solves_the_condition_and_orders_with_friction() {
        let beta = 0.5 / 1.4; // ν = 0.3: (1 − 0.6)/(2 · 0.7) ≈ 0.286
        let mut last = 0.0;
        for mu in [0.1, 0.2, 0.5, 1.0, 2.0] {
            let k = stick_ratio(mu, beta);
            let (_, e) = complete_elliptic(k);
            let (kk, ke) = complete_elliptic((1.0 - k * k).sqrt());
            assert!((beta * e - mu * (kk - ke)).abs() < 1e-12, "μ = {mu}");
            assert!(k > last && k < 1.0, "μ = {mu}: c/a = {k}");
            last = k;
        }
        assert_eq!(stick_ratio(0.5, 0.0), 1.0);
        assert_eq!(stick_ratio(0.0, 0.3), 0.0);
        assert_eq!(stick_ratio(0.5, -0.3), stick_ratio(0.5, 0.3));
    }
}
