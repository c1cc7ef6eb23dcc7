//! Sparse tangent matrix with a fixed pattern and a direct solve through faer.
//!
//! Every node owns two equation slots (`2i`, `2i+1`) whatever its constraint status;
//! constrained slots get an identity row/column. The sparsity pattern therefore never
//! changes during a solve, so the symbolic factorisations (fill-reducing ordering,
//! elimination structure) are computed once and reused for every numeric
//! factorisation.
//!
//! # Solve chain
//! The frictionless tangent `S` is symmetric (`symmetric.rs`):
//! 1. supernodal Cholesky `L Lᵀ`;
//! 2. when Cholesky fails (the reduced Hessian need not be positive definite away from
//!    equilibrium), `L D Lᵀ` without pivoting, accepted if its solution's residual is
//!    small. Indefinite tangents come in runs (the Newton iterations of a step near the
//!    contact edge), so after a failed Cholesky the next factorisations try `L D Lᵀ` first,
//!    until one has a positive `D` (the matrix was positive definite): Cholesky first again;
//! 3. else the symmetric-indefinite `L B Lᵀ` (Bunch–Kaufman pivoting inside the
//!    supernodes);
//! 4. LU with partial pivoting as the last resort (`lu.rs`).
//!
//! Steps 1–3 share one symbolic structure and work memory, and read the matrix's lower
//! triangle already in the fill-reducing order, gathered through a fixed map
//! (`OrderedLower`).
//!
//! The frictional tangent is the symmetric matrix plus a few non-symmetric rows, one per
//! contact node with friction (`woodbury.rs`): `K = S + Σᵢ e_{rᵢ} vᵢᵀ = S + E Vᵀ`, a
//! rank-`m` update with `m` at most the number of contact-face nodes.
//! [`SparseSystem::solve`] solves it by the Sherman–Morrison–Woodbury identity:
//! `z = S⁻¹ b` through the symmetric chain above, a dense `m × m` system
//! `(I + Vᵀ S⁻¹ E) y = Vᵀ z` (LU with partial pivoting), and `x = S⁻¹ (b − E y)` with the
//! same factorisation, accepted if the residual of `K` is small; else the full `K` goes to
//! LU (step 4), whose symbolic structure is that of `KᵀK` and which costs several
//! Cholesky factorisations of `S` (`docs/performance.md`).
//!
//! `Vᵀ S⁻¹ E` needs `S⁻¹` only on the equations `T` that the updates touch. When those are
//! ordered last in the factorisation ([`SparseSystem::order_last`], `trailing.rs`: the model
//! orders the contact face and the layer of nodes above it last), the factor's trailing
//! block `L_TT` factors the Schur complement `Σ` of `S` onto `T`, and `(S⁻¹)_TT = Σ⁻¹`: the
//! `m` columns of `S⁻¹ E` on `T` cost two dense triangular solves of size `|T|` instead of
//! `m` sparse solves of the whole system (the gain: `docs/performance.md`). Otherwise
//! (updates beyond `T`, or a pivoted `L B Lᵀ` or LU factorisation of `S`), the `m` unit
//! vectors `e_{rᵢ}` are solved for.
//!
//! Because `S⁻¹ E` on `T` is at hand, a system whose updated rows (and right-hand sides on
//! them) change is solved again on `T` with a dense `m × m` system and no factorisation
//! ([`SparseSystem::solve_switching_rows`]): the semismooth Newton step of the friction
//! law switches nodes between pieces of the law that way, reading the candidate steps on
//! `T` only, and the whole system is solved once it has settled.
//!
//! # Files
//! This file holds the matrix ([`SparseSystem`]: pattern, values, element and diagonal
//! positions, counters) and the entry points [`SparseSystem::solve`] and
//! [`SparseSystem::solve_switching_rows`]; `symmetric.rs` the chain for `S`, `lu.rs` the
//! LU, `woodbury.rs` the row updates and their solve, `trailing.rs` the trailing block.

mod lu;
mod symmetric;
mod trailing;
mod woodbury;

#[cfg(test)]
mod test_support;

pub use woodbury::RowChange;

use faer::dyn_stack::MemBuffer;
use faer::sparse::linalg::cholesky::SymbolicCholesky;
use faer::sparse::linalg::lu::{NumericLu, SymbolicLu};
use faer::sparse::SymbolicSparseColMatRef;
use symmetric::OrderedLower;
use woodbury::RowUpdates;

/// Acceptance of a solution that may be inaccurate, `‖A x − b‖₂² ≤ tol · ‖b‖₂²`: a relative
/// residual of 10⁻⁸, far above the round-off of a stable factorisation, so that only an
/// inaccurate solution is rejected: an unpivoted `L D Lᵀ` factored unstably (then
/// `L B Lᵀ`), or a Woodbury solve with an ill-conditioned `I + Vᵀ S⁻¹ E` (then LU of the
/// whole matrix).
const RESIDUAL_RTOL_SQUARED: f64 = 1e-16;

/// A permutation of the equations: forward (new position → equation) and inverse.
type Permutation = (Vec<usize>, Vec<usize>);

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
    /// Unit vectors of updated rows solved for so far (Woodbury without the trailing block).
    woodbury_unit_solves: usize,
    /// The symbolic LU structure, computed on the first LU.
    symbolic_lu: Option<SymbolicLu<usize>>,
    /// LU factors, kept between factorisations so that their storage is reused.
    numeric_lu: NumericLu<usize, f64>,
    lu_scratch: Option<Scratch>,
    /// Work memory of the Cholesky-family factorisations and solves, kept across
    /// factorisations.
    llt_scratch: Option<Scratch>,
    /// The symbolic structure of the Cholesky-family factorisations, computed on the
    /// first solve.
    symbolic_cholesky: Option<std::sync::Arc<SymbolicCholesky<usize>>>,
    /// The matrix as the Cholesky-family factorisations read it.
    ordered: OrderedLower,
    /// The numeric factor of the Cholesky-family factorisation held.
    llt_values: Vec<f64>,
    /// The `L B Lᵀ` factorisation's subdiagonal of `B` and its permutation.
    lblt_subdiag: Vec<f64>,
    lblt_perm: Permutation,
    /// Which factorisation of the symmetric part the last successful solve left in
    /// `llt_values` (or in `numeric_lu`).
    factored: Factored,
    /// The last symmetric part was indefinite: the next factorisation tries `L D Lᵀ` before
    /// Cholesky (see the [module documentation](self)).
    expect_indefinite: bool,
    /// The equations ordered last in the Cholesky factorisation ([`Self::order_last`]),
    /// in their order there.
    trailing: Vec<usize>,
    /// Each equation's position among `trailing` (`usize::MAX`: not among them).
    trailing_slot: Vec<usize>,
}

/// The factorisation of the symmetric part `S` held by a [`SparseSystem`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Factored {
    None,
    Llt,
    Ldlt,
    Lblt,
    Lu,
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
            woodbury_unit_solves: 0,
            symbolic_lu: None,
            numeric_lu: NumericLu::new(),
            lu_scratch: None,
            llt_scratch: None,
            symbolic_cholesky: None,
            ordered: OrderedLower::default(),
            llt_values: Vec::new(),
            lblt_subdiag: Vec::new(),
            lblt_perm: (Vec::new(), Vec::new()),
            factored: Factored::None,
            expect_indefinite: false,
            trailing: Vec::new(),
            trailing_slot: vec![usize::MAX; ndof],
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

    /// Unit vectors of updated rows solved for so far: the Woodbury solves that could not
    /// read `S⁻¹` from the factor's trailing block ([`Self::order_last`]).
    pub fn woodbury_unit_solves(&self) -> usize {
        self.woodbury_unit_solves
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

    /// Row `r` of the symmetric part, its entries `(column, value)` (column `r` of the
    /// pattern, read by symmetry).
    pub fn symmetric_row(&self, r: usize) -> Vec<(usize, f64)> {
        (self.col_ptr[r]..self.col_ptr[r + 1])
            .map(|k| (self.row_idx[k], self.values[k]))
            .collect()
    }

    /// Value position of entry `(r, c)`, if it is in the pattern.
    fn position(&self, r: usize, c: usize) -> Option<usize> {
        let s = &self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]];
        s.binary_search(&r).ok().map(|k| self.col_ptr[c] + k)
    }

    /// `y = S x`, the symmetric part.
    fn mul(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.n];
        for (c, &xc) in x.iter().enumerate() {
            for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                y[self.row_idx[k]] += self.values[k] * xc;
            }
        }
        y
    }

    /// `y = K x`, row updates included.
    fn mul_updated(&self, x: &[f64]) -> Vec<f64> {
        let mut y = self.mul(x);
        for (i, &r) in self.updates.rows.iter().enumerate() {
            y[r] += self.updates.dot(i, x);
        }
        y
    }

    /// Solve `K xⱼ = bⱼ` in place for several right-hand sides, row updates included: the
    /// symmetric chain when there are no row updates, else the Woodbury solve (see the
    /// [module documentation](self)); [`Self::solve_switching_rows`] with no switch.
    pub fn solve(&mut self, rhs: &mut [Vec<f64>]) -> Result<(), LinSolveError> {
        self.solve_switching_rows(rhs, 0, |_| None).map(|_| ())
    }

    /// Solve `K xⱼ = bⱼ` again for the matrix of the last [`Self::solve`], unchanged since:
    /// with the factorisation it left (no new one) when the matrix has no row updates, else
    /// as [`Self::solve`] does.
    pub fn solve_again(&mut self, rhs: &mut [Vec<f64>]) -> Result<(), LinSolveError> {
        if self.updates.is_empty() && self.solve_symmetric_held(rhs)? {
            return Ok(());
        }
        self.solve(rhs)
    }
}
