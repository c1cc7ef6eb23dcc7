//! The edge rule: where the contact edge lies in a converged state.
//!
//! At an edge event on node `k` the discrete solution has zero gap up to `x_k`, but its
//! nodal forces are the work-equivalent integrals `∫ p N_i dx`, so zero force on node `k`
//! means the pressure vanishes beyond `x_{k−1}`: the edge lies in `[x_{k−1}, x_k]` (current
//! positions). The default rule ([`EdgeRule`], [`edge_position`]) puts it at a fraction of
//! that interval that depends on the shape of the element ([`EDGE_FRACTION_BY_ASPECT`]),
//! calibrated on Westergaard's solution. The alternatives, a fixed fraction
//! ([`EdgeRule::Fraction`]) and gap fits through the next free nodes
//! ([`EdgeRule::GapPower`], [`EdgeRule::PeriodicGap`]), and how each converges, are
//! compared in docs/replication.md R7. Between
//! events (unloading, a pressure target) the edge node is the one after the last loaded
//! node ([`loaded_edge_node`]).

use serde::{Deserialize, Serialize};

use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::Forces;
use crate::fe::newton::residual_tolerance;
use crate::fe::SolveOptions;

/// Rule placing the contact edge `a` inside `[x_{k−1}, x_k]` (current positions) at an
/// edge event on node `k`: node `k` touches with zero force, node `k − 1` carries force
/// (see the [module documentation](self)).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum EdgeRule {
    /// `a = x_{k−1} + φ (x_k − x_{k−1})` with a fixed fraction `φ`. Near the edge the
    /// discrete solution is self-similar at the scale of the element (the far field is
    /// the `√(a − x)` pressure / `(x − a)^{3/2}` gap of the continuum, the mesh is locally
    /// uniform), so the edge of the continuum solution sits at a mesh-independent
    /// fraction `φ` of the last loaded element; any rule that uses nodal values at a
    /// distance `O(h)` from the edge errs by `O(h)` unless it reproduces that fraction.
    /// [`DISCRETE_EDGE_FRACTION`] is its calibration on the default mesh.
    Fraction(f64),
    /// `a = x_{k−1} + φ(r) (x_k − x_{k−1})` with `φ(r) = c₀ + c₁ r + c₂ r²` (clamped to
    /// `[0, 1]`), `r` the current height over width of the last loaded element: the mean
    /// height of its two vertical edges at the face over `x_k − x_{k−1}`. The self-similar
    /// edge solution of [`EdgeRule::Fraction`] lives at the scale of the element, so its
    /// fraction depends on the element's shape, which the grading and the stretch of the
    /// surface vary along the face (from r ≈ 1.5 under the peak to r ≈ 0.6 near the valley,
    /// less at AR 0.3). The default, with [`EDGE_FRACTION_BY_ASPECT`].
    AspectFraction([f64; 3]),
    /// Fit of the periodic Westergaard gap shape `g ∝ G(x; a)` through the vertical gaps
    /// of nodes `k + 1`, `k + 2` (exact in the linear limit, `(x − a)^{3/2}` near the
    /// edge). At finite strain the gap is not of that shape, and the rule errs where the
    /// aspect ratio is large (docs/replication.md R7, the contact edge).
    PeriodicGap,
    /// Fit of `g ∝ (x − a)^{3/2}` through the vertical gaps of nodes `k + 1`, `k + 2`.
    GapPower,
}

/// The discrete edge fraction `φ` of [`EdgeRule::Fraction`] for the Q1/P0 element with
/// the default [`crate::fe::Grading`], calibrated on the exact solution: with linear
/// kinematics and a small aspect ratio, the `a` that Westergaard's
/// `p̄/E* = π (Δ/λ) sin²(π a/λ)` gives for the computed `p̄`, as a fraction of
/// `[x_{k−1}, x_k]`, on three meshes (`PHI_CALIB=1 cargo run --release --example
/// fe_study`; the calibration and its check at finite strain are in docs/replication.md
/// R7). The fraction the gap-fit rules use for the edges their fits do not cover.
pub const DISCRETE_EDGE_FRACTION: f64 = 0.64;

/// The coefficients `[c₀, c₁, c₂]` of [`EdgeRule::AspectFraction`]'s `φ(r)`, calibrated on the
/// exact solution as [`DISCRETE_EDGE_FRACTION`] is (linear kinematics, AR = 0.01, the `a` that
/// Westergaard gives for the computed `p̄`): a least-squares quadratic in `r` through the
/// events with a/λ ∈ [0.05, 0.30] and `r ≤ 1.7` of the 64 × 32 mesh with the gradings
/// (peak ratio, first layer) ∈ {4, 16} × {0.25, 0.5, 1} and (2, 2), whose last loaded
/// elements span `r` ≈ 0.2–1.7: 195 events, residuals −0.007…+0.012 (`ASPECT_CALIB=1 cargo run
/// --release --example fe_study`; docs/replication.md R7).
pub const EDGE_FRACTION_BY_ASPECT: [f64; 3] = [0.6099, 0.0009, 0.0266];

impl Default for EdgeRule {
    fn default() -> Self {
        EdgeRule::AspectFraction(EDGE_FRACTION_BY_ASPECT)
    }
}

impl EdgeRule {
    /// The fraction of the element between the loaded face node `loaded` and its free
    /// neighbour `free` (current positions) at which the rule puts an edge, measured from the
    /// loaded node. The gap-fit rules give [`DISCRETE_EDGE_FRACTION`]: their fits cover only the
    /// right edge of a patch at the peak ([`edge_position`]).
    pub(crate) fn fraction(self, model: &Model, st: &State, loaded: usize, free: usize) -> f64 {
        match self {
            EdgeRule::Fraction(phi) => phi,
            EdgeRule::AspectFraction(c) => {
                let r = element_aspect(model, st, loaded, free);
                (c[0] + c[1] * r + c[2] * r * r).clamp(0.0, 1.0)
            }
            EdgeRule::GapPower | EdgeRule::PeriodicGap => DISCRETE_EDGE_FRACTION,
        }
    }
}

/// Current height over width of the surface element between face nodes `i` and `j`
/// (neighbours): the mean of its two vertical edges' heights (face node to the node above)
/// over `|x_j − x_i|`; 0 for a degenerate width.
pub(crate) fn element_aspect(model: &Model, st: &State, i: usize, j: usize) -> f64 {
    let mesh = &model.mesh;
    let height = |c: usize| st.x[mesh.above_bottom[c]][1] - st.x[mesh.bottom[c]][1];
    let width = (st.x[mesh.bottom[j]][0] - st.x[mesh.bottom[i]][0]).abs();
    if width > 0.0 {
        0.5 * (height(i) + height(j)) / width
    } else {
        0.0
    }
}

/// Bisections of [`invert_decreasing`]: `2⁻⁶⁰` of an interval shorter than λ/2
/// (< 4.4·10⁻¹⁹ λ) is below one ulp of any `x ≥ 2⁻⁹ λ`: the bisection ends at round-off.
const GAP_FIT_BISECTIONS: usize = 60;

/// The vertical contact multiplier `λ` above which a face node counts as loaded, given the
/// multipliers `lam` of every face node and the `force_scale` of the state's assembly
/// ([`Forces::force_scale`]): `multiplier_rtol` times the largest multiplier, and no less than
/// the Newton tolerance the state was converged to, below which a force is indistinguishable
/// from zero (at zero load every multiplier is; unloading through the displacement of a loading
/// edge event leaves that event's node with a multiplier of the order of the tolerance).
pub(crate) fn loaded_threshold(
    model: &Model,
    lam: &[f64],
    opts: &SolveOptions,
    force_scale: f64,
) -> f64 {
    let scale = lam.iter().fold(0.0_f64, |m, l| m.max(l.abs()));
    let tolerance = residual_tolerance(model, opts, opts.newton.residual_rtol, force_scale);
    (opts.contact.multiplier_rtol * scale).max(tolerance)
}

/// The node that plays the edge event's target in a converged state that is not an event (the
/// unloading branch), with internal forces `f`: the node after the last loaded one
/// ([`loaded_threshold`]), so that the edge lies in the last loaded element as at an event. At
/// an event state it is the event's node whether or not the solve left that node, touching with
/// zero force, active; the peak node 0 when no node carries load; at most the valley node.
pub(crate) fn loaded_edge_node(
    model: &Model,
    st: &State,
    f: &Forces,
    opts: &SolveOptions,
) -> usize {
    let lam = model.multipliers(st, &f.grad);
    let threshold = loaded_threshold(model, &lam, opts, f.force_scale);
    match (0..lam.len()).rev().find(|&i| lam[i] > threshold) {
        Some(i) => (i + 1).min(lam.len() - 1),
        None => 0,
    }
}

/// Contact half-width at an edge event on node `k` (rule documented at [`EdgeRule`]; the
/// gap fits fall back to the midpoint of `[x_{k−1}, x_k]` unless the gaps of nodes
/// `k + 1`, `k + 2` are positive and increasing).
pub(crate) fn edge_position(model: &Model, st: &State, k: usize, rule: EdgeRule) -> f64 {
    let b = &model.mesh.bottom;
    let x = |i: usize| st.x[b[i]][0];
    let lo = x(k.saturating_sub(1));
    let hi = x(k);
    if let EdgeRule::Fraction(_) | EdgeRule::AspectFraction(_) = rule {
        return lo + rule.fraction(model, st, k.saturating_sub(1), k) * (hi - lo);
    }
    if k + 2 < b.len() {
        let gaps = model.gaps(st);
        let (g1, g2) = (gaps[k + 1], gaps[k + 2]);
        if g1 > 0.0 && g2 > g1 {
            return match rule {
                EdgeRule::GapPower => {
                    let r = (g1 / g2).powf(2.0 / 3.0);
                    ((x(k + 1) - r * x(k + 2)) / (1.0 - r)).clamp(lo, hi)
                }
                EdgeRule::PeriodicGap => periodic_gap_fit(x(k + 1), x(k + 2), g1 / g2, lo, hi),
                EdgeRule::Fraction(_) | EdgeRule::AspectFraction(_) => {
                    unreachable!("handled above")
                }
            };
        }
    }
    0.5 * (lo + hi)
}

/// Gap shape of the periodic (Westergaard) contact beyond the edge `a`, up to a
/// constant factor (units of λ, `a < x ≤ ½`):
///
/// ```text
/// g'(x) ∝ cos πx √(sin²πx − sin²πa)
/// G(x; a) = ½ [ s √(s² − c²) − c² ln((s + √(s² − c²))/c) ],  s = sin πx, c = sin πa
/// ```
///
/// (`∝ (s − c)^{3/2}` near the edge). Exact in the linear limit.
fn periodic_gap_shape(x: f64, a: f64) -> f64 {
    let pi = std::f64::consts::PI;
    let (s, c) = ((pi * x).sin(), (pi * a).sin());
    if s <= c {
        return 0.0;
    }
    if c <= 0.0 {
        return 0.5 * s * s;
    }
    let r = (s * s - c * c).sqrt();
    0.5 * (s * r - c * c * ((s + r) / c).ln())
}

/// The `a ∈ [lo, hi]` with `G(x₁; a)/G(x₂; a) = ratio` ([`periodic_gap_shape`]; the
/// ratio decreases with `a`), clamped to the interval ([`invert_decreasing`]).
fn periodic_gap_fit(x1: f64, x2: f64, ratio: f64, lo: f64, hi: f64) -> f64 {
    let r = |a: f64| periodic_gap_shape(x1, a) / periodic_gap_shape(x2, a);
    invert_decreasing(r, ratio, lo, hi)
}

/// The `v ∈ [lo, hi]` at which the decreasing function `r` takes the value `target`, by
/// bisection ([`GAP_FIT_BISECTIONS`]); `lo` where `r(lo) ≤ target`, `hi` where `r(hi) ≥ target`.
/// The gap fits of the edges invert a ratio of gap shapes with it.
pub(crate) fn invert_decreasing(r: impl Fn(f64) -> f64, target: f64, lo: f64, hi: f64) -> f64 {
    if r(lo) <= target {
        return lo;
    }
    if r(hi) >= target {
        return hi;
    }
    let (mut l, mut h) = (lo, hi);
    for _ in 0..GAP_FIT_BISECTIONS {
        let m = 0.5 * (l + h);
        if r(m) > target {
            l = m;
        } else {
            h = m;
        }
    }
    0.5 * (l + h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::test_problems::coarse_sinusoid;
    use crate::fe::{build_model, Interface};

    /// The coarse-mesh model of a frictionless sinusoid and its state with every face node
    /// active, with internal forces whose face multipliers are `lam` (zero elsewhere) and whose
    /// element forces are of order one.
    fn state_with_multipliers(lam: impl Fn(usize) -> f64) -> (Model, State, Forces, SolveOptions) {
        let (problem, opts) = coarse_sinusoid(0.1, Interface::Frictionless);
        let model = build_model(&problem, &opts);
        let mut st = model.initial_state();
        st.active.iter_mut().for_each(|a| *a = true);
        let mut grad = vec![0.0; 2 * model.num_nodes()];
        for (k, &n) in model.mesh.bottom.iter().enumerate() {
            grad[2 * n + 1] = lam(k);
        }
        let forces = Forces {
            energy: 0.0,
            grad,
            resid: Vec::new(),
            dresid_dd: Vec::new(),
            force_scale: 1.0,
            friction_complementarity: 0.0,
        };
        (model, st, forces, opts)
    }

    /// Loaded nodes `0 … 4` put the edge node at 5, whether node 5 carries nothing or a force
    /// within the Newton tolerance (`residual_rtol · 1 + residual_atol · (G + κ)` = 2·10⁻¹⁰
    /// here), as the node of a loading event does when unloading passes its displacement;
    /// round-off multipliers of either sign, as at zero load, load no node: the edge node is the
    /// peak's. A threshold relative to the largest multiplier alone (`multiplier_rtol` 10⁻⁹)
    /// would count node 5 as loaded in the second case and half the nodes in the third.
    #[test]
    fn the_edge_node_follows_the_loaded_nodes_and_ignores_forces_within_the_tolerance() {
        let loaded = |k: usize| if k < 5 { 1e-2 * (5 - k) as f64 } else { 0.0 };
        let (model, st, f, opts) = state_with_multipliers(loaded);
        assert_eq!(loaded_edge_node(&model, &st, &f, &opts), 5);
        let (model, st, f, opts) =
            state_with_multipliers(|k| if k == 5 { 1e-10 } else { loaded(k) });
        assert!(1e-10 > opts.contact.multiplier_rtol * 5e-2);
        assert_eq!(loaded_edge_node(&model, &st, &f, &opts), 5);
        let round_off =
            |k: usize| if k.is_multiple_of(2) { 3e-15 } else { -2e-15 } * (k + 1) as f64;
        let (model, st, f, opts) = state_with_multipliers(round_off);
        assert_eq!(loaded_edge_node(&model, &st, &f, &opts), 0);
    }

    /// [`periodic_gap_fit`] inverts the gap ratio of [`periodic_gap_shape`] inside the
    /// interval and clamps outside it.
    #[test]
    fn periodic_gap_fit_recovers_the_edge() {
        let (lo, hi) = (0.2, 0.22);
        let (x1, x2) = (0.24, 0.26);
        let ratio = |a: f64| periodic_gap_shape(x1, a) / periodic_gap_shape(x2, a);
        for a in [0.201, 0.21, 0.219] {
            let fit = periodic_gap_fit(x1, x2, ratio(a), lo, hi);
            assert!((fit - a).abs() < 1e-12, "a = {a}: fit {fit}");
        }
        assert_eq!(periodic_gap_fit(x1, x2, ratio(0.19), lo, hi), lo);
        assert_eq!(periodic_gap_fit(x1, x2, ratio(0.23), lo, hi), hi);
    }
}
