//! Where the patch edges of a profile lie in any converged state, not only at their own events.
//!
//! The edge rule ([`crate::fe::EdgeRule`]) places an edge at an edge event: node `k` touches
//! with zero force, and the edge lies at the rule's fraction `φ` of `[x_{k−1}, x_k]`. A profile's
//! contact has several patches and each point of its curve is the event of one node only, so
//! every other edge is caught between two of its own events. An edge whose last loaded node is
//! `i` (free neighbour `j`, loaded inner neighbour `m`) travels from `E₀ = x_m + φ (x_i − x_m)`,
//! where it was when `i` touched, to `E₁ = x_i + φ (x_j − x_i)`, where it will be when `j`
//! touches. How far it has come is read from the force that `i` has taken up since it touched:
//! the discrete solution near an edge is self-similar at the scale of the element (the reason
//! `φ` is mesh-independent), so the place `t ∈ [0, 1]` of the edge between `E₀` and `E₁` is a
//! function of the force ratio `ρ = f_i/f_m` and of the element's shape
//! ([`edge_progress`], calibrated on Westergaard's solution as `φ` is). The edge beside the
//! event's own node is the edge rule's `E₁` ([`patch_edge`]).
//!
//! Where a patch is born, where two merge, and where one vanishes, the edges are within an
//! element or two of each other and no longer self-similar:
//! * **Merges.** When the last free node `j` between two patches touches, the opening of the
//!   continuum solution is still open (both its edges short of `x_j`, each by about the edge
//!   rule's `1 − φ` of an element or more), and it closes as `j` takes up load: the two edges go
//!   on toward `x_j` by the same progress law, now of `f_j` over each loaded neighbour, and the
//!   patches are one when they pass `x_j` ([`opening_around`]). Where several nodes of the
//!   opening touched together, it closes around the least loaded of them only (a node that a
//!   neighbour outweighs is inside a patch). The event edges of such an opening follow the
//!   progress law too.
//! * **Births.** A patch of at most [`YOUNG_PATCH_NODES`] loaded nodes is placed as a whole: the
//!   local contact `[c − b, c + b]` of a parabolic crest (Hertz) whose gap, `∝ ½[u √(u² − b²) −
//!   b² ln((u + √(u² − b²))/b)]` at the distance `u` from `c`, has the ratios of the gaps of the
//!   first two free nodes on each side ([`young_patch`]): a crest need not lie on a node. Where
//!   those gaps are not available (a symmetry line) each edge is the half-width fitted on its own
//!   side ([`hertz_half_width`]), at most `E₁`.
//! * **A patch that vanishes** is a birth in reverse: the same rules read its last nodes.
//!
//! Edges on the symmetry lines (the peak at `x = 0`, the valley at `x = ½`) see their mirror
//! images: the node beyond the valley node is its left neighbour's mirror.

use crate::fe::contact::edge_rule::{element_aspect, invert_decreasing};
use crate::fe::model::{Model, State};
use crate::fe::EdgeRule;

/// The coefficients `[c₀, c₁, c₂, c₃]` of the progress law
/// `t(ρ, r) = ρ + (c₀ + c₁ r) ρ² + (c₂ + c₃ r) ρ³` ([`edge_progress`]), `r` the current height over
/// width of the elements beside the edge's last loaded node (as [`EdgeRule::AspectFraction`] reads
/// it). Calibrated on the exact solution as [`crate::fe::EDGE_FRACTION_BY_ASPECT`] is (linear
/// kinematics, AR = 0.01, Westergaard's `a` for the computed `p̄`): 684 states a quarter, half and
/// three quarters of the load between consecutive edge events with a/λ ∈ [0.05, 0.30] on the
/// 64 × 32 mesh with the gradings (peak ratio, first layer) ∈ {1, 4, 16} × {0.5, 1} and (2, 2),
/// `r` ≈ 0.25–2.5; residuals −0.06…+0.07 of an element, RMS 0.021 (`PROGRESS_CALIB=1 cargo run
/// --release --example fe_study`; docs/replication.md R13).
pub const EDGE_PROGRESS_BY_FORCE_RATIO: [f64; 4] = [0.9098, -0.2879, 0.5779, 0.1149];

/// A patch of at most this many loaded nodes is young: too narrow for the edge rule's
/// self-similar edge (its two edges are within two elements of each other), it is placed as a
/// whole by the local contact its gaps show ([`young_patch`]). Measured against the boundary-element
/// solution (linear kinematics, the four profiles of the two-scale scene, meshes 96 and 192):
/// young patches of 1–2 nodes by their gaps halve the largest error of a newborn patch on mesh
/// 192, 3 or more make it worse at mesh 96 (docs/replication.md R13).
const YOUNG_PATCH_NODES: usize = 2;

/// Bisections of [`young_patch`]'s centre: `2⁻⁶⁰` of two elements is far below round-off.
const CENTRE_BISECTIONS: usize = 60;

/// The place `t ∈ [0, 1]` of an edge between `E₀` and `E₁` (module documentation) from the force
/// ratio `rho` of its last loaded node to the next one in, at element aspect `r`
/// ([`EDGE_PROGRESS_BY_FORCE_RATIO`]).
fn edge_progress(rho: f64, r: f64) -> f64 {
    let c = EDGE_PROGRESS_BY_FORCE_RATIO;
    (rho + (c[0] + c[1] * r) * rho * rho + (c[2] + c[3] * r) * rho.powi(3)).clamp(0.0, 1.0)
}

/// The contact-face neighbour of node `i` one step toward `toward` (a neighbour of `i`), across a
/// symmetry line when `toward` lies on it: the mirror image of the node beyond it.
pub(crate) fn step_beyond(i: usize, toward: usize, last: usize) -> usize {
    match (toward > i, toward) {
        (true, t) if t == last => i,
        (true, t) => t + 1,
        (false, 0) => i,
        (false, t) => t - 1,
    }
}

/// A patch edge caught between its own events: its last loaded node `i` touched after its inner
/// neighbour `m`, and its free neighbour `j` has not touched yet. It lies between `from`
/// (`E₀`, where it was when `i` touched) and `reach` (`E₁`, where it will be when `j`
/// touches), both of the edge rule at the state's current positions (units of λ), at the
/// progress `t` the force ratio reads ([`edge_progress`]) until the whole loading curve is
/// known ([`crate::fe::contact::edge_tracks`] places it by the load between those touchdowns).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TravellingEdge {
    /// Index of its patch in the state's patches.
    pub(crate) patch: usize,
    /// Which end of the patch it is: 0 its start (smaller `x`), 1 its end.
    pub(crate) end: usize,
    /// Its last loaded node `i` (face order).
    pub(crate) node: usize,
    /// The free node `j` beyond it.
    pub(crate) free: usize,
    /// `E₀` (units of λ).
    pub(crate) from: f64,
    /// `E₁` (units of λ).
    pub(crate) reach: f64,
}

/// A placed patch edge: its current `x` (units of λ) and, when it is travelling between its own
/// events, its `E₀` and `E₁` ([`TravellingEdge`]).
struct PlacedEdge {
    x: f64,
    between: Option<[f64; 2]>,
}

/// The edge of a patch whose last loaded node, face order, is `i` and whose free neighbour beyond
/// it is `j` (`i ± 1`), given the vertical contact multipliers `lam` and which nodes are
/// `loaded` (module documentation).
fn patch_edge(
    model: &Model,
    st: &State,
    rule: EdgeRule,
    (lam, loaded): (&[f64], &[bool]),
    event: Option<usize>,
    i: usize,
    j: usize,
) -> PlacedEdge {
    let at = |x: f64| PlacedEdge { x, between: None };
    let b = &model.mesh.bottom;
    let last = b.len() - 1;
    let x = |k: usize| st.x[b[k]][0];
    let beyond_j = step_beyond(i, j, last);
    let reach = x(i) + rule.fraction(model, st, i, j) * (x(j) - x(i));
    // the event's own edge is the edge rule's, unless the event closes an opening
    if event == Some(j) && !loaded[beyond_j] {
        return at(reach);
    }
    let inner = step_beyond(j, i, last);
    let inner = (inner != j).then_some(inner);
    match inner {
        Some(m) if loaded[m] && lam[m] > 0.0 => {
            let from = x(m) + rule.fraction(model, st, m, i) * (x(i) - x(m));
            let r = 0.5 * (element_aspect(model, st, m, i) + element_aspect(model, st, i, j));
            PlacedEdge {
                x: from + edge_progress(lam[i] / lam[m], r) * (reach - from),
                between: Some([from, reach]),
            }
        }
        _ => {
            let gaps = model.gaps(st);
            let most = (reach - x(i)).abs();
            let (g1, g2) = (gaps[j], gaps[beyond_j]);
            let half_width = if beyond_j != i && g1 > 0.0 && g2 > g1 {
                let (u1, u2) = ((x(j) - x(i)).abs(), (x(beyond_j) - x(i)).abs());
                hertz_half_width(u1, u2, g1 / g2, most)
            } else {
                0.5 * most
            };
            at(x(i) + half_width * (reach - x(i)).signum())
        }
    }
}

/// The contact patches of a profile's state in `[0, ½]` (as
/// [`crate::fe::contact::patches::contact_patches`] gives them): each of the `runs` of `loaded`
/// nodes `[i₀, i₁]` (in order), its outer edges placed by [`patch_edge`], split where a node inside
/// it still has an opening around it ([`opening_around`]); with the edges among them that travel
/// between their own events.
pub(crate) fn profile_patches(
    model: &Model,
    st: &State,
    rule: EdgeRule,
    (lam, loaded): (&[f64], &[bool]),
    event: Option<usize>,
    mut runs: Vec<[usize; 2]>,
) -> (Vec<[f64; 2]>, Vec<TravellingEdge>) {
    let b = &model.mesh.bottom;
    let last = b.len() - 1;
    let x = |k: usize| st.x[b[k]][0];
    let edge = |i: usize, j: usize| patch_edge(model, st, rule, (lam, loaded), event, i, j);
    let opening = |j: usize, left: usize, right: usize| {
        opening_around(model, st, rule, lam, j, [left, right])
    };
    let gaps = model.gaps(st);
    let young = |i0: usize, i1: usize| {
        let fits = i0 >= 2 && i1 + 2 <= last;
        fits.then(|| {
            let pos = [x(i0 - 2), x(i0 - 1), x(i1 + 1), x(i1 + 2)];
            young_patch(
                pos,
                [gaps[i0 - 2], gaps[i0 - 1], gaps[i1 + 1], gaps[i1 + 2]],
            )
        })
        .flatten()
    };
    // a crest's touchdown is a patch's birth: the event's node alone, no loaded neighbour
    let born = event.filter(|&k| {
        !loaded[k]
            && !loaded[step_beyond(k + 1, k, last)]
            && !loaded[step_beyond(k.saturating_sub(1), k, last)]
    });
    if let Some(k) = born {
        let at = runs.partition_point(|r| r[0] < k);
        runs.insert(at, [k, k]);
    }
    let mut patches = Vec::new();
    let mut travelling = Vec::new();
    let mut placed = |edge: PlacedEdge, patch: usize, end: usize, node: usize, free: usize| {
        if let Some([from, reach]) = edge.between {
            travelling.push(TravellingEdge {
                patch,
                end,
                node,
                free,
                from,
                reach,
            });
        }
        edge.x
    };
    for [i0, i1] in runs {
        if born == Some(i0) {
            patches.push(young(i0, i1).unwrap_or([x(i0), x(i0)]));
            continue;
        }
        if i1 + 1 - i0 <= YOUNG_PATCH_NODES {
            if let Some(p) = young(i0, i1) {
                patches.push(p);
                continue;
            }
        }
        let mut start = match i0 {
            0 if i1 > 0 => opening(0, 1, 1).map_or(x(0), |o| o[1]),
            0 => x(0),
            _ => placed(edge(i0, i0 - 1), patches.len(), 0, i0, i0 - 1),
        };
        for j in i0 + 1..i1 {
            // an opening closes around the least loaded node of its stretch: a node that a
            // neighbour outweighs from neither side is inside a patch
            if lam[j] > lam[j - 1] || lam[j] > lam[j + 1] {
                continue;
            }
            if let Some([l, r]) = opening(j, j - 1, j + 1) {
                patches.push([start, l]);
                start = r;
            }
        }
        let end = match i1 {
            i if i == last && i0 < i1 => {
                opening(last, last - 1, last - 1).map_or(x(last), |o| o[0])
            }
            i if i == last => x(last),
            _ => {
                let edge = edge(i1, i1 + 1);
                placed(edge, patches.len(), 1, i1, i1 + 1)
            }
        };
        patches.push([start, end]);
    }
    (patches, travelling)
}

/// A young patch: the local (Hertz) contact `[c − b, c + b]` whose gap shape
/// ([`hertz_gap_shape`] about `c`) has the gap ratios of the two free nodes on each side
/// (`pos`, `gaps`: the second and first free node on the left, the first and second on the
/// right), if both are open and growing outward.
fn young_patch(pos: [f64; 4], g: [f64; 4]) -> Option<[f64; 2]> {
    if !(g[1] > 0.0 && g[0] > g[1] && g[2] > 0.0 && g[3] > g[2]) {
        return None;
    }
    let half_widths = |c: f64| {
        let left = hertz_half_width(c - pos[1], c - pos[0], g[1] / g[0], c - pos[1]);
        let right = hertz_half_width(pos[2] - c, pos[3] - c, g[2] / g[3], pos[2] - c);
        (left, right)
    };
    let (mut lo, mut hi) = (pos[1], pos[2]);
    for _ in 0..CENTRE_BISECTIONS {
        let mid = 0.5 * (lo + hi);
        let (l, r) = half_widths(mid);
        if l < r {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let c = 0.5 * (lo + hi);
    let (l, r) = half_widths(c);
    let b = 0.5 * (l + r);
    Some([c - b, c + b])
}

/// The opening still left around the loaded node `j` between its loaded neighbours `left` and
/// `right` (`j ∓ 1`; the same node, the mirror image, when `j` lies on a symmetry line), if any.
/// Two patches merge in the load stepping when the last free node between them touches, but the
/// opening of the continuum solution then spans the edge rule's `[x_l + φ (x_j − x_l), x_r − φ (x_r
/// − x_j)]`; from there each of its edges moves on toward `x_j` as a patch edge does across an
/// element, by the progress law of the force ratio `f_j/f_l` (`f_j/f_r`), and the opening closes
/// when they pass `x_j`.
fn opening_around(
    model: &Model,
    st: &State,
    rule: EdgeRule,
    lam: &[f64],
    j: usize,
    [left, right]: [usize; 2],
) -> Option<[f64; 2]> {
    let b = &model.mesh.bottom;
    let x = |k: usize| st.x[b[k]][0];
    // how far an edge has come from the loaded node `n` toward `j`, as a fraction of the element
    let reached = |n: usize| {
        if lam[n] <= 0.0 {
            return 1.0;
        }
        let t = edge_progress(lam[j] / lam[n], element_aspect(model, st, n, j));
        (rule.fraction(model, st, n, j) + t).min(1.0)
    };
    let from_left = x(left) + reached(left) * (x(j) - x(left));
    let from_right = x(right) + reached(right) * (x(j) - x(right));
    let (l, r) = match (left == right, left > j) {
        (false, _) => (from_left, from_right),
        (true, false) => (from_left, 2.0 * x(j) - from_left),
        (true, true) => (2.0 * x(j) - from_right, from_right),
    };
    (l < r).then_some([l, r])
}

/// The gap of a rigid parabola over the local contact of half-width `b` at the distance `u` from
/// its centre, up to a constant factor: `½[u √(u² − b²) − b² ln((u + √(u² − b²))/b)]` (`u²/2` for
/// `b = 0`; 0 inside the contact).
fn hertz_gap_shape(u: f64, b: f64) -> f64 {
    if u <= b {
        return 0.0;
    }
    if b <= 0.0 {
        return 0.5 * u * u;
    }
    let s = (u * u - b * b).sqrt();
    0.5 * (u * s - b * b * ((u + s) / b).ln())
}

/// The half-width `b ∈ [0, most]` at which [`hertz_gap_shape`] has the gap ratio `ratio` between
/// the distances `u1 < u2` (the ratio falls as `b` grows), clamped to the interval.
fn hertz_half_width(u1: f64, u2: f64, ratio: f64, most: f64) -> f64 {
    invert_decreasing(
        |b| hertz_gap_shape(u1, b) / hertz_gap_shape(u2, b),
        ratio,
        0.0,
        most,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At the events the progress law gives the edge rule's ends: 0 when the last loaded node has
    /// just touched, 1 (clamped) at the ratio the next event leaves.
    #[test]
    fn progress_runs_from_zero_to_one() {
        assert_eq!(edge_progress(0.0, 1.0), 0.0);
        assert_eq!(edge_progress(0.8, 1.0), 1.0);
        let mut previous = 0.0;
        for k in 1..=60 {
            let t = edge_progress(k as f64 * 0.01, 1.0);
            assert!(t > previous, "monotone");
            previous = t;
        }
    }

    /// [`hertz_half_width`] inverts the gap ratio of [`hertz_gap_shape`] and clamps outside.
    #[test]
    fn hertz_fit_recovers_the_half_width() {
        let (u1, u2) = (1.0, 2.0);
        let ratio = |b: f64| hertz_gap_shape(u1, b) / hertz_gap_shape(u2, b);
        for b in [0.1, 0.4, 0.7] {
            assert!((hertz_half_width(u1, u2, ratio(b), 0.8) - b).abs() < 1e-12);
        }
        assert_eq!(hertz_half_width(u1, u2, 0.3, 0.8), 0.0);
        assert_eq!(hertz_half_width(u1, u2, ratio(0.9), 0.8), 0.8);
    }

    #[test]
    fn a_step_beyond_a_symmetry_line_is_a_mirror_image() {
        assert_eq!(step_beyond(3, 4, 10), 5);
        assert_eq!(step_beyond(3, 2, 10), 1);
        assert_eq!(step_beyond(9, 10, 10), 9);
        assert_eq!(step_beyond(1, 0, 10), 1);
    }
}
