//! Fourier compliances of the elastic bodies: how far a surface-pressure harmonic
//! `p̃ cos(q x)` pushes the surface in, `ũ = C(q) p̃` (plane strain, frictionless surface).
//!
//! Units: `q` in 1/λ, lengths in λ, compliances in λ/E*, where `E* = E/(1 − ν²)` is the
//! plane-strain modulus of the body's own material.
//!
//! - Half-plane (Johnson, *Contact Mechanics*, 1985, §13.2): `C(q) = 2/(E* q)`.
//! - Layer of thickness `h` bonded to a rigid base: `C_h(q) = S(qh, ν) · 2/(E* q)` with
//!
//!   ```text
//!   S = [(3 − 4ν) sinh 2qh − 2qh] / [(3 − 4ν) cosh 2qh + 2(qh)² + (1 − 2ν)² + 4(1 − ν)²]
//!   ```
//!
//!   the inverse of the finite-thickness stiffness factor of `PeriodicFFTElasticHalfSpace`
//!   (`thickness=`, `poisson=`) in ContactMechanics (github.com/ContactEngineering/ContactMechanics,
//!   `ContactMechanics/FFTElasticHalfSpace.py`), whose constant `4ν(2ν − 3) + 5` is the same
//!   `(1 − 2ν)² + 4(1 − ν)²`. One Fourier mode of a surface load on a 3-D slab is a plane-strain
//!   problem, so it applies here as written. It is checked, not taken on trust: the tests solve
//!   Navier's equations for the layer (one mode, bonded base, shear-free surface) by shooting and
//!   match `S` to 1e-11, and check both limits: `S → 1` as `qh → ∞` (the half-plane), and the thin
//!   layer `S → qh (1 − 2ν)/(2(1 − ν)²)` (uniaxial strain, `ũ = p̃ h/M` with the oedometric
//!   modulus `M`) or, incompressible, `S → (2/3)(qh)³` (squeeze flow of a bonded film).
//!
//! A nearly incompressible solid given by `κ/G` has `ν = (3κ/G − 2)/(2(3κ/G + 1))`
//! (`κ/G = 1000`: `ν ≈ 0.4995`).

use super::BemError;

/// The elastic body a profile is pressed on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ElasticBody {
    /// The half-plane: compliance `2/(E* q)`.
    HalfPlane,
    /// A layer bonded to a rigid base: compliance `S(qh, ν) · 2/(E* q)` ([`layer_compliance`]).
    Layer {
        /// Thickness `h/λ` (finite, > 0).
        thickness: f64,
        /// Poisson ratio `ν` (`−1 < ν ≤ ½`).
        poisson: f64,
    },
}

impl ElasticBody {
    /// Its compliance over the half-plane's at the wavenumber `q` (1/λ): 1 for the half-plane,
    /// `S(qh, ν)` for a layer ([`layer_to_half_plane_ratio`]).
    pub fn over_half_plane(self, q: f64) -> Result<f64, BemError> {
        match self {
            ElasticBody::HalfPlane => {
                check_wavenumber(q)?;
                Ok(1.0)
            }
            ElasticBody::Layer { thickness, poisson } => {
                layer_to_half_plane_ratio(q, thickness, poisson)
            }
        }
    }
}

/// The half-plane's compliance `2/(E* q)` (units λ/E*, `q` in 1/λ, finite and `> 0`).
pub fn half_plane_compliance(q: f64) -> Result<f64, BemError> {
    check_wavenumber(q)?;
    Ok(half_plane(q))
}

/// `2/q`, for a `q` known to be positive.
pub(super) fn half_plane(q: f64) -> f64 {
    2.0 / q
}

fn check_wavenumber(q: f64) -> Result<(), BemError> {
    if q.is_finite() && q > 0.0 {
        Ok(())
    } else {
        Err(BemError::InvalidInput {
            field: "wavenumber q·λ",
            value: q,
            allowed: "finite, > 0",
        })
    }
}

/// The compliance of a layer of thickness `h` (units of λ) bonded to a rigid base, Poisson
/// ratio `ν` (`−1 < ν ≤ ½`), for the wavenumber `q` (1/λ): `S(qh, ν) · 2/(E* q)`, in λ/E* of the
/// layer's material ([`layer_to_half_plane_ratio`]).
pub fn layer_compliance(q: f64, thickness: f64, poisson: f64) -> Result<f64, BemError> {
    Ok(layer_to_half_plane_ratio(q, thickness, poisson)? * half_plane(q))
}

/// `S(qh, ν)`: the layer's compliance over the half-plane's for the same material and wavenumber
/// (module doc); between 0 and 1.
pub fn layer_to_half_plane_ratio(q: f64, thickness: f64, poisson: f64) -> Result<f64, BemError> {
    let (numerator, _, denominator) = layer_terms(q, thickness, poisson)?;
    Ok(numerator / denominator)
}

/// `1 − S(qh, ν)`: how much softer the half-plane is than the layer, computed without
/// cancellation, so that it stays accurate for a thick layer, where it is
/// `≈ (4(qh)² + 4qh + 2(1 − 2ν)² + 8(1 − ν)²) e^{−2qh}/(3 − 4ν)`.
pub fn layer_compliance_deficit(q: f64, thickness: f64, poisson: f64) -> Result<f64, BemError> {
    let (_, deficit, denominator) = layer_terms(q, thickness, poisson)?;
    Ok(deficit / denominator)
}

/// The numerator and denominator of `S` and their difference, all times `2e^{−2qh}` so that
/// nothing overflows for a thick layer; the numerator as `(2 − 4ν) sinh t + (sinh t − t)`
/// (`t = 2qh`), a sum of non-negative terms.
fn layer_terms(q: f64, thickness: f64, poisson: f64) -> Result<(f64, f64, f64), BemError> {
    let check = |field: &'static str, value: f64, ok: bool, allowed: &'static str| {
        if ok {
            Ok(())
        } else {
            Err(BemError::InvalidInput {
                field,
                value,
                allowed,
            })
        }
    };
    check_wavenumber(q)?;
    check(
        "layer thickness h/λ",
        thickness,
        thickness.is_finite() && thickness > 0.0,
        "finite, > 0",
    )?;
    check(
        "Poisson ratio ν",
        poisson,
        poisson > -1.0 && poisson <= 0.5,
        "−1 < ν ≤ 0.5",
    )?;
    let nu = poisson;
    let t = 2.0 * q * thickness;
    let e = (-t).exp();
    let sinh_scaled = -(-2.0 * t).exp_m1(); // 2 e^{−t} sinh t
    let sinh_minus_t_scaled = if t < 0.1 {
        // t³/3! + t⁵/5! + …, relative error below 1e-16 here
        let t2 = t * t;
        let series = t * t2 / 6.0 * (1.0 + t2 / 20.0 * (1.0 + t2 / 42.0 * (1.0 + t2 / 72.0)));
        2.0 * e * series
    } else {
        sinh_scaled - 2.0 * t * e
    };
    let numerator = (2.0 - 4.0 * nu) * sinh_scaled + sinh_minus_t_scaled;
    let constant = (1.0 - 2.0 * nu).powi(2) + 4.0 * (1.0 - nu).powi(2);
    let denominator = (3.0 - 4.0 * nu) * (1.0 + e * e) + (t * t + 2.0 * constant) * e;
    // denominator − numerator, term by term
    let deficit = (t * t + 2.0 * t + 2.0 * constant) * e + 2.0 * (3.0 - 4.0 * nu) * e * e;
    Ok((numerator, deficit, denominator))
}

/// One surface harmonic's compliance matrix over the half-plane's frictionless `2/(E* q)`, for
/// a body that carries shear as well as pressure: with `p̃ cos qx` the pressure and `q̃ sin qx` the
/// shear traction on the solid (along `+x`), the surface moves in by `ũ_z cos qx` and along `+x`
/// by `ũ_x sin qx`,
///
/// ```text
/// ũ_z = (2/(E* q)) (normal p̃ − coupling q̃),     ũ_x = (2/(E* q)) (tangential q̃ − coupling p̃)
/// ```
///
/// which on the grid is `u_z = K (S_n p + S_c H q)`, `u_x = K (S_t q − S_c H p)` (`H cos = sin`).
/// The matrix is symmetric (Betti's reciprocity) and positive definite (the stored energy).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HarmonicCompliance {
    /// `S_n`: pressure to normal displacement (the frictionless ratio, [`layer_to_half_plane_ratio`]).
    pub normal: f64,
    /// `S_t`: shear to tangential displacement.
    pub tangential: f64,
    /// `S_c`: shear to normal and pressure to tangential displacement; Dundurs' `β` on the
    /// half-plane.
    pub coupling: f64,
}

impl HarmonicCompliance {
    /// The half-plane of Poisson ratio `ν`, every harmonic alike: `S_n = S_t = 1`,
    /// `S_c = β = (1 − 2ν)/(2(1 − ν))` (Johnson, *Contact Mechanics*, 1985, eqs. 2.25).
    pub fn half_plane(poisson: f64) -> Self {
        Self {
            normal: 1.0,
            tangential: 1.0,
            coupling: dundurs_beta(poisson),
        }
    }

    /// A layer of thickness `h` (λ) bonded to a rigid base, Poisson ratio `ν`, at the wavenumber
    /// `q` (1/λ). With `t = 2qh` and `D` the denominator of [`layer_to_half_plane_ratio`]:
    ///
    /// ```text
    /// S_n = [(3 − 4ν) sinh t − t]/D,   S_t = [(3 − 4ν) sinh t + t]/D,
    /// S_c = [(1 − 2ν)(3 − 4ν)(cosh t − 1) − 2(qh)²] / (2(1 − ν) D)
    /// ```
    ///
    /// from the general solution of Navier's equations for one mode (`e^{±qz}`, `z e^{±qz}`) with
    /// the base held and the surface loaded, checked against a shooting solution (tests). Limits:
    /// the half-plane's `(1, 1, β)` for a thick layer; a thin one shears like a block,
    /// `S_t → qh/(1 − ν)`; the coupling changes sign below `qh ≈ 1.0` at ν 0.3 (−0.0144 at
    /// `qh = 0.5`, +0.069 at `π/2`), and an incompressible layer is coupled too, through its
    /// base (`S_c → −(qh)²` thin).
    pub fn layer(q: f64, thickness: f64, poisson: f64) -> Result<Self, BemError> {
        let (normal, _, denominator) = layer_terms(q, thickness, poisson)?;
        let nu = poisson;
        let t = 2.0 * q * thickness;
        let e = (-t).exp();
        // every term times 2e^{−t}, as in `layer_terms`
        let sinh_scaled = -(-2.0 * t).exp_m1();
        let tangential = (3.0 - 4.0 * nu) * sinh_scaled + 2.0 * t * e;
        let cosh_minus_one_scaled = (-t).exp_m1().powi(2);
        let coupling = (1.0 - 2.0 * nu) * (3.0 - 4.0 * nu) * cosh_minus_one_scaled - t * t * e;
        Ok(Self {
            normal: normal / denominator,
            tangential: tangential / denominator,
            coupling: coupling / (2.0 * (1.0 - nu) * denominator),
        })
    }

    /// `body`'s matrix at the wavenumber `q`; `poisson` is the half-plane's (a layer has its own).
    pub fn of(body: ElasticBody, q: f64, poisson: f64) -> Result<Self, BemError> {
        match body {
            ElasticBody::HalfPlane => {
                check_wavenumber(q)?;
                Ok(Self::half_plane(poisson))
            }
            ElasticBody::Layer { thickness, poisson } => Self::layer(q, thickness, poisson),
        }
    }
}

/// Dundurs' `β = (1 − 2ν)/(2(1 − ν))` of an elastic body on a rigid one.
pub fn dundurs_beta(poisson: f64) -> f64 {
    (1.0 - 2.0 * poisson) / (2.0 * (1.0 - poisson))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The surface's response by shooting: Navier's equations for one mode `u_x = U(z) sin qx`,
    /// `u_z = W(z) cos qx` (z the depth, G = 1), RK4 from the bonded base `z = h` (U = W = 0) up
    /// to the surface, where `σ_zz = −p̃` and `σ_xz = −q̃` (the load `p̃ cos qx` inwards,
    /// `q̃ sin qx` along `+x`); returns `(W(0), U(0))` over the half-plane's `(1 − ν)/q` (= 2/(E* q)).
    fn shooting_response(q: f64, h: f64, nu: f64, load: [f64; 2]) -> [f64; 2] {
        let lam = 2.0 * nu / (1.0 - 2.0 * nu);
        let rhs = |y: [f64; 4]| {
            let [u, w, du, dw] = y;
            let ddu = q * q * u + (lam + 1.0) * q * (q * u + dw);
            let ddw = (q * q * w - (lam + 1.0) * q * du) / (lam + 2.0);
            [du, dw, ddu, ddw]
        };
        let shoot = |y0: [f64; 4]| {
            let steps = 4000;
            let dz = -h / steps as f64;
            let mut y = y0;
            let add = |y: [f64; 4], k: [f64; 4], s: f64| std::array::from_fn(|i| y[i] + s * k[i]);
            for _ in 0..steps {
                let k1 = rhs(y);
                let k2 = rhs(add(y, k1, dz / 2.0));
                let k3 = rhs(add(y, k2, dz / 2.0));
                let k4 = rhs(add(y, k3, dz));
                y = std::array::from_fn(|i| {
                    y[i] + dz / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
                });
            }
            let [u, w, du, dw] = y;
            // (shear σ_xz/sin, normal σ_zz/cos, U, W) at the surface
            (du - q * w, lam * (q * u + dw) + 2.0 * dw, u, w)
        };
        let (sa, na, ua, wa) = shoot([0.0, 0.0, 1.0, 0.0]);
        let (sb, nb, ub, wb) = shoot([0.0, 0.0, 0.0, 1.0]);
        // α sa + β sb = −q̃, α na + β nb = −p̃
        let [p, t] = load;
        let det = sa * nb - sb * na;
        let alpha = (-t * nb + p * sb) / det;
        let beta = (-p * sa + t * na) / det;
        let scale = q / (1.0 - nu);
        [
            (alpha * wa + beta * wb) * scale,
            (alpha * ua + beta * ub) * scale,
        ]
    }

    /// `S` by shooting ([`shooting_response`] under pressure alone).
    fn shooting_ratio(q: f64, h: f64, nu: f64) -> f64 {
        shooting_response(q, h, nu, [1.0, 0.0])[0]
    }

    /// The layer's matrix against the shooting solution, every entry within 1e-10 of the
    /// largest (the shear column and the pressure column give the coupling twice: Betti).
    #[test]
    fn the_layer_matrix_solves_navier_equations() {
        for nu in [0.0, 0.3, 0.45, 0.4995] {
            for qh in [0.05, 0.5, 1.0, 3.0] {
                let m = HarmonicCompliance::layer(qh, 1.0, nu).unwrap();
                let [wp, up] = shooting_response(qh, 1.0, nu, [1.0, 0.0]);
                let [wq, uq] = shooting_response(qh, 1.0, nu, [0.0, 1.0]);
                let scale = m.tangential;
                let pairs = [
                    (m.normal, wp),
                    (m.tangential, uq),
                    (-m.coupling, wq),
                    (-m.coupling, up),
                ];
                for (closed, shot) in pairs {
                    assert!(
                        (closed - shot).abs() < 1e-10 * scale,
                        "ν = {nu}, qh = {qh}: {m:?} vs {pairs:?}"
                    );
                }
            }
        }
    }

    /// The limits: the half-plane's `(1, 1, β)` for a thick layer; a thin layer shears as a
    /// block (`S_t → qh/(1 − ν)`) and couples as `−(qh)²` when incompressible; the matrix is
    /// positive definite throughout.
    #[test]
    fn the_layer_matrix_has_its_limits() {
        for nu in [0.0, 0.3, 0.4995, 0.5] {
            let thick = HarmonicCompliance::layer(40.0, 1.0, nu).unwrap();
            let half = HarmonicCompliance::half_plane(nu);
            assert!((thick.normal - 1.0).abs() < 1e-15, "ν = {nu}");
            assert!((thick.tangential - 1.0).abs() < 1e-15, "ν = {nu}");
            assert!((thick.coupling - half.coupling).abs() < 1e-15, "ν = {nu}");
            for qh in [1e-4, 0.01, 0.3, 1.0, 2.0, 5.0] {
                let m = HarmonicCompliance::layer(qh, 1.0, nu).unwrap();
                assert!(
                    m.normal * m.tangential > m.coupling * m.coupling,
                    "ν = {nu}, qh = {qh}: {m:?}"
                );
            }
            let qh = 1e-4;
            let thin = HarmonicCompliance::layer(qh, 1.0, nu).unwrap();
            assert!(
                (thin.tangential / (qh / (1.0 - nu)) - 1.0).abs() < 1e-6,
                "ν = {nu}: {thin:?}"
            );
        }
        let thin = HarmonicCompliance::layer(1e-3, 1.0, 0.5).unwrap();
        assert!((thin.coupling / -1e-6 - 1.0).abs() < 1e-5, "{thin:?}");
        assert_eq!(HarmonicCompliance::half_plane(0.5).coupling, 0.0);
    }

    /// The closed form against the shooting solution, 1e-11 relative (measured ≤ 7e-14).
    #[test]
    fn the_layer_ratio_solves_navier_equations() {
        for nu in [0.0, 0.3, 0.45] {
            for qh in [0.05, 0.5, 1.0, 3.0] {
                let closed = layer_to_half_plane_ratio(qh, 1.0, nu).unwrap();
                let shot = shooting_ratio(qh, 1.0, nu);
                assert!(
                    ((closed - shot) / shot).abs() < 1e-11,
                    "ν = {nu}, qh = {qh}: {closed} vs {shot}"
                );
            }
        }
    }

    /// Both limits: the half-plane for a thick layer; uniaxial strain or squeeze flow for a thin
    /// one (relative 1e-6 at qh = 1e-4, where the next term is O(qh)²).
    #[test]
    fn the_layer_ratio_has_both_limits() {
        let s = |qh: f64, nu: f64| layer_to_half_plane_ratio(qh, 1.0, nu).unwrap();
        for nu in [0.0, 0.3, 0.4995, 0.5] {
            assert!((s(30.0, nu) - 1.0).abs() < 1e-15, "ν = {nu}");
            assert!((s(1e3, nu) - 1.0).abs() < 1e-15, "ν = {nu}");
            assert!(s(0.7, nu) < s(0.8, nu) && s(0.8, nu) < 1.0);
        }
        let qh = 1e-4;
        for nu in [0.0_f64, 0.3] {
            let thin = qh * (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu).powi(2));
            assert!((s(qh, nu) / thin - 1.0).abs() < 1e-6, "ν = {nu}");
        }
        let squeeze = 2.0 / 3.0 * qh.powi(3);
        assert!((s(qh, 0.5) / squeeze - 1.0).abs() < 1e-6);
        // continuous at ν = ½
        assert!((s(1.0, 0.5) - s(1.0, 0.5 - 1e-9)).abs() < 1e-8);
    }

    /// A layer one wavelength thick, nearly incompressible (κ/G = 1000, ν ≈ 0.4995), against the
    /// half-plane for the harmonics of order 1, 8 and 16 (`q = 2πn`): 1 − S = 6.4369e-4,
    /// 2.25e-40 and 1.95e-83, the last two equal to the asymptotic form to 1e-3.
    #[test]
    fn a_layer_one_wavelength_thick_is_a_half_plane_for_fine_harmonics() {
        let k_over_g: f64 = 1000.0;
        let nu = (3.0 * k_over_g - 2.0) / (2.0 * (3.0 * k_over_g + 1.0));
        assert!((nu - 0.4995).abs() < 1e-6);
        let deficit =
            |n: f64| layer_compliance_deficit(std::f64::consts::TAU * n, 1.0, nu).unwrap();
        let ratio = |n: f64| layer_to_half_plane_ratio(std::f64::consts::TAU * n, 1.0, nu).unwrap();
        assert!(
            (deficit(1.0) - 6.436_88e-4).abs() < 1e-9,
            "{}",
            deficit(1.0)
        );
        assert!((1.0 - ratio(1.0) - deficit(1.0)).abs() < 1e-15);
        let asymptotic = |n: f64| {
            let qh = std::f64::consts::TAU * n;
            let c = (1.0 - 2.0 * nu).powi(2) + 4.0 * (1.0 - nu).powi(2);
            (4.0 * qh * qh + 4.0 * qh + 2.0 * c) * (-2.0 * qh).exp() / (3.0 - 4.0 * nu)
        };
        for n in [8.0, 16.0] {
            assert!(
                (deficit(n) / asymptotic(n) - 1.0).abs() < 1e-3,
                "n = {n}: {}",
                deficit(n)
            );
            assert_eq!(ratio(n), 1.0);
        }
        assert!(
            (deficit(8.0) / 2.25e-40 - 1.0).abs() < 1e-2,
            "{}",
            deficit(8.0)
        );
        assert!(
            (deficit(16.0) / 1.95e-83 - 1.0).abs() < 1e-2,
            "{}",
            deficit(16.0)
        );
    }

    #[test]
    fn the_layer_ratio_refuses_bad_inputs() {
        assert!(layer_to_half_plane_ratio(0.0, 1.0, 0.3).is_err());
        assert!(layer_to_half_plane_ratio(1.0, f64::INFINITY, 0.3).is_err());
        let e = layer_to_half_plane_ratio(1.0, 1.0, 0.6)
            .unwrap_err()
            .to_string();
        assert!(e.contains("Poisson"), "{e}");
        assert!(layer_compliance(1.0, 1.0, f64::NAN).is_err());
        assert!(half_plane_compliance(-1.0).is_err());
        assert_eq!(
            half_plane_compliance(std::f64::consts::TAU).unwrap(),
            1.0 / std::f64::consts::PI
        );
    }
}
