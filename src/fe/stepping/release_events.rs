//! Release events: a contact node whose normal force would turn tensile leaves contact at the
//! slab displacement where that force vanishes.
//!
//! The active-set update of a load step ([`crate::fe::newton::active_set`]) releases such a node wherever
//! the step happens to end. In the node-event stepping of a profile ([`crate::fe::stepping::loading`]) a
//! release found in the step of a touchdown is located as an event of its own when it comes
//! first ([`first_release`]): regula falsi (Illinois) on the slab displacement between the
//! last converged state and the touchdown, each trial a displacement-controlled step from the
//! last converged state with the node held active and the touchdown's target held free,
//! until the node's release force (what the active-set test compares) vanishes within the
//! release threshold ([`locate_release`]). At the event the node, touching with zero force,
//! is released; the next step starts with it free.

use crate::fe::error::{FailCause, StepFail};
use crate::fe::model::{Model, State};
use crate::fe::newton::active_set::{equilibrate, release_forces, release_scale, Hold};
use crate::fe::newton::assembly::Assembly;
use crate::fe::stepping::displacement_step::displacement_step;
use crate::fe::stepping::event_search::open_gap_tolerance;
use crate::fe::stepping::node_events::passed_touchdowns;
use crate::fe::stepping::step_control::{RegulaFalsi, StepCuts, Trial};
use crate::fe::SolveOptions;

/// Most trial displacements of one release search (regula falsi on a force that is smooth in
/// the slab displacement converges in a handful; a safeguard).
const MAX_RELEASE_TRIALS: usize = 40;

/// Contact-face nodes in contact in `from` and free in the converged `found`: released on the
/// way from one to the other.
pub(crate) fn released_nodes(from: &State, found: &State) -> Vec<usize> {
    (0..from.active.len())
        .filter(|&i| from.active[i] && !found.active[i])
        .collect()
}

/// A located release.
#[derive(Clone, Debug)]
pub(crate) struct Release {
    /// The converged state at the release, the node free, slip not committed.
    pub(crate) state: State,
    /// The released contact-face node.
    pub(crate) node: usize,
}

/// A release search's outcome and the Newton iterations it spent, a release found or not.
#[derive(Clone, Debug, Default)]
pub(crate) struct ReleaseSearch {
    /// The release, if the node lets go on the way.
    pub(crate) release: Option<Release>,
    /// Newton iterations spent: the trial steps, failed ones included.
    pub(crate) iterations: usize,
}

/// The release force of `node` in the converged state `st`, and the release threshold there
/// (`multiplier_rtol` times the largest release force).
fn release_force(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    st: &State,
    node: usize,
) -> (f64, f64) {
    let f = asm
        .assemble(model, st, false)
        .expect("converged state is not inverted");
    let forces = release_forces(model, st, &f.grad);
    (
        forces[node],
        opts.contact.multiplier_rtol * release_scale(&forces),
    )
}

/// Where contact node `node` of the converged state `from` (compressive there) lets go on the
/// way to the slab displacement `beyond_d` (either direction), the nodes of `hold` kept as they
/// are and `node` held active until its release force vanishes within the release threshold.
/// No release when, held active, it is still compressive at `beyond_d`: it does not let go on
/// the way. A trial step that fails is cut back towards its start (at most `max_step_cuts`
/// times); the iterations it spent count.
pub(crate) fn locate_release(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    from: &State,
    node: usize,
    beyond_d: f64,
    hold: Hold,
) -> Result<ReleaseSearch, StepFail> {
    let held = Hold {
        active: Some(node),
        ..hold
    };
    let (f0, _) = release_force(model, asm, opts, from, node);
    let mut search = RegulaFalsi::new(
        Trial {
            x: from.d,
            f: f0,
            at: from.clone(),
        },
        None,
    );
    let (beyond, mut iterations) = displacement_step(model, asm, opts, from, beyond_d, held)?;
    let (fb, tol) = release_force(model, asm, opts, &beyond, node);
    if fb >= -tol {
        return Ok(ReleaseSearch {
            release: None,
            iterations,
        });
    }
    search.beyond = Some((beyond_d, fb));
    let mut cuts = StepCuts::new(opts.steps.max_step_cuts);
    let mut next = search.next(0.0, 1.0).expect("bracketed");
    for _ in 0..MAX_RELEASE_TRIALS {
        let d = next;
        let start = &search.below.at;
        let (mut st, it) = match displacement_step(model, asm, opts, start, d, held) {
            Ok(converged) => converged,
            Err(f) => {
                next = cuts.after_failure((start.d, d), f, &mut iterations)?;
                continue;
            }
        };
        iterations += it;
        let (f, tol) = release_force(model, asm, opts, &st, node);
        if f.abs() <= tol {
            // touching with zero force: releasing it leaves the equilibrium as it is
            st.active[node] = false;
            iterations += equilibrate(model, asm, &mut st, opts, hold)
                .map_err(|failed| failed.after(iterations))?;
            return Ok(ReleaseSearch {
                release: Some(Release { state: st, node }),
                iterations,
            });
        }
        search.insert(Trial { x: d, f, at: st });
        next = search.next(0.0, 1.0).expect("bracketed");
    }
    Err(StepFail::from(FailCause::Diverged {
        iteration: iterations,
        residual: f64::NAN,
        reason: format!(
            "the release of contact node {node} was not located in {MAX_RELEASE_TRIALS} trials"
        ),
    }))
}

/// The release that comes before the touchdown `found` of free node `target` from the
/// converged state `from`, if any: among the nodes the step released ([`released_nodes`]),
/// the one that lets go first ([`locate_release`], the target held free), provided that the
/// target is still open there and no other node has touched on the way
/// ([`passed_touchdowns`]); otherwise the touchdown is the event. Its iterations are those of
/// every search, whichever is kept.
pub(crate) fn first_release(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    from: &State,
    found: &State,
    target: usize,
) -> Result<ReleaseSearch, StepFail> {
    let mut first: Option<Release> = None;
    let mut iterations = 0;
    let hold = Hold::free(Some(target));
    for j in released_nodes(from, found) {
        let search = locate_release(model, asm, opts, from, j, found.d, hold)
            .map_err(|failed| failed.after(iterations))?;
        iterations += search.iterations;
        if let Some(r) = search.release {
            if first.as_ref().is_none_or(|f| r.state.d < f.state.d) {
                first = Some(r);
            }
        }
    }
    let release = first.filter(|r| {
        model.gaps(&r.state)[target] > open_gap_tolerance(model)
            && passed_touchdowns(model, from, &r.state, None).is_none()
    });
    Ok(ReleaseSearch {
        release,
        iterations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::newton::assembly::Assembly;
    use crate::fe::stepping::test_fixtures::loaded_sinusoid;

    /// The converged states of the frictionless AR 0.1 sinusoid on the coarse mesh, edge event
    /// by edge event up to a/λ = 0.3, with the model and its assembly.
    fn loaded() -> (Model, Assembly, SolveOptions, Vec<State>) {
        loaded_sinusoid(0.1, 0.3)
    }

    /// The last node in contact.
    fn last_active(st: &State) -> usize {
        (0..st.active.len())
            .rev()
            .find(|&i| st.active[i])
            .expect("in contact")
    }

    /// A frictionless contact is reversible: retracting the slab from the last event, the node
    /// that touched at the event before lets go where it touched. Its located release lies at
    /// that event's slab displacement (measured relative difference 1.9e-11, asserted 1e-10: both
    /// searches stop within their gap tolerances, `edge_gap_rtol` of the target's first gap, which
    /// allow a relative error in `d` of about `edge_gap_rtol · Δd/d`, `Δd` the event's increment), and the state there is the loading state (positions within
    /// 1e-11 λ; measured 5.1e-12 λ, the difference of `d`, 1.7e-12 λ, times the path's rate).
    #[test]
    fn unloading_release_lies_where_loading_touched() {
        let (model, mut asm, opts, states) = loaded();
        let m = states.len() - 1;
        assert!(m >= 3, "{m} events");
        let node = last_active(&states[m - 1]);
        let release = locate_release(
            &model,
            &mut asm,
            &opts,
            &states[m],
            node,
            states[m - 2].d,
            Hold::NONE,
        )
        .expect("the release search converges")
        .release
        .expect("the node lets go on the way back");
        assert_eq!(release.node, node);
        assert!(!release.state.active[node]);
        let touched = &states[m - 1];
        let rel = (release.state.d / touched.d - 1.0).abs();
        eprintln!(
            "release at d/λ = {:.12e}, touchdown at {:.12e} ({rel:.1e})",
            release.state.d, touched.d
        );
        assert!(
            rel <= 1e-10,
            "release d {} vs touchdown d {}: {rel:e}",
            release.state.d,
            touched.d
        );
        let moved = release
            .state
            .x
            .iter()
            .zip(&touched.x)
            .map(|(a, b)| (a[0] - b[0]).abs().max((a[1] - b[1]).abs()))
            .fold(0.0, f64::max);
        eprintln!("largest position difference {moved:.1e} λ");
        assert!(moved <= 1e-11, "positions differ by {moved:e} λ");
        assert_eq!(
            release.state.active,
            touched
                .active
                .iter()
                .enumerate()
                .map(|(i, &a)| a && i != node)
                .collect::<Vec<_>>()
        );
    }

    /// A node that stays compressive on the way (the peak, retracting by one event) has no
    /// release.
    #[test]
    fn compressive_node_has_no_release() {
        let (model, mut asm, opts, states) = loaded();
        let m = states.len() - 1;
        let none = locate_release(
            &model,
            &mut asm,
            &opts,
            &states[m],
            0,
            states[m - 1].d,
            Hold::NONE,
        )
        .expect("the step converges");
        assert!(none.release.is_none());
        assert!(none.iterations > 0, "the step beyond is counted");
    }

    /// Released nodes are those in contact before and free after.
    #[test]
    fn released_nodes_are_active_before_and_free_after() {
        let (_, _, _, states) = loaded();
        let (mut before, mut after) = (states[1].clone(), states[1].clone());
        before.active = vec![true, true, false, true];
        after.active = vec![true, false, true, false];
        assert_eq!(released_nodes(&before, &after), vec![1, 3]);
    }
}
