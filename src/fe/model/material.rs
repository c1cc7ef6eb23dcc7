//! Compressible neo-Hookean material in plane strain.
//!
//! Strain energy per unit reference volume (3D form, plane strain `F₃₃ = 1`):
//!
//! ```text
//! W(F) = G/2 (Ī₁ − 3) + κ/2 (J − 1)²,   Ī₁ = J^(−2/3) tr C,   C = FᵀF,   J = det F
//! ```
//!
//! with the in-plane 2×2 deformation gradient `F` and `tr C = F:F + 1`.
//! The solver splits `W` into the isochoric part `W_iso = G/2 (J^(−2/3) (F:F + 1) − 3)`,
//! evaluated here pointwise, and the volumetric part, which the element treats with
//! the mean-dilatation energy (see [`crate::fe::model::element`]).
//!
//! Isochoric first Piola–Kirchhoff stress and tangent (`a = J^(−2/3)`, `F⁻ᵀ` the
//! inverse transpose):
//!
//! ```text
//! P_iJ     = G a (F_iJ − (I₁/3) F⁻ᵀ_iJ)
//! A_iJkL   = ∂P_iJ/∂F_kL
//!          = G a [ δ_ik δ_JL − (2/3)(F⁻ᵀ_kL F_iJ + F_kL F⁻ᵀ_iJ)
//!                  + (2/9) I₁ F⁻ᵀ_iJ F⁻ᵀ_kL + (I₁/3) F⁻ᵀ_iL F⁻ᵀ_kJ ]
//! ```
//!
//! For `J ≤ 0` the energy is undefined (the material would be inverted); the functions
//! return `None` and the solver treats the configuration as having infinite energy.
//!
//! Units: stresses are in units of the shear modulus `G` (the solver uses `G = 1`).

/// Plane-strain modulus over shear modulus, `E*/G`, for bulk-to-shear ratio `κ/G`.
///
/// `E = 9κG/(3κ+G)`, `ν = (3κ−2G)/(2(3κ+G))`, `E* = E/(1−ν²)`.
pub fn estar_over_g(kappa_over_g: f64) -> f64 {
    let k = kappa_over_g;
    let e = 9.0 * k / (3.0 * k + 1.0);
    let nu = poisson_ratio(k);
    e / (1.0 - nu * nu)
}

/// Poisson's ratio `ν = (3κ−2G)/(2(3κ+G))` for bulk-to-shear ratio `κ/G`.
pub fn poisson_ratio(kappa_over_g: f64) -> f64 {
    let k = kappa_over_g;
    (3.0 * k - 2.0) / (2.0 * (3.0 * k + 1.0))
}

/// Neo-Hookean constants (shear modulus `g`, bulk modulus `kappa`).
#[derive(Clone, Copy, Debug)]
pub struct NeoHooke {
    /// Shear modulus `G`.
    pub g: f64,
    /// Bulk modulus `κ`.
    pub kappa: f64,
}

/// Isochoric energy density, stress and tangent at one point.
#[derive(Clone, Copy, Debug)]
pub struct IsoResponse {
    /// `W_iso`.
    pub w: f64,
    /// First Piola–Kirchhoff stress `P[i][J]`.
    pub p: [[f64; 2]; 2],
    /// Tangent `A[i][J][k][L] = ∂P_iJ/∂F_kL`.
    pub a: [[[[f64; 2]; 2]; 2]; 2],
}

/// Pointwise isochoric quantities from which the element builds its stress and
/// tangent in closed form (see [`crate::fe::model::element::tangent`]).
#[derive(Clone, Copy, Debug)]
pub struct IsoKinematics {
    /// `W_iso`.
    pub w: f64,
    /// `G J^(−2/3)`.
    pub ga: f64,
    /// `I₁ = F:F + 1` (`tr C` in plane strain).
    pub i1: f64,
    /// `F⁻ᵀ`.
    pub fit: [[f64; 2]; 2],
}

/// `J^(−2/3)`. Nearly incompressible states have `|J − 1| ≪ 1`; there `y = J^(−1/3)`
/// comes from two Newton steps `y ← y (4 − J y³)/3` on `y⁻³ = J`, started at the
/// second-order Taylor value `1 − e/3 + 2e²/9` (`e = J − 1`; relative error
/// `≈ 14|e|³/81 ≤ 2.2·10⁻⁵` for `|e| ≤ 0.05`; a step maps an error `δ` to `≈ 2δ²`:
/// `10⁻⁹`, then below round-off), and `J^(−2/3) = y²`. Elsewhere through the cube root,
/// which is slower than these two steps (docs/performance.md, solver choices).
#[inline]
fn j_minus_two_thirds(j: f64) -> f64 {
    const THIRD: f64 = 1.0 / 3.0;
    let e = j - 1.0;
    if e.abs() <= 0.05 {
        let mut y = 1.0 + e * (-THIRD + e * (2.0 / 9.0));
        for _ in 0..2 {
            y *= (4.0 - j * y * y * y) * THIRD;
        }
        y * y
    } else {
        let c = j.cbrt();
        1.0 / (c * c)
    }
}

impl NeoHooke {
    /// `W_iso`, `G J^(−2/3)`, `I₁` and `F⁻ᵀ`; `None` when `det F ≤ 0`.
    #[inline]
    pub fn iso_kinematics(&self, f: &[[f64; 2]; 2]) -> Option<IsoKinematics> {
        let j = f[0][0] * f[1][1] - f[0][1] * f[1][0];
        if j <= 0.0 || !j.is_finite() {
            return None;
        }
        let i1 =
            f[0][0] * f[0][0] + f[0][1] * f[0][1] + f[1][0] * f[1][0] + f[1][1] * f[1][1] + 1.0;
        let ga = self.g * j_minus_two_thirds(j);
        let inv_j = 1.0 / j;
        Some(IsoKinematics {
            w: 0.5 * (ga * i1 - 3.0 * self.g),
            ga,
            i1,
            fit: [
                [f[1][1] * inv_j, -f[1][0] * inv_j],
                [-f[0][1] * inv_j, f[0][0] * inv_j],
            ],
        })
    }

    /// Isochoric energy density, stress and (optionally filled) tangent; `None` when
    /// `det F ≤ 0`.
    pub fn iso_response(&self, f: &[[f64; 2]; 2], want_tangent: bool) -> Option<IsoResponse> {
        let j = f[0][0] * f[1][1] - f[0][1] * f[1][0];
        if j <= 0.0 || !j.is_finite() {
            return None;
        }
        let i1 =
            f[0][0] * f[0][0] + f[0][1] * f[0][1] + f[1][0] * f[1][0] + f[1][1] * f[1][1] + 1.0;
        let a = j_minus_two_thirds(j);
        let inv_j = 1.0 / j;
        // F⁻ᵀ = cof(F)/J
        let fit = [
            [f[1][1] * inv_j, -f[1][0] * inv_j],
            [-f[0][1] * inv_j, f[0][0] * inv_j],
        ];
        let g = self.g;
        let w = 0.5 * g * (a * i1 - 3.0);
        let mut p = [[0.0; 2]; 2];
        for i in 0..2 {
            for jj in 0..2 {
                p[i][jj] = g * a * (f[i][jj] - i1 / 3.0 * fit[i][jj]);
            }
        }
        let mut t = [[[[0.0; 2]; 2]; 2]; 2];
        if want_tangent {
            let ga = g * a;
            for i in 0..2 {
                for jj in 0..2 {
                    for k in 0..2 {
                        for l in 0..2 {
                            let delta = if i == k && jj == l { 1.0 } else { 0.0 };
                            t[i][jj][k][l] = ga
                                * (delta
                                    - 2.0 / 3.0 * (fit[k][l] * f[i][jj] + f[k][l] * fit[i][jj])
                                    + 2.0 / 9.0 * i1 * fit[i][jj] * fit[k][l]
                                    + i1 / 3.0 * fit[i][l] * fit[k][jj]);
                        }
                    }
                }
            }
        }
        Some(IsoResponse { w, p, a: t })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `J^(−2/3)` by Newton steps near `J = 1` and by the cube root elsewhere agrees with
    /// `powf` to round-off (a few units in the last place) on both sides of the switch at
    /// `|J − 1| = 0.05`.
    #[test]
    fn j_minus_two_thirds_is_exact_to_round_off() {
        let mut largest = 0.0_f64;
        for i in 0..=20_000 {
            let j = 0.9 + 0.2 * f64::from(i) / 20_000.0;
            let exact = j.powf(-2.0 / 3.0);
            largest = largest.max((j_minus_two_thirds(j) / exact - 1.0).abs());
        }
        assert!(
            largest <= 4.0 * f64::EPSILON,
            "largest relative error {largest:e}"
        );
    }
}
