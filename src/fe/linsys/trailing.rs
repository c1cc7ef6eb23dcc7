//! The trailing block: the equations that the row updates touch, ordered last in the
//! Cholesky factorisations so that `S⁻¹` on them is read from the factor's dense trailing
//! block instead of solved for one unit vector at a time (see the
//! [module documentation](super)).

use super::{pattern, Factored, LinSolveError, Permutation, SparseSystem};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::triangular_solve;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
use faer::{Mat, Par};

impl SparseSystem {
    /// Order the equations `dofs` last in the Cholesky factorisation (the others by
    /// approximate minimum degree among themselves), before the first solve. When every
    /// row update and every column it touches lies among them, the Woodbury solve takes
    /// `(S⁻¹)` on them from the factor's dense trailing block (the inverse of the Schur
    /// complement of `S` onto them) instead of solving for one unit vector per updated
    /// row: two ordinary solves per Newton system instead of `m + 1`
    /// ([`Self::solve_switching_rows`]).
    pub fn order_last(&mut self, dofs: &[usize]) {
        assert!(
            self.symbolic_cholesky.is_none(),
            "ordered before the first solve"
        );
        self.trailing_slot.iter_mut().for_each(|s| *s = usize::MAX);
        self.trailing.clear();
        for &d in dofs {
            if self.trailing_slot[d] == usize::MAX {
                self.trailing_slot[d] = self.trailing.len();
                self.trailing.push(d);
            }
        }
    }

    /// The fill-reducing ordering with the `trailing` equations last: approximate minimum
    /// degree among the others, then `trailing` in their order (forward and inverse
    /// permutations); `None` when no equations are ordered last.
    pub(super) fn trailing_ordering(&self) -> Result<Option<Permutation>, LinSolveError> {
        if self.trailing.is_empty() {
            return Ok(None);
        }
        let lead: Vec<usize> = (0..self.n)
            .filter(|&d| self.trailing_slot[d] == usize::MAX)
            .collect();
        let mut lead_slot = vec![usize::MAX; self.n];
        for (i, &d) in lead.iter().enumerate() {
            lead_slot[d] = i;
        }
        // the pattern among the leading equations (rows stay sorted: `lead` is increasing)
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for &d in &lead {
            let rows = &self.row_idx[self.col_ptr[d]..self.col_ptr[d + 1]];
            row_idx.extend(
                rows.iter()
                    .map(|&r| lead_slot[r])
                    .filter(|&r| r != usize::MAX),
            );
            col_ptr.push(row_idx.len());
        }
        let nl = lead.len();
        let (mut fwd, mut inv) = (vec![0usize; nl], vec![0usize; nl]);
        let mut mem = MemBuffer::new(amd::order_scratch::<usize>(nl, row_idx.len()));
        amd::order(
            &mut fwd,
            &mut inv,
            pattern(nl, &col_ptr, &row_idx),
            Default::default(),
            MemStack::new(&mut mem),
        )
        .map_err(|e| LinSolveError::Symbolic(format!("{e:?}")))?;
        let perm_fwd: Vec<usize> = fwd
            .iter()
            .map(|&i| lead[i])
            .chain(self.trailing.iter().copied())
            .collect();
        let mut perm_inv = vec![0; self.n];
        for (p, &d) in perm_fwd.iter().enumerate() {
            perm_inv[d] = p;
        }
        Ok(Some((perm_fwd, perm_inv)))
    }

    /// `true` when every updated row and every column of the updates is ordered last.
    pub(super) fn updates_within_trailing(&self) -> bool {
        let kept = |d: usize| self.trailing_slot[d] != usize::MAX;
        !self.trailing.is_empty()
            && self.updates.rows.iter().all(|&r| kept(r))
            && self
                .updates
                .entries
                .iter()
                .all(|row| row.iter().all(|&(c, _)| kept(c)))
    }

    /// `(S⁻¹ E)` on the trailing equations from the factor's trailing block, `E` the unit
    /// vectors of the updated rows: with the trailing equations `T` last, the factor's
    /// block `L_TT` factors the Schur complement `Σ` of `S` onto them (`Σ = L_TT L_TTᵀ`, or
    /// `L_TT D_TT L_TTᵀ` for `L D Lᵀ`), and `(S⁻¹)_TT = Σ⁻¹`. `None` when the factorisation
    /// held is not a supernodal `L Lᵀ` or `L D Lᵀ` or the result is not finite.
    pub(super) fn trailing_inverse_columns(&self) -> Option<Mat<f64>> {
        let unit_diagonal = match self.factored {
            Factored::Llt => false,
            Factored::Ldlt => true,
            _ => return None,
        };
        let symbolic = self.symbolic_cholesky.as_ref()?;
        // the factor's positions are the ordered ones only if faer kept that order
        let SymbolicCholeskyRaw::Supernodal(supernodal) = symbolic.raw() else {
            return None;
        };
        if symbolic.perm().is_some() {
            return None;
        }
        let c = self.trailing.len();
        let first = self.n - c;
        // the trailing block of the factor (LDLᵀ stores D on L's unit diagonal)
        let factor = SupernodalLltRef::new(supernodal, &self.llt_values);
        let mut l = Mat::<f64>::zeros(c, c);
        for s in (0..supernodal.n_supernodes()).rev() {
            let node = factor.supernode(s);
            let (start, val) = (node.start(), node.val());
            let width = val.ncols();
            if start + width <= first {
                break;
            }
            for jj in first.saturating_sub(start)..width {
                let col = start + jj - first;
                for r in jj..width {
                    l[(start + r - first, col)] = val[(r, jj)];
                }
                for (idx, &row) in node.pattern().iter().enumerate() {
                    l[(row - first, col)] = val[(width + idx, jj)];
                }
            }
        }
        let m = self.updates.len();
        let mut z = Mat::<f64>::zeros(c, m);
        for (i, &r) in self.updates.rows.iter().enumerate() {
            z[(self.trailing_slot[r], i)] = 1.0;
        }
        // the forward solve starts at the first updated row (above it, `L⁻¹ E` is zero)
        let s0 = self
            .updates
            .rows
            .iter()
            .map(|&r| self.trailing_slot[r])
            .min()
            .unwrap_or(c);
        let l_low = l.as_ref().submatrix(s0, s0, c - s0, c - s0);
        let par = Par::Seq;
        if unit_diagonal {
            triangular_solve::solve_unit_lower_triangular_in_place(
                l_low,
                z.as_mut().subrows_mut(s0, c - s0),
                par,
            );
            for i in s0..c {
                let d = l[(i, i)];
                z.row_mut(i).iter_mut().for_each(|v| *v /= d);
            }
            triangular_solve::solve_unit_upper_triangular_in_place(l.transpose(), z.as_mut(), par);
        } else {
            triangular_solve::solve_lower_triangular_in_place(
                l_low,
                z.as_mut().subrows_mut(s0, c - s0),
                par,
            );
            triangular_solve::solve_upper_triangular_in_place(l.transpose(), z.as_mut(), par);
        }
        let finite = (0..m).all(|j| z.col(j).iter().all(|v| v.is_finite()));
        finite.then_some(z)
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{
        assert_matches_dense, assert_switches_once, strip_rhs, trailing_strip,
    };
    use super::super::RowChange;
    use super::*;

    /// With the updates' rows and columns ordered last, the Woodbury solve reads `S⁻¹` there
    /// from the factor's trailing block (no unit-vector solves), after a Cholesky and, for
    /// an indefinite `S`, after an `L D Lᵀ`; both agree with a dense LU of `S + E Vᵀ`.
    #[test]
    fn trailing_block_solve_matches_dense_lu() {
        for indefinite in [false, true] {
            let mut sys = trailing_strip();
            if indefinite {
                let p = sys.diag_pos[1];
                sys.values[p] = -12.0;
            }
            for (r, c, v) in [(9, 7, 4.0), (9, 9, -2.5), (12, 6, -6.0), (12, 15, 3.0)] {
                sys.add_to_row(r, c, v);
            }
            let dense = Mat::from_fn(16, 16, |r, c| sys.get(r, c));
            let b = strip_rhs(2);
            let mut x = b.clone();
            sys.solve(&mut x).expect("solvable");
            let expected = if indefinite {
                Factored::Ldlt
            } else {
                Factored::Llt
            };
            assert_eq!(sys.factored, expected);
            assert_eq!(sys.woodbury_unit_solves(), 0, "indefinite: {indefinite}");
            // one Cholesky (and an L D Lᵀ after it fails), no LU of the whole matrix: the
            // trailing-block solution passed the residual check
            assert_eq!(sys.factorisations(), 1 + usize::from(indefinite));
            for (xj, bj) in x.iter().zip(&b) {
                assert_matches_dense(&dense, xj, bj);
            }
        }
    }

    /// An update touching an equation that is not ordered last: one unit-vector solve per
    /// updated row instead, the same solution.
    #[test]
    fn updates_beyond_the_trailing_block_solve_by_unit_vectors() {
        let mut sys = trailing_strip();
        for (r, c, v) in [(9, 7, 4.0), (12, 2, -6.0)] {
            sys.add_to_row(r, c, v);
        }
        let dense = Mat::from_fn(16, 16, |r, c| sys.get(r, c));
        let b = strip_rhs(1);
        let mut x = b.clone();
        sys.solve(&mut x).expect("solvable");
        assert_eq!(sys.woodbury_unit_solves(), 2);
        assert_eq!(sys.factorisations(), 1);
        assert_matches_dense(&dense, &x[0], &b[0]);
    }

    /// The switching solve on the trailing block: `switch` sees the solutions on the
    /// trailing equations (NaN elsewhere); a change within them gives the changed system's
    /// solution without a new factorisation; a change touching another equation cannot be
    /// applied there, and the assembled solution is returned.
    #[test]
    fn switched_solve_on_the_trailing_block() {
        let mut sys = trailing_strip();
        sys.add_to_row(9, 7, 4.0);
        sys.add_to_row(12, 12, 0.0);
        let change = RowChange {
            row: 12,
            entries: vec![(12, 25.0), (8, -3.0)],
            rhs: vec![2.0],
        };
        let b = assert_switches_once(&mut sys, &change, |shown| {
            assert!(shown[0][..6].iter().all(|v| v.is_nan()));
            assert!(shown[0][6..].iter().all(|v| v.is_finite()));
        });
        assert_eq!(sys.woodbury_unit_solves(), 0);
        // a change that touches equation 1 (not ordered last): the assembled solution
        let mut assembled = vec![b.clone()];
        sys.solve(&mut assembled).expect("solvable");
        let beyond = RowChange {
            entries: vec![(1, 5.0)],
            ..change.clone()
        };
        let mut x = vec![b.clone()];
        let passes = sys
            .solve_switching_rows(&mut x, 4, |_| Some(vec![beyond.clone()]))
            .expect("solvable");
        assert_eq!(passes, None);
        assert_eq!(x, assembled);
    }
}
