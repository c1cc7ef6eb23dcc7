//! An unloading step's prediction through its slip front. As the slab retracts, the zone where
//! the face slides backward grows inward from the contact edges, about a node per step: a node
//! stuck at the step's start, near its band's edge, ends the step sliding tens of band widths.
//! The load tangent holds it stuck, so the prediction moves it by little, and Newton's first
//! steps from there overshoot its slip and crawl (docs/performance.md, "where a regular unloading
//! step's iterations go"). Here the step is predicted along a piecewise-linear path instead:
//! along the tangent until the first stuck node reaches its band's edge, that node put on its slip
//! branch (a row change, solved by Woodbury with the tangent's own factorisation), on along the
//! new tangent, and so on to the step's end.
//!
//! Only nodes under the Orowan threshold `τ_max ℓ` switch: it does not move along the path, so a
//! slip row linearised at the step's start stays exact along it; the Coulomb threshold `μ N`
//! moves with the normal force, and switching Coulomb nodes made the prediction worse (16 loops of
//! mesh 48 at μ 1: 5.457 Newton iterations per unloading row against 5.225 without any switch, and
//! 4.951 with the Orowan nodes alone; docs/performance.md, "the slip front followed").

use serde::{Deserialize, Serialize};

use crate::fe::contact::friction::{Branch, Regime};
use crate::fe::model::Model;
use crate::fe::newton::assembly::Assembly;
use crate::fe::newton::friction_rows::{FrictionRow, LawPiece};
use crate::fe::newton::friction_step::{row_changes, RightHandSides};

/// How an unloading step's prediction treats the stuck nodes that start to slide in it (under the
/// penalty friction law; loading steps and exact stick take the load tangent as it is).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SlipFront {
    /// Followed through their switches to slip ([`piecewise_rate`]).
    #[default]
    Followed,
    /// Held stuck, as the load tangent has them: the curved Taylor prediction.
    Held,
}

/// Most nodes one prediction switches: a cap, not tuned (a step's slip front moves by one or
/// two nodes).
const MAX_SWITCHES: usize = 12;

/// A stuck node reaching its band's edge along the path.
struct Crossing {
    /// Its index among the friction rows.
    index: usize,
    /// The fraction of the remaining step at which it reaches the edge.
    fraction: f64,
    /// The slip branch it goes on.
    branch: Branch,
}

/// `(q(d + dd) − q(d)) / dd` along the piecewise-linear path through the slip front (module
/// documentation), from the tangent `rate` (`K rate = load_column`, `load_column = −∂r/∂d`) of
/// the state whose tangent `asm` holds factored; `None` when no node switches (the tangent's own
/// prediction then stands), without penalty friction, or where a solve fails.
pub(crate) fn piecewise_rate(
    model: &Model,
    asm: &mut Assembly,
    load_column: &[f64],
    rate: &[f64],
    dd: f64,
) -> Option<Vec<f64>> {
    let law = model.friction.filter(|law| !law.exact_stick())?;
    let rows = asm.friction_rows.clone();
    let mut pieces: Vec<LawPiece> = rows.iter().map(|r| r.at).collect();
    let mut moved = vec![0.0; rate.len()];
    let mut rate = rate.to_vec();
    let mut left = 1.0;
    let mut switches = 0;
    while switches < MAX_SWITCHES {
        let Some(next) = first_to_slide(&rows, &pieces, (&moved, &rate), left * dd, law.slip_c)
        else {
            break;
        };
        advance(&mut moved, &rate, next.fraction * left * dd);
        left *= 1.0 - next.fraction;
        pieces[next.index].slip = next.branch;
        rate = solved_on(asm, &rows, &pieces, load_column, law.slip_c)?;
        switches += 1;
    }
    if switches == 0 {
        return None;
    }
    advance(&mut moved, &rate, left * dd);
    Some(moved.iter().map(|m| m / dd).collect())
}

/// The stuck Orowan node that reaches its band's edge first over `step` (units of λ) along
/// `rate`, from positions `moved` past the step's start.
fn first_to_slide(
    rows: &[FrictionRow],
    pieces: &[LawPiece],
    (moved, rate): (&[f64], &[f64]),
    step: f64,
    slip_c: f64,
) -> Option<Crossing> {
    let stuck = |i: &usize| pieces[*i].slip == Branch::Stick && pieces[*i].regime == Regime::Orowan;
    let crossing = |i: usize| {
        let r = &rows[i];
        let at = r.trial_slip + r.w * moved[r.row];
        let change = r.w * rate[r.row] * step;
        let end = at + change;
        (end.abs() > slip_c && change != 0.0).then(|| Crossing {
            index: i,
            fraction: ((slip_c * end.signum() - at) / change).clamp(0.0, 1.0),
            branch: match end > 0.0 {
                true => Branch::SlipForward,
                false => Branch::SlipBackward,
            },
        })
    };
    (0..rows.len())
        .filter(stuck)
        .filter_map(crossing)
        .min_by(|a, b| a.fraction.total_cmp(&b.fraction))
}

/// `moved += rate · step`.
fn advance(moved: &mut [f64], rate: &[f64], step: f64) {
    for (m, v) in moved.iter_mut().zip(rate) {
        *m += v * step;
    }
}

/// The tangent's rate with each friction row on its piece in `pieces` (those that differ from
/// the assembled one changed, [`row_changes`]).
fn solved_on(
    asm: &mut Assembly,
    rows: &[FrictionRow],
    pieces: &[LawPiece],
    load_column: &[f64],
    slip_c: f64,
) -> Option<Vec<f64>> {
    let mut changes = Some(row_changes(rows, pieces, slip_c, RightHandSides::Load));
    let mut rhs = vec![load_column.to_vec()];
    let switched = asm
        .sys
        .solve_switching_rows(&mut rhs, 1, |_| changes.take());
    let [rate] = <[Vec<f64>; 1]>::try_from(rhs).ok()?;
    matches!(switched, Ok(Some(_))).then_some(rate)
}
