//! Sparse tangent matrix with a fixed pattern and a direct solve through faer.
//!
//! Every node owns two equation slots (`2i`, `2i+1`) whatever its constraint status;
//! constrained slots get an identity row/column. The sparsity pattern therefore never
//! changes during a solve, so the symbolic factorisations (fill-reducing ordering,
//! elimination structure) are computed once and reused for every numeric
//! factorisation.
//!
//! # Solve chain
//! The frictionless tangent is symmetric ([`SparseSystem::solve_symmetric_multi`]):
//! 1. supernodal Cholesky `L Lᵀ`;
//! 2. when Cholesky fails (the reduced Hessian need not be positive definite away from
//!    equilibrium), `L D Lᵀ` without pivoting, accepted if its solution's residual is
//!    small;
//! 3. else the symmetric-indefinite `L B Lᵀ` (Bunch–Kaufman pivoting inside the
//!    supernodes);
//! 4. LU with partial pivoting as the last resort.
//!
//! Steps 1–3 share one symbolic structure and work memory. The non-symmetric frictional
//! tangent goes to LU directly ([`SparseSystem::lu_solve_multi`]).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuSymbolicParams, NumericLu, SymbolicLu};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::Side;
use faer::{Conj, MatMut, Par};

/// Acceptance of an unpivoted `L D Lᵀ` solution, `‖A x − b‖₂² ≤ tol · ‖b‖₂²`: a relative
/// residual of 10⁻⁸, far above the round-off of a stable factorisation, so that only an
/// inaccurate (unstably factored) solution is rejected (measured: every indefinite
/// tangent of an AR = 0.3 curve passes, see `ldlt_solve`).
const LDLT_RESIDUAL_RTOL_SQUARED: f64 = 1e-16;

/// Failure of the sparse direct solve.
#[derive(Debug, Clone, thiserror::Error)]
pub enum LinSolveError {
    /// Symbolic analysis failed.
    #[error("symbolic factorisation failed: {0}")]
    Symbolic(String),
    /// Numeric factorisation failed (singular matrix).
    #[error("numeric factorisation failed: {0}")]
    Numeric(String),
}

/// The sparsity pattern as faer's symbolic matrix (checked once per factorisation).
fn pattern<'a>(
    n: usize,
    col_ptr: &'a [usize],
    row_idx: &'a [usize],
) -> SymbolicSparseColMatRef<'a, usize> {
    SymbolicSparseColMatRef::new_checked(n, n, col_ptr, None, row_idx)
}

/// Solve every right-hand side with `solve` (the triangular solves of a factorisation) on
/// a copy; write the solutions back and return `true` only if all of them are finite (a
/// numerically singular factorisation gives infinities or NaNs).
fn solve_all_finite(rhs: &mut [Vec<f64>], mut solve: impl FnMut(MatMut<'_, f64>)) -> bool {
    let mut out: Vec<Vec<f64>> = rhs.to_vec();
    for x in out.iter_mut() {
        let n = x.len();
        solve(MatMut::from_column_major_slice_mut(x, n, 1));
    }
    if out.iter().all(|x| x.iter().all(|v| v.is_finite())) {
        rhs.clone_from_slice(&out);
        true
    } else {
        false
    }
}

/// Work memory of a factorisation, kept across factorisations.
struct Scratch {
    req: faer::dyn_stack::StackReq,
    buf: MemBuffer,
}

impl Scratch {
    fn new(req: faer::dyn_stack::StackReq) -> Self {
        Self {
            req,
            buf: MemBuffer::new(req),
        }
    }
}

impl Clone for Scratch {
    fn clone(&self) -> Self {
        Self::new(self.req)
    }
}

impl std::fmt::Debug for Scratch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Scratch({:?})", self.req)
    }
}

/// CSC matrix with element-to-value maps.
#[derive(Clone, Debug)]
pub struct SparseSystem {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Values (CSC order).
    pub values: Vec<f64>,
    /// For each element, the value position of its `(a, b)` dof pair (`8a+b`, row
    /// `a`, column `b`).
    pub elem_pos: Vec<[usize; 64]>,
    /// Value position of each diagonal entry.
    pub diag_pos: Vec<usize>,
    symbolic: Option<SymbolicLu<usize>>,
    /// LU factors, kept between factorisations so that their storage is reused.
    numeric_lu: NumericLu<usize, f64>,
    lu_scratch: Option<Scratch>,
    /// Work memory of the Cholesky-family factorisations and solves, kept across
    /// factorisations.
    llt_scratch: Option<Scratch>,
    symbolic_llt: Option<std::sync::Arc<SymbolicCholesky<usize>>>,
    llt_values: Vec<f64>,
    lblt_subdiag: Vec<f64>,
    lblt_perm: (Vec<usize>, Vec<usize>),
}

impl SparseSystem {
    /// Pattern of `ndof` equations coupled by elements with 8 dofs each.
    pub fn new(ndof: usize, elem_dofs: &[[usize; 8]]) -> Self {
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); ndof];
        for d in elem_dofs {
            for &c in d {
                for &r in d {
                    cols[c].push(r);
                }
            }
        }
        for (c, col) in cols.iter_mut().enumerate() {
            col.push(c);
            col.sort_unstable();
            col.dedup();
        }
        let mut col_ptr = Vec::with_capacity(ndof + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for col in &cols {
            row_idx.extend_from_slice(col);
            col_ptr.push(row_idx.len());
        }
        let pos = |r: usize, c: usize| -> usize {
            let s = &row_idx[col_ptr[c]..col_ptr[c + 1]];
            col_ptr[c] + s.binary_search(&r).expect("entry in pattern")
        };
        let elem_pos = elem_dofs
            .iter()
            .map(|d| {
                let mut p = [0usize; 64];
                for a in 0..8 {
                    for b in 0..8 {
                        p[8 * a + b] = pos(d[a], d[b]);
                    }
                }
                p
            })
            .collect();
        let diag_pos = (0..ndof).map(|c| pos(c, c)).collect();
        let nnz = row_idx.len();
        Self {
            n: ndof,
            col_ptr,
            row_idx,
            values: vec![0.0; nnz],
            elem_pos,
            diag_pos,
            symbolic: None,
            numeric_lu: NumericLu::new(),
            lu_scratch: None,
            llt_scratch: None,
            symbolic_llt: None,
            llt_values: Vec::new(),
            lblt_subdiag: Vec::new(),
            lblt_perm: (Vec::new(), Vec::new()),
        }
    }

    /// Number of equations.
    pub fn size(&self) -> usize {
        self.n
    }

    /// Zero all values.
    pub fn clear(&mut self) {
        self.values.iter_mut().for_each(|v| *v = 0.0);
    }

    /// Entry `(r, c)` (zero if outside the pattern).
    pub fn get(&self, r: usize, c: usize) -> f64 {
        let s = &self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]];
        match s.binary_search(&r) {
            Ok(k) => self.values[self.col_ptr[c] + k],
            Err(_) => 0.0,
        }
    }

    /// Value position of entry `(r, c)`, if it is in the pattern.
    pub fn position(&self, r: usize, c: usize) -> Option<usize> {
        let s = &self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]];
        s.binary_search(&r).ok().map(|k| self.col_ptr[c] + k)
    }

    /// `y = A x`.
    pub fn mul(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.n];
        for (c, &xc) in x.iter().enumerate() {
            for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                y[self.row_idx[k]] += self.values[k] * xc;
            }
        }
        y
    }

    /// Supernodal sparse Cholesky (AMD ordering, sequential) of the lower triangle
    /// and solve for every right-hand side; `false` if the matrix is not numerically
    /// positive definite. The default faer heuristic picks the simplicial variant for
    /// these 2D meshes, which measured about 3× slower, so supernodal is forced.
    fn llt_solve(&mut self, rhs: &mut [Vec<f64>]) -> Result<bool, LinSolveError> {
        let sym = pattern(self.n, &self.col_ptr, &self.row_idx);
        if self.symbolic_llt.is_none() {
            let params = CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            };
            let s = factorize_symbolic_cholesky(sym, Side::Lower, SymmetricOrdering::Amd, params)
                .map_err(|e| LinSolveError::Symbolic(format!("{e:?}")))?;
            self.llt_values = vec![0.0; s.len_val()];
            let par = Par::Seq;
            let req = s
                .factorize_numeric_llt_scratch::<f64>(par, Default::default())
                .or(s.factorize_numeric_ldlt_scratch::<f64>(par, Default::default()))
                .or(s.factorize_numeric_intranode_lblt_scratch::<f64>(par, Default::default()))
                .or(s.solve_in_place_scratch::<f64>(1, par));
            self.llt_scratch = Some(Scratch::new(req));
            self.symbolic_llt = Some(std::sync::Arc::new(s));
        }
        let symbolic = self.symbolic_llt.clone().expect("symbolic set above");
        let mat = SparseColMatRef::new(sym, &self.values);
        let par = Par::Seq;
        let buf = &mut self.llt_scratch.as_mut().expect("scratch set above").buf;
        let llt = match symbolic.factorize_numeric_llt(
            &mut self.llt_values,
            mat,
            Side::Lower,
            Default::default(),
            par,
            MemStack::new(buf),
            Default::default(),
        ) {
            Ok(l) => l,
            Err(_) => return Ok(false),
        };
        Ok(solve_all_finite(rhs, |x| {
            llt.solve_in_place_with_conj(Conj::No, x, par, MemStack::new(buf))
        }))
    }

    /// Solve `A xⱼ = bⱼ` in place for several right-hand sides of a symmetric matrix
    /// (one factorisation, by the solve chain of the [module documentation](self)).
    pub fn solve_symmetric_multi(&mut self, rhs: &mut [Vec<f64>]) -> Result<(), LinSolveError> {
        if self.llt_solve(rhs)? || self.ldlt_solve(rhs)? || self.lblt_solve(rhs)? {
            return Ok(());
        }
        self.lu_solve_multi(rhs)
    }

    /// Sparse `L D Lᵀ` factorisation without pivoting (on the Cholesky symbolic
    /// structure) and solve; `false` on a zero pivot or if a solution is not accurate
    /// (`‖A x − b‖₂ > 10⁻⁸ ‖b‖₂`: without pivoting an indefinite matrix may factor
    /// unstably). Measured at AR = 0.3 (64×32): every indefinite tangent of a curve
    /// (≈ 130) passes, and the curve's time in indefinite factorisations drops by a
    /// fifth against `L B Lᵀ`.
    fn ldlt_solve(&mut self, rhs: &mut [Vec<f64>]) -> Result<bool, LinSolveError> {
        let sym = pattern(self.n, &self.col_ptr, &self.row_idx);
        let symbolic = self.symbolic_llt.clone().expect("Cholesky tried first");
        let mat = SparseColMatRef::new(sym, &self.values);
        let par = Par::Seq;
        let buf = &mut self.llt_scratch.as_mut().expect("Cholesky tried first").buf;
        let ldlt = match symbolic.factorize_numeric_ldlt(
            &mut self.llt_values,
            mat,
            Side::Lower,
            Default::default(),
            par,
            MemStack::new(buf),
            Default::default(),
        ) {
            Ok(l) => l,
            Err(_) => return Ok(false),
        };
        let b = rhs.to_vec();
        if !solve_all_finite(rhs, |x| {
            ldlt.solve_in_place_with_conj(Conj::No, x, par, MemStack::new(buf))
        }) {
            return Ok(false);
        }
        let accurate = rhs.iter().zip(&b).all(|(x, b)| {
            let r2: f64 = self
                .mul(x)
                .iter()
                .zip(b)
                .map(|(a, b)| (a - b) * (a - b))
                .sum();
            let b2: f64 = b.iter().map(|v| v * v).sum();
            r2 <= LDLT_RESIDUAL_RTOL_SQUARED * b2
        });
        if !accurate {
            rhs.clone_from_slice(&b);
        }
        Ok(accurate)
    }

    /// Sparse symmetric-indefinite `L B Lᵀ` factorisation (Bunch–Kaufman pivoting inside
    /// the supernodes, on the Cholesky symbolic structure) and solve; `false` if the
    /// solution is not finite. Used when Cholesky and `L D Lᵀ` fail: the tangent of trial
    /// states away from equilibrium can be indefinite; this gives the same Newton step
    /// as LU at about the cost of a Cholesky factorisation (measured: one sparse LU of these
    /// matrices costs 5–10 Cholesky factorisations).
    fn lblt_solve(&mut self, rhs: &mut [Vec<f64>]) -> Result<bool, LinSolveError> {
        let sym = pattern(self.n, &self.col_ptr, &self.row_idx);
        let symbolic = self.symbolic_llt.clone().expect("Cholesky tried first");
        let mat = SparseColMatRef::new(sym, &self.values);
        let par = Par::Seq;
        self.lblt_subdiag.resize(self.n, 0.0);
        self.lblt_perm.0.resize(self.n, 0);
        self.lblt_perm.1.resize(self.n, 0);
        let buf = &mut self.llt_scratch.as_mut().expect("Cholesky tried first").buf;
        let lblt = symbolic.factorize_numeric_intranode_lblt(
            &mut self.llt_values,
            &mut self.lblt_subdiag,
            &mut self.lblt_perm.0,
            &mut self.lblt_perm.1,
            mat,
            Side::Lower,
            par,
            MemStack::new(buf),
            Default::default(),
        );
        Ok(solve_all_finite(rhs, |x| {
            lblt.solve_in_place_with_conj(Conj::No, x, par, MemStack::new(buf))
        }))
    }

    /// Sparse LU with partial pivoting (COLAMD ordering, computed once) for any square
    /// matrix, in particular the non-symmetric frictional tangent; the factors' storage
    /// and the work memory are reused between factorisations (fresh allocations measured
    /// 15 % of a friction curve in page faults).
    pub fn lu_solve_multi(&mut self, rhs: &mut [Vec<f64>]) -> Result<(), LinSolveError> {
        let sym = pattern(self.n, &self.col_ptr, &self.row_idx);
        let mat = SparseColMatRef::new(sym, &self.values);
        let par = Par::Seq;
        if self.symbolic.is_none() {
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
            self.symbolic = Some(symbolic);
        }
        let symbolic = self.symbolic.as_ref().expect("symbolic set above");
        let buf = &mut self.lu_scratch.as_mut().expect("scratch set above").buf;
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
        Ok(())
    }
}
