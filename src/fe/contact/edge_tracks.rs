//! A profile's patch edges placed between their own events by the load, once the loading curve
//! knows when each edge's next node touched.
//!
//! An edge whose last loaded node `i` touched after its inner neighbour `m` travels from `E₀`
//! (where the edge rule put it when `i` touched) to `E₁` (where it will put it when the free
//! node `j` beyond touches: [`TravellingEdge`]). At the state itself only the forces show how far
//! it has come (the progress law of [`crate::fe::contact::patch_edge`], calibrated on a single
//! sinusoid's edge). The loading curve knows more: the mean pressures `p̄ᵢ` and `p̄ⱼ` at which `i`
//! and `j` touched, the two loads at which the edge stood exactly at `E₀` and at `E₁`. Between
//! them the edge moves on smoothly with the load (it crosses one element), so its place is read
//! from the load, `t = (p̄ − p̄ᵢ)/(p̄ⱼ − p̄ᵢ)`, the edge at `E₀ + t (E₁ − E₀)`: linear
//! interpolation between two of its own events, each placed as accurately as the edge rule places
//! a sinusoid's edge.
//!
//! An edge whose `j` touches as the last free node between two patches (a merge), or does not
//! touch before the curve ends, keeps its progress law. The curve's points are final once every
//! travelling edge of theirs is placed so, or [`MAX_LAG`] points later ([`EdgeTracks::settled`]).

use crate::fe::contact::patch_edge::{step_beyond, TravellingEdge};
use crate::fe::contact::patches::contact_fraction;
use crate::fe::contact::stick_zone::stick_zone;
use crate::fe::CurvePoint;

/// The most points a loading point waits for the touchdowns that place its travelling edges:
/// beyond it they keep their progress law. The waits measured on the two-scale profiles
/// (`1:0.1,8:0.05` and `1:0.1,16:0.1`, 192 elements along the face) are at most 14 points, 99 %
/// within 11 (docs/replication.md R13); it bounds how long a point's state is held before the step
/// callback sees it.
pub(crate) const MAX_LAG: usize = 32;

/// What the edge placement needs of one loading point.
struct TrackedPoint {
    /// Its mean pressure `p̄/E*`.
    p_over_estar: f64,
    /// Which contact-face nodes are in contact.
    active: Vec<bool>,
    /// Its travelling edges.
    travelling: Vec<TravellingEdge>,
    /// Its stick intervals before they are cut to the patches.
    stick_runs: Vec<[f64; 2]>,
    /// The current `x` of the peak node.
    peak_x: f64,
}

/// The loading points of a profile's curve as the edge placement sees them, and when each
/// contact-face node touched.
pub(crate) struct EdgeTracks {
    points: Vec<TrackedPoint>,
    /// Per contact-face node, the points at which it touched, in order: the point whose state
    /// first has it in contact, or the one before when it was already touching there.
    touches: Vec<Vec<usize>>,
    /// Per contact-face node, whether it is in contact in the last recorded state.
    in_contact: Vec<bool>,
}

impl EdgeTracks {
    /// No point yet, for a contact face of `nodes` nodes.
    pub(crate) fn new(nodes: usize) -> Self {
        Self {
            points: Vec::new(),
            touches: vec![Vec::new(); nodes],
            in_contact: vec![false; nodes],
        }
    }

    /// Nodes found touching in the last recorded state, brought into contact before the next
    /// step (`active`: the contact status they now have): they touched at that point.
    pub(crate) fn touching_before_step(&mut self, active: &[bool]) {
        let Some(last) = self.points.len().checked_sub(1) else {
            return;
        };
        for (k, &a) in active.iter().enumerate() {
            if a && !self.in_contact[k] {
                self.touches[k].push(last);
                self.in_contact[k] = true;
            }
        }
    }

    /// The next loading point: its mean pressure, contact status, travelling edges, stick runs
    /// and peak position.
    pub(crate) fn record(
        &mut self,
        p_over_estar: f64,
        active: &[bool],
        travelling: Vec<TravellingEdge>,
        (stick_runs, peak_x): (Vec<[f64; 2]>, f64),
    ) {
        let index = self.points.len();
        for (k, &a) in active.iter().enumerate() {
            if a && !self.in_contact[k] {
                self.touches[k].push(index);
            }
            self.in_contact[k] = a;
        }
        self.points.push(TrackedPoint {
            p_over_estar,
            active: active.to_vec(),
            travelling,
            stick_runs,
            peak_x,
        });
    }

    /// The touchdown of `node` last at or before point `k`.
    fn touched_by(&self, node: usize, k: usize) -> Option<usize> {
        let t = &self.touches[node];
        t[..t.partition_point(|&i| i <= k)].last().copied()
    }

    /// The touchdown of `node` first at or after point `k`.
    fn touches_from(&self, node: usize, k: usize) -> Option<usize> {
        let t = &self.touches[node];
        t.get(t.partition_point(|&i| i < k)).copied()
    }

    /// The progress of the travelling edge `e` of point `k` between its own events by the load
    /// (module documentation), once its free node has touched as this edge's next event: with
    /// its last loaded node still in contact and the node beyond free (not a merge).
    fn progress_by_load(&self, k: usize, e: &TravellingEdge) -> Option<f64> {
        let last = self.in_contact.len() - 1;
        let from = self.touched_by(e.node, k)?;
        let to = self.touches_from(e.free, k + 1)?;
        let at = &self.points[to];
        let beyond = step_beyond(e.node, e.free, last);
        if !at.active[e.node] || at.active[beyond] {
            return None;
        }
        let (p0, p1) = (self.points[from].p_over_estar, at.p_over_estar);
        let p = self.points[k].p_over_estar;
        (p1 > p0).then(|| ((p - p0) / (p1 - p0)).clamp(0.0, 1.0))
    }

    /// Whether point `k` is final: each of its travelling edges has had its next touchdown (after
    /// the point: the curve's last point never moves), or
    /// [`MAX_LAG`] points have been recorded since, or `complete` (the curve has ended).
    pub(crate) fn settled(&self, k: usize, complete: bool) -> bool {
        complete
            || self.points.len() > k + MAX_LAG
            || self.points[k]
                .travelling
                .iter()
                .all(|e| self.touches_from(e.free, k + 1).is_some())
    }

    /// Point `k` with its travelling edges placed by the load where their next touchdown is
    /// known: its `patches` moved, and the point's contact fraction, half-width (the outermost
    /// patch edge) and stick zone measured again.
    pub(crate) fn place(&self, k: usize, point: &mut CurvePoint, patches: &mut [[f64; 2]]) {
        let tracked = &self.points[k];
        let mut moved = false;
        for e in &tracked.travelling {
            if let Some(t) = self.progress_by_load(k, e) {
                patches[e.patch][e.end] = e.from + t * (e.reach - e.from);
                moved = true;
            }
        }
        if !moved {
            return;
        }
        point.contact_fraction = contact_fraction(patches);
        point.a_over_lambda = patches.last().map_or(0.0, |p| p[1]);
        let stick = stick_zone(&tracked.stick_runs, patches, tracked.peak_x);
        point.stick_fraction = stick.fraction;
        point.stick_half_width_over_lambda = stick.central_half_width;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point at `p̄/E*` whose only travelling edge is the end of patch `[0, 0.12]`: last loaded
    /// node 1, free node 2, from `E₀ = 0.1` to `E₁ = 0.2`.
    fn point(tracks: &mut EdgeTracks, p: f64, active: &[bool]) {
        let edge = TravellingEdge {
            patch: 0,
            end: 1,
            node: 1,
            free: 2,
            from: 0.1,
            reach: 0.2,
        };
        tracks.record(p, active, vec![edge], (vec![], 0.0));
    }

    fn curve_point(fraction: f64) -> CurvePoint {
        CurvePoint {
            a_over_lambda: 0.5 * fraction,
            p_over_estar: 0.0,
            p_over_estar_reaction: 0.0,
            slab_displacement_over_lambda: 0.0,
            newton_iterations: 0,
            active_nodes: 0,
            contact_fraction: fraction,
            patches: 1,
            stick_fraction: 0.0,
            stick_half_width_over_lambda: 0.0,
            friction_work_over_estar_lambda2: 0.0,
        }
    }

    /// Between the touchdowns of its last loaded node (at p̄ = 1) and of its free neighbour (at
    /// p̄ = 3) the edge is placed by the load: at p̄ = 2 halfway from `E₀` to `E₁`.
    #[test]
    fn an_edge_between_its_touchdowns_is_placed_by_the_load() {
        let (two, three) = (
            [true, true, false, false, false],
            [true, true, true, false, false],
        );
        let mut tracks = EdgeTracks::new(5);
        point(&mut tracks, 1.0, &two);
        point(&mut tracks, 2.0, &two);
        assert!(!tracks.settled(1, false), "waits for node 2");
        assert!(tracks.settled(1, true), "the curve has ended");
        point(&mut tracks, 3.0, &three);
        assert!(tracks.settled(1, false));
        let mut patches = [[0.0, 0.12]];
        let mut p = curve_point(0.24);
        tracks.place(1, &mut p, &mut patches);
        assert!((patches[0][1] - 0.15).abs() < 1e-15, "{patches:?}");
        assert!((p.contact_fraction - 0.3).abs() < 1e-15);
        assert_eq!(p.a_over_lambda, patches[0][1]);
        // the last point has no later touchdown: it keeps its place
        let mut last = [[0.0, 0.12]];
        tracks.place(2, &mut curve_point(0.24), &mut last);
        assert_eq!(last, [[0.0, 0.12]]);
    }

    /// When the free node touches as the last free node between two patches (a merge), the edge
    /// keeps its progress law.
    #[test]
    fn a_merge_is_not_the_edges_next_event() {
        let mut tracks = EdgeTracks::new(5);
        point(&mut tracks, 1.0, &[true, true, false, true, true]);
        point(&mut tracks, 2.0, &[true, true, false, true, true]);
        point(&mut tracks, 3.0, &[true, true, true, true, true]);
        let mut patches = [[0.0, 0.12]];
        tracks.place(1, &mut curve_point(0.24), &mut patches);
        assert_eq!(patches, [[0.0, 0.12]]);
    }

    /// A point waits at most [`MAX_LAG`] later points for its touchdowns.
    #[test]
    fn a_point_waits_a_bounded_number_of_points() {
        let two = [true, true, false, false, false];
        let mut tracks = EdgeTracks::new(5);
        for k in 0..MAX_LAG {
            point(&mut tracks, k as f64, &two);
        }
        assert!(!tracks.settled(0, false));
        point(&mut tracks, 99.0, &two);
        assert!(tracks.settled(0, false));
    }
}
