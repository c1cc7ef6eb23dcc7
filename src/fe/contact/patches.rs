//! The contact of a converged state as patches: maximal runs of loaded contact-face nodes,
//! each with its two edges placed by the edge rule, and the contact fraction they add up to.
//!
//! A node is loaded when its vertical contact multiplier `λ` is clearly positive (above
//! [`crate::fe::contact::edge_rule::loaded_threshold`], as
//! [`crate::fe::contact::edge_rule::loaded_edge_node`] reads it),
//! except the node of an event, which touches with zero force by construction (its force is
//! the remainder of the event's gap tolerance, far above `multiplier_rtol`).
//! For a profile with finer harmonics the patches and their edges are those of
//! [`crate::fe::contact::patch_edge`] (each edge placed between its own events, openings that close
//! after a merge, young patches by their gaps). For a single sinusoid, whose points are its one
//! edge's own events, a run of loaded nodes `i₀ … i₁` (face order, increasing `X`) is one patch:
//! * its right edge lies in `[x_{i₁}, x_{i₁+1}]` and its left edge in `[x_{i₀−1}, x_{i₀}]`
//!   (current positions), each at the edge rule's fraction of the element measured from the
//!   loaded node ([`crate::fe::EdgeRule::fraction`]; a rule that fits gaps places the right edge of the
//!   patch at the peak as [`edge_position`] does and uses
//!   [`crate::fe::contact::edge_rule::DISCRETE_EDGE_FRACTION`] for the other edges, which its fits do not
//!   cover);
//! * a patch that reaches a symmetry line (the peak node 0 at `x = 0`, the valley node at
//!   `x = ½`) has its edge there: the patch continues in the mirror image.
//!
//! The contact fraction is the total contact length over λ: the patches of the half
//! wavelength `[0, ½]` and their mirror images, `2 Σ (end − start)`; `2a/λ` for the single
//! patch `[0, a]` of a sinusoid.

use crate::fe::contact::edge_rule::{edge_position, loaded_threshold};
use crate::fe::contact::patch_edge::{profile_patches, TravellingEdge};
use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::Forces;
use crate::fe::SolveOptions;

/// The contact patches of `st` (with assembled forces `f`) in `[0, ½]`, in order of `x`,
/// each `[start, end]` (units of λ, current positions), and those of a profile's edges that
/// travel between their own events ([`TravellingEdge`]; none for a sinusoid); `event` is the
/// node of the event that produced `st`, if any.
pub(crate) fn contact_patches(
    model: &Model,
    st: &State,
    f: &Forces,
    opts: &SolveOptions,
    event: Option<usize>,
) -> (Vec<[f64; 2]>, Vec<TravellingEdge>) {
    let rule = opts.contact.edge_rule;
    let lam = model.multipliers(st, &f.grad);
    let threshold = loaded_threshold(model, &lam, opts, f.force_scale);
    let loaded: Vec<bool> = lam
        .iter()
        .enumerate()
        .map(|(i, &l)| l > threshold && event != Some(i))
        .collect();
    if !model.indenter.profile.is_sinusoid() {
        return profile_patches(model, st, rule, (&lam, &loaded), event, runs(&loaded));
    }
    let b = &model.mesh.bottom;
    let last = b.len() - 1;
    let x = |i: usize| st.x[b[i]][0];
    let phi = |loaded: usize, free: usize| rule.fraction(model, st, loaded, free);
    let mut patches = Vec::new();
    for [i0, i1] in runs(&loaded) {
        let start = if i0 == 0 {
            x(0)
        } else {
            x(i0) - phi(i0, i0 - 1) * (x(i0) - x(i0 - 1))
        };
        let end = if i1 == last {
            x(last)
        } else if i0 == 0 {
            edge_position(model, st, i1 + 1, rule)
        } else {
            x(i1) + phi(i1, i1 + 1) * (x(i1 + 1) - x(i1))
        };
        patches.push([start, end]);
    }
    (patches, Vec::new())
}

/// The maximal runs of `true` in `flags`, as `[first, last]` index pairs in order.
pub(crate) fn runs(flags: &[bool]) -> Vec<[usize; 2]> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < flags.len() {
        if !flags[i] {
            i += 1;
            continue;
        }
        let first = i;
        while i + 1 < flags.len() && flags[i + 1] {
            i += 1;
        }
        out.push([first, i]);
        i += 1;
    }
    out
}

/// Total contact length over λ of the patches of a half wavelength and their mirror images.
pub fn contact_fraction(patches: &[[f64; 2]]) -> f64 {
    2.0 * patches.iter().map(|p| p[1] - p[0]).sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_are_the_maximal_runs_of_true() {
        let (t, f) = (true, false);
        assert_eq!(
            runs(&[t, t, f, t, f, f, t, t, t]),
            vec![[0, 1], [3, 3], [6, 8]]
        );
        assert_eq!(runs(&[f, f]), Vec::<[usize; 2]>::new());
        assert_eq!(runs(&[]), Vec::<[usize; 2]>::new());
    }
}
