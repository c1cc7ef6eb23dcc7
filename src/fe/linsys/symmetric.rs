//! The symmetric chain for the symmetric part `S`: supernodal Cholesky, else `L D Lᵀ`
//! without pivoting, else `L B Lᵀ`, else LU ([`super::lu`]); one symbolic structure
//! (computed once, with the equations of [`SparseSystem::order_last`] last) and one work
//! memory for the three Cholesky-family factorisations, which read the matrix's lower
//! triangle in the fill-reducing order ([`OrderedLower`]). After a failed Cholesky the
//! following factorisations try `L D Lᵀ` first, until one finds a positive `D` (see the
//! [module documentation](super)).

use super::{
    pattern, residual_within, Factored, LinSolveError, Scratch, SparseSystem, RESIDUAL_RTOL_SQUARED,
};
use faer::dyn_stack::MemStack;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, IntranodeLbltRef, LdltRef, LltRef,
    SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SparseColMatRef;
use faer::Side;
use faer::{Conj, MatMut, Par};

/// Solve every right-hand side with `solve` (the triangular solves of a factorisation,
/// all columns at once) on a copy in the factorisation's order (`order[i]`: the equation
/// at position `i`); write the solutions back and return `true` only if all of them are
/// finite (a numerically singular factorisation gives infinities or NaNs).
fn solve_all_finite(
    rhs: &mut [Vec<f64>],
    order: &[usize],
    solve: impl FnOnce(MatMut<'_, f64>),
) -> bool {
    let n = order.len();
    let mut block: Vec<f64> = rhs
        .iter()
        .flat_map(|b| order.iter().map(move |&e| b[e]))
        .collect();
    solve(MatMut::from_column_major_slice_mut(
        &mut block,
        n,
        rhs.len(),
    ));
    if block.iter().all(|v| v.is_finite()) {
        for (x, col) in rhs.iter_mut().zip(block.chunks_exact(n)) {
            for (&e, &v) in order.iter().zip(col) {
                x[e] = v;
            }
        }
        true
    } else {
        false
    }
}

/// The lower triangle of the matrix in the Cholesky factorisations' fill-reducing order,
/// gathered from the matrix's values by a fixed map before each factorisation (faer
/// permutes a matrix given in another order at every factorisation, a share of a curve's
/// time: `docs/performance.md`).
#[derive(Clone, Debug, Default)]
pub(super) struct OrderedLower {
    /// The equation at each position.
    order: Vec<usize>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// The value position (in the matrix's `values`) of each entry.
    source: Vec<usize>,
    values: Vec<f64>,
}

impl OrderedLower {
    /// The lower triangle of the pattern `(col_ptr, row_idx)` under the permutation
    /// `order` (position → equation, `position` its inverse).
    fn new(col_ptr: &[usize], row_idx: &[usize], order: Vec<usize>, position: &[usize]) -> Self {
        let mut lower = Self {
            col_ptr: vec![0],
            ..Self::default()
        };
        for (j, &e) in order.iter().enumerate() {
            let mut column: Vec<(usize, usize)> = (col_ptr[e]..col_ptr[e + 1])
                .map(|k| (position[row_idx[k]], k))
                .filter(|&(i, _)| i >= j)
                .collect();
            column.sort_unstable();
            for (i, k) in column {
                lower.row_idx.push(i);
                lower.source.push(k);
            }
            lower.col_ptr.push(lower.row_idx.len());
        }
        lower.values = vec![0.0; lower.source.len()];
        lower.order = order;
        lower
    }

    /// Copy the matrix's `values` in.
    fn gather(&mut self, values: &[f64]) {
        for (v, &k) in self.values.iter_mut().zip(&self.source) {
            *v = values[k];
        }
    }

    fn matrix(&self) -> SparseColMatRef<'_, usize, f64> {
        SparseColMatRef::new(
            pattern(self.order.len(), &self.col_ptr, &self.row_idx),
            &self.values,
        )
    }
}

impl SparseSystem {
    /// Solve `S xⱼ = bⱼ` in place for several right-hand sides of the symmetric part
    /// (one factorisation, by the solve chain of the [module documentation](super)): the
    /// accuracy of an unpivoted `L D Lᵀ` is checked on every right-hand side.
    pub(super) fn solve_symmetric(&mut self, rhs: &mut [Vec<f64>]) -> Result<(), LinSolveError> {
        self.ensure_symbolic_cholesky()?;
        self.ordered.gather(&self.values);
        let solved = if self.expect_indefinite {
            if self.ldlt_step(rhs)? {
                self.expect_indefinite = !self.ldlt_positive();
                true
            } else {
                self.lblt_step(rhs)?
            }
        } else {
            self.llt_step(rhs)? || {
                self.expect_indefinite = true;
                self.ldlt_step(rhs)? || self.lblt_step(rhs)?
            }
        };
        if solved {
            return Ok(());
        }
        self.solve_by_lu(rhs)
    }

    /// Step 1 of the chain: Cholesky and solve; `false` if the matrix is not numerically
    /// positive definite or a solution is not finite.
    fn llt_step(&mut self, rhs: &mut [Vec<f64>]) -> Result<bool, LinSolveError> {
        Ok(self.factor_llt() && self.hold_and_solve(Factored::Llt, rhs)?)
    }

    /// Step 2 of the chain: `L D Lᵀ` and solve; `false` on a zero pivot or if a solution
    /// is not accurate (`‖A x − b‖₂ > 10⁻⁸ ‖b‖₂`: without pivoting an indefinite matrix may
    /// factor unstably), `rhs` then unchanged.
    fn ldlt_step(&mut self, rhs: &mut [Vec<f64>]) -> Result<bool, LinSolveError> {
        if !self.factor_ldlt() {
            return Ok(false);
        }
        let b = rhs.to_vec();
        if !self.hold_and_solve(Factored::Ldlt, rhs)? {
            return Ok(false);
        }
        let accurate = rhs
            .iter()
            .zip(&b)
            .all(|(x, b)| residual_within(&self.mul(x), b, RESIDUAL_RTOL_SQUARED));
        if !accurate {
            self.factored = Factored::None;
            rhs.clone_from_slice(&b);
        }
        Ok(accurate)
    }

    /// Step 3 of the chain: `L B Lᵀ` and solve; `false` if a solution is not finite.
    fn lblt_step(&mut self, rhs: &mut [Vec<f64>]) -> Result<bool, LinSolveError> {
        self.factor_lblt();
        self.hold_and_solve(Factored::Lblt, rhs)
    }

    /// Solve with the factorisation `kind` just computed into `llt_values`
    /// ([`Self::solve_symmetric_held`]); it is held from then on if every solution is
    /// finite.
    fn hold_and_solve(
        &mut self,
        kind: Factored,
        rhs: &mut [Vec<f64>],
    ) -> Result<bool, LinSolveError> {
        self.factored = kind;
        let finite = self.solve_symmetric_held(rhs)?;
        if !finite {
            self.factored = Factored::None;
        }
        Ok(finite)
    }

    /// Solve `S xⱼ = bⱼ` in place with the factorisation of `S` held (no new
    /// factorisation, except for an LU, whose factors are not kept); `false` if a
    /// solution is not finite.
    pub(super) fn solve_symmetric_held(
        &mut self,
        rhs: &mut [Vec<f64>],
    ) -> Result<bool, LinSolveError> {
        if self.factored == Factored::Lu {
            self.solve_by_lu(rhs)?;
            return Ok(true);
        }
        let symbolic = self
            .symbolic_cholesky
            .clone()
            .ok_or_else(|| LinSolveError::Numeric("no factorisation held".into()))?;
        let par = Par::Seq;
        let scratch = self.llt_scratch.as_mut().expect("set with the symbolic");
        scratch.reserve(symbolic.solve_in_place_scratch::<f64>(rhs.len(), par));
        let buf = &mut scratch.buf;
        let values = &self.llt_values;
        Ok(match self.factored {
            Factored::Llt => solve_all_finite(rhs, &self.ordered.order, |x| {
                LltRef::new(&symbolic, values).solve_in_place_with_conj(
                    Conj::No,
                    x,
                    par,
                    MemStack::new(buf),
                )
            }),
            Factored::Ldlt => solve_all_finite(rhs, &self.ordered.order, |x| {
                LdltRef::new(&symbolic, values).solve_in_place_with_conj(
                    Conj::No,
                    x,
                    par,
                    MemStack::new(buf),
                )
            }),
            Factored::Lblt => {
                let (fwd, inv) = &self.lblt_perm;
                let perm = PermRef::new_checked(fwd, inv, self.n);
                solve_all_finite(rhs, &self.ordered.order, |x| {
                    IntranodeLbltRef::new(&symbolic, values, &self.lblt_subdiag, perm)
                        .solve_in_place_with_conj(Conj::No, x, par, MemStack::new(buf))
                })
            }
            Factored::None | Factored::Lu => {
                return Err(LinSolveError::Numeric("no factorisation held".into()))
            }
        })
    }

    /// The symbolic Cholesky structure and the work memory of the Cholesky-family
    /// factorisations, computed on first use: approximate minimum degree ordering (with
    /// the equations of [`Self::order_last`] last, if any), supernodal (the default faer
    /// heuristic picks the simplicial variant for these 2D meshes, slower here:
    /// `docs/performance.md`).
    fn ensure_symbolic_cholesky(&mut self) -> Result<(), LinSolveError> {
        if self.symbolic_cholesky.is_some() {
            return Ok(());
        }
        let sym = pattern(self.n, &self.col_ptr, &self.row_idx);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let trailing = self.trailing_ordering()?;
        let ordering = match &trailing {
            Some((fwd, inv)) => SymmetricOrdering::Custom(PermRef::new_checked(fwd, inv, self.n)),
            None => SymmetricOrdering::Amd,
        };
        let ordered = factorize_symbolic_cholesky(sym, Side::Lower, ordering, params)
            .map_err(|e| LinSolveError::Symbolic(format!("{e:?}")))?;
        let (order, position) = match ordered.perm() {
            Some(p) => (p.arrays().0.to_vec(), p.arrays().1.to_vec()),
            None => ((0..self.n).collect(), (0..self.n).collect()),
        };
        self.ordered = OrderedLower::new(&self.col_ptr, &self.row_idx, order, &position);
        // the symbolic analysis of an unpermuted matrix reads its upper triangle whatever
        // the side named (faer 0.24), so it is given the transpose of the ordered lower one
        let ordered = &self.ordered;
        let upper = pattern(self.n, &ordered.col_ptr, &ordered.row_idx)
            .transpose()
            .to_col_major()
            .map_err(|e| LinSolveError::Symbolic(format!("{e:?}")))?;
        let s = factorize_symbolic_cholesky(
            upper.as_ref(),
            Side::Upper,
            SymmetricOrdering::Identity,
            params,
        )
        .map_err(|e| LinSolveError::Symbolic(format!("{e:?}")))?;
        self.llt_values = vec![0.0; s.len_val()];
        let par = Par::Seq;
        let req = s
            .factorize_numeric_llt_scratch::<f64>(par, Default::default())
            .or(s.factorize_numeric_ldlt_scratch::<f64>(par, Default::default()))
            .or(s.factorize_numeric_intranode_lblt_scratch::<f64>(par, Default::default()))
            .or(s.solve_in_place_scratch::<f64>(1, par));
        self.llt_scratch = Some(Scratch::new(req));
        self.symbolic_cholesky = Some(std::sync::Arc::new(s));
        Ok(())
    }

    /// Whether the factorisation held says the symmetric part is indefinite: an `L D Lᵀ`
    /// with a pivot that is not positive, or the pivoting `L B Lᵀ` or LU that the chain falls
    /// back to when `L D Lᵀ` fails (a Cholesky factorisation, or none, says nothing).
    pub fn held_factorisation_indefinite(&self) -> bool {
        match self.factored {
            Factored::Ldlt => !self.ldlt_positive(),
            Factored::Lblt | Factored::Lu => true,
            Factored::Llt | Factored::None => false,
        }
    }

    /// `true` when the `L D Lᵀ` factorisation held has a positive `D` (the matrix was
    /// positive definite: Cholesky would have succeeded), or when that cannot be read (a
    /// simplicial factorisation).
    fn ldlt_positive(&self) -> bool {
        let Some(symbolic) = self.symbolic_cholesky.as_ref() else {
            return true;
        };
        let SymbolicCholeskyRaw::Supernodal(supernodal) = symbolic.raw() else {
            return true;
        };
        // `L D Lᵀ` stores `D` on the unit diagonal of `L`
        let factor = SupernodalLltRef::new(supernodal, &self.llt_values);
        (0..supernodal.n_supernodes()).all(|s| {
            let val = factor.supernode(s).val();
            (0..val.ncols()).all(|j| val[(j, j)] > 0.0)
        })
    }

    /// What every factorisation on the Cholesky symbolic structure does first: count it, forget
    /// the factor held so far, and hand out the symbolic structure.
    fn start_cholesky_family_factorisation(&mut self) -> std::sync::Arc<SymbolicCholesky<usize>> {
        self.factorisations += 1;
        self.factored = Factored::None;
        self.symbolic_cholesky.clone().expect("symbolic set")
    }

    /// Supernodal sparse Cholesky `L Lᵀ` (sequential) of the gathered lower triangle into
    /// `llt_values`: the one Cholesky factorisation; `false` if the matrix is not
    /// numerically positive definite.
    fn factor_llt(&mut self) -> bool {
        let symbolic = self.start_cholesky_family_factorisation();
        let buf = &mut self
            .llt_scratch
            .as_mut()
            .expect("set with the symbolic")
            .buf;
        let factored = symbolic.factorize_numeric_llt(
            &mut self.llt_values,
            self.ordered.matrix(),
            Side::Lower,
            Default::default(),
            Par::Seq,
            MemStack::new(buf),
            Default::default(),
        );
        factored.is_ok()
    }

    /// Sparse `L D Lᵀ` without pivoting, on the Cholesky symbolic structure, of the
    /// gathered lower triangle into `llt_values`: the one `L D Lᵀ` factorisation; `false`
    /// on a zero pivot. Cheaper than `L B Lᵀ` on the indefinite tangents, which it
    /// factors accurately enough as a rule (`docs/performance.md`).
    fn factor_ldlt(&mut self) -> bool {
        let symbolic = self.start_cholesky_family_factorisation();
        let buf = &mut self
            .llt_scratch
            .as_mut()
            .expect("set with the symbolic")
            .buf;
        let factored = symbolic.factorize_numeric_ldlt(
            &mut self.llt_values,
            self.ordered.matrix(),
            Side::Lower,
            Default::default(),
            Par::Seq,
            MemStack::new(buf),
            Default::default(),
        );
        factored.is_ok()
    }

    /// Sparse symmetric-indefinite `L B Lᵀ` (Bunch–Kaufman pivoting inside the
    /// supernodes, on the Cholesky symbolic structure) of the gathered lower triangle into
    /// `llt_values`, `lblt_subdiag` and `lblt_perm`: the one `L B Lᵀ` factorisation. It
    /// gives the Newton step of an LU at about the cost of a Cholesky factorisation
    /// (`docs/performance.md` compares the two).
    fn factor_lblt(&mut self) {
        self.lblt_subdiag.resize(self.n, 0.0);
        self.lblt_perm.0.resize(self.n, 0);
        self.lblt_perm.1.resize(self.n, 0);
        let symbolic = self.start_cholesky_family_factorisation();
        let buf = &mut self
            .llt_scratch
            .as_mut()
            .expect("set with the symbolic")
            .buf;
        symbolic.factorize_numeric_intranode_lblt(
            &mut self.llt_values,
            &mut self.lblt_subdiag,
            &mut self.lblt_perm.0,
            &mut self.lblt_perm.1,
            self.ordered.matrix(),
            Side::Lower,
            Par::Seq,
            MemStack::new(buf),
            Default::default(),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{assert_matches_dense, strip, strip_rhs};
    use super::*;
    use faer::Mat;

    /// After a failed Cholesky the next factorisation is `L D Lᵀ` first (one factorisation
    /// for an indefinite matrix instead of two), until an `L D Lᵀ` finds a positive `D`:
    /// Cholesky first again. Every solution agrees with a dense LU.
    #[test]
    fn indefinite_runs_factor_by_ldlt_first() {
        let mut sys = strip();
        let diagonal = sys.diag_pos[1];
        let b = strip_rhs(1);
        // (indefinite?, factorisations of this solve, factorisation held after it)
        let runs = [
            (false, 1, Factored::Llt),
            (true, 2, Factored::Ldlt),
            (true, 1, Factored::Ldlt),
            (false, 1, Factored::Ldlt),
            (false, 1, Factored::Llt),
        ];
        for (step, (indefinite, count, held)) in runs.into_iter().enumerate() {
            sys.values[diagonal] = if indefinite { -12.0 } else { 11.0 };
            let dense = Mat::from_fn(16, 16, |r, c| sys.get(r, c));
            let before = sys.factorisations();
            let mut x = b.clone();
            sys.solve(&mut x).expect("solvable");
            assert_eq!(sys.factorisations() - before, count, "solve {step}");
            assert_eq!(sys.factored, held, "solve {step}");
            assert_matches_dense(&dense, &x[0], &b[0]);
        }
    }
}
