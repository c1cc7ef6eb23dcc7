//! The friction part of an assembly, in one place (the law itself is
//! [`crate::fe::contact::friction`]; the semismooth choice of each node's piece of the law,
//! [`crate::fe::newton::friction_step`]): each active sliding node's friction force into its
//! residual and, with the matrix, its friction row under either regime ([`FrictionRow`]), of
//! which the assembled piece's row goes into the tangent, its own entry into the symmetric values
//! and the rest as a row update ([`crate::fe::linsys`]), so that a switch of the semismooth step
//! changes updates only. Formulas at [`crate::fe::contact::friction`].
//!
//! Under the penalty law a sliding node that lies beyond its stick band also carries a hold row
//! ([`HeldRow`], [`returning_offset`]): the step that the semismooth choice puts on stick holds it
//! at its band's middle instead of on the band's spring continued out to `e*`.

use crate::fe::contact::friction::{Branch, FrictionEval, FrictionLaw, Regime};
use crate::fe::linsys::SparseSystem;
use crate::fe::model::{Model, SlotMap, State};

/// Where the friction of a state goes: the reduced residual, and with the matrix `∂r/∂d`, the
/// tangent and the friction rows that the semismooth step reads.
pub(in crate::fe) struct FrictionSinks<'a> {
    pub(in crate::fe) resid: &'a mut [f64],
    pub(in crate::fe) dresid_dd: &'a mut [f64],
    /// The tangent and the friction rows (none without the matrix).
    pub(in crate::fe) tangent: Option<(&'a mut SparseSystem, &'a mut Vec<FrictionRow>)>,
}

/// Adds the friction of every active sliding contact-face node of `st` (`grad` its internal
/// forces, `normal_rows` the normal-force rows of the element loop, with the matrix) to `sinks`.
/// Returns the law's complementarity residual ([`complementarity`]), 0 under the penalty law.
///
/// Under exact stick a held node's equation is its constraint `k (x − x_anchor) = 0`
/// instead of its equilibrium `c·g = 0` (its friction force is the reaction): the residual
/// is replaced, and in the tangent the row becomes `k e_x` through a row update on the
/// symmetric part, which keeps the node's column (the other equations still depend on its
/// position); the equilibrium row is kept in the [`FrictionRow`] for the semismooth step's
/// decisions and switches ([`HeldRow`]).
pub(in crate::fe) fn add_friction(
    model: &Model,
    st: &State,
    map: &SlotMap,
    law: &FrictionLaw,
    (grad, normal_rows): (&[f64], &[NormalForceRow]),
    sinks: FrictionSinks<'_>,
) -> f64 {
    let FrictionSinks {
        resid,
        dresid_dd,
        mut tangent,
    } = sinks;
    let mut worst = 0.0_f64;
    let iterate = model.iterate_forces(st, grad);
    let forces = (grad, iterate.as_deref());
    for (k, &n) in model.mesh.bottom.iter().enumerate() {
        if !st.active[k] || map[n][0].is_none() {
            continue;
        }
        let f = model.friction_eval(st, k, forces, law);
        let equilibrium = resid[2 * n];
        let offset = st.x[n][0] - st.slip[k].anchor_x;
        let held = f.held(law);
        worst = worst.max(complementarity(law, &f, equilibrium));
        resid[2 * n] = match held {
            true => law.hold_stiffness * offset,
            false => equilibrium + f.force,
        };
        let Some((sys, friction_rows)) = tangent.as_mut() else {
            continue;
        };
        let held_row = match law.exact_stick() {
            true => Some(offset),
            false => returning_offset(law, &f, (offset, st.slip[k].elastic)),
        }
        .map(|offset| HeldRow {
            equilibrium: sys.symmetric_row(2 * n),
            resid: equilibrium,
            resid_dd: dresid_dd[2 * n],
            offset,
            stiffness: law.hold_stiffness,
        });
        let row = friction_row(model, law, map, (k, &f), forces, &normal_rows[k], held_row);
        let assembled = row.law_row(row.at, law.slip_c);
        match held {
            true => sys.add_to_row(2 * n, 2 * n, assembled.own),
            false => {
                sys.values[sys.diag_pos[2 * n]] += assembled.own;
                sys.add_to_row(2 * n, 2 * n, 0.0);
            }
        }
        for (col, v) in assembled.others {
            sys.add_to_row(2 * n, col, v);
        }
        dresid_dd[2 * n] += assembled.force_dd;
        friction_rows.push(row);
    }
    worst
}

/// How far node `f` is from the exact-stick law, as a force (units `G λ`; 0 under the
/// penalty law and on an open node), given its equilibrium residual `c·g`: a held node whose
/// friction force exceeds its threshold by `(|c·g| − w L)⁺`, a sliding one whose slip runs
/// against its force by `k (−φ s)⁺`. Newton converges only where this is within the residual
/// tolerance too, so that a converged state is on the law.
fn complementarity(law: &FrictionLaw, f: &FrictionEval, equilibrium: f64) -> f64 {
    if !law.exact_stick() || f.regime == Regime::Open {
        return 0.0;
    }
    match f.branch {
        Branch::Stick => (equilibrium.abs() - f.w * f.limit).max(0.0),
        slide => law.hold_stiffness * (-slide.sign() * f.trial_slip).max(0.0),
    }
}

/// Under the penalty law, the offset from its band's middle (`e* = 0`) of a sliding node that
/// lies beyond its band, `|e*| > e_c`, whose hold row then returns it there: `x − x_m`, where
/// `x_m = x_anchor − e_n/w` is the position at which its trial elastic slip `e_n + S(x) −
/// S(x_anchor)` vanishes (`|e_n| ≤ e_c`; to within `e_n` times the change of the arc's slope `w`
/// between the node and its anchor; `offset_from_anchor` is `x − x_anchor`). `None` for any
/// other node.
///
/// Why: a sliding node that the semismooth step puts on stick is linearised on the band's spring
/// continued out to `e*` ([`FrictionRow::law_row`]), whose force there is `e*/e_c` times the
/// threshold. The node that has just touched is the common case: its threshold vanishes when it
/// touches, so the predictor lets it slide tens of band widths (and in the Coulomb regime the
/// threshold itself depends on the normal force, which the nearly incompressible layer's
/// pressure error swings), and the spring's step from there is no better a guess (from 80 band
/// widths out it landed at 160); the line search then crawls for many iterations. A stuck node
/// ends inside its band, within `e_c` of the middle, so holding it there lands the step where the
/// spring holds (docs/performance.md, "a node beyond its band returned to it").
fn returning_offset(
    law: &FrictionLaw,
    f: &FrictionEval,
    (offset_from_anchor, elastic): (f64, f64),
) -> Option<f64> {
    let beyond = f.branch != Branch::Stick && f.trial_slip.abs() > law.slip_c;
    beyond.then(|| offset_from_anchor + elastic / f.w)
}

/// What holding a node needs: its equilibrium row (the symmetric tangent's row, own column
/// included), residual `c·g` and `∂(c·g)/∂d`, the offset `x − x_hold` from where it is held and
/// the scale `k` of its hold row. Under exact stick every node has one (`x_hold` its anchor):
/// the semismooth step reads the equilibrium row to linearise a held node's reaction, and
/// replaces it to hold a sliding node. Under the penalty law a sliding node beyond its band has
/// one (`x_hold` its band's middle, [`returning_offset`]), which replaces its row where the
/// step puts it on stick.
#[derive(Clone, Debug, Default)]
pub(in crate::fe) struct HeldRow {
    pub(in crate::fe) equilibrium: Vec<(usize, f64)>,
    pub(in crate::fe) resid: f64,
    pub(in crate::fe) resid_dd: f64,
    pub(in crate::fe) offset: f64,
    pub(in crate::fe) stiffness: f64,
}

impl HeldRow {
    /// The change that holds the node (`row` its equation): `k e_x` replaces the
    /// equilibrium row, `k (x − x_hold)` its residual and 0 its `∂/∂d`.
    fn law_row(&self, row: usize) -> LawRow {
        let own: f64 = self
            .equilibrium
            .iter()
            .filter(|e| e.0 == row)
            .map(|e| e.1)
            .sum();
        LawRow {
            own: self.stiffness - own,
            others: self
                .equilibrium
                .iter()
                .filter(|e| e.0 != row)
                .map(|&(c, v)| (c, -v))
                .collect(),
            force: self.stiffness * self.offset - self.resid,
            force_dd: -self.resid_dd,
        }
    }

    /// The node's equilibrium residual `c·g` after the step `(δq, δd)`, linearised: the
    /// reaction a held node needs is `−` this.
    pub(in crate::fe) fn resid_after(&self, step: &[f64], dd: f64) -> f64 {
        self.resid
            + self.resid_dd * dd
            + self
                .equilibrium
                .iter()
                .map(|&(c, v)| v * step[c])
                .sum::<f64>()
    }
}

/// The normal-force row `(−y_s', 1)ᵀ H[node, ·]` of an active sliding node mapped to slots
/// (column, value), and its derivative with respect to the slab displacement `d`: the
/// linearisation of the normal force `N` on which the Coulomb threshold `μ N` depends.
#[derive(Clone, Debug, Default)]
pub(in crate::fe) struct NormalForceRow {
    pub(in crate::fe) entries: Vec<(usize, f64)>,
    pub(in crate::fe) dd: f64,
}

/// The friction row of active sliding contact-face node `k` under either regime
/// (formulas in [`crate::fe::contact::friction`]): Coulomb from its normal-force row, Orowan from the
/// positions of its face neighbours. `forces`: the internal forces of the residual and, where
/// the state has a pressure iterate, of the iterate: the Coulomb row's own entries are the
/// iterate's (the mixed method's linearisation of `w μ N φ`, whose `δN` condenses onto the
/// residual's normal-force row), its threshold `w L` the residual's
/// ([`crate::fe::contact::friction::NormalForce`]).
fn friction_row(
    model: &Model,
    law: &FrictionLaw,
    map: &SlotMap,
    (k, f): (usize, &FrictionEval),
    (grad, iterate): (&[f64], Option<&[f64]>),
    normal: &NormalForceRow,
    held: Option<HeldRow>,
) -> FrictionRow {
    let n = model.mesh.bottom[k];
    let (_, w_limit) = f.coulomb_own(law, [grad[2 * n], grad[2 * n + 1]]);
    let own_forces = iterate.unwrap_or(grad);
    let (own_phi, own_dphi) = f.coulomb_own(law, [own_forces[2 * n], own_forces[2 * n + 1]]);
    let mut coulomb_phi = vec![(2 * n, own_phi)];
    coulomb_phi.extend(normal.entries.iter().map(|&(c, v)| (c, law.mu * v)));
    let coulomb = RegimeRow {
        per_phi: coulomb_phi,
        w_limit,
        per_dphi: own_dphi,
        per_phi_dd: law.mu * normal.dd,
    };
    let cn = map[n][0].expect("sliding slot");
    let (own_phi, own_dphi) = f.orowan_own(law, cn);
    let mut orowan_phi = vec![(2 * n, own_phi)];
    for (side, m) in [k.wrapping_sub(1), k + 1].into_iter().enumerate() {
        let Some(&nm) = model.mesh.bottom.get(m) else {
            continue;
        };
        for t in 0..2 {
            let Some(cm) = map[nm][t] else { continue };
            orowan_phi.push((2 * nm + t, f.orowan_neighbour(law, side, cm)));
        }
    }
    let orowan = RegimeRow {
        per_phi: orowan_phi,
        w_limit: own_dphi,
        per_dphi: own_dphi,
        per_phi_dd: 0.0,
    };
    f.row((2 * n, k), (coulomb, orowan), held)
}

/// The friction part of one active node's tangent row under one regime, per unit `φ` and
/// `dφ/dx`: `∂(w L φ)/∂q = φ · per_phi + dφ/dx · per_dphi e_x`, `∂(w L φ)/∂d = φ · per_phi_dd`
/// (formulas at [`crate::fe::contact::friction`]). `w_limit = w L` is the regime's
/// threshold times `w` (`μ (g_y − y_s' g_x)` in the Coulomb regime, `w τ_max ℓ` in the
/// Orowan one), and `per_phi` its derivative: the linearisation of `w L`. `per_dphi` is
/// `w L` too, read from the pressure iterate's forces where the state has one
/// ([`friction_row`]).
#[derive(Clone, Debug, Default)]
pub(in crate::fe) struct RegimeRow {
    /// Row entries per unit `φ` (`(column, value)`); the first is the own column.
    pub per_phi: Vec<(usize, f64)>,
    /// `w L`, the residual's.
    pub w_limit: f64,
    /// `w L` at the iterate (the own diagonal entry per unit `dφ/dx`).
    pub per_dphi: f64,
    /// `∂(w L)/∂d`.
    pub per_phi_dd: f64,
}

impl RegimeRow {
    /// `w L` after the step `δq` (linearised).
    fn w_limit_after(&self, step: &[f64]) -> f64 {
        self.w_limit + self.per_phi.iter().map(|&(c, v)| v * step[c]).sum::<f64>()
    }
}

/// The friction part of one node's tangent row, residual and `∂r/∂d` on one piece of the
/// law ([`FrictionRow::law_row`]).
#[derive(Clone, Debug, Default)]
pub(in crate::fe) struct LawRow {
    /// Own diagonal entry.
    pub own: f64,
    /// The other entries (`(column, value)`; a column may repeat).
    pub others: Vec<(usize, f64)>,
    /// `w L φ`.
    pub force: f64,
    /// `∂(w L φ)/∂d`.
    pub force_dd: f64,
}

/// Where on the friction law a node lies: the threshold's regime and the return mapping's
/// branch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(in crate::fe) struct LawPiece {
    /// `Open` (`N ≤ 0`, no friction), `Coulomb` or `Orowan`.
    pub regime: Regime,
    /// Stick, or slip either way.
    pub slip: Branch,
}

/// The friction row of one active node's tangent under either regime and any branch of the
/// return mapping, at the assembled state: what the semismooth Newton step needs to put
/// the node on another piece of the law without reassembling ([`crate::fe::newton::friction_step`]).
/// The residual is `r_x = c·g + w L φ`.
#[derive(Clone, Debug)]
pub(in crate::fe) struct FrictionRow {
    /// Equation (slot) of the node's sliding unknown.
    pub row: usize,
    /// The node's index on the contact face.
    pub face: usize,
    /// What holding the node needs: under exact stick, at its anchor; under the penalty law,
    /// for a sliding node beyond its band, at the band's middle ([`returning_offset`]); else
    /// none.
    pub held: Option<HeldRow>,
    /// Trial elastic slip `e*` at the assembled state.
    pub trial_slip: f64,
    /// `w = √(1 + y_s'²)`.
    pub w: f64,
    /// The piece of the law the state lies on.
    pub at: LawPiece,
    /// The row under the Coulomb regime, `L = μ N`.
    pub coulomb: RegimeRow,
    /// The row under the Orowan regime, `L = τ_max ℓ`.
    pub orowan: RegimeRow,
}

impl FrictionRow {
    /// The row of `regime` (none when open).
    fn regime_row(&self, regime: Regime) -> Option<&RegimeRow> {
        match regime {
            Regime::Open => None,
            Regime::Coulomb => Some(&self.coulomb),
            Regime::Orowan => Some(&self.orowan),
        }
    }

    /// The node's friction on piece `on` of the law at the assembled state (the branch's
    /// affine law at `e*`; nothing when open).
    ///
    /// The force `w L φ` is a product: its linearisation is `φ δ(w L) + w L δφ`. On the stick
    /// branch of a node that lies beyond the band (a sliding node that the semismooth step
    /// puts on stick), the affine `φ = e*/e_c` is far above 1 (60 at AR 0.3 near the edge),
    /// and `φ δ(w L)` would tie the node's row to 60 times its threshold's sensitivity (60 μ
    /// times the normal force's row in the Coulomb regime), though wherever the step lands
    /// on that branch `|φ| ≤ 1`: with the affine factor the Newton step is several element
    /// lengths long and the line search cuts it to a small fraction. The factor of `δ(w L)`
    /// is therefore `φ` clamped to `[−1, 1]`, the value it has at any landing point on the
    /// branch; the force and `δφ` keep the affine law. Inside the band (every assembled row)
    /// nothing changes (docs/performance.md, frictional speed). Where the node has a hold row
    /// (under exact stick; under the penalty law beyond its band, [`returning_offset`]), its
    /// stick branch is that hold instead.
    pub(in crate::fe) fn law_row(&self, on: LawPiece, slip_c: f64) -> LawRow {
        let Some(r) = self.regime_row(on.regime) else {
            return LawRow::default();
        };
        if let (Branch::Stick, Some(held)) = (on.slip, &self.held) {
            return held.law_row(self.row);
        }
        let (phi, dphi) = on.slip.mobilisation(self.trial_slip, slip_c, self.w);
        let phi_landed = phi.clamp(-1.0, 1.0);
        let (own, others) = r.per_phi.split_first().expect("the own column first");
        LawRow {
            own: phi_landed * own.1 + dphi * r.per_dphi,
            others: others.iter().map(|&(c, v)| (c, phi_landed * v)).collect(),
            force: phi * r.w_limit,
            force_dd: phi_landed * r.per_phi_dd,
        }
    }

    /// `w L` of `regime` after the step `δq`, linearised (none when open).
    pub(in crate::fe) fn w_limit_after(&self, regime: Regime, step: &[f64]) -> Option<f64> {
        self.regime_row(regime).map(|r| r.w_limit_after(step))
    }

    /// The regime to assume after the step `δq`: the smaller of the linearised thresholds
    /// `w L` of the Coulomb and Orowan regimes (the rule of [`FrictionLaw::eval`]). An open
    /// node (`N ≤ 0`, released by the active-set loop after the solve) stays open unless
    /// `leave_open` (the penalty law's node beyond its band that can be returned to it,
    /// [`returning_offset`]) and its step gives it a positive threshold, and a node stays in its
    /// regime where the step would open it: switching into and out of the open regime in general
    /// made the choice cost more iterations (docs/performance.md, frictional speed).
    pub(in crate::fe) fn regime_after(&self, step: &[f64], leave_open: bool) -> Regime {
        let coulomb = self.coulomb.w_limit_after(step);
        let orowan = self.orowan.w_limit_after(step);
        match self.at.regime {
            Regime::Open if !leave_open => Regime::Open,
            at if coulomb <= 0.0 => at,
            _ if coulomb <= orowan => Regime::Coulomb,
            _ => Regime::Orowan,
        }
    }

    /// This row without its hold: a sliding node's stick branch is then the band's spring
    /// continued out to `e*` ([`Self::law_row`]).
    pub(in crate::fe) fn without_hold(&self) -> Self {
        Self {
            held: None,
            ..self.clone()
        }
    }

    /// The change of the row's entries, of `r_x` and of `∂r_x/∂d` when piece `to` of the
    /// law replaces the assembled one: `(entries, Δr_x, Δ∂r_x/∂d)`.
    pub(in crate::fe) fn switched(
        &self,
        to: LawPiece,
        slip_c: f64,
    ) -> (Vec<(usize, f64)>, f64, f64) {
        let (new, old) = (self.law_row(to, slip_c), self.law_row(self.at, slip_c));
        let mut entries = vec![(self.row, new.own - old.own)];
        entries.extend(new.others);
        entries.extend(old.others.into_iter().map(|(c, v)| (c, -v)));
        (entries, new.force - old.force, new.force_dd - old.force_dd)
    }
}

impl FrictionEval {
    /// The friction row of contact-face node `face` (slot `row`) from its rows under either
    /// regime and, under exact stick, what holding it needs.
    pub(in crate::fe) fn row(
        &self,
        (row, face): (usize, usize),
        (coulomb, orowan): (RegimeRow, RegimeRow),
        held: Option<HeldRow>,
    ) -> FrictionRow {
        FrictionRow {
            row,
            face,
            held,
            trial_slip: self.trial_slip,
            w: self.w,
            at: LawPiece {
                regime: self.regime,
                slip: self.branch,
            },
            coulomb,
            orowan,
        }
    }

    /// Coulomb regime, own unknown (`g` the node's internal force): the entry
    /// `μ (dφ/dx) (g_y − y_s' g_x) − μ φ y_s'' g_x` as `(per unit φ, per unit dφ/dx)`.
    pub(in crate::fe) fn coulomb_own(&self, law: &FrictionLaw, g: [f64; 2]) -> (f64, f64) {
        let (gx, gy) = (g[0], g[1]);
        (-law.mu * self.c * gx, law.mu * (gy - self.s * gx))
    }

    /// Orowan regime, own unknown with slot vector `slot`: the entry
    /// `τ_max (y_s' y_s''/w ℓ φ + w φ (∂ℓ/∂P)·c + w ℓ dφ/dx)` as
    /// `(per unit φ, per unit dφ/dx)`.
    pub(in crate::fe) fn orowan_own(&self, law: &FrictionLaw, slot: [f64; 2]) -> (f64, f64) {
        let own = self.dell[1][0] * slot[0] + self.dell[1][1] * slot[1];
        (
            law.tau_max * (self.s * self.c / self.w * self.ell + self.w * own),
            law.tau_max * self.w * self.ell,
        )
    }

    /// Orowan regime, slot `slot` of the previous (`side = 0`) or next (`side = 1`)
    /// contact-face neighbour, per unit `φ`: `w τ_max (∂ℓ/∂P_m)·c_m`.
    pub(in crate::fe) fn orowan_neighbour(
        &self,
        law: &FrictionLaw,
        side: usize,
        slot: [f64; 2],
    ) -> f64 {
        let dl = self.dell[2 * side];
        self.w * law.tau_max * (dl[0] * slot[0] + dl[1] * slot[1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sliding node beyond the band switched to stick: only its own diagonal (the stick
    /// spring `w · w L/e_c`) and its force (`w L (e*/e_c − 1)`) change; the threshold's
    /// sensitivity keeps the factor `φ = 1` of any landing point on the branch, and `∂r/∂d`
    /// does not change ([`FrictionRow::law_row`]).
    #[test]
    fn stick_row_beyond_the_band_keeps_the_threshold_factor_of_the_band() {
        let slip_c = 1e-3;
        let regime_row = |scale: f64| RegimeRow {
            per_phi: vec![(4, 2.0 * scale), (5, -3.0 * scale), (7, 0.5 * scale)],
            w_limit: 0.05 * scale,
            per_dphi: 0.05 * scale,
            per_phi_dd: 0.7 * scale,
        };
        let at = LawPiece {
            regime: Regime::Coulomb,
            slip: Branch::SlipForward,
        };
        let row = FrictionRow {
            row: 4,
            face: 0,
            held: None,
            trial_slip: 60.0 * slip_c,
            w: 1.3,
            at,
            coulomb: regime_row(1.0),
            orowan: regime_row(10.0),
        };
        let stick = LawPiece {
            slip: Branch::Stick,
            ..at
        };
        let (entries, d_resid, d_resid_dd) = row.switched(stick, slip_c);
        let column = |c: usize| {
            entries
                .iter()
                .filter(|e| e.0 == c)
                .map(|e| e.1)
                .sum::<f64>()
        };
        let spring = 1.3 * 0.05 / slip_c;
        assert!((column(4) - spring).abs() <= 1e-12 * spring);
        for c in [5, 7] {
            assert!(column(c).abs() <= 1e-15, "column {c}: {}", column(c));
        }
        assert!((d_resid - 0.05 * 59.0).abs() <= 1e-12);
        assert!(d_resid_dd.abs() <= 1e-15);
    }
}
