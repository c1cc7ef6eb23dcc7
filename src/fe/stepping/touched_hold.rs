//! The contact-face nodes that have just touched, held where they touched in the load tangent.
//!
//! A node touches at its event with no normal force, so under the penalty friction law its slip
//! threshold `L = min(μN, τ_max ℓ)` and its stick spring `L/e_c` vanish there, and the consistent
//! load tangent lets it slide freely. Along the path its normal force grows from zero, and with it
//! the spring, within one band width `e_c` of slip: where the node sticks, a predictor along the
//! free tangent puts it band widths beyond its anchor (8.4 `e_c` at AR 0.18, τ_max 0.1 MPa, mesh 96,
//! where it converges at 0.4 `e_c`) and in tension, and the event's first Newton step only brings it
//! back (docs/performance.md, "the node that has just touched"). [`TouchedHold`] holds each such
//! node where it touched in the load path instead: the rate and the curvature of its sliding
//! unknown are zero, by the reaction that holds it, as far as friction can hold it (the
//! reaction's rate within the threshold's, `μ N'`); a node that needs more slides with that
//! reaction, and at μ → 0 the tangent is the frictionless one. This chooses the predictor, not
//! the law: the converged states are the same.

use faer::linalg::solvers::Solve;
use faer::Mat;
use serde::{Deserialize, Serialize};

use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::Assembly;

/// How the load tangent treats the contact-face nodes that have just touched (under the penalty
/// friction law; exact stick holds them by their own rows, and without friction nothing slides).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TouchedNodes {
    /// Held where they touched ([`TouchedHold`]).
    #[default]
    Held,
    /// Free to slide, as the consistent tangent has them (no threshold at zero normal force).
    Free,
}

/// The committed elastic slip, over the band width `e_c`, below which a node in contact has not
/// moved since it was anchored: the node that touched at this state (its event's solve leaves it
/// where the touchdown put it). A round-off bound; a stuck node elsewhere on the face carries a
/// slip of order `e_c`.
const TOUCHED_SLIP_OVER_BAND: f64 = 1e-9;

/// The sliding unknowns of the nodes that have just touched and the tangent's response to a unit
/// force on each, `K z_i = e_i`, with which [`TouchedHold::hold_rate`] removes their motion from a
/// direction of the load path. The responses are solved with the load tangent's own right-hand
/// side, on its factorisation: [`TouchedHold::at`] names the slots, [`TouchedHold::unit_loads`]
/// the right-hand sides, [`TouchedHold::with_responses`] takes their solutions.
pub(crate) struct TouchedHold {
    /// The held nodes: contact-face index and slot (sliding unknown).
    nodes: Vec<(usize, usize)>,
    /// `z_i = K⁻¹ e_i` per held slot.
    responses: Vec<Vec<f64>>,
    /// Per node, its reaction where friction cannot hold it and it slides
    /// ([`TouchedHold::limited_by_friction`]); `None` where it is held.
    slides: Vec<Option<f64>>,
}

impl TouchedHold {
    /// The nodes of `st` that have just touched, to be held as `touched` says: none without the
    /// penalty friction law or with [`TouchedNodes::Free`].
    pub(crate) fn at(model: &Model, st: &State, touched: TouchedNodes) -> Self {
        let nodes = match (model.friction, touched) {
            (Some(law), TouchedNodes::Held) if !law.exact_stick() => {
                just_touched(model, st, law.slip_c)
            }
            _ => Vec::new(),
        };
        Self {
            slides: vec![None; nodes.len()],
            nodes,
            responses: Vec::new(),
        }
    }

    /// No node is held.
    pub(crate) fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The unit force `e_i` on each held slot, as right-hand sides of length `dofs`.
    pub(crate) fn unit_loads(&self, dofs: usize) -> impl Iterator<Item = Vec<f64>> + '_ {
        self.nodes.iter().map(move |&(_, s)| {
            let mut e = vec![0.0; dofs];
            e[s] = 1.0;
            e
        })
    }

    /// The hold with `K⁻¹` of its [`Self::unit_loads`], in their order.
    pub(crate) fn with_responses(self, responses: Vec<Vec<f64>>) -> Self {
        debug_assert_eq!(responses.len(), self.nodes.len());
        Self { responses, ..self }
    }

    /// The hold limited by friction along the load path `rate` (the load tangent with every
    /// node free): a held node's reaction, the friction force rate `T'` that holds it, may not
    /// exceed its threshold's rate `μ N'` (the Coulomb piece, where a node at zero normal force
    /// is), `N'` the normal force's rate along the held path (a difference quotient over `eps` of
    /// the slab displacement). A node whose hold needs more slides instead, its reaction the
    /// threshold's rate (none where `N' ≤ 0`: it leaves contact), and the others are held again,
    /// until every held node holds. `None` where a state is inverted.
    pub(crate) fn limited_by_friction(
        mut self,
        model: &Model,
        asm: &mut Assembly,
        (st, rate): (&State, &[f64]),
        eps: f64,
    ) -> Option<Self> {
        let Some(law) = model.friction.filter(|_| !self.nodes.is_empty()) else {
            return Some(self);
        };
        let map = model.slot_map(st);
        let normal_at = |asm: &mut Assembly, at: &State| -> Option<Vec<f64>> {
            let f = asm.assemble(model, at, false)?;
            Some(model.normal_forces(at, &f.grad))
        };
        let before = normal_at(asm, st)?;
        loop {
            let mut path = rate.to_vec();
            self.slide(&mut path);
            let reactions = self.remove_held(&mut path);
            let after = normal_at(asm, &model.along(st, &path, eps))?;
            let mut slides = false;
            for (i, &(k, slot)) in self.nodes.iter().enumerate() {
                let w = map[slot / 2][0].map_or(1.0, |[a, b]| a.hypot(b));
                let limit = law.mu * ((after[k] - before[k]) / eps).max(0.0) * w;
                if self.slides[i].is_none() && reactions[i].abs() > limit {
                    self.slides[i] = Some(limit.copysign(reactions[i]));
                    slides = true;
                }
            }
            if !slides {
                return Some(self);
            }
        }
    }

    /// The load path's rate `v` with the nodes held: each sliding node's reaction applied
    /// ([`Self::slide`]), then the held nodes' motion removed ([`Self::remove_held`]).
    pub(crate) fn hold_rate(&self, v: &mut [f64]) {
        self.slide(v);
        self.remove_held(v);
    }

    /// The load path's curvature `w` with the held nodes held ([`Self::remove_held`]); a sliding
    /// node's threshold varies along the path by what its normal force does, which the rate's
    /// reaction has taken at first order only, so its curvature is left free.
    pub(crate) fn hold_curvature(&self, w: &mut [f64]) {
        self.remove_held(w);
    }

    /// `v − Σ c_i z_i` over the sliding nodes, `c_i` the reaction each slides with.
    fn slide(&self, v: &mut [f64]) {
        for (z, c) in self.responses.iter().zip(&self.slides) {
            if let Some(c) = c {
                subtract(v, *c, z);
            }
        }
    }

    /// `v` with the held nodes' components removed by the reactions that hold them, `v − Z c`
    /// with `Z_S c = v_S` over the held slots `S`. Returns every node's reaction (a force on its
    /// slot's direction per unit of what `v` is the rate of; a sliding node's, its own).
    fn remove_held(&self, v: &mut [f64]) -> Vec<f64> {
        let mut reactions: Vec<f64> = self.slides.iter().map(|s| s.unwrap_or(0.0)).collect();
        let held: Vec<usize> = (0..self.nodes.len())
            .filter(|&i| self.slides[i].is_none())
            .collect();
        let m = held.len();
        if m == 0 {
            return reactions;
        }
        let slot = |i: usize| self.nodes[held[i]].1;
        let at_slots = Mat::from_fn(m, m, |i, j| self.responses[held[j]][slot(i)]);
        let rhs = Mat::from_fn(m, 1, |i, _| v[slot(i)]);
        let c = at_slots.partial_piv_lu().solve(&rhs);
        for (j, &i) in held.iter().enumerate() {
            reactions[i] = c[(j, 0)];
            subtract(v, reactions[i], &self.responses[i]);
        }
        reactions
    }
}

/// `v − c z`.
fn subtract(v: &mut [f64], c: f64, z: &[f64]) {
    for (vi, zi) in v.iter_mut().zip(z) {
        *vi -= c * zi;
    }
}

/// The contact-face nodes of `st` that have not moved since they were anchored (committed elastic
/// slip below [`TOUCHED_SLIP_OVER_BAND`] band widths `slip_c`), with their sliding unknowns; a node
/// on a symmetry line has none.
fn just_touched(model: &Model, st: &State, slip_c: f64) -> Vec<(usize, usize)> {
    let map = model.slot_map(st);
    (model.mesh.bottom.iter().enumerate())
        .filter(|&(k, &n)| {
            st.active[k]
                && map[n][0].is_some()
                && st.slip[k].elastic.abs() <= TOUCHED_SLIP_OVER_BAND * slip_c
        })
        .map(|(k, &n)| (k, 2 * n))
        .collect()
}
