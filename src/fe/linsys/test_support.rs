//! Test fixtures of the linear-algebra tests: a 3-element strip of 16 equations, its
//! right-hand sides, and checks against a dense LU.

use super::{RowChange, SparseSystem};
use faer::linalg::solvers::Solve;
use faer::Mat;

/// A 3-element strip (16 equations): symmetric, diagonally dominant values with
/// deterministic off-diagonal entries.
pub(super) fn strip() -> SparseSystem {
    let elems: Vec<[usize; 8]> = (0..3)
        .map(|e| std::array::from_fn(|i| (4 * e + i) % 16))
        .collect();
    let mut sys = SparseSystem::new(16, &elems);
    for c in 0..16 {
        for k in sys.col_ptr[c]..sys.col_ptr[c + 1] {
            let r = sys.row_idx[k];
            sys.values[k] = if r == c {
                10.0 + c as f64
            } else {
                (((r + c) * 7 % 5) as f64 - 2.0) * 0.3
            };
        }
    }
    sys
}

/// Right-hand sides for the strip.
pub(super) fn strip_rhs(count: usize) -> Vec<Vec<f64>> {
    (0..count)
        .map(|j| {
            (0..16)
                .map(|i| ((i * 3 + j * 5) % 7) as f64 - 3.0)
                .collect()
        })
        .collect()
}

/// `x` against the dense LU solution of `dense x = b`, to 10⁻¹² relative.
pub(super) fn assert_matches_dense(dense: &Mat<f64>, x: &[f64], b: &[f64]) {
    let reference = dense
        .partial_piv_lu()
        .solve(Mat::from_fn(16, 1, |i, _| b[i]));
    for (i, v) in x.iter().enumerate() {
        assert!(
            (v - reference[(i, 0)]).abs() <= 1e-12 * (1.0 + reference[(i, 0)].abs()),
            "x[{i}] = {v} vs dense {}",
            reference[(i, 0)]
        );
    }
}

/// `strip()` with equations 6–15 ordered last.
pub(super) fn trailing_strip() -> SparseSystem {
    let mut sys = strip();
    sys.order_last(&(6..16).collect::<Vec<_>>());
    sys
}

/// The system of `sys` and right-hand side `b` under `change` (one right-hand side), dense.
fn changed_system(sys: &SparseSystem, b: &[f64], change: &RowChange) -> (Mat<f64>, Vec<f64>) {
    let dense = Mat::from_fn(16, 16, |r, c| {
        let extra: f64 = change
            .entries
            .iter()
            .filter(|&&(col, _)| r == change.row && col == c)
            .map(|&(_, v)| v)
            .sum();
        sys.get(r, c) + extra
    });
    let mut changed_b = b.to_vec();
    changed_b[change.row] += change.rhs[0];
    (dense, changed_b)
}

/// Solve `sys` for the strip's right-hand side, with a `switch` that asks for `change`
/// once (`inspect` sees every solution shown to it): one factorisation, one changed solve,
/// two calls of `switch`, and the changed system's solution (dense LU). Returns the
/// right-hand side.
pub(super) fn assert_switches_once(
    sys: &mut SparseSystem,
    change: &RowChange,
    inspect: impl Fn(&[Vec<f64>]),
) -> Vec<f64> {
    let b = strip_rhs(1).remove(0);
    let (dense, changed_b) = changed_system(sys, &b, change);
    let factorisations = sys.factorisations();
    let mut seen = 0;
    let mut x = vec![b.clone()];
    let passes = sys
        .solve_switching_rows(&mut x, 4, |shown| {
            seen += 1;
            inspect(shown);
            (seen == 1).then(|| vec![change.clone()])
        })
        .expect("solvable");
    assert_eq!((passes, seen), (Some(1), 2));
    assert_eq!(sys.factorisations(), factorisations + 1);
    assert_matches_dense(&dense, &x[0], &changed_b);
    b
}
