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
//!    small. Indefinite tangents come in runs (the Newton iterations of a step near the
//!    contact edge), so after a failed Cholesky the next factorisations try `L D Lᵀ` first,
//!    until one has a positive `D` (the matrix was positive definite): Cholesky first again;
//! 3. else the symmetric-indefinite `L B Lᵀ` (Bunch–Kaufman pivoting inside the
//!    supernodes);
//! 4. LU with partial pivoting as the last resort.
//!
//! Steps 1–3 share one symbolic structure and work memory, and read the matrix's lower
//! triangle already in the fill-reducing order, gathered through a fixed map
//! (`OrderedLower`).
//!
//! The frictional tangent is the symmetric matrix plus a few non-symmetric rows, one per
//! contact node with friction ([`RowUpdates`]): `K = S + Σᵢ e_{rᵢ} vᵢᵀ = S + E Vᵀ`, a
//! rank-`m` update with `m` at most the number of contact-face nodes.
//! [`SparseSystem::solve_multi`] solves it by the Sherman–Morrison–Woodbury identity:
//! `z = S⁻¹ b` through the symmetric chain above, a dense `m × m` system
//! `(I + Vᵀ S⁻¹ E) y = Vᵀ z` (LU with partial pivoting), and `x = S⁻¹ (b − E y)` with the
//! same factorisation, accepted if the residual of `K` is small; else the full `K` goes to
//! LU (step 4). A sparse LU of `K` costs 5–10 Cholesky factorisations of `S` (its
//! symbolic structure is that of `KᵀK`).
//!
//! `Vᵀ S⁻¹ E` needs `S⁻¹` only on the equations `T` that the updates touch. When those are
//! ordered last in the factorisation ([`SparseSystem::order_last`]: the model orders the
//! contact face and the layer of nodes above it last), the factor's trailing block
//! `L_TT` factors the Schur complement `Σ` of `S` onto `T`, and `(S⁻¹)_TT = Σ⁻¹`: the
//! `m` columns of `S⁻¹ E` on `T` cost two dense triangular solves of size `|T|`
//! instead of `m` sparse solves of the whole system (measured: README, "Frictional
//! speed"). Otherwise (updates beyond `T`, or a pivoted `L B Lᵀ` or LU factorisation of
//! `S`), the `m` unit vectors `e_{rᵢ}` are solved for.
//!
//! Because `S⁻¹ E` on `T` is at hand, a system whose updated rows (and right-hand sides on
//! them) change is solved again on `T` with a dense `m × m` system and no factorisation
//! ([`SparseSystem::solve_multi_switching`]): the semismooth Newton step of the friction
//! law switches nodes between pieces of the law that way, reading the candidate steps on
//! `T` only, and the whole system is solved once it has settled.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::solvers::Solve;
use faer::linalg::triangular_solve;
use faer::perm::PermRef;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, IntranodeLbltRef, LdltRef, LltRef,
    SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
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

/// The lower triangle of the matrix in the Cholesky factorisations' fill-reducing order,
/// gathered from the matrix's values by a fixed map before each factorisation (faer
/// permutes a matrix given in another order at every factorisation: measured 4–5 % of a
/// curve).
#[derive(Clone, Debug, Default)]
struct OrderedLower {
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

/// What the Woodbury solve needs of `S⁻¹`, on the equations `kept` that the row updates
/// and their changes touch: `S⁻¹ bⱼ` there and `(S⁻¹ E)` there (`E` the unit vectors of
/// the updated rows, in the order of the updates).
struct WoodburyParts {
    /// Which equations are kept, and where.
    kept: Kept,
    /// `(S⁻¹ bⱼ)` on the kept equations.
    z_b: Vec<Vec<f64>>,
    /// `(S⁻¹ E)` on the kept equations (kept × updates).
    z_e: Mat<f64>,
}

/// The Woodbury solutions of one system on the kept equations
/// ([`SparseSystem::woodbury_reduced`]).
#[derive(Clone, Debug)]
struct Reduced {
    /// The changes of the right-hand sides on the updated rows (updates × right-hand sides).
    beta: Mat<f64>,
    /// The capacitance system's solution (updates × right-hand sides).
    y: Mat<f64>,
    /// The solutions on the kept equations.
    x: Vec<Vec<f64>>,
}

/// The equations of [`WoodburyParts`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kept {
    /// Those ordered last ([`SparseSystem::order_last`]), at their `trailing_slot`.
    Trailing,
    /// All of them, at their own index.
    All,
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
    symbolic: Option<SymbolicLu<usize>>,
    /// LU factors, kept between factorisations so that their storage is reused.
    numeric_lu: NumericLu<usize, f64>,
    lu_scratch: Option<Scratch>,
    /// Work memory of the Cholesky-family factorisations and solves, kept across
    /// factorisations.
    llt_scratch: Option<Scratch>,
    symbolic_llt: Option<std::sync::Arc<SymbolicCholesky<usize>>>,
    /// The matrix as the Cholesky-family factorisations read it.
    ordered: OrderedLower,
    llt_values: Vec<f64>,
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
            symbolic: None,
            numeric_lu: NumericLu::new(),
            lu_scratch: None,
            llt_scratch: None,
            symbolic_llt: None,
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

    /// Order the equations `dofs` last in the Cholesky factorisation (the others by
    /// approximate minimum degree among themselves), before the first solve. When every
    /// row update and every column it touches lies among them, the Woodbury solve takes
    /// `(S⁻¹)` on them from the factor's dense trailing block (the inverse of the Schur
    /// complement of `S` onto them) instead of solving for one unit vector per updated
    /// row: two ordinary solves per Newton system instead of `m + 1`
    /// ([`Self::solve_multi_switching`]).
    pub fn order_last(&mut self, dofs: &[usize]) {
        assert!(
            self.symbolic_llt.is_none(),
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
    fn trailing_ordering(&self) -> Result<Option<Permutation>, LinSolveError> {
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
    fn updates_within_trailing(&self) -> bool {
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
    fn trailing_inverse_columns(&self) -> Option<Mat<f64>> {
        let unit_diagonal = match self.factored {
            Factored::Llt => false,
            Factored::Ldlt => true,
            _ => return None,
        };
        let symbolic = self.symbolic_llt.as_ref()?;
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

    /// The symmetric solves `S⁻¹ bⱼ` (one factorisation of `S`) and `S⁻¹ E` on the
    /// equations the updates touch: from the factor's trailing block when the updates lie
    /// among the equations ordered last ([`Self::order_last`]), else one solve per
    /// unit vector of an updated row, on every equation.
    fn woodbury_parts(&mut self, rhs: &[Vec<f64>]) -> Result<WoodburyParts, LinSolveError> {
        let mut z_b = rhs.to_vec();
        self.solve_symmetric_checked(&mut z_b, rhs.len())?;
        if self.updates_within_trailing() {
            if let Some(z_e) = self.trailing_inverse_columns() {
                let z_b = z_b
                    .iter()
                    .map(|z| self.trailing.iter().map(|&d| z[d]).collect())
                    .collect();
                return Ok(WoodburyParts {
                    kept: Kept::Trailing,
                    z_b,
                    z_e,
                });
            }
        }
        let n = self.n;
        let mut units: Vec<Vec<f64>> = self
            .updates
            .rows
            .iter()
            .map(|&r| {
                let mut e = vec![0.0; n];
                e[r] = 1.0;
                e
            })
            .collect();
        self.woodbury_unit_solves += units.len();
        if !self.resolve(&mut units)? {
            return Err(LinSolveError::Numeric("non-finite solution".into()));
        }
        let z_e = Mat::from_fn(n, units.len(), |i, j| units[j][i]);
        Ok(WoodburyParts {
            kept: Kept::All,
            z_b,
            z_e,
        })
    }

    /// The solutions of `(K + Σ e_r Δvᵣᵀ) x = b + Σ e_r Δbᵣ` on the kept equations, from
    /// `parts` ([`RowChange`]s on updated rows only, `Δb` per right-hand side):
    /// `y = (I + V′ᵀ Z_E)⁻¹ V′ᵀ z′_b` with `z′_b = S⁻¹ (b + E β)`, `β` the changes of the
    /// right-hand sides, and `x = z′_b − Z_E y` there. `None` if a change touches an
    /// equation that is not kept or the result is not finite.
    fn woodbury_reduced(&self, parts: &WoodburyParts, changes: &[RowChange]) -> Option<Reduced> {
        let (k, m) = (parts.z_b.len(), self.updates.len());
        let local = |d: usize| match parts.kept {
            Kept::Trailing => self.trailing_slot[d],
            Kept::All => d,
        };
        let touched_kept = changes
            .iter()
            .all(|c| c.entries.iter().all(|&(col, _)| local(col) != usize::MAX));
        if !touched_kept {
            return None;
        }
        let mut extra: Vec<&[(usize, f64)]> = vec![&[]; m];
        let mut beta = Mat::<f64>::zeros(m, k);
        let mut z_b = parts.z_b.clone();
        for change in changes {
            let i = self.updates.slot[change.row];
            assert!(i != usize::MAX, "a row change on an updated row");
            extra[i] = &change.entries;
            for (j, &b) in change.rhs.iter().enumerate() {
                beta[(i, j)] += b;
                z_b[j]
                    .iter_mut()
                    .zip(parts.z_e.col(i).iter())
                    .for_each(|(z, e)| *z += b * e);
            }
        }
        let updates = &self.updates;
        let dot = |i: usize, x: &dyn Fn(usize) -> f64| {
            updates.entries[i]
                .iter()
                .chain(extra[i])
                .map(|&(c, v)| v * x(local(c)))
                .sum::<f64>()
        };
        let capacitance = Mat::from_fn(m, m, |i, j| {
            f64::from(u8::from(i == j)) + dot(i, &|l| parts.z_e[(l, j)])
        });
        let projected = Mat::from_fn(m, k, |i, j| dot(i, &|l| z_b[j][l]));
        let y = capacitance.partial_piv_lu().solve(&projected);
        for (j, x) in z_b.iter_mut().enumerate() {
            for i in 0..m {
                let yi = y[(i, j)];
                x.iter_mut()
                    .zip(parts.z_e.col(i).iter())
                    .for_each(|(xv, zv)| *xv -= yi * zv);
            }
        }
        let finite = z_b.iter().flatten().all(|v| v.is_finite());
        finite.then_some(Reduced { beta, y, x: z_b })
    }

    /// `reduced` as full-length vectors for the `switch` of
    /// [`Self::solve_multi_switching`]: the equations that are not kept are NaN.
    fn switch_view(&self, parts: &WoodburyParts, reduced: &Reduced) -> Vec<Vec<f64>> {
        match parts.kept {
            Kept::All => reduced.x.clone(),
            Kept::Trailing => reduced
                .x
                .iter()
                .map(|x| {
                    let mut full = vec![f64::NAN; self.n];
                    for (&d, &v) in self.trailing.iter().zip(x) {
                        full[d] = v;
                    }
                    full
                })
                .collect(),
        }
    }

    /// The full solutions of the system that `reduced` solves on the kept equations:
    /// `x = S⁻¹ (b + E (β − y))` with the factorisation held (or `reduced` itself when
    /// every equation is kept); `None` if one is not finite or its residual exceeds
    /// `10⁻⁸ ‖b‖`.
    fn woodbury_full(
        &mut self,
        parts: &WoodburyParts,
        rhs: &[Vec<f64>],
        changes: &[RowChange],
        reduced: &Reduced,
    ) -> Result<Option<Vec<Vec<f64>>>, LinSolveError> {
        let solutions = match parts.kept {
            Kept::All => reduced.x.clone(),
            Kept::Trailing => {
                let mut x = rhs.to_vec();
                for (i, &r) in self.updates.rows.iter().enumerate() {
                    for (j, xj) in x.iter_mut().enumerate() {
                        xj[r] += reduced.beta[(i, j)] - reduced.y[(i, j)];
                    }
                }
                if !self.resolve(&mut x)? {
                    return Ok(None);
                }
                x
            }
        };
        let accurate = solutions.iter().zip(rhs).enumerate().all(|(j, (x, bj))| {
            let mut kx = self.mul_updated(x);
            let mut b = bj.clone();
            for change in changes {
                kx[change.row] += change.entries.iter().map(|&(c, v)| v * x[c]).sum::<f64>();
                b[change.row] += change.rhs[j];
            }
            residual_within(&kx, &b, RESIDUAL_RTOL_SQUARED)
        });
        Ok(accurate.then_some(solutions))
    }

    /// Solve `S xⱼ = bⱼ` in place with the factorisation of `S` held (no new
    /// factorisation, except for an LU, whose factors are not kept); `false` if a
    /// solution is not finite.
    fn resolve(&mut self, rhs: &mut [Vec<f64>]) -> Result<bool, LinSolveError> {
        if self.factored == Factored::Lu {
            self.lu_solve_multi(rhs)?;
            return Ok(true);
        }
        let symbolic = self
            .symbolic_llt
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

    /// LU of the full matrix `K`: the updates added into the values for the factorisation.
    fn lu_solve_updated(&mut self, rhs: &mut [Vec<f64>]) -> Result<(), LinSolveError> {
        let symmetric = self.values.clone();
        for (i, &r) in self.updates.rows.iter().enumerate() {
            for &(c, v) in &self.updates.entries[i] {
                let p = self.position(r, c).expect("row updates lie in the pattern");
                self.values[p] += v;
            }
        }
        // the factorisation of `S` held stays the one for later solves
        let held = self.factored;
        let solved = self.lu_solve_multi(rhs);
        self.values = symmetric;
        self.factored = held;
        solved
    }

    /// Solve `K xⱼ = bⱼ`: the symmetric chain when there are no row updates, else the
    /// Woodbury solve (`woodbury_parts`): `y = (I + Vᵀ Z_E)⁻¹ Vᵀ z_b` on the
    /// equations the updates touch, `x = S⁻¹ (b − E y)`, accepted if
    /// `‖K x − b‖ ≤ 10⁻⁸ ‖b‖` for every right-hand side, else LU of `K`.
    ///
    /// Before that, `switch` may change updated rows of the system in view of its
    /// solutions: it is shown the solutions (exact on the equations ordered last,
    /// [`Self::order_last`], when the updates lie among them, NaN elsewhere; exact
    /// everywhere otherwise) and returns the [`RowChange`]s (relative to the assembled `K`
    /// and `b`) under which it wants the system solved next, or `None` when the solutions
    /// it was shown are the ones it wants. The changed systems reuse the factorisation
    /// and cost a dense `m × m` solve each. At most `max_switches` changed solves; if
    /// `switch` has not settled by then, or the settled system's solution is inaccurate,
    /// the solutions of the assembled system are returned. Returns the number of changed
    /// solves behind the solutions returned (`max_switches` when the switch gave up).
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
        let assembled = self.woodbury_reduced(&parts, &[]);
        let mut current = assembled.clone();
        let mut changes = Vec::new();
        let mut passes = 0;
        let settled = loop {
            let Some(reduced) = &current else {
                break false;
            };
            let Some(next) = switch(&self.switch_view(&parts, reduced)) else {
                break true;
            };
            if passes == max_switches {
                break false;
            }
            passes += 1;
            current = self.woodbury_reduced(&parts, &next);
            changes = next;
        };
        if settled && passes > 0 {
            let reduced = current.as_ref().expect("settled on a solution");
            if let Some(x) = self.woodbury_full(&parts, rhs, &changes, reduced)? {
                rhs.clone_from_slice(&x);
                return Ok(passes);
            }
        }
        let full = match &assembled {
            Some(reduced) => self.woodbury_full(&parts, rhs, &[], reduced)?,
            None => None,
        };
        match full {
            Some(x) => rhs.clone_from_slice(&x),
            None => self.lu_solve_updated(rhs)?,
        }
        Ok(if settled && passes == 0 {
            0
        } else {
            max_switches
        })
    }

    /// The symbolic Cholesky structure and the work memory of the Cholesky-family
    /// factorisations, computed on first use: approximate minimum degree ordering (with
    /// the equations of [`Self::order_last`] last, if any), supernodal (the default faer
    /// heuristic picks the simplicial variant for these 2D meshes, which measured about 3×
    /// slower).
    fn ensure_symbolic_cholesky(&mut self) -> Result<(), LinSolveError> {
        if self.symbolic_llt.is_some() {
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
        self.symbolic_llt = Some(std::sync::Arc::new(s));
        Ok(())
    }

    /// Supernodal sparse Cholesky (sequential) of the lower triangle and solve for every
    /// right-hand side; `false` if the matrix is not numerically positive definite.
    fn llt_solve(&mut self, rhs: &mut [Vec<f64>]) -> Result<bool, LinSolveError> {
        let symbolic = self.symbolic_llt.clone().expect("symbolic set");
        let buf = &mut self
            .llt_scratch
            .as_mut()
            .expect("set with the symbolic")
            .buf;
        self.factorisations += 1;
        self.factored = Factored::None;
        let factored = symbolic.factorize_numeric_llt(
            &mut self.llt_values,
            self.ordered.matrix(),
            Side::Lower,
            Default::default(),
            Par::Seq,
            MemStack::new(buf),
            Default::default(),
        );
        if factored.is_err() {
            return Ok(false);
        }
        self.solve_with(Factored::Llt, rhs)
    }

    /// Solve with the numeric factorisation `kind` just computed into `llt_values`
    /// ([`Self::resolve`]); it is held from then on if every solution is finite.
    fn solve_with(&mut self, kind: Factored, rhs: &mut [Vec<f64>]) -> Result<bool, LinSolveError> {
        self.factored = kind;
        let finite = self.resolve(rhs)?;
        if !finite {
            self.factored = Factored::None;
        }
        Ok(finite)
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
        self.ensure_symbolic_cholesky()?;
        self.ordered.gather(&self.values);
        let solved = if self.expect_indefinite {
            if self.ldlt_solve(rhs, checked)? {
                self.expect_indefinite = !self.ldlt_positive();
                true
            } else {
                self.lblt_solve(rhs)?
            }
        } else {
            self.llt_solve(rhs)? || {
                self.expect_indefinite = true;
                self.ldlt_solve(rhs, checked)? || self.lblt_solve(rhs)?
            }
        };
        if solved {
            return Ok(());
        }
        self.lu_solve_multi(rhs)
    }

    /// `true` when the `L D Lᵀ` factorisation held has a positive `D` (the matrix was
    /// positive definite: Cholesky would have succeeded), or when that cannot be read (a
    /// simplicial factorisation).
    fn ldlt_positive(&self) -> bool {
        let Some(symbolic) = self.symbolic_llt.as_ref() else {
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

    /// Sparse `L D Lᵀ` factorisation without pivoting (on the Cholesky symbolic
    /// structure) and solve; `false` on a zero pivot or if a solution is not accurate
    /// (`‖A x − b‖₂ > 10⁻⁸ ‖b‖₂`: without pivoting an indefinite matrix may factor
    /// unstably). Measured at AR = 0.3 (64×32): every indefinite tangent of a curve
    /// (≈ 130) passes, and the curve's time in indefinite factorisations drops by a
    /// fifth against `L B Lᵀ`.
    fn ldlt_solve(&mut self, rhs: &mut [Vec<f64>], checked: usize) -> Result<bool, LinSolveError> {
        let symbolic = self.symbolic_llt.clone().expect("symbolic set");
        let buf = &mut self
            .llt_scratch
            .as_mut()
            .expect("set with the symbolic")
            .buf;
        self.factorisations += 1;
        self.factored = Factored::None;
        // the values gathered by `solve_symmetric_checked`
        let factored = symbolic.factorize_numeric_ldlt(
            &mut self.llt_values,
            self.ordered.matrix(),
            Side::Lower,
            Default::default(),
            Par::Seq,
            MemStack::new(buf),
            Default::default(),
        );
        if factored.is_err() {
            return Ok(false);
        }
        let b = rhs.to_vec();
        if !self.solve_with(Factored::Ldlt, rhs)? {
            return Ok(false);
        }
        let accurate = rhs
            .iter()
            .zip(&b)
            .take(checked)
            .all(|(x, b)| residual_within(&self.mul(x), b, RESIDUAL_RTOL_SQUARED));
        if !accurate {
            self.factored = Factored::None;
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
        let symbolic = self.symbolic_llt.clone().expect("symbolic set");
        self.lblt_subdiag.resize(self.n, 0.0);
        self.lblt_perm.0.resize(self.n, 0);
        self.lblt_perm.1.resize(self.n, 0);
        let buf = &mut self
            .llt_scratch
            .as_mut()
            .expect("set with the symbolic")
            .buf;
        self.factorisations += 1;
        self.factored = Factored::None;
        // the values gathered by `solve_symmetric_checked`
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
        self.solve_with(Factored::Lblt, rhs)
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
        let b = strip_rhs(2);
        let mut x = b.clone();
        sys.solve_multi(&mut x).expect("solvable");
        for (xj, bj) in x.iter().zip(&b) {
            assert_matches_dense(&dense, xj, bj);
        }
        // clearing drops the updates: the matrix is symmetric again
        sys.clear();
        assert_eq!(sys.updates.len(), 0);
        assert_eq!(sys.get(9, 12), 0.0);
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
    fn assert_switches_once(
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
            .solve_multi_switching(&mut x, 4, |shown| {
                seen += 1;
                inspect(shown);
                (seen == 1).then(|| vec![change.clone()])
            })
            .expect("solvable");
        assert_eq!((passes, seen), (1, 2));
        assert_eq!(sys.factorisations(), factorisations + 1);
        assert_matches_dense(&dense, &x[0], &changed_b);
        b
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
        let b = assert_switches_once(&mut sys, &change, |_| {});
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

    /// `strip()` with equations 6–15 ordered last.
    fn trailing_strip() -> SparseSystem {
        let mut sys = strip();
        sys.order_last(&(6..16).collect::<Vec<_>>());
        sys
    }

    /// Right-hand sides for the strip.
    fn strip_rhs(count: usize) -> Vec<Vec<f64>> {
        (0..count)
            .map(|j| {
                (0..16)
                    .map(|i| ((i * 3 + j * 5) % 7) as f64 - 3.0)
                    .collect()
            })
            .collect()
    }

    /// `x` against the dense LU solution of `dense x = b`, to 10⁻¹² relative.
    fn assert_matches_dense(dense: &Mat<f64>, x: &[f64], b: &[f64]) {
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
            sys.solve_multi(&mut x).expect("solvable");
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
        sys.solve_multi(&mut x).expect("solvable");
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
        sys.solve_multi(&mut assembled).expect("solvable");
        let beyond = RowChange {
            entries: vec![(1, 5.0)],
            ..change.clone()
        };
        let mut x = vec![b.clone()];
        let passes = sys
            .solve_multi_switching(&mut x, 4, |_| Some(vec![beyond.clone()]))
            .expect("solvable");
        assert_eq!(passes, 4);
        assert_eq!(x, assembled);
    }

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
            sys.solve_multi(&mut x).expect("solvable");
            assert_eq!(sys.factorisations() - before, count, "solve {step}");
            assert_eq!(sys.factored, held, "solve {step}");
            assert_matches_dense(&dense, &x[0], &b[0]);
        }
    }
}
