//! The frictional matrix `K = S + E Vᵀ`: the non-symmetric row updates ([`RowUpdates`]) and
//! their solve by the Sherman–Morrison–Woodbury identity on top of a factorisation of `S`,
//! including the switching solve ([`SparseSystem::solve_switching_rows`]) that changes
//! updated rows and solves again without a new factorisation (see the
//! [module documentation](super)).

use super::{residual_within, LinSolveError, SparseSystem, RESIDUAL_RTOL_SQUARED};
use faer::linalg::solvers::Solve;
use faer::Mat;

/// Non-symmetric rows added to the symmetric matrix: `K = S + Σᵢ e_{rᵢ} vᵢᵀ`, each row
/// `rᵢ` with its sparse vector `vᵢ` (entries `(column, value)`, a column may repeat: the
/// entries add up).
#[derive(Clone, Debug, Default)]
pub(super) struct RowUpdates {
    /// Index into `rows` of each equation's update (`usize::MAX`: none).
    slot: Vec<usize>,
    /// The updated rows, in the order of their first entry.
    pub(super) rows: Vec<usize>,
    /// Each updated row's entries `(column, value)`.
    pub(super) entries: Vec<Vec<(usize, f64)>>,
}

impl RowUpdates {
    pub(super) fn new(n: usize) -> Self {
        Self {
            slot: vec![usize::MAX; n],
            rows: Vec::new(),
            entries: Vec::new(),
        }
    }

    pub(super) fn clear(&mut self) {
        for &r in &self.rows {
            self.slot[r] = usize::MAX;
        }
        self.rows.clear();
        self.entries.clear();
    }

    /// Number of updated rows.
    pub(super) fn len(&self) -> usize {
        self.rows.len()
    }

    /// `true` when the matrix is its symmetric part.
    pub(super) fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    pub(super) fn add(&mut self, row: usize, col: usize, value: f64) {
        if self.slot[row] == usize::MAX {
            self.slot[row] = self.rows.len();
            self.rows.push(row);
            self.entries.push(Vec::new());
        }
        self.entries[self.slot[row]].push((col, value));
    }

    /// `vᵢ · x` of update `i`.
    pub(super) fn dot(&self, i: usize, x: &[f64]) -> f64 {
        self.entries[i].iter().map(|&(c, v)| v * x[c]).sum()
    }

    /// Entry `(r, c)` of the updates.
    pub(super) fn get(&self, r: usize, c: usize) -> f64 {
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

/// A change of one updated row of the system ([`SparseSystem::solve_switching_rows`]):
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

impl SparseSystem {
    /// Solve `K xⱼ = bⱼ`: the symmetric chain when there are no row updates, else the
    /// Woodbury solve (`woodbury_parts`): `y = (I + Vᵀ Z_E)⁻¹ Vᵀ z_b` on the
    /// equations the updates touch, `x = S⁻¹ (b − E y)`, accepted if
    /// `‖K x − b‖ ≤ 10⁻⁸ ‖b‖` for every right-hand side, else LU of `K`.
    ///
    /// Before the full solve, `switch` may change updated rows of the system in view of its
    /// solutions: it is shown the solutions (exact on the equations ordered last,
    /// [`Self::order_last`], when the updates lie among them, NaN elsewhere; exact
    /// everywhere otherwise) and returns the [`RowChange`]s (relative to the assembled `K`
    /// and `b`) under which it wants the system solved next, or `None` when the solutions
    /// it was shown are the ones it wants. The changed systems reuse the factorisation
    /// and cost a dense `m × m` solve each. At most `max_switches` changed solves; if
    /// `switch` has not settled by then, or the settled system's solution is inaccurate,
    /// the solutions of the assembled system are returned. Returns the number of changed
    /// solves behind the solutions returned, `None` when the switch gave up and the
    /// assembled system's solutions are returned. Fails at
    /// once, factorising nothing, when the caller asked the solve to stop
    /// ([`crate::fe::interrupt`]).
    pub fn solve_switching_rows(
        &mut self,
        rhs: &mut [Vec<f64>],
        max_switches: usize,
        mut switch: impl FnMut(&[Vec<f64>]) -> Option<Vec<RowChange>>,
    ) -> Result<Option<usize>, LinSolveError> {
        // a solve the caller asked to stop factorises nothing more (`crate::fe::interrupt`)
        if crate::fe::interrupt::requested() {
            return Err(LinSolveError::Numeric(
                crate::fe::interrupt::INTERRUPTED.into(),
            ));
        }
        if self.updates.is_empty() {
            self.solve_symmetric(rhs)?;
            return Ok(Some(0));
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
                return Ok(Some(passes));
            }
        }
        let full = match &assembled {
            Some(reduced) => self.woodbury_full(&parts, rhs, &[], reduced)?,
            None => None,
        };
        match full {
            Some(x) => rhs.clone_from_slice(&x),
            None => self.solve_updated_by_lu(rhs)?,
        }
        Ok((settled && passes == 0).then_some(0))
    }

    /// The symmetric solves `S⁻¹ bⱼ` (one factorisation of `S`) and `S⁻¹ E` on the
    /// equations the updates touch: from the factor's trailing block when the updates lie
    /// among the equations ordered last ([`Self::order_last`]), else one solve per
    /// unit vector of an updated row, on every equation.
    fn woodbury_parts(&mut self, rhs: &[Vec<f64>]) -> Result<WoodburyParts, LinSolveError> {
        let mut z_b = rhs.to_vec();
        self.solve_symmetric(&mut z_b)?;
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
        if !self.solve_symmetric_held(&mut units)? {
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
    /// [`Self::solve_switching_rows`]: the equations that are not kept are NaN.
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
                if !self.solve_symmetric_held(&mut x)? {
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
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{
        assert_matches_dense, assert_switches_once, strip, strip_rhs,
    };
    use super::*;

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
        sys.solve(&mut x).expect("solvable");
        for (xj, bj) in x.iter().zip(&b) {
            assert_matches_dense(&dense, xj, bj);
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
        let b = assert_switches_once(&mut sys, &change, |_| {});
        // a switch that never settles: the assembled solution
        let mut assembled = vec![b.clone()];
        sys.solve(&mut assembled).expect("solvable");
        let mut restless = vec![b.clone()];
        let passes = sys
            .solve_switching_rows(&mut restless, 3, |_| Some(vec![change.clone()]))
            .expect("solvable");
        assert_eq!(passes, None);
        assert_eq!(restless, assembled);
    }
}
