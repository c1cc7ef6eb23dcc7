//! Bilinear quadrilateral (Q1) with the mean-dilatation (Q1/P0) volumetric energy.
//!
//! Element energy (reference area `V_e`, current area `v_e`):
//!
//! ```text
//! Π_e = ∫_{Ω_e} G/2 (J^(−2/3) tr C − 3) dV  +  V_e κ/2 (v_e/V_e − 1)²
//! ```
//!
//! The isochoric integral uses 2×2 Gauss quadrature. `v_e` is the exact area of the
//! current bilinear quad (shoelace formula of its four corners):
//!
//! ```text
//! v = ½ Σ_k (x_k y_{k+1} − x_{k+1} y_k)
//! ∂v/∂x_k = ½ (y_{k+1} − y_{k−1}),   ∂v/∂y_k = ½ (x_{k−1} − x_{k+1})
//! ∂²v/∂x_k∂y_{k+1} = ½,  ∂²v/∂x_k∂y_{k−1} = −½   (all other second derivatives 0)
//! ```
//!
//! so the volumetric gradient is `κ (v/V − 1) ∇v` and its Hessian
//! `κ/V ∇v ∇vᵀ + κ (v/V − 1) ∇²v`.
//!
//! Why this choice: a single constant dilatation per element is exactly the Q1/P0
//! (mean-dilatation) mixed element with the pressure condensed out, which is free of
//! volumetric locking for `κ/G` up to 10⁴ and beyond (see `tests/solver/fe_locking.rs`),
//! and it keeps the problem a pure-displacement minimisation with a symmetric
//! Hessian, which the exact nonlinear contact elimination and energy line search rely
//! on. Continuous-pressure Taylor–Hood elements were avoided because of the surface
//! folds reported for them on this problem.
//!
//! Inversion: the element is declared inverted (energy `+∞`, functions return `None`)
//! if any of the four corner Jacobians is non-positive (for a bilinear map, the
//! Jacobian determinant is bilinear in the parent coordinates, so positive corners
//! imply a positive Jacobian everywhere), or any Gauss-point `J ≤ 0`, or `v_e ≤ 0`.

use crate::fe::model::material::NeoHooke;

const GP: f64 = 0.577_350_269_189_625_8; // 1/√3

/// Reference data of one quad: shape-function gradients at the Gauss points.
#[derive(Clone, Debug)]
pub struct QuadRef {
    /// `dn[g][a] = ∂N_a/∂X` at Gauss point `g`.
    pub dn: [[[f64; 2]; 4]; 4],
    /// Gauss weight times reference Jacobian determinant.
    pub wdet: [f64; 4],
    /// Reference area `V_e`.
    pub area: f64,
}

/// Energy, gradient and Hessian of one element with respect to its 8 current
/// coordinates ordered `(x₀, y₀, x₁, y₁, …)`.
#[derive(Clone, Debug)]
pub struct ElementTangent {
    /// Element energy.
    pub energy: f64,
    /// Gradient (internal nodal forces).
    pub grad: [f64; 8],
    /// Hessian (tangent stiffness), row-major.
    pub hess: [[f64; 8]; 8],
}

impl QuadRef {
    /// Build from the four reference corners, counter-clockwise.
    pub fn new(xr: &[[f64; 2]; 4]) -> Self {
        let pts = [(-GP, -GP), (GP, -GP), (GP, GP), (-GP, GP)];
        let mut dn = [[[0.0; 2]; 4]; 4];
        let mut wdet = [0.0; 4];
        for (g, &(xi, eta)) in pts.iter().enumerate() {
            let dxi = [
                -(1.0 - eta) / 4.0,
                (1.0 - eta) / 4.0,
                (1.0 + eta) / 4.0,
                -(1.0 + eta) / 4.0,
            ];
            let deta = [
                -(1.0 - xi) / 4.0,
                -(1.0 + xi) / 4.0,
                (1.0 + xi) / 4.0,
                (1.0 - xi) / 4.0,
            ];
            let mut jm = [[0.0; 2]; 2];
            for a in 0..4 {
                jm[0][0] += xr[a][0] * dxi[a];
                jm[0][1] += xr[a][0] * deta[a];
                jm[1][0] += xr[a][1] * dxi[a];
                jm[1][1] += xr[a][1] * deta[a];
            }
            let det = jm[0][0] * jm[1][1] - jm[0][1] * jm[1][0];
            let inv = [
                [jm[1][1] / det, -jm[0][1] / det],
                [-jm[1][0] / det, jm[0][0] / det],
            ];
            for a in 0..4 {
                // ∂N/∂X_J = ∂N/∂ξ_m (J⁻¹)_mJ
                dn[g][a][0] = dxi[a] * inv[0][0] + deta[a] * inv[1][0];
                dn[g][a][1] = dxi[a] * inv[0][1] + deta[a] * inv[1][1];
            }
            wdet[g] = det;
        }
        Self {
            dn,
            wdet,
            area: shoelace(xr),
        }
    }

    fn deformation_gradient(&self, g: usize, x: &[[f64; 2]; 4]) -> [[f64; 2]; 2] {
        let mut f = [[0.0; 2]; 2];
        for a in 0..4 {
            for i in 0..2 {
                for jj in 0..2 {
                    f[i][jj] += x[a][i] * self.dn[g][a][jj];
                }
            }
        }
        f
    }
}

/// Shoelace area of a quad with corners counter-clockwise.
pub fn shoelace(x: &[[f64; 2]; 4]) -> f64 {
    let mut v = 0.0;
    for k in 0..4 {
        let n = (k + 1) % 4;
        v += x[k][0] * x[n][1] - x[n][0] * x[k][1];
    }
    0.5 * v
}

/// True when every corner Jacobian of the current quad is positive.
pub fn corners_ok(x: &[[f64; 2]; 4]) -> bool {
    (0..4).all(|k| {
        let n = x[(k + 1) % 4];
        let p = x[(k + 3) % 4];
        let e1 = [n[0] - x[k][0], n[1] - x[k][1]];
        let e2 = [p[0] - x[k][0], p[1] - x[k][1]];
        let c = e1[0] * e2[1] - e1[1] * e2[0];
        c > 0.0 && c.is_finite()
    })
}

/// Element energy; `None` if the element is inverted.
pub fn energy(q: &QuadRef, mat: &NeoHooke, x: &[[f64; 2]; 4]) -> Option<f64> {
    gradient(q, mat, x).map(|(e, _)| e)
}

/// Gradient `∂v/∂x` of the current element area (shoelace formula), `[x₀, y₀, x₁, …]`.
pub(crate) fn area_gradient(x: &[[f64; 2]; 4]) -> [f64; 8] {
    let mut dv = [0.0; 8];
    for k in 0..4 {
        let n = (k + 1) % 4;
        let p = (k + 3) % 4;
        dv[2 * k] = 0.5 * (x[n][1] - x[p][1]);
        dv[2 * k + 1] = 0.5 * (x[p][0] - x[n][0]);
    }
    dv
}

/// Element energy and gradient (no Hessian); `None` if the element is inverted.
pub fn gradient(q: &QuadRef, mat: &NeoHooke, x: &[[f64; 2]; 4]) -> Option<(f64, [f64; 8])> {
    if !corners_ok(x) {
        return None;
    }
    let mut energy = 0.0;
    let mut grad = [0.0; 8];
    for g in 0..4 {
        let f = q.deformation_gradient(g, x);
        let k = mat.iso_kinematics(&f)?;
        let w = q.wdet[g];
        energy += w * k.w;
        // P = G a (F − (I₁/3) F⁻ᵀ)
        let c = k.i1 / 3.0;
        let wga = w * k.ga;
        let p = [
            [
                wga * (f[0][0] - c * k.fit[0][0]),
                wga * (f[0][1] - c * k.fit[0][1]),
            ],
            [
                wga * (f[1][0] - c * k.fit[1][0]),
                wga * (f[1][1] - c * k.fit[1][1]),
            ],
        ];
        for (a, d) in q.dn[g].iter().enumerate() {
            grad[2 * a] += p[0][0] * d[0] + p[0][1] * d[1];
            grad[2 * a + 1] += p[1][0] * d[0] + p[1][1] * d[1];
        }
    }
    let v = shoelace(x);
    if v <= 0.0 {
        return None;
    }
    let r = v / q.area - 1.0;
    energy += 0.5 * mat.kappa * q.area * r * r;
    let kr = mat.kappa * r;
    for (g, dv) in grad.iter_mut().zip(area_gradient(x)) {
        *g += kr * dv;
    }
    Some((energy, grad))
}

/// Element energy, gradient and Hessian; `None` if the element is inverted.
///
/// Isochoric part in closed form per Gauss point (weight `w`): with the node vectors
/// `f_a = F ∇N_a`, `h_a = F⁻ᵀ ∇N_a` and `n_ab = ∇N_a · ∇N_b`, contracting the tangent
/// `A_iJkL` of [`crate::fe::model::material`] with `∇N_a`, `∇N_b` gives
///
/// ```text
/// g_ai  = w G a (f_ai − (I₁/3) h_ai)
/// K_aibk = w G a [ δ_ik n_ab − (2/3)(f_ai h_bk + h_ai f_bk)
///                  + (2/9) I₁ h_ai h_bk + (I₁/3) h_bi h_ak ]
/// ```
///
/// (`a = J^(−2/3)`); only the blocks `b ≥ a` are computed, the rest by symmetry.
#[allow(non_snake_case)]
pub fn tangent(
    q: &QuadRef,
    mat: &NeoHooke,
    x: &[[f64; 2]; 4],
    geometric_pressure: Option<f64>,
) -> Option<ElementTangent> {
    if !corners_ok(x) {
        return None;
    }
    let mut energy = 0.0;
    let mut grad = [0.0; 8];
    let mut hess = [[0.0; 8]; 8];
    for g in 0..4 {
        let f = q.deformation_gradient(g, x);
        let k = mat.iso_kinematics(&f)?;
        let w = q.wdet[g];
        energy += w * k.w;
        let dn = &q.dn[g];
        let mut fa = [[0.0; 2]; 4];
        let mut ha = [[0.0; 2]; 4];
        for a in 0..4 {
            for i in 0..2 {
                fa[a][i] = f[i][0] * dn[a][0] + f[i][1] * dn[a][1];
                ha[a][i] = k.fit[i][0] * dn[a][0] + k.fit[i][1] * dn[a][1];
            }
        }
        let s = w * k.ga;
        let c1 = k.i1 / 3.0;
        let c2 = 2.0 / 9.0 * k.i1;
        for a in 0..4 {
            for i in 0..2 {
                grad[2 * a + i] += s * (fa[a][i] - c1 * ha[a][i]);
            }
            for b in a..4 {
                let nab = dn[a][0] * dn[b][0] + dn[a][1] * dn[b][1];
                for i in 0..2 {
                    for kk in 0..2 {
                        let mut v = -2.0 / 3.0 * (fa[a][i] * ha[b][kk] + ha[a][i] * fa[b][kk])
                            + c2 * ha[a][i] * ha[b][kk]
                            + c1 * ha[b][i] * ha[a][kk];
                        if i == kk {
                            v += nab;
                        }
                        hess[2 * a + i][2 * b + kk] += s * v;
                    }
                }
            }
        }
    }
    for r in 0..8 {
        for c in 0..r {
            if c / 2 < r / 2 {
                hess[r][c] = hess[c][r];
            }
        }
    }
    // mean-dilatation volumetric part
    let v = shoelace(x);
    if v <= 0.0 {
        return None;
    }
    let V = q.area;
    let r = v / V - 1.0;
    energy += 0.5 * mat.kappa * V * r * r;
    let dv = area_gradient(x);
    let kr = mat.kappa * r;
    let kv = mat.kappa / V;
    for a in 0..8 {
        grad[a] += kr * dv[a];
        for b in 0..8 {
            hess[a][b] += kv * dv[a] * dv[b];
        }
    }
    let pg = geometric_pressure.unwrap_or(kr);
    for k in 0..4 {
        let n = (k + 1) % 4;
        let p = (k + 3) % 4;
        hess[2 * k][2 * n + 1] += 0.5 * pg;
        hess[2 * n + 1][2 * k] += 0.5 * pg;
        hess[2 * k][2 * p + 1] -= 0.5 * pg;
        hess[2 * p + 1][2 * k] -= 0.5 * pg;
    }
    Some(ElementTangent { energy, grad, hess })
}
