//! The limit of a mesh sequence: `p(n) = p₀ + c₁/n + c₂/n²` fitted by least squares through the
//! values on several meshes (`n` elements along the face), and how far that limit moves when a
//! mesh is left out. The speed–accuracy scene's reference is this limit of the finite-strain
//! curves on fine meshes at each a/λ (docs/replication.md R11).
//!
//! Both terms are needed: the edge rule's residual error falls at first order and the bulk
//! element's at second, and which one leads changes along a curve; a Richardson step with one
//! order errs by the other term.

use faer::prelude::*;
use faer::Mat;

/// Least-squares coefficients `[c₀, …, c_d]` of `y ≈ Σ c_k x^k` (column-pivoted QR, faer);
/// `None` with fewer points than coefficients or a non-finite result.
pub fn polynomial_least_squares(xs: &[f64], ys: &[f64], degree: usize) -> Option<Vec<f64>> {
    let n = xs.len().min(ys.len());
    if n <= degree {
        return None;
    }
    let design = Mat::from_fn(n, degree + 1, |i, k| xs[i].powi(k as i32));
    let rhs = Mat::from_fn(n, 1, |i, _| ys[i]);
    let solution = design.col_piv_qr().solve_lstsq(&rhs);
    let c: Vec<f64> = (0..=degree).map(|k| solution[(k, 0)]).collect();
    c.iter().all(|v| v.is_finite()).then_some(c)
}

/// The limit `p₀` of `p(n) = p₀ + c₁/n + c₂/n²` through `values` on `meshes` (at least three).
pub fn mesh_limit(meshes: &[usize], values: &[f64]) -> Option<f64> {
    let h: Vec<f64> = meshes.iter().map(|&n| 1.0 / n as f64).collect();
    polynomial_least_squares(&h, values, 2).map(|c| c[0])
}

/// The limit of [`mesh_limit`] over all `meshes`, and its spread relative to it: the largest
/// `|p₀(subset) − p₀|/|p₀|` over the subsets that leave one mesh out (each of at least three
/// meshes). With three meshes the fit is exact and no mesh can be left out: the spread is then
/// that of the two-mesh first-order Richardson steps, `|R₁(n₂, n₃) − p₀|` and
/// `|R₁(n₁, n₂) − p₀|`.
pub fn mesh_limit_with_spread(meshes: &[usize], values: &[f64]) -> Option<(f64, f64)> {
    let p0 = mesh_limit(meshes, values)?;
    let mut spread = 0.0f64;
    if meshes.len() > 3 {
        for left_out in 0..meshes.len() {
            let kept = (0..meshes.len()).filter(|&i| i != left_out);
            let sub_meshes: Vec<usize> = kept.clone().map(|i| meshes[i]).collect();
            let sub_values: Vec<f64> = kept.map(|i| values[i]).collect();
            let sub = mesh_limit(&sub_meshes, &sub_values)?;
            spread = spread.max(((sub - p0) / p0).abs());
        }
    } else {
        for w in 0..meshes.len() - 1 {
            let (n1, n2) = (meshes[w] as f64, meshes[w + 1] as f64);
            let r1 = crate::accuracy::richardson(values[w], values[w + 1], n2 / n1, 1.0);
            spread = spread.max(((r1 - p0) / p0).abs());
        }
    }
    Some((p0, spread))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sequence with exactly the fitted form gives its limit back, to round-off, and a spread
    /// at round-off; a third-order term makes the spread grow with it.
    #[test]
    fn the_limit_of_an_exact_sequence_is_recovered() {
        let meshes = [64, 96, 128, 192];
        let p = |n: usize, c3: f64| {
            let h = 1.0 / n as f64;
            0.5 + 0.3 * h - 20.0 * h * h + c3 * h * h * h
        };
        let values: Vec<f64> = meshes.iter().map(|&n| p(n, 0.0)).collect();
        let (p0, spread) = mesh_limit_with_spread(&meshes, &values).unwrap();
        assert!((p0 - 0.5).abs() < 1e-12, "{p0}");
        assert!(spread < 1e-10, "{spread}");
        let values: Vec<f64> = meshes.iter().map(|&n| p(n, 50.0)).collect();
        let (p0, spread) = mesh_limit_with_spread(&meshes, &values).unwrap();
        assert!(
            (p0 / 0.5 - 1.0).abs() < 4e-4 && spread > 1e-6,
            "{p0} {spread}"
        );
        assert!(mesh_limit(&meshes[..2], &values[..2]).is_none());
    }

    /// With three meshes the fit is exact, and the spread is that of the first-order Richardson
    /// steps: for p(n) = 0.5 + 0.3/n it is zero, a second-order term makes it positive.
    #[test]
    fn three_meshes_spread_by_the_first_order_steps() {
        let meshes = [32, 48, 72];
        let first: Vec<f64> = meshes.iter().map(|&n| 0.5 + 0.3 / n as f64).collect();
        let (p0, spread) = mesh_limit_with_spread(&meshes, &first).unwrap();
        assert!((p0 - 0.5).abs() < 1e-12 && spread < 1e-12, "{p0} {spread}");
        let second: Vec<f64> = meshes.iter().map(|&n| 0.5 + 5.0 / (n * n) as f64).collect();
        let (p0, spread) = mesh_limit_with_spread(&meshes, &second).unwrap();
        assert!((p0 - 0.5).abs() < 1e-12 && spread > 1e-4, "{p0} {spread}");
    }

    #[test]
    fn least_squares_fits_a_quadratic() {
        let xs = [0.0, 1.0, 2.0, 3.0, 4.0];
        let ys: Vec<f64> = xs.iter().map(|x| 1.0 - 2.0 * x + 0.5 * x * x).collect();
        let c = polynomial_least_squares(&xs, &ys, 2).unwrap();
        for (got, want) in c.iter().zip([1.0, -2.0, 0.5]) {
            assert!((got - want).abs() < 1e-12, "{c:?}");
        }
    }
}
