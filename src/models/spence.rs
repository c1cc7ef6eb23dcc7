//! Spence's limit: the central stick zone of a frictional Hertzian (parabolic) contact under
//! monotonic normal loading (D. A. Spence, J. Elasticity 5, 297–319, 1975), in Goodman's
//! approximation (the pressure Hertzian, `p = p₀ √(1 − ξ²)`, `ξ = x/a`). Independent of both
//! solvers; docs/verification.md ("Frictional boundary elements") derives it.
//!
//! Loading is self-similar: the fields at contact half-width `a` are those at any other scaled
//! by `a`, so the stick ratio `k = c/a` depends on μ and Dundurs' β alone. The compressible
//! solid is drawn inwards, so friction acts outward: `q = μ p sign ξ` where the face slips,
//! `k < |ξ| < 1`. In the stick zone the tangential strain is Johnson's eq. 2.25,
//! `ε = −(2/E*)(β p + H q)`, and the shear there, `q = μ p sign ξ + φ`, solves the finite
//! Hilbert equation `H φ = G` on `|ξ| < k` with
//!
//! ```text
//! G(ξ) = −β √(1 − ξ²) − γ |ξ| − μ H[√(1 − s²) sign s](ξ),
//! H[√(1 − s²) sign s](ξ) = (1/π) [2 + c ln((1 − c)/(1 + c))],   c = √(1 − ξ²)
//! ```
//!
//! (units `p₀` and `a`). The strain `γ|ξ|` of the stick zone is what the load history leaves:
//! a point caught by the growing stick zone keeps the displacement it had, and self-similarity
//! (`u_x = a² U(x/a)`, `∂u_x/∂a = 0` at fixed `x`) makes `U ∝ ξ|ξ|` there.
//! - **Proportional loading** (one step from the unloaded state: the stick zone has not moved
//!   at all, `γ = 0`): `φ` bounded at the fronts requires `∫ G/√(k² − ξ²) = 0`, which is
//!   `β E(k) = μ [K(k′) − E(k′)]` (`K`, `E` complete elliptic integrals of modulus `k`,
//!   `k′ = √(1 − k²)`): [`proportional_stick_ratio`].
//! - **Incremental loading** (Spence's problem): boundedness fixes `γ(k)` instead, and the front
//!   is where the shear meets `μ p` smoothly, `φ = o(√(k − |ξ|))`: the coefficient of the
//!   square root, `J(k) = ∫₀^π [G(k cos θ) − G(k)]/(k cos θ − k) dθ`, vanishes (the bounded
//!   solution of the finite Hilbert inversion, its square-root term read at the front). A
//!   square root of one sign puts the stick zone's shear above `μ p`, of the other slips the
//!   face the wrong way: [`incremental_stick_ratio`].

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

/// The stick ratio `c/a` of proportional loading in Goodman's approximation (module doc), for
/// the friction coefficient `mu` (≥ 0) and Dundurs' `beta` (its sign only orients the shear):
/// 1 when `β = 0` (nothing slips), 0 when `μ = 0` (nothing sticks), else the root of
/// `|β| E(k) = μ [K(k′) − E(k′)]` by bisection, to rounding.
pub fn proportional_stick_ratio(mu: f64, beta: f64) -> f64 {
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
    root_of_rising(0.0, 1.0, 200, excess)
}

/// The root of `f` between `lo` (where `f < 0`) and `hi` (where `f ≥ 0`), by at most
/// `iterations` bisections, stopping when the interval cannot shrink further.
fn root_of_rising(mut lo: f64, mut hi: f64, iterations: usize, f: impl Fn(f64) -> f64) -> f64 {
    for _ in 0..iterations {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// `H[√(1 − s²) sign s](ξ)` on `|ξ| < 1` (module doc): the Hilbert transform of the slip zone's
/// shear continued over the whole contact, in closed form.
fn hilbert_of_signed_hertz(xi: f64) -> f64 {
    let c = (1.0 - xi * xi).sqrt();
    (2.0 + c * ((1.0 - c) / (1.0 + c)).ln()) / std::f64::consts::PI
}

/// Midpoint-rule integral of `f` over `[0, span]` on `n` points.
fn midpoint(span: f64, n: usize, f: impl Fn(f64) -> f64) -> f64 {
    let h = span / n as f64;
    (0..n).map(|i| f((i as f64 + 0.5) * h)).sum::<f64>() * h
}

/// Midpoint-rule integral over `θ ∈ [0, π]` (the substitution `ξ = k cos θ` that removes
/// `1/√(k² − ξ²)`), on `n` points: the log singularity of [`hilbert_of_signed_hertz`] at `ξ = 0`
/// falls between points.
fn over_theta(n: usize, f: impl Fn(f64) -> f64) -> f64 {
    midpoint(std::f64::consts::PI, n, f)
}

/// The incremental stick ratio's two conditions at the trial ratio `k` (module doc): the
/// stick zone's strain slope `γ` that keeps the shear bounded, and the square-root coefficient
/// `J(k)` of the shear at the front under it (negative: the stick zone's shear would exceed
/// `μ p`; positive: the face beside it would slip the wrong way).
pub fn incremental_conditions(mu: f64, beta: f64, k: f64) -> (f64, f64) {
    const POINTS: usize = 8000;
    let base = |xi: f64| -beta * (1.0 - xi * xi).sqrt() - mu * hilbert_of_signed_hertz(xi);
    // ∫ G/√(k² − ξ²) dξ = 0, with ∫ |ξ|/√(k² − ξ²) dξ = 2k
    let gamma = over_theta(POINTS, |t| base(k * t.cos())) / (2.0 * k);
    let g = |xi: f64| base(xi) - gamma * xi.abs();
    let g_front = g(k);
    let j = over_theta(POINTS, |t| {
        let xi = k * t.cos();
        (g(xi) - g_front) / (xi - k)
    });
    (gamma, j)
}

/// Spence's stick ratio `c/a` of incremental (monotonic) loading in Goodman's approximation
/// (module doc) for the friction coefficient `mu` (≥ 0) and Dundurs' `beta`: 1 when `β = 0`, 0
/// when `μ = 0`, else the root of `J(k)` by bisection on `[10⁻⁶, 1 − 10⁻⁶]` (`J` rises through
/// zero once there; a root beyond either end returns that end). Accurate to about 1e-5 (the
/// quadrature on 8000 points; 2000 and 32000 points agree with it to 6e-5 and 1.4e-5).
pub fn incremental_stick_ratio(mu: f64, beta: f64) -> f64 {
    let beta = beta.abs();
    if beta == 0.0 {
        return 1.0;
    }
    if mu == 0.0 {
        return 0.0;
    }
    let (lo, hi) = (1e-6f64, 1.0 - 1e-6);
    let root_coefficient = |k: f64| incremental_conditions(mu, beta, k).1;
    if root_coefficient(hi) < 0.0 {
        return hi;
    }
    root_of_rising(lo, hi, 48, root_coefficient)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Midpoint-rule quadrature of a smooth integrand on `[0, π/2]`.
    fn quad(f: impl Fn(f64) -> f64) -> f64 {
        midpoint(std::f64::consts::FRAC_PI_2, 20_000, f)
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
        let beta = 0.4 / 1.4; // ν = 0.3: (1 − 0.6)/(2 · 0.7) ≈ 0.286
        let mut last = 0.0;
        for mu in [0.1, 0.2, 0.5, 1.0, 2.0] {
            let k = proportional_stick_ratio(mu, beta);
            let (_, e) = complete_elliptic(k);
            let (kk, ke) = complete_elliptic((1.0 - k * k).sqrt());
            assert!((beta * e - mu * (kk - ke)).abs() < 1e-12, "μ = {mu}");
            assert!(k > last && k < 1.0, "μ = {mu}: c/a = {k}");
            last = k;
        }
        assert_eq!(proportional_stick_ratio(0.5, 0.0), 1.0);
        assert_eq!(proportional_stick_ratio(0.0, 0.3), 0.0);
        assert_eq!(
            proportional_stick_ratio(0.5, -0.3),
            proportional_stick_ratio(0.5, 0.3)
        );
    }

    /// The closed form of the slip zone's Hilbert transform against quadrature of its
    /// definition, `(1/π) PV ∫₋₁¹ f(s)/(ξ − s) ds` with `f = √(1 − s²) sign s`, the pole
    /// subtracted: `(1/π) [∫ (f(s) − f(ξ))/(ξ − s) ds + f(ξ) ln((1 + ξ)/(1 − ξ))]`.
    #[test]
    fn the_slip_zones_hilbert_transform_is_its_closed_form() {
        let f = |s: f64| (1.0 - s * s).sqrt() * s.signum();
        for xi in [0.2f64, 0.5, 0.8] {
            let n = 200_000;
            let h = 2.0 / n as f64;
            let regular: f64 = (0..n)
                .map(|i| -1.0 + (i as f64 + 0.5) * h)
                .map(|s| (f(s) - f(xi)) / (xi - s))
                .sum::<f64>()
                * h;
            let numeric = (regular + f(xi) * ((1.0 + xi) / (1.0 - xi)).ln()) / std::f64::consts::PI;
            let closed = hilbert_of_signed_hertz(xi);
            assert!(
                (numeric - closed).abs() < 1e-4,
                "ξ = {xi}: {numeric} vs {closed}"
            );
        }
    }

    /// With no history (γ = 0) the incremental conditions' boundedness is the proportional
    /// condition: `γ(k)` vanishes at the proportional ratio (measured −1.1e-4 at μ 0.2, where
    /// the log singularity of the quadrature weighs most). The incremental ratio lies beyond it
    /// (μ 0.5, ν 0.3: 0.9677, against 0.5517 proportionally; 0.4057 and 0.9999 at μ 0.2 and 1),
    /// and there `γ < 0`: the stuck face is held drawn inwards.
    #[test]
    fn the_incremental_ratio_extends_the_proportional_one() {
        let beta = 0.4 / 1.4;
        for mu in [0.2, 0.5, 1.0] {
            let k0 = proportional_stick_ratio(mu, beta);
            let (gamma0, _) = incremental_conditions(mu, beta, k0);
            assert!(gamma0.abs() < 2e-4, "μ = {mu}: γ({k0}) = {gamma0}");
        }
        let want = [(0.2, 0.40573), (0.5, 0.96774), (1.0, 0.99987)];
        for (mu, k) in want {
            let got = incremental_stick_ratio(mu, beta);
            assert!((got - k).abs() < 1e-4, "μ = {mu}: {got} vs {k}");
            let (gamma, j) = incremental_conditions(mu, beta, got);
            assert!(
                gamma < 0.0 && j.abs() < 1e-3,
                "μ = {mu}: γ = {gamma}, J = {j}"
            );
        }
    }
}
