//! Two curves of one problem solved two ways, compared point by point.
use wavy::fe::{Curve, MeshLevel, NewtonOptions, SolveOptions, StepOptions};

/// The options of a curve on the coarse mesh to a/λ 0.4, Newton's default options changed by
/// `choose`: the cheap curve on which a choice of the Newton method is shown to change the path,
/// not the curve.
pub(crate) fn coarse_to_0_4(choose: impl FnOnce(&mut NewtonOptions)) -> SolveOptions {
    let mut newton = NewtonOptions::default();
    choose(&mut newton);
    SolveOptions {
        mesh: MeshLevel::Coarse,
        until_a_over_lambda: 0.4,
        newton,
        ..Default::default()
    }
}

/// [`coarse_to_0_4`] with the stepping options as `choose` sets them.
pub(crate) fn coarse_steps_to_0_4(choose: impl FnOnce(&mut StepOptions)) -> SolveOptions {
    let mut opts = coarse_to_0_4(|_| {});
    choose(&mut opts.steps);
    opts
}

/// The largest relative difference of a/λ and p̄/E* between the points of `a` and `b`, which
/// must have the same points (asserted).
pub(crate) fn largest_relative_difference(a: &Curve, b: &Curve) -> f64 {
    assert_eq!(a.points.len(), b.points.len(), "the two curves' points");
    let mut largest = 0.0_f64;
    for (p, q) in a.points.iter().zip(&b.points) {
        for (x, y) in [
            (p.a_over_lambda, q.a_over_lambda),
            (p.p_over_estar, q.p_over_estar),
        ] {
            largest = largest.max((x / y - 1.0).abs());
        }
    }
    largest
}
