//! Interpolation of load curves at fixed `a/λ` and the mesh-convergence table.
//!
//! Curves are compared at common `a/λ` values. Because `p̄ ∝ sin²(πa/λ)` in the linear
//! limit, `√p̄` is a smooth, nearly linear function of `a` at small `a`; it is
//! interpolated with the cubic Lagrange polynomial through the four converged points
//! nearest to `a` (two on each side where possible).
//!
//! Richardson extrapolation for three meshes refined by a constant factor `ρ` (`f₁`
//! coarse, `f₂` default, `f₃` fine; `ρ = 1.5` for the named levels): the observed order
//! is `q = log(|f₁ − f₂| / |f₂ − f₃|) / log ρ`; a global order `q̄` is computed from the
//! root-mean-square differences over all `a` values (per-`a` orders are noisy where the
//! differences are tiny) and the error estimate of the default mesh is
//! `|f₂ − f₃| · ρ^q̃ / (ρ^q̃ − 1)`, relative to `f₃`, with `q̃ = q̄` limited to `[1, 2]`:
//! the formal orders of the two error sources, the contact-edge location (first order,
//! `O(h)` within the last loaded element) and the Q1 load at a fixed slab displacement
//! (second order). Where the two partly cancel on the coarse mesh the observed order
//! comes out larger than 2, and the limit keeps the estimate from shrinking below
//! `ρ²/(ρ² − 1) |f₂ − f₃|` (1.8 |f₂ − f₃| for ρ = 1.5); below 1 the factor is at most
//! `ρ/(ρ − 1)` (3 for ρ = 1.5).

use super::{solve_curve, CurveFailure, CurvePoint, LayerProblem, MeshLevel, SolveOptions};
use std::ops::ControlFlow;

/// `p̄/E*` at `a/λ` by cubic interpolation of `√p̄` (see module docs); `None` outside
/// the range of the points. A point whose `a` does not exceed the previous one's is
/// skipped: the curve may repeat an edge position (a node that touches with a
/// vanishing force, is released and touches again at a marginally larger slab displacement), and
/// the interpolation needs distinct abscissae (closer than 10⁻⁶ counts as repeated;
/// distinct events are an element length, ≳ 10⁻³, apart).
/// The formal orders of the FE error (the contact-edge location, first order, and the Q1 load
/// at a fixed displacement, second order): an observed order is limited to this range before it
/// extrapolates.
pub const FORMAL_ORDER_RANGE: (f64, f64) = (1.0, 2.0);

pub fn p_at(points: &[CurvePoint], a_over_lambda: f64) -> Option<f64> {
    let mut xs: Vec<f64> = Vec::with_capacity(points.len());
    let mut ys: Vec<f64> = Vec::with_capacity(points.len());
    for p in points {
        if xs.last().is_none_or(|&l| p.a_over_lambda > l + 1e-6) {
            xs.push(p.a_over_lambda);
            ys.push(p.p_over_estar.max(0.0).sqrt());
        }
    }
    let n = xs.len();
    if n < 2 {
        return None;
    }
    let a = a_over_lambda;
    if a < xs[0] || a > xs[n - 1] {
        return None;
    }
    let k = xs.iter().position(|&x| x >= a).unwrap_or(n - 1).max(1); // xs[k-1] < a <= xs[k]
    let lo = k.saturating_sub(2);
    let hi = (lo + 4).min(n);
    let lo = hi.saturating_sub(4);
    let mut s = 0.0;
    for i in lo..hi {
        let mut l = 1.0;
        for j in lo..hi {
            if i != j {
                l *= (a - xs[j]) / (xs[i] - xs[j]);
            }
        }
        s += l * ys[i];
    }
    Some(s * s)
}

/// One row of the convergence table.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ConvergenceRow {
    /// `a/λ`.
    pub a_over_lambda: f64,
    /// `p̄/E*` on the coarse, default and fine meshes.
    pub p_over_estar: [f64; 3],
    /// Observed order at this `a` (NaN where undefined).
    pub observed_order: f64,
    /// Richardson estimate of the relative error of the default mesh (global order,
    /// limited to `[1, 2]`).
    pub default_relative_error: f64,
}

/// Mesh-convergence table.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ConvergenceTable {
    /// Rows.
    pub rows: Vec<ConvergenceRow>,
    /// Global observed order from RMS differences.
    pub observed_order: f64,
}

/// Build the table from three curves (coarse, default, fine; refinement ratio `ratio`).
pub fn convergence_table(
    curves: [&[CurvePoint]; 3],
    ratio: f64,
    a_values: &[f64],
) -> Option<ConvergenceTable> {
    let mut vals = Vec::new();
    for &a in a_values {
        let f = [
            p_at(curves[0], a)?,
            p_at(curves[1], a)?,
            p_at(curves[2], a)?,
        ];
        vals.push((a, f));
    }
    let (mut s12, mut s23) = (0.0, 0.0);
    for (_, f) in &vals {
        s12 += ((f[0] - f[1]) / f[2]).powi(2);
        s23 += ((f[1] - f[2]) / f[2]).powi(2);
    }
    let q = (s12.sqrt() / s23.sqrt()).ln() / ratio.ln();
    let rq = ratio.powf(q.clamp(FORMAL_ORDER_RANGE.0, FORMAL_ORDER_RANGE.1));
    let rows = vals
        .into_iter()
        .map(|(a, f)| ConvergenceRow {
            a_over_lambda: a,
            p_over_estar: f,
            observed_order: ((f[0] - f[1]).abs() / (f[1] - f[2]).abs()).ln() / ratio.ln(),
            default_relative_error: ((f[1] - f[2]) / f[2]).abs() * rq / (rq - 1.0),
        })
        .collect();
    Some(ConvergenceTable {
        rows,
        observed_order: q,
    })
}

/// Solve on the coarse, default and fine meshes and tabulate the convergence at the
/// given `a/λ` values (which must lie inside every curve).
pub fn mesh_convergence(
    problem: &LayerProblem,
    opts: &SolveOptions,
    a_values: &[f64],
) -> Result<ConvergenceTable, Box<CurveFailure>> {
    mesh_convergence_levels(
        problem,
        opts,
        [MeshLevel::Coarse, MeshLevel::Default, MeshLevel::Fine],
        a_values,
    )
}

/// As [`mesh_convergence`] on three given meshes, refined by a constant ratio of their
/// element counts along the face (the middle one plays the role of the "default" mesh
/// in the table).
pub fn mesh_convergence_levels(
    problem: &LayerProblem,
    opts: &SolveOptions,
    levels: [MeshLevel; 3],
    a_values: &[f64],
) -> Result<ConvergenceTable, Box<CurveFailure>> {
    let invalid = |field, value, allowed| {
        Box::new(CurveFailure {
            error: super::SolveError::InvalidInput {
                field,
                value,
                allowed,
            },
            points: Vec::new(),
            unloading: Vec::new(),
        })
    };
    let nx = levels.map(|l| l.counts().0 as f64);
    let ratio = nx[1] / nx[0];
    if !(ratio > 1.0 && (nx[2] / nx[1] - ratio).abs() <= 1e-9 * ratio) {
        return Err(invalid(
            "levels",
            nx[2] / nx[1],
            "element counts refined by one constant ratio > 1",
        ));
    }
    let mut curves = Vec::new();
    for level in levels {
        let o = SolveOptions {
            mesh: level,
            ..*opts
        };
        curves.push(solve_curve(problem, &o, &mut |_| ControlFlow::Continue(()))?.points);
    }
    convergence_table([&curves[0], &curves[1], &curves[2]], ratio, a_values).ok_or_else(|| {
        invalid(
            "a_values",
            f64::NAN,
            "inside the computed range of every curve",
        )
    })
}
