//! Node events: the contact of a profile grows in several patches, so the next event of the
//! load stepping is whichever free contact-face node touches first, wherever it lies (a new
//! patch at a crest, or the edge of a patch advancing), not the node beyond one edge.
//!
//! The target is chosen by the load tangent `z = ∂q/∂d` of the last converged state: the free
//! node whose gap closes at the smallest slab-displacement increment along it
//! ([`earliest_touchdown`]). The tangent is a first-order prediction; when the converged event
//! shows another node that touched on the way (free with an open gap before, in contact at the
//! event: the active-set update caught it penetrating), that node came first and becomes the
//! target ([`passed_touchdowns`], `crate::fe::stepping::loading`). A node whose normal force would turn
//! tensile in that step is released where its force vanishes, and that release is the event
//! when it comes first ([`crate::fe::stepping::release_events`]); a patch may shrink or vanish from one
//! event to the next.
//! For a single sinusoid the first free node to touch is the one beyond the edge, and the
//! events are the edge events of [`crate::fe::stepping::event_search`].

use crate::fe::model::{Model, State};
use crate::fe::stepping::event_search::{
    activate_touching_among, closing_increment, open_gap_tolerance,
};

/// Free contact-face nodes with a clearly open gap: the candidates of the next event.
fn open_nodes(model: &Model, st: &State) -> Vec<(usize, f64)> {
    let open_tol = open_gap_tolerance(model);
    model
        .gaps(st)
        .into_iter()
        .enumerate()
        .filter(|&(i, g)| !st.active[i] && g > open_tol)
        .collect()
}

/// Activate every free node that touches (gap at most the open-gap tolerance, left so by the
/// last event with a vanishing force): it carries load as soon as the load grows. Except
/// `released`, the node the last event released: its force would turn tensile.
pub(crate) fn activate_touching_anywhere(model: &Model, st: &mut State, released: Option<usize>) {
    let nodes = (0..st.active.len()).filter(|&i| Some(i) != released);
    activate_touching_among(model, st, nodes);
}

/// The first of `candidates` to close: the smallest closing increment along the tangent `z`,
/// or, where none closes along it (or there is no tangent), the smallest gap. Ties go to the
/// node nearer the peak.
fn first_to_close(
    model: &Model,
    st: &State,
    candidates: &[(usize, f64)],
    z: Option<&[f64]>,
) -> Option<usize> {
    let by_tangent = z.and_then(|z| {
        candidates
            .iter()
            .filter_map(|&(i, g)| closing_increment(model, st, i, g, z).map(|inc| (i, inc)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
    });
    by_tangent.or_else(|| {
        candidates
            .iter()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|&(i, _)| i)
    })
}

/// The target of the next node event from the converged state `st` with load tangent `z`:
/// the open node that closes first ([`first_to_close`]); `None` when every node is in
/// contact.
pub(crate) fn earliest_touchdown(model: &Model, st: &State, z: Option<&[f64]>) -> Option<usize> {
    first_to_close(model, st, &open_nodes(model, st), z)
}

/// Nodes open in `from` that are in contact in the converged event `found`: they touched
/// before the event's target. The one the tangent `z` predicted first, or `None`.
pub(crate) fn passed_touchdowns(
    model: &Model,
    from: &State,
    found: &State,
    z: Option<&[f64]>,
) -> Option<usize> {
    let passed: Vec<(usize, f64)> = open_nodes(model, from)
        .into_iter()
        .filter(|&(i, _)| found.active[i])
        .collect();
    first_to_close(model, from, &passed, z)
}
