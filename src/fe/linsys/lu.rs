//! LU with partial pivoting: the last resort of the solve chain, for the symmetric part `S`
//! when the Cholesky family fails, and for the full frictional matrix `K` when the Woodbury
//! solve is not accurate (see the [module documentation](super)).
//!
//! faer's LU factors are read through a borrow of the factorisation call, so they are not
//! held between solves: a later solve with an LU of `S` factors again
//! ([`SparseSystem::solve_symmetric_held`]).

use super::{pattern, Factored, LinSolveError, Scratch, SparseSystem};
use faer::dyn_stack::MemStack;
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuSymbolicParams};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SparseColMatRef;
use faer::{Conj, MatMut, Par};

impl SparseSystem {
    /// Solve `K xⱼ = bⱼ` by LU of the full matrix `K` (the last resort of the Woodbury
    /// solve): the row updates are added into the values for the factorisation, and the
    /// symmetric values and the factorisation of `S` held are restored after it.
    pub(super) fn solve_updated_by_lu(
        &mut self,
        rhs: &mut [Vec<f64>],
    ) -> Result<(), LinSolveError> {
        let symmetric = self.values.clone();
        for (i, &r) in self.updates.rows.iter().enumerate() {
            for &(c, v) in &self.updates.entries[i] {
                let p = self.position(r, c).expect("row updates lie in the pattern");
                self.values[p] += v;
            }
        }
        // the factorisation of `S` held stays the one for later solves
        let held = self.factored;
        let solved = self.solve_by_lu(rhs);
        self.values = symmetric;
        self.factored = held;
        solved
    }

    /// Solve `A xⱼ = bⱼ` in place for the matrix in `values`, by sparse LU with partial
    /// pivoting (COLAMD ordering, computed once): the one LU factorisation, of `S` as the
    /// last step of the symmetric chain or of `K` ([`Self::solve_updated_by_lu`]). The
    /// factors' storage and the work memory are reused between factorisations (fresh
    /// allocations cost a share of a friction curve in page faults: `docs/performance.md`).
    /// An error if the factorisation fails or a solution is not finite.
    pub(super) fn solve_by_lu(&mut self, rhs: &mut [Vec<f64>]) -> Result<(), LinSolveError> {
        let sym = pattern(self.n, &self.col_ptr, &self.row_idx);
        let mat = SparseColMatRef::new(sym, &self.values);
        let par = Par::Seq;
        if self.symbolic_lu.is_none() {
            let params = LuSymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            };
            let symbolic = factorize_symbolic_lu(sym, params)
                .map_err(|e| LinSolveError::Symbolic(format!("{e:?}")))?;
            let req = symbolic
                .factorize_numeric_lu_scratch::<f64>(par, Default::default())
                .or(symbolic.solve_in_place_scratch::<f64>(1, par));
            self.lu_scratch = Some(Scratch::new(req));
            self.symbolic_lu = Some(symbolic);
        }
        let symbolic = self.symbolic_lu.as_ref().expect("symbolic set above");
        let scratch = self.lu_scratch.as_mut().expect("scratch set above");
        scratch.reserve(symbolic.solve_in_place_scratch::<f64>(rhs.len(), par));
        let buf = &mut scratch.buf;
        self.factorisations += 1;
        self.factored = Factored::None;
        let lu = symbolic
            .factorize_numeric_lu(
                &mut self.numeric_lu,
                mat,
                par,
                MemStack::new(buf),
                Default::default(),
            )
            .map_err(|e| LinSolveError::Numeric(format!("{e:?}")))?;
        for x in rhs.iter_mut() {
            let n = x.len();
            lu.solve_in_place_with_conj(
                Conj::No,
                MatMut::from_column_major_slice_mut(x, n, 1),
                par,
                MemStack::new(buf),
            );
            if x.iter().any(|v| !v.is_finite()) {
                return Err(LinSolveError::Numeric("non-finite solution".into()));
            }
        }
        self.factored = Factored::Lu;
        Ok(())
    }
}
