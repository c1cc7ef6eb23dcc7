//! The frictional Newton step: the solve of the Newton system of the last assembled tangent,
//! with the semismooth choice of each friction node's piece of the law.
//!
//! With friction, the step is a semismooth Newton step of the piecewise-smooth friction
//! law: each node's piece of the law (threshold regime and return-mapping branch) is the
//! one its linearised state after the step lies on, not the one of the current state. A
//! sliding node whose trial slip after the step, `e* + w δx`, leaves its slip branch (lands
//! in the stick band or beyond it, on the other side) is put on the stick branch, and back
//! on its slip branch for good if its stick step lands there ([`BranchChoice::after_step`]);
//! a node whose linearised thresholds cross takes the smaller one, Coulomb or Orowan
//! ([`crate::fe::contact::friction::FrictionRow::regime_after`]). The rows and residuals of the new pieces replace the
//! assembled ones ([`crate::fe::contact::friction::FrictionRow::switched`], exact inside the band: unit test in
//! [`crate::fe::newton::assembly`]; beyond it the threshold's sensitivity keeps the band's factor,
//! [`crate::fe::contact::friction::FrictionRow::law_row`]) and the system is solved again by Woodbury with the same
//! factorisation (`SparseSystem::solve_switching_rows`), until the pieces agree with the
//! step; if they have not within [`MAX_BRANCH_SWITCHES`], the assembled step is taken.
//!
//! A sliding node that lies beyond its band, `|e*| > e_c`, and is put on stick is held at its
//! band's middle for the step instead of linearised on the band's spring continued out to `e*`
//! ([`crate::fe::NewtonOptions::return_into_band`]; the hold row of
//! `crate::fe::newton::friction_rows`); such a node, open at the iterate (`N ≤ 0`), also takes
//! the regime its step's thresholds give it. Where it sticks, the converged state lies inside the band; where it slides, its stick
//! step lands beyond the band again and it returns to its slip branch for good, as before.
//!
//! Under exact stick ([`crate::fe::contact::friction`]) the pieces are chosen the same way, by
//! the primal–dual active-set decision [`Branch::decide`] on the linearised step: a held
//! node's reaction from its equilibrium row, a sliding node's slip `s + w δx`, and the
//! linearised threshold (`decide_exact`). Holding a node replaces its equilibrium row by its
//! constraint row, a row change like any other, so one factorisation settles every switch of a
//! step (within [`MAX_BRANCH_SWITCHES`], as above). The pieces the step was solved on are
//! returned, for the state after the step to hold. Not done, because it made curves fail to
//! converge (AR 0.3, τ_max/E* 0.1, coarse mesh, `c_t` 10 G): keeping a node's piece once it has
//! changed twice or more within one step.
//!
//! Why: the slip tangent is flat, so a node whose solution lies in the narrow stick band is
//! thrown from slip one way to slip the other and back (Newton's cycle on a saturating
//! law), and a node near the Coulomb–Orowan crossover flips between the two thresholds; the
//! line search then crawls through either with steps of 1/32–1/4. Both switches change the
//! path to each equilibrium, not the equilibrium (test
//! `semismooth_branch_choice_changes_the_path_not_the_curve` in `tests/solver/fe_friction.rs`);
//! what they save is in docs/performance.md. Not done, because the switches cycled or cost
//! more iterations: letting stick nodes slide when their step leaves the band, or any node
//! take whatever branch its step lands on; switching into and out of the open regime
//! ([`crate::fe::contact::friction::FrictionRow::regime_after`]); the switch in the predictor's load tangent.

use crate::fe::contact::friction::{Branch, Regime};
use crate::fe::error::{FailCause, StepFail};
use crate::fe::linsys::{LinSolveError, RowChange};
use crate::fe::model::Model;
use crate::fe::newton::assembly::Assembly;
use crate::fe::newton::friction_rows::{FrictionRow, HeldRow, LawPiece};
use crate::fe::SolveOptions;

/// Most changed solves per Newton step in the semismooth choice of the friction branches.
/// The choice settles in one or two changes where it settles; a cap, not tuned: beyond it
/// the assembled step is taken.
const MAX_BRANCH_SWITCHES: usize = 8;

/// Solve the Newton system of iteration `iteration` on the last assembled tangent (`asm`),
/// `rhs[0] = −r` and, if present, `rhs[1] = −∂r/∂d`; `direction` maps the solutions to the
/// step `(δq, δd)` (for the bordered solve, a combination of the two; `δd = 0` otherwise).
/// With friction and [`NewtonOptions::semismooth_friction`], the pieces of the friction law
/// are chosen by where the step lands (module documentation); otherwise the assembled
/// tangent is solved as it is. Returns, under exact stick, each friction node's piece of the
/// law in the step solved (`(face index, branch)`), which the state after the step holds;
/// `None` otherwise. A failed solve ends the Newton solve ([`StepFail::Linear`]).
pub(crate) fn solve_newton_step(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    rhs: &mut [Vec<f64>],
    iteration: usize,
    direction: impl Fn(&[Vec<f64>]) -> (Vec<f64>, f64),
) -> Result<Option<Vec<(usize, Branch)>>, StepFail> {
    let failed = |e: LinSolveError| {
        StepFail::from(FailCause::Linear {
            iteration,
            message: e.to_string(),
        })
    };
    let law = match model.friction {
        Some(law) if opts.newton.semismooth_friction || law.exact_stick() => law,
        _ => return asm.sys.solve(rhs).map(|_| None).map_err(failed),
    };
    let returning = law.exact_stick() || opts.newton.return_into_band;
    let unreturned: Vec<FrictionRow>;
    let rows = match returning {
        true => &asm.friction_rows,
        false => {
            unreturned = asm
                .friction_rows
                .iter()
                .map(FrictionRow::without_hold)
                .collect();
            &unreturned
        }
    };
    let columns = match rhs.len() > 1 {
        true => RightHandSides::ResidualAndLoad,
        false => RightHandSides::Residual,
    };
    let mut choice = PieceChoice {
        exact: law.exact_stick(),
        assumed: rows.iter().map(|r| r.at).collect(),
        branches: rows
            .iter()
            .map(|r| BranchChoice::assembled(r.at.slip))
            .collect(),
        slip_c: law.slip_c,
        c_t: opts.newton.stick_decision_stiffness * law.hold_stiffness,
    };
    let switching = asm
        .sys
        .solve_switching_rows(rhs, MAX_BRANCH_SWITCHES, |solutions| {
            let landed = choice.landed(rows, direction(solutions));
            if landed == choice.assumed {
                return None;
            }
            choice.assumed = landed;
            Some(row_changes(rows, &choice.assumed, law.slip_c, columns))
        });
    let switched = switching.map_err(failed)?;
    if !law.exact_stick() {
        return Ok(None);
    }
    let solved: Vec<LawPiece> = match switched {
        Some(_) => choice.assumed,
        None => rows.iter().map(|r| r.at).collect(),
    };
    Ok(Some(
        rows.iter()
            .zip(solved)
            .map(|(r, piece)| (r.face, piece.slip))
            .collect(),
    ))
}

/// The semismooth choice of the friction nodes' pieces of the law within one Newton step.
struct PieceChoice {
    /// The law is exact stick: the pieces are decided by [`decide_exact`].
    exact: bool,
    /// Each friction row's piece that the last solve assumed.
    assumed: Vec<LawPiece>,
    /// Each row's return-mapping choice under the penalty law (the stick branch of a node
    /// beyond its band being its hold at the band's middle, where it has a hold row).
    branches: Vec<BranchChoice>,
    /// The penalty law's elastic slip `e_c` (units of λ).
    slip_c: f64,
    /// Stiffness of the exact-stick decision (`stick_decision_stiffness · k`).
    c_t: f64,
}

impl PieceChoice {
    /// The piece each row lands on after the step `(δq, δd)` solved on the assumed pieces:
    /// its threshold's regime after the step, and its slip branch by the exact-stick decision
    /// ([`decide_exact`]) or the penalty law's choice ([`BranchChoice::after_step`]).
    fn landed(&mut self, rows: &[FrictionRow], (step, dd): (Vec<f64>, f64)) -> Vec<LawPiece> {
        let mut landed = self.assumed.clone();
        for (i, r) in rows.iter().enumerate() {
            // under the penalty law a hold row is a node beyond its band, which may leave
            // the open regime for the step (module documentation)
            let regime = r.regime_after(&step, !self.exact && r.held.is_some());
            let slip = match r.held.as_ref().filter(|_| self.exact) {
                Some(held) => {
                    decide_exact(r, held, (self.assumed[i], regime), (&step, dd), self.c_t)
                }
                None => {
                    let slip = Branch::of(r.trial_slip + r.w * step[r.row], self.slip_c);
                    self.branches[i] = self.branches[i].after_step(r.at.slip, slip);
                    self.branches[i].assumed
                }
            };
            landed[i] = LawPiece { regime, slip };
        }
        landed
    }
}

/// The right-hand sides a row change updates: the residual's `−r`, with the load column
/// `−∂r/∂d` for the bordered solve, or the load column alone for the load tangent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(in crate::fe) enum RightHandSides {
    Residual,
    ResidualAndLoad,
    Load,
}

/// The row changes that put each friction row whose piece in `pieces` differs from its
/// assembled one on that piece ([`FrictionRow::switched`]), on the right-hand sides `columns`.
pub(in crate::fe) fn row_changes(
    rows: &[FrictionRow],
    pieces: &[LawPiece],
    slip_c: f64,
    columns: RightHandSides,
) -> Vec<RowChange> {
    rows.iter()
        .zip(pieces)
        .filter(|(r, &b)| r.at != b)
        .map(|(r, &b)| {
            let (entries, d_resid, d_resid_dd) = r.switched(b, slip_c);
            let rhs = match columns {
                RightHandSides::Residual => vec![-d_resid],
                RightHandSides::ResidualAndLoad => vec![-d_resid, -d_resid_dd],
                RightHandSides::Load => vec![-d_resid_dd],
            };
            RowChange {
                row: r.row,
                entries,
                rhs,
            }
        })
        .collect()
}

/// The exact-stick piece of node `r` after the step `(δq, δd)` solved with the node on
/// `assumed` (and `regime` its threshold's regime after the step): [`Branch::decide`] on the
/// linearised friction force (a held node's reaction `−(c·g)/w` from its equilibrium row, a
/// sliding node's `φ L`), its linearised slip from the anchor, `s + w δx`, and its linearised
/// threshold. An open node (`N ≤ 0`) has no friction force and no threshold: it slides the way
/// it moves.
fn decide_exact(
    r: &FrictionRow,
    held: &HeldRow,
    (assumed, regime): (LawPiece, Regime),
    (step, dd): (&[f64], f64),
    c_t: f64,
) -> Branch {
    let limit = r.w_limit_after(regime, step).map_or(0.0, |wl| wl / r.w);
    let force = match (assumed.slip, assumed.regime) {
        (_, Regime::Open) => 0.0,
        (Branch::Stick, _) => -held.resid_after(step, dd) / r.w,
        (slide, _) => slide.sign() * limit,
    };
    let slip = r.trial_slip + r.w * step[r.row];
    Branch::decide(force, slip, limit.max(0.0), c_t)
}

/// One node's return-mapping branch in the semismooth choice of a Newton step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct BranchChoice {
    /// The branch assumed for the step.
    assumed: Branch,
    /// The node went back to its assembled slip branch: the choice is final.
    settled: bool,
}

impl BranchChoice {
    /// The start of the choice: the branch of the assembled state.
    fn assembled(at: Branch) -> Self {
        Self {
            assumed: at,
            settled: false,
        }
    }

    /// The choice after a step that lands the node on `landed`, its assembled state being
    /// on `at`:
    /// - a sliding node whose step leaves its slip branch (for the stick band or the other
    ///   way) is put on the stick branch;
    /// - a node so put on the stick branch whose stick step lands back on the slip branch it
    ///   came from returns to that branch for good: neither branch's step is consistent
    ///   (the linearised node sits at the band's edge), and the assembled one is kept;
    /// - a stick node stays stuck (letting it slide when its step leaves the band made the
    ///   choice cycle or cost more iterations).
    ///
    /// Each node thus switches at most twice, so the choice ends. Returning to the slip
    /// branch, rather than keeping the stick branch in the second case, saves tangent
    /// assemblies (docs/performance.md).
    fn after_step(self, at: Branch, landed: Branch) -> Self {
        if self.settled || landed == self.assumed || at == Branch::Stick {
            return self;
        }
        match self.assumed {
            Branch::Stick if landed == at => Self {
                assumed: at,
                settled: true,
            },
            Branch::Stick => self,
            _ => Self::assembled(Branch::Stick),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The semismooth branch choice: a sliding node whose step leaves its slip branch goes
    /// on stick; back to its slip branch for good if its stick step lands there again; a
    /// stick node stays stuck; the choice ends.
    #[test]
    fn branch_choice_switches_a_node_at_most_twice() {
        use Branch::{SlipBackward, SlipForward, Stick};
        let sliding = BranchChoice::assembled(SlipForward);
        assert_eq!(sliding.after_step(SlipForward, SlipForward), sliding);
        let stuck = sliding.after_step(SlipForward, Stick);
        assert_eq!(stuck.assumed, Stick);
        assert_eq!(sliding.after_step(SlipForward, SlipBackward).assumed, Stick);
        assert_eq!(stuck.after_step(SlipForward, SlipBackward), stuck);
        let back = stuck.after_step(SlipForward, SlipForward);
        assert_eq!(back.assumed, SlipForward);
        for landed in [Stick, SlipBackward, SlipForward] {
            assert_eq!(back.after_step(SlipForward, landed), back);
        }
        let sticking = BranchChoice::assembled(Stick);
        for landed in [SlipBackward, SlipForward] {
            assert_eq!(sticking.after_step(Stick, landed), sticking);
        }
    }
}
