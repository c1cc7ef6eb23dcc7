//! The stick zone of a converged frictional state: where the contact face sticks to the
//! indenter, as intervals with their stick–slip fronts placed inside their elements, and the
//! two measures a curve point reports of it.
//!
//! # Which nodes stick
//! A contact-face node sticks when it is active and its committed elastic slip is inside the
//! band of the regularised law, `|e_{n+1}| < e_c` ([`crate::fe::contact::friction`]: a node that
//! slid is committed at `|e| = e_c` exactly); under exact stick (`e_c = 0`), when it is held. A
//! node on a symmetry line (the peak `x = 0`, the
//! valley `x = ½`) has no sliding unknown: it sticks when its face neighbour does, so that a stick
//! zone reaching the line continues in its mirror image.
//!
//! # Where a front lies
//! Inside a stick zone the mobilisation `r = |e|/e_c` is the traction over the slip threshold,
//! `|τ|/τ_sl` (under exact stick that ratio itself, the node's friction force over its threshold,
//! `|T|/L`); it reaches 1 at a stick–slip front, where in the continuum it does so like
//! `1 − r ∝ √(distance)` (the square-root behaviour of the Cattaneo–Mindlin traction at the edge
//! of its stick zone). So `(1 − r)²` is linear in `x` near the front: it is extrapolated to zero
//! from the zone's last two nodes and the front placed there, clipped to the element between the
//! last stick node and the first slip node (the element's midpoint when the zone has a single
//! node or `(1 − r)²` does not fall toward the front). A zone is cut to the contact patches: the
//! face beyond a contact edge neither sticks nor slips.

use crate::fe::contact::patches::runs;
use crate::fe::model::{Model, State};

/// The stick zone of a state, measured as a curve point reports it (units of λ).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct StickZone {
    /// Total stick length over λ of the half wavelength's stick intervals and their mirror
    /// images, `2 Σ (end − start)` (the stick counterpart of the contact fraction; 0 without
    /// friction).
    pub(crate) fraction: f64,
    /// Half-width of the stick interval at the peak, `x` of its front (0 when the peak
    /// slips, when no contact reaches it, or without friction).
    pub(crate) central_half_width: f64,
}

/// Per contact-face node of `st` (face order), `grad` its internal forces: whether it sticks
/// (module documentation); all `false` without friction.
pub(crate) fn stick_nodes(model: &Model, st: &State, grad: &[f64]) -> Vec<bool> {
    let n = model.mesh.bottom.len();
    let Some(law) = model.friction else {
        return vec![false; n];
    };
    let mobilisation = mobilisation(model, st, grad);
    let mut stick: Vec<bool> = (0..n)
        .map(|k| match law.exact_stick() {
            true => st.active[k] && mobilisation[k] < 1.0,
            false => st.active[k] && st.slip[k].elastic.abs() < law.slip_c,
        })
        .collect();
    if n >= 2 {
        stick[0] = st.active[0] && stick[1];
        stick[n - 1] = st.active[n - 1] && stick[n - 2];
    }
    stick
}

/// The stick intervals of `st` in `[0, ½]` (current `x`, in order), each from front to front,
/// before they are cut to the contact patches ([`cut_to_patches`]); `grad` the state's internal
/// forces.
pub(crate) fn stick_runs(model: &Model, st: &State, grad: &[f64]) -> Vec<[f64; 2]> {
    if model.friction.is_none() {
        return Vec::new();
    }
    let stick = stick_nodes(model, st, grad);
    let b = &model.mesh.bottom;
    let last = b.len() - 1;
    let x = |k: usize| st.x[b[k]][0];
    let mobilisation = mobilisation(model, st, grad);
    let gap = |k: usize| (1.0 - mobilisation[k]).powi(2);
    // the front beyond stick node `j` toward its slip neighbour `out`, from `j` and the stick
    // node `inner` before it (if any)
    let front = |j: usize, out: usize, inner: Option<usize>| {
        let (xj, xo) = (x(j), x(out));
        let mid = 0.5 * (xj + xo);
        let Some(i) = inner else { return mid };
        let (qi, qj) = (gap(i), gap(j));
        if qi <= qj {
            return mid;
        }
        let reach = qj * (xj - x(i)) / (qi - qj);
        let at = xj + reach;
        if xo > xj {
            at.clamp(xj, xo)
        } else {
            at.clamp(xo, xj)
        }
    };
    let mut intervals = Vec::new();
    for [k0, k1] in runs(&stick) {
        let start = if k0 == 0 {
            x(0)
        } else {
            front(k0, k0 - 1, (k0 < k1).then_some(k0 + 1))
        };
        let end = if k1 == last {
            x(last)
        } else {
            front(k1, k1 + 1, (k0 < k1).then_some(k1 - 1))
        };
        intervals.push([start, end]);
    }
    intervals
}

/// Under exact stick, a friction force within this fraction of the largest threshold on the
/// face of its own threshold is at the threshold, and so is a threshold this small: such a node
/// counts as sliding. At the threshold a held node and a node sliding by nothing are the same
/// state to the Newton tolerance of the forces (10⁻¹⁰ of the largest nodal force), and the Newton
/// path decides which label it carries; the node that has just touched at an edge event carries
/// a normal force at that tolerance, and its `|T|/L` is a ratio of two round-off values. Far above
/// that tolerance, far below the margin of any node that holds load.
const AT_THRESHOLD: f64 = 1e-6;

/// Per contact-face node of a frictional `st` (`grad` its internal forces), the mobilisation
/// `r ∈ [0, 1]`: the committed elastic slip over the band, `|e|/e_c`, under the penalty law;
/// the friction force over the threshold, `|T|/L`, under exact stick, 1 at the threshold
/// ([`AT_THRESHOLD`]).
fn mobilisation(model: &Model, st: &State, grad: &[f64]) -> Vec<f64> {
    let law = model.friction.expect("a frictional model");
    match law.exact_stick() {
        true => {
            let limits = model.friction_thresholds(st, grad);
            let margin = AT_THRESHOLD * limits.iter().fold(0.0_f64, |m, &l| m.max(l));
            let forces = model.tangential_forces(st, grad);
            forces
                .iter()
                .zip(&limits)
                .map(|(t, &l)| match l - t.abs() > margin {
                    true => t.abs() / l,
                    false => 1.0,
                })
                .collect()
        }
        false => st
            .slip
            .iter()
            .map(|h| (h.elastic.abs() / law.slip_c).min(1.0))
            .collect(),
    }
}

/// The stick `runs` ([`stick_runs`]) cut to the contact `patches` (`[start, end]` each, in
/// order): the stick intervals.
pub(crate) fn cut_to_patches(runs: &[[f64; 2]], patches: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut intervals = Vec::new();
    for &[start, end] in runs {
        for p in patches {
            let (s, e) = (start.max(p[0]), end.min(p[1]));
            if e > s {
                intervals.push([s, e]);
            }
        }
    }
    intervals
}

/// The stick zone of the stick `runs` ([`stick_runs`]) cut to the contact `patches`
/// ([`StickZone`]); `peak`, the current `x` of the peak node.
pub(crate) fn stick_zone(runs: &[[f64; 2]], patches: &[[f64; 2]], peak: f64) -> StickZone {
    let intervals = cut_to_patches(runs, patches);
    StickZone {
        fraction: 2.0 * intervals.iter().map(|i| i[1] - i[0]).sum::<f64>(),
        central_half_width: intervals
            .first()
            .filter(|i| i[0] <= peak)
            .map_or(0.0, |i| i[1]),
    }
}
