//! The fixtures of the stepping's unit tests: a sinusoid on the coarse mesh, loaded and unloaded,
//! and the distance between two states.

use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::Assembly;
use crate::fe::stepping::loading::loading_branch;
use crate::fe::stepping::unloading::released_at_zero_force;
use crate::fe::test_problems::coarse_sinusoid;
use crate::fe::{build_model, estar_over_g, Interface, SolveOptions};

/// The converged states of the frictionless sinusoid of aspect ratio `aspect_ratio` (finite
/// kinematics, κ/G 1000, a layer one wavelength thick) on the coarse mesh, edge event by edge
/// event up to `until_a_over_lambda`, with the model, its assembly and the options.
pub(crate) fn loaded_sinusoid(
    aspect_ratio: f64,
    until_a_over_lambda: f64,
) -> (Model, Assembly, SolveOptions, Vec<State>) {
    loaded_sinusoid_with(aspect_ratio, until_a_over_lambda, Interface::Frictionless)
}

/// [`loaded_sinusoid`] with the interface `interface`.
pub(crate) fn loaded_sinusoid_with(
    aspect_ratio: f64,
    until_a_over_lambda: f64,
    interface: Interface,
) -> (Model, Assembly, SolveOptions, Vec<State>) {
    let (problem, mut opts) = coarse_sinusoid(aspect_ratio, interface);
    opts.until_a_over_lambda = until_a_over_lambda;
    let model = build_model(&problem, &opts);
    let mut asm = Assembly::new(&model);
    let estar = estar_over_g(problem.kappa_over_g);
    let mut states = Vec::new();
    loading_branch(&model, &mut asm, &opts, estar, &mut |_, at| {
        states.push(at.state.clone());
        std::ops::ControlFlow::Continue(())
    })
    .unwrap_or_else(|f| panic!("the coarse AR {aspect_ratio} curve: {}", f.error));
    (model, asm, opts, states)
}

/// Unloads the last of `states` through the `steps` loading displacements before it as the
/// unloading branch does: at each, the base's force-free nodes released
/// ([`released_at_zero_force`]), `step(asm, base, d)` takes the step to `d` and returns its
/// converged state, whose slip is committed and which is the next base.
pub(crate) fn unload_through(
    model: &Model,
    asm: &mut Assembly,
    states: &[State],
    steps: usize,
    mut step: impl FnMut(&mut Assembly, &State, f64) -> State,
) {
    let mut base = states.last().expect("a loaded state").clone();
    for target in states.iter().rev().skip(1).take(steps) {
        base = released_at_zero_force(model, asm, &base).unwrap_or(base);
        let mut next = step(asm, &base, target.d);
        asm.commit_slip(model, &mut next);
        base = next;
    }
}

/// The largest distance (units of λ, the larger coordinate) of a node of `a` from its place in `b`.
pub(crate) fn largest_distance(a: &State, b: &State) -> f64 {
    (a.x.iter().zip(&b.x))
        .map(|(p, q)| (p[0] - q[0]).abs().max((p[1] - q[1]).abs()))
        .fold(0.0, f64::max)
}
