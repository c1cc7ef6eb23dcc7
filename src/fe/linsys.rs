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
//! Steps 1–3 share one symbolic structure and work memory.
//!
//! The frictional tangent is the symmetric matrix plus a few non-symmetric rows, one per
//! contact node with friction ([`RowUpdates`]): `K = S + Σᵢ e_{rᵢ} vᵢᵀ`, a rank-`m`
//! update with `m` at most the number of contact-face nodes. [`SparseSystem::solve_multi`]
//! solves it by the Sherman–Morrison–Woodbury identity: `S` through the symmetric chain
//! above with the `m` unit vectors `e_{rᵢ}` as extra right-hand sides, then a dense
//! `m × m` system (`I + Vᵀ S⁻¹ E`, LU with partial pivoting), accepted if the residual
//! of `K` is small; else the full `K` goes to LU (step 4). A sparse LU of `K` costs
//! 5–10 Cholesky factorisations of `S` (its symbolic structure is that of `KᵀK`);
//! the `m` extra right-hand sides cost less (measured: README, "Frictional speed").
//!
//! Because `S⁻¹ E` is at hand, a system whose updated rows (and right-hand sides on them)
//! change is solved again with a dense `m × m` system and no factorisation
//! ([`SparseSystem::solve_multi_switching`]): the semismooth Newton step of the friction
//! law switches nodes between pieces of the law that way.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuSymbolicParams, NumericLu, SymbolicLu};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::Side;
use faer::{Conj, Mat, MatMut, Par};

/// Acceptance of a solution that may be inaccurate, `‖A x − b‖₂² ≤ tol · ‖b‖₂²`: a relative
/// residual of 10⁻⁸, far above the round-off of a stable factorisation, so that only an
/// inaccurate solution is rejected: an unpivoted `L D Lᵀ` factored unstably (measured:
/// every indefinite tangent of an AR = 0.3 curve passes, see `ldlt_solve`), or a Woodbury
/// solve with an ill-conditioned `I + Vᵀ S⁻¹ E` (then LU of the whole matrix).
const RESIDUAL_RTOL_SQUARED: f64 = 1e-16;

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

/// Solve every right-hand side with `solve` (the triangular solves of a factorisation,
/// all columns at once) on a copy; write the solutions back and return `true` only if
/// all of them are finite (a numerically singular factorisation gives infinities or
/// NaNs).
fn solve_all_finite(rhs: &mut [Vec<f64>], solve: impl FnOnce(MatMut<'_, f64>)) -> bool {
    let Some(n) = rhs.first().map(Vec::len) else {
        return true;
    };
    let mut block: Vec<f64> = rhs.iter().flatten().copied().collect();
    solve(MatMut::from_column_major_slice_mut(
        &mut block,
        n,
        rhs.len(),
    ));
    if block.iter().all(|v| v.is_finite()) {
        for (x, col) in rhs.iter_mut().zip(block.chunks_exact(n)) {
            x.copy_from_slice(col);
        }
        true
    } else {
        false
    }
}

/// `‖A x − b‖₂² ≤ rtol_squared · ‖b‖₂²`, given `A x`.
fn residual_within(ax: &[f64], b: &[f64], rtol_squared: f64) -> bool {
    let r2: f64 = ax.iter().zip(b).map(|(a, b)| (a - b) * (a - b)).sum();
    let b2: f64 = b.iter().map(|v| v * v).sum();
    r2 <= rtol_squared * b2
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

    /// Grow to at least `req` (a solve with more right-hand sides than before).
    fn reserve(&mut self, req: faer::dyn_stack::StackReq) {
        let merged = self.req.or(req);
        if merged != self.req {
            *self = Self::new(merged);
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

/// Non-symmetric rows added to the symmetric matrix: `K = S + Σᵢ e_{rᵢ} vᵢᵀ`, each row
/// `rᵢ` with its sparse vector `vᵢ` (entries `(column, value)`, a column may repeat: the
/// entries add up).
#[derive(Clone, Debug, Default)]
struct RowUpdates {
    /// Index into `rows` of each equation's update (`usize::MAX`: none).
    slot: Vec<usize>,
    rows: Vec<usize>,
    entries: Vec<Vec<(usize, f64)>>,
}

impl RowUpdates {
    fn new(n: usize) -> Self {
        Self {
            slot: vec![usize::MAX; n],
            rows: Vec::new(),
            entries: Vec::new(),
        }
    }

    fn clear(&mut self) {
        for &r in &self.rows {
            self.slot[r] = usize::MAX;
        }
        self.rows.clear();
        self.entries.clear();
    }

    /// Number of updated rows.
    fn len(&self) -> usize {
        self.rows.len()
    }

    /// `true` when the matrix is its symmetric part.
    fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    fn add(&mut self, row: usize, col: usize, value: f64) {
        if self.slot[row] == usize::MAX {
            self.slot[row] = self.rows.len();
            self.rows.push(row);
            self.entries.push(Vec::new());
        }
        self.entries[self.slot[row]].push((col, value));
    }

    /// `vᵢ · x` of update `i`.
    fn dot(&self, i: usize, x: &[f64]) -> f64 {
        self.entries[i].iter().map(|&(c, v)| v * x[c]).sum()
    }

    /// Entry `(r, c)` of the updates.
    fn get(&self, r: usize, c: usize) -> f64 {
        match self.slot[r] {
            usize::MAX => 0.0,
            i => self.entries[i]
                .iter()
                .filter(|&&(col, _)| col == c)
                .map(|&(_, v)| v)
                .sum(),
        }
    }
}

/// A change of one updated row of the system ([`SparseSystem::solve_multi_switching`]):
/// entries added to the row (`(column, value)`) and to the right-hand sides on it (one
/// value per right-hand side).
#[derive(Clone, Debug, PartialEq)]
pub struct RowChange {
    /// The equation; it must carry a row update.
    pub row: usize,
    /// Entries added to the row.
    pub entries: Vec<(usize, f64)>,
    /// Value added to each right-hand side on the row.
    pub rhs: Vec<f64>,
}

/// `S⁻¹` of the right-hand sides (`z_b`) and of the unit vectors of the updated rows
/// (`z_e`, in the order of the updates).
struct WoodburyParts {
    z_b: Vec<Vec<f64>>,
    z_e: Vec<Vec<f64>>,
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
    /// Non-symmetric rows on top of the symmetric `values` (friction; empty otherwise).
    updates: RowUpdates,
    /// Factorisations computed so far (any kind).
    factorisations: usize,
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
            updates: RowUpdates::new(ndof),
            factorisations: 0,
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

    /// Zero all values and drop the row updates.
    pub fn clear(&mut self) {
        self.values.iter_mut().for_each(|v| *v = 0.0);
        self.updates.clear();
    }

    /// Add `value` to entry `(row, col)` of the non-symmetric row `row` ([`RowUpdates`]):
    /// the symmetric `values` stay symmetric.
    pub fn add_to_row(&mut self, row: usize, col: usize, value: f64) {
        self.updates.add(row, col, value);
    }

    /// Numeric factorisations computed so far, of any kind.
    pub fn factorisations(&self) -> usize {
        self.factorisations
    }

    /// Entry `(r, c)` of the matrix, row updates included (zero if outside the pattern).
    pub fn get(&self, r: usize, c: usize) -> f64 {
        let s = &self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]];
        let symmetric = match s.binary_search(&r) {
            Ok(k) => self.values[self.col_ptr[c] + k],
            Err(_) => 0.0,
        };
        symmetric + self.updates.get(r, c)
    }

    /// Value position of entry `(r, c)`, if it is in the pattern.
    pub fn position(&self, r: usize, c: usize) -> Option<usize> {
        let s = &self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]];
        s.binary_search(&r).ok().map(|k| self.col_ptr[c] + k)
    }

    /// `y = S x`, the symmetric part.
    pub fn mul(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.n];
        for (c, &xc) in x.iter().enumerate() {
            for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                y[self.row_idx[k]] += self.values[k] * xc;
            }
        }
        y
    }

    /// `y = K x`, row updates included.
    pub fn mul_updated(&self, x: &[f64]) -> Vec<f64> {
        let mut y = self.mul(x);
        for (i, &r) in self.updates.rows.iter().enumerate() {
            y[r] += self.updates.dot(i, x);
        }
        y
    }

    /// Solve `K xⱼ = bⱼ` in place for several right-hand sides: the symmetric chain when
    /// there are no row updates, else the Woodbury solve (see the
    /// [module documentation](self)).
    pub fn solve_multi(&mut self, rhs: &mut [Vec<f64>]) -> Result<(), LinSolveError> {
        self.solve_multi_switching(rhs, 0, |_| None).map(|_| ())
    }

    /// `Z = S⁻¹ [B, E]`: the symmetric solves of the right-hand sides and of the unit
    /// vectors of the updated rows.
    fn woodbury_parts(&mut self, rhs: &[Vec<f64>]) -> Result<WoodburyParts, LinSolveError> {
        let (n, k) = (self.n, rhs.len());
        let mut block: Vec<Vec<f64>> = rhs.to_vec();
        for &r in &self.updates.rows {
            let mut e = vec![0.0; n];
            e[r] = 1.0;
            block.push(e);
        }
        self.solve_symmetric_checked(&mut block, k)?;
        let z_e = block.split_off(k);
        Ok(WoodburyParts { z_b: block, z_e })
    }

    /// The solutions of `(K + Σ e_r Δvᵣᵀ) x = b + Σ e_r Δbᵣ` from `parts` ([`RowChange`]s
    /// on updated rows only, `Δb` per right-hand side), or `None` if one is not finite or
    /// its residual exceeds `10⁻⁸ ‖b‖`.
    fn woodbury_combine(
        &self,
        parts: &WoodburyParts,
        rhs: &[Vec<f64>],
        changes: &[RowChange],
    ) -> Option<Vec<Vec<f64>>> {
        let (k, m) = (rhs.len(), self.updates.len());
        // the changed rows' extra entries, and the changed right-hand sides through
        // S⁻¹ (b + E β) = Z_B + Z_E β
        let mut extra: Vec<&[(usize, f64)]> = vec![&[]; m];
        let mut z_b = parts.z_b.clone();
        let mut b = rhs.to_vec();
        for change in changes {
            let i = self.updates.slot[change.row];
            assert!(i != usize::MAX, "a row change on an updated row");
            extra[i] = &change.entries;
            for (j, &beta) in change.rhs.iter().enumerate() {
                b[j][change.row] += beta;
                z_b[j]
                    .iter_mut()
                    .zip(&parts.z_e[i])
                    .for_each(|(z, e)| *z += beta * e);
            }
        }
        let dot = |i: usize, x: &[f64]| {
            self.updates.dot(i, x) + extra[i].iter().map(|&(c, v)| v * x[c]).sum::<f64>()
        };
        let capacitance = Mat::from_fn(m, m, |i, j| {
            f64::from(u8::from(i == j)) + dot(i, &parts.z_e[j])
        });
        let projected = Mat::from_fn(m, k, |i, j| dot(i, &z_b[j]));
        let y = capacitance.partial_piv_lu().solve(&projected);
        let solutions: Vec<Vec<f64>> = (0..k)
            .map(|j| {
                let mut x = z_b[j].clone();
                for (i, ze) in parts.z_e.iter().enumerate() {
                    let yi = y[(i, j)];
                    x.iter_mut().zip(ze).for_each(|(xv, zv)| *xv -= yi * zv);
                }
                x
            })
            .collect();
        let accurate = solutions.iter().zip(&b).all(|(x, bj)| {
            let mut kx = self.mul_updated(x);
            for change in changes {
                kx[change.row] += change.entries.iter().map(|&(c, v)| v * x[c]).sum::<f64>();
            }
            x.iter().all(|v| v.is_finite()) && residual_within(&kx, bj, RESIDUAL_RTOL_SQUARED)
        });
        accurate.then_some(solutions)
    }

    /// LU of the full matrix `K`: the updates added into the values for the factorisation.
    fn lu_solve_updated(&mut self, rhs: &mut [Vec<f64>]) -> Result<(), LinSolveError> {
        let symmetric = self.values.clone();
        for (i, &r) in self.updates.rows.iter().enumerate() {
            for &(c, v) in &self.updates.entries[i] {
                let p = self.position(r, c).expect("row updates lie in the pattern");
                self.values[p] += v;
            }
        }
        let solved = self.lu_solve_multi(rhs);
        self.values = symmetric;
        solved
    }

    /// Solve `K xⱼ = bⱼ`: the symmetric chain when there are no row updates, else the
    /// Woodbury solve `Z = S⁻¹ [B, E]` in one symmetric solve, `y = (I + Vᵀ Z_E)⁻¹ Vᵀ Z_B`,
    /// `X = Z_B − Z_E y`, accepted if `‖K x − b‖ ≤ 10⁻⁸ ‖b‖` for every right-hand side,
    /// else LU of `K`. Then let `switch` change updated rows of the system in view of the
    /// solutions: `switch` returns the [`RowChange`]s (relative
    /// to the assembled `K` and `b`) under which it wants the system solved next, or
    /// `None` when the solutions it was given are the ones it wants. The changed systems
    /// reuse the factorisation (Woodbury). At most `max_switches` changed solves; if
    /// `switch` has not settled by then, or a changed solve is inaccurate, the solutions
    /// of the assembled system are returned. Returns the number of changed solves.
    pub fn solve_multi_switching(
        &mut self,
        rhs: &mut [Vec<f64>],
        max_switches: usize,
        mut switch: impl FnMut(&[Vec<f64>]) -> Option<Vec<RowChange>>,
    ) -> Result<usize, LinSolveError> {
        if self.updates.is_empty() {
            self.solve_symmetric_multi(rhs)?;
            return Ok(0);
        }
        let parts = self.woodbury_parts(rhs)?;
        let assembled = match self.woodbury_combine(&parts, rhs, &[]) {
            Some(solutions) => solutions,
            None => {
                let mut solutions = rhs.to_vec();
                self.lu_solve_updated(&mut solutions)?;
                solutions
            }
        };
        let mut current = assembled.clone();
        for pass in 0..=max_switches {
            let Some(changes) = switch(&current) else {
                rhs.clone_from_slice(&current);
                return Ok(pass);
            };
            if pass == max_switches {
                break;
            }
            match self.woodbury_combine(&parts, rhs, &changes) {
                Some(solutions) => current = solutions,
                None => break,
            }
        }
        rhs.clone_from_slice(&assembled);
        Ok(max_switches)
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
        let scratch = self.llt_scratch.as_mut().expect("scratch set above");
        scratch.reserve(symbolic.solve_in_place_scratch::<f64>(rhs.len(), par));
        let buf = &mut scratch.buf;
        self.factorisations += 1;
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
    fn solve_symmetric_multi(&mut self, rhs: &mut [Vec<f64>]) -> Result<(), LinSolveError> {
        let all = rhs.len();
        self.solve_symmetric_checked(rhs, all)
    }

    /// [`Self::solve_symmetric_multi`], with the accuracy of an unpivoted `L D Lᵀ`
    /// checked on the first `checked` right-hand sides only (the others are checked by
    /// the caller).
    fn solve_symmetric_checked(
        &mut self,
        rhs: &mut [Vec<f64>],
        checked: usize,
    ) -> Result<(), LinSolveError> {
        if self.llt_solve(rhs)? || self.ldlt_solve(rhs, checked)? || self.lblt_solve(rhs)? {
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
    fn ldlt_solve(&mut self, rhs: &mut [Vec<f64>], checked: usize) -> Result<bool, LinSolveError> {
        let sym = pattern(self.n, &self.col_ptr, &self.row_idx);
        let symbolic = self.symbolic_llt.clone().expect("Cholesky tried first");
        let mat = SparseColMatRef::new(sym, &self.values);
        let par = Par::Seq;
        let scratch = self.llt_scratch.as_mut().expect("Cholesky tried first");
        scratch.reserve(symbolic.solve_in_place_scratch::<f64>(rhs.len(), par));
        let buf = &mut scratch.buf;
        self.factorisations += 1;
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
        let accurate = rhs
            .iter()
            .zip(&b)
            .take(checked)
            .all(|(x, b)| residual_within(&self.mul(x), b, RESIDUAL_RTOL_SQUARED));
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
        let scratch = self.llt_scratch.as_mut().expect("Cholesky tried first");
        scratch.reserve(symbolic.solve_in_place_scratch::<f64>(rhs.len(), par));
        let buf = &mut scratch.buf;
        self.factorisations += 1;
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
    fn lu_solve_multi(&mut self, rhs: &mut [Vec<f64>]) -> Result<(), LinSolveError> {
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
        let scratch = self.lu_scratch.as_mut().expect("scratch set above");
        scratch.reserve(symbolic.solve_in_place_scratch::<f64>(rhs.len(), par));
        let buf = &mut scratch.buf;
        self.factorisations += 1;
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3-element strip (16 equations): symmetric, diagonally dominant values with
    /// deterministic off-diagonal entries.
    fn strip() -> SparseSystem {
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

    /// The Woodbury solve of `S + E Vᵀ` against a dense LU of the same matrix (read back
    /// through `get`, so the row updates are part of it), for two right-hand sides, with
    /// updates large enough to make the matrix far from symmetric.
    #[test]
    fn row_updated_solve_matches_dense_lu() {
        let mut sys = strip();
        let updates = [
            (3, 5, 4.0),
            (3, 3, -2.5),
            (9, 1, -6.0),
            (9, 12, 3.0),
            (9, 12, 1.5),
        ];
        for (r, c, v) in updates {
            sys.add_to_row(r, c, v);
        }
        assert_eq!(sys.updates.len(), 2);
        let dense = Mat::from_fn(16, 16, |r, c| sys.get(r, c));
        assert_eq!(dense[(9, 12)] - strip().get(9, 12), 4.5);
        let b: Vec<Vec<f64>> = (0..2)
            .map(|j| {
                (0..16)
                    .map(|i| ((i * 3 + j * 5) % 7) as f64 - 3.0)
                    .collect()
            })
            .collect();
        let mut x = b.clone();
        sys.solve_multi(&mut x).expect("solvable");
        let lu = dense.partial_piv_lu();
        for (xj, bj) in x.iter().zip(&b) {
            let reference = lu.solve(Mat::from_fn(16, 1, |i, _| bj[i]));
            for (i, v) in xj.iter().enumerate() {
                assert!(
                    (v - reference[(i, 0)]).abs() <= 1e-12 * (1.0 + reference[(i, 0)].abs()),
                    "x[{i}] = {v} vs dense {}",
                    reference[(i, 0)]
                );
            }
        }
        // clearing drops the updates: the matrix is symmetric again
        sys.clear();
        assert_eq!(sys.updates.len(), 0);
        assert_eq!(sys.get(9, 12), 0.0);
    }

    /// The switching solve: a [`RowChange`] on an updated row (entries and right-hand
    /// side) gives the solution of the changed system (dense LU of it), without a new
    /// factorisation; `switch` sees the assembled solution first, then the changed one;
    /// a switch that never settles falls back to the assembled solution.
    #[test]
    fn switched_solve_matches_dense_lu_of_the_changed_system() {
        let mut sys = strip();
        sys.add_to_row(3, 5, 4.0);
        sys.add_to_row(9, 9, 0.0);
        let change = RowChange {
            row: 9,
            entries: vec![(9, 25.0), (1, -3.0)],
            rhs: vec![2.0],
        };
        let b: Vec<f64> = (0..16).map(|i| ((i * 3) % 7) as f64 - 3.0).collect();
        let mut changed_b = b.clone();
        changed_b[9] += 2.0;
        let dense = Mat::from_fn(16, 16, |r, c| {
            let extra: f64 = change
                .entries
                .iter()
                .filter(|&&(col, _)| r == 9 && col == c)
                .map(|&(_, v)| v)
                .sum();
            sys.get(r, c) + extra
        });
        let reference = dense
            .partial_piv_lu()
            .solve(Mat::from_fn(16, 1, |i, _| changed_b[i]));
        let factorisations = sys.factorisations();
        let mut seen = 0;
        let mut x = vec![b.clone()];
        let passes = sys
            .solve_multi_switching(&mut x, 4, |_| {
                seen += 1;
                (seen == 1).then(|| vec![change.clone()])
            })
            .expect("solvable");
        assert_eq!((passes, seen), (1, 2));
        assert_eq!(sys.factorisations(), factorisations + 1);
        for (i, v) in x[0].iter().enumerate() {
            assert!(
                (v - reference[(i, 0)]).abs() <= 1e-12 * (1.0 + reference[(i, 0)].abs()),
                "x[{i}] = {v} vs dense {}",
                reference[(i, 0)]
            );
        }
        // a switch that never settles: the assembled solution
        let mut assembled = vec![b.clone()];
        sys.solve_multi(&mut assembled).expect("solvable");
        let mut restless = vec![b.clone()];
        let passes = sys
            .solve_multi_switching(&mut restless, 3, |_| Some(vec![change.clone()]))
            .expect("solvable");
        assert_eq!(passes, 3);
        assert_eq!(restless, assembled);
    }
}
