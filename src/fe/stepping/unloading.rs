//! The unloading branch of a loading–unloading cycle: from the loaded state back to zero
//! load, with the friction history carried through.

use crate::fe::contact::measure::{measure_between_events, Measured};
use crate::fe::error::{CurveFailure, SolveError, StepFail};
use crate::fe::model::{Model, State};
use crate::fe::newton::active_set::{release_forces, release_scale};
use crate::fe::newton::assembly::Assembly;
use crate::fe::stepping::displacement_step::unloading_step;
use crate::fe::stepping::load_path::LoadPath;
use crate::fe::stepping::loading::loading_branch;
use crate::fe::stepping::step_control::{StepCuts, STEP_CUT_FACTOR};
use crate::fe::stepping::step_state::Converged;
use crate::fe::{Curve, CurvePoint, LoadDirection, SolveOptions};
use std::ops::ControlFlow;

/// Trace the loading branch as [`crate::fe::stepping::loading::trace`], then unload back to zero load with the friction
/// history carried through ([`unload`]); `on_step` sees every converged point with its
/// branch and a view of its state, and its `Break` stops the cycle ([`SolveError::Stopped`]).
pub(crate) fn trace_cycle(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    estar: f64,
    on_step: &mut dyn FnMut(LoadDirection, &CurvePoint, Converged<'_>) -> ControlFlow<()>,
) -> Result<Curve, Box<CurveFailure>> {
    let mut path = loading_branch(model, asm, opts, estar, &mut |p, at| {
        on_step(LoadDirection::Loading, p, at)
    })?;
    let unloading = unload(model, asm, opts, estar, &mut path, &mut |p, at| {
        on_step(LoadDirection::Unloading, p, at)
    })?;
    Ok(path.finish(model, asm, estar, unloading))
}

/// The unloading branch from the loaded state of `path` back to zero load.
///
/// Displacement-controlled: the slab retracts through the slab displacements of the loading
/// events in reverse (each interval in [`crate::fe::StepOptions::unloading_substeps`] equal
/// steps, [`retraced_displacements`]), then to `d = 0`, so that a frictionless (reversible) cycle revisits the loading
/// states and the two branches can be compared point by point. Each step (from its base with
/// the nodes that carry no force released, [`released_at_zero_force`]) predicts along the load
/// tangent, releases the contact edges tensile at the prediction, equilibrates (nodes whose
/// normal force turns tensile are released, the return mapping carries the slip history,
/// committed after every step; [`unloading_step`]) and is measured with the edge in the last loaded element, as at the
/// loading events ([`measure_between_events`]). A step that fails is approached through
/// intermediate displacements (the remaining increment halved, at most `max_step_cuts` times
/// in a row and never below the first event's increment cut as often, [`StepCuts`]) that serve as initial guesses only: the slip history is committed,
/// and points are recorded, at the scheduled displacements alone, so that the discrete load
/// path, and with it the dissipated energy, does not depend on where Newton needed help
/// (where the cuts fall moves with the round-off of the linear solves); a point's Newton
/// iterations count those of the intermediate steps and failed tries that led to it (all of a
/// failed try's: [`crate::fe::error::StepFail::iterations`]). When contact remains
/// at `d = 0` with a positive mean pressure (slip locked in by friction; "positive" meaning
/// above `residual_rtol` times the largest mean pressure of the cycle, the round-off of the
/// summed contact forces), the slab goes on retracting by the first event's increment until the last node
/// lets go; contact still held once the slab is as far out as it had been
/// pressed in is an error.
fn unload(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    estar: f64,
    path: &mut LoadPath,
    on_step: &mut dyn FnMut(&CurvePoint, Converged<'_>) -> ControlFlow<()>,
) -> Result<Vec<CurvePoint>, Box<CurveFailure>> {
    let mut retraction = Retraction::start(path, opts);
    loop {
        let next = retraction.next_target(path, opts);
        let Some(Target { d, scheduled }) = next.map_err(|e| retraction.fail(path, e))? else {
            break;
        };
        retraction
            .count_step(path, opts)
            .map_err(|e| retraction.fail(path, e))?;
        // exactly the target, so that a reversible cycle revisits the loading displacements
        let released = released_at_zero_force(model, asm, retraction.base(path));
        let base = released.as_ref().unwrap_or(retraction.base(path));
        let step = unloading_step(model, asm, opts, base, d);
        match step {
            Ok((mut st, iterations)) if scheduled => {
                asm.commit_slip(model, &mut st);
                let measured = measure_between_events(model, asm, &st, estar, opts);
                let flow = retraction.record(model, path, (st, measured), iterations, on_step);
                if flow.is_break() {
                    let points = path.points.len() + retraction.points.len();
                    return Err(retraction.fail(path, SolveError::Stopped { points }));
                }
            }
            Ok((st, iterations)) => retraction.pass_through(st, iterations),
            Err(failed) => retraction
                .cut(path, failed, d)
                .map_err(|e| retraction.fail(path, e))?,
        }
    }
    Ok(retraction.points)
}

/// A contact-face node carries no force, for the unloading branch, when its release force
/// ([`release_forces`]) is at most this times the largest: at the events it is 10⁻¹¹ of it, the
/// next smallest 0.05 (frictionless AR 0.3, meshes 48 and 96), so the choice is far from both.
const ZERO_FORCE_RTOL: f64 = 1e-6;

/// `st` with the active nodes that carry no force ([`ZERO_FORCE_RTOL`]) released; `None` when
/// there is none or `st` is inverted. The node that closed at a loading event carries no force
/// at its slab displacement, and any retraction makes its force tensile, so the unloading step
/// from there starts with it free rather than with an active-set pass that holds it on the
/// indenter. Without a normal force it has no friction force either, so the branch is the same,
/// only Newton's path to it shorter (docs/performance.md, "the force-free nodes released"; a node with
/// a positive force is left to the passes: released ahead by its predicted force, the branch
/// moves, 2026-11-29 there).
pub(in crate::fe::stepping) fn released_at_zero_force(
    model: &Model,
    asm: &mut Assembly,
    st: &State,
) -> Option<State> {
    let f = asm.assemble(model, st, false)?;
    let forces = release_forces(model, st, &f.grad);
    let scale = release_scale(&forces);
    let unloaded = |k: &usize| st.active[*k] && forces[*k] <= ZERO_FORCE_RTOL * scale;
    let zero: Vec<usize> = (0..st.active.len()).filter(unloaded).collect();
    if zero.is_empty() {
        return None;
    }
    let mut released = st.clone();
    for k in zero {
        released.active[k] = false;
    }
    Some(released)
}

/// One slab displacement the unloading branch steps to.
#[derive(Clone, Copy, Debug)]
struct Target {
    /// The slab displacement (units of λ).
    d: f64,
    /// Scheduled (committed and recorded as a point) or intermediate (an initial guess for the
    /// next target only).
    scheduled: bool,
}

/// Where the unloading branch stands between its steps.
struct Retraction {
    /// The targets still ahead, as a stack: the next one last.
    targets: Vec<Target>,
    /// The slab displacement of the loaded state (units of λ): contact still held with the slab
    /// as far out as it had been pressed in is an error.
    d_max: f64,
    /// How far the slab retracts per step past `d = 0` (units of λ): the first loading event's
    /// increment.
    retract_increment: f64,
    /// The intermediate state past the last committed one (`path.cur`), if the last step
    /// reached an intermediate target: where the next step starts ([`Self::base`]).
    passed: Option<State>,
    /// Newton iterations of the intermediate steps and failed tries since the last point.
    spent: usize,
    /// The step cuts made in a row, and their limits.
    cuts: StepCuts,
    /// Steps tried so far, intermediate and failed ones included.
    steps: usize,
    /// The unloading branch's points so far.
    points: Vec<CurvePoint>,
}

impl Retraction {
    /// At the loaded state of `path`, the loading points' displacements ahead in reverse
    /// ([`retraced_displacements`]), then `d = 0`.
    fn start(path: &LoadPath, opts: &SolveOptions) -> Self {
        let event_displacements = retraced_displacements(path, opts.steps.unloading_substeps);
        let d_max = path.cur.d;
        let retract_increment = event_displacements.first().copied().unwrap_or(d_max);
        let scheduled = |d| Target { d, scheduled: true };
        let mut targets = vec![scheduled(0.0)];
        let before_loaded = event_displacements.len().saturating_sub(1);
        targets.extend(
            event_displacements[..before_loaded]
                .iter()
                .map(|&d| scheduled(d)),
        );
        Self {
            targets,
            d_max,
            retract_increment,
            passed: None,
            spent: 0,
            cuts: unloading_cuts(opts, retract_increment),
            steps: 0,
            points: Vec::new(),
        }
    }

    /// Where the next step starts: the last committed state, or the intermediate one past it.
    fn base<'a>(&'a self, path: &'a LoadPath) -> &'a State {
        self.passed.as_ref().unwrap_or(&path.cur)
    }

    /// `p̄/E*` of the last point, unloading or (before the first) loading.
    fn last_p_over_estar(&self, path: &LoadPath) -> f64 {
        let last = self.points.last().or(path.points.last());
        last.map_or(0.0, |p| p.p_over_estar)
    }

    /// The next target; at `d = 0` or beyond, `None` once no contact force is left, else the
    /// slab retracted by [`Self::retract_increment`] more, and an error once it is as far out as
    /// it had been pressed in ([`SolveError::ContactPersists`]).
    fn next_target(
        &mut self,
        path: &LoadPath,
        opts: &SolveOptions,
    ) -> Result<Option<Target>, SolveError> {
        if let Some(&target) = self.targets.last() {
            return Ok(Some(target));
        }
        let active = path.cur.active.iter().filter(|&&b| b).count();
        let p_over_estar = self.last_p_over_estar(path);
        // zero load: within the round-off of the loaded state's p̄, the largest of the cycle
        let p_max_over_estar = path.points.last().map_or(0.0, |p| p.p_over_estar);
        if p_over_estar <= opts.newton.residual_rtol * p_max_over_estar || active == 0 {
            return Ok(None);
        }
        let d = path.cur.d - self.retract_increment;
        if d < -self.d_max {
            return Err(SolveError::ContactPersists {
                slab_displacement_over_lambda: path.cur.d,
                p_over_estar,
                active_nodes: active,
            });
        }
        let target = Target { d, scheduled: true };
        self.targets.push(target);
        Ok(Some(target))
    }

    /// Counts a step; more than `max_steps` is [`SolveError::TooManySteps`].
    fn count_step(&mut self, path: &LoadPath, opts: &SolveOptions) -> Result<(), SolveError> {
        self.steps += 1;
        match self.steps > opts.steps.max_steps {
            true => Err(SolveError::TooManySteps {
                steps: opts.steps.max_steps,
                a_over_lambda: path.a,
            }),
            false => Ok(()),
        }
    }

    /// A scheduled target reached (`state`, its slip committed, and what was measured there, in
    /// `iterations` Newton iterations of its own): recorded as the branch's next point, which
    /// `on_step` sees; the path moves on to it. Returns `on_step`'s answer.
    fn record(
        &mut self,
        model: &Model,
        path: &mut LoadPath,
        (state, measured): (State, Measured),
        iterations: usize,
        on_step: &mut dyn FnMut(&CurvePoint, Converged<'_>) -> ControlFlow<()>,
    ) -> ControlFlow<()> {
        let Measured {
            mut point, grad, ..
        } = measured;
        point.newton_iterations = std::mem::take(&mut self.spent) + iterations;
        let at = Converged {
            model,
            state: &state,
            grad: &grad,
        };
        let flow = on_step(&point, at);
        path.a = point.a_over_lambda;
        path.grad = grad;
        self.passed = None;
        path.prev = Some(std::mem::replace(&mut path.cur, state));
        self.points.push(point);
        self.targets.pop();
        self.cuts.reset();
        flow
    }

    /// An intermediate target reached: the next step starts from `state`.
    fn pass_through(&mut self, state: State, iterations: usize) {
        self.spent += iterations;
        self.passed = Some(state);
        self.targets.pop();
        self.cuts.reset();
    }

    /// The step to `target` failed: an intermediate target between it and the base goes first
    /// ([`StepCuts`]), or, with no cut left, [`SolveError::UnloadingStalled`].
    fn cut(&mut self, path: &LoadPath, failed: StepFail, target: f64) -> Result<(), SolveError> {
        let from = self.base(path).d;
        match self.cuts.cut(from, target) {
            Some(d) => {
                self.spent += failed.iterations();
                self.targets.push(Target {
                    d,
                    scheduled: false,
                });
                Ok(())
            }
            None => Err(SolveError::UnloadingStalled {
                slab_displacement_over_lambda: from,
                target,
                cuts: self.cuts.made(),
                reason: failed.into_error(self.steps, target).to_string(),
            }),
        }
    }

    /// The failure `error`, with the loading branch of `path` and the unloading points so far.
    fn fail(&mut self, path: &LoadPath, error: SolveError) -> Box<CurveFailure> {
        Box::new(CurveFailure {
            error,
            points: path.points.clone(),
            unloading: std::mem::take(&mut self.points),
        })
    }
}

/// The slab displacements the unloading branch retraces, in loading order: those of the loading
/// points exactly (so that a reversible cycle revisits the loading states), each interval from
/// the one before (from `d = 0` for the first) split into `substeps` equal steps.
fn retraced_displacements(path: &LoadPath, substeps: usize) -> Vec<f64> {
    let loading = path.points.iter().map(|p| p.slab_displacement_over_lambda);
    let mut from = 0.0;
    let mut retraced = Vec::with_capacity(path.points.len() * substeps);
    for to in loading {
        let between = (1..substeps).map(|j| from + (to - from) * j as f64 / substeps as f64);
        retraced.extend(between.chain([to]));
        from = to;
    }
    retraced
}

/// The cuts of the unloading steps: at most `max_step_cuts` in a row, and never to an increment
/// below `smallest_increment` (the first event's) cut `max_step_cuts` times. A converged
/// intermediate step resets the count of cuts in a row, so without the floor a Newton solve that
/// stalls above its tolerance would be approached by ever smaller steps that converge trivially,
/// one failure each, until `max_steps`.
fn unloading_cuts(opts: &SolveOptions, smallest_increment: f64) -> StepCuts {
    let cuts = opts.steps.max_step_cuts;
    let floor = smallest_increment * STEP_CUT_FACTOR.powi(cuts as i32);
    StepCuts::with_floor(cuts, floor)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::newton::active_set::{equilibrate, Hold};
    use crate::fe::stepping::displacement_step::displacement_step;
    use crate::fe::stepping::predictor::{predictor, tangent_at};
    use crate::fe::stepping::test_fixtures::{
        largest_distance, loaded_sinusoid_with, unload_through,
    };
    use crate::fe::Interface;

    /// The coarse AR 0.3 sinusoid with τ_max/E* 0.1 and μ 1, loaded to a/λ 0.3 event by event.
    fn loaded_with_friction() -> (Model, Assembly, SolveOptions, Vec<State>) {
        let interface = Interface::coulomb_orowan(1.0, 0.1, 0.005);
        loaded_sinusoid_with(0.3, 0.3, interface)
    }

    /// A frictional step's converged state does not depend on the order in which its contact
    /// set changed. Coarse AR 0.3, τ_max/E* 0.1, loaded to a/λ 0.3 and pressed a twentieth of
    /// an event interval further: the contact node next to the edge, released at the predicted
    /// state, penetrates, is put back by the active-set passes with the history committed at
    /// the step's start, and converges where the step that held it throughout does (positions
    /// apart by 3.7e-15 λ, asserted 1e-12 λ; started afresh on its return, 7.2e-3 λ).
    #[test]
    fn a_node_released_and_put_back_within_a_step_keeps_its_history() {
        let (model, mut asm, opts, states) = loaded_with_friction();
        let [before, loaded] = [2, 1].map(|back| &states[states.len() - back]);
        let d = loaded.d + 0.05 * (loaded.d - before.d);
        let tangent = tangent_at(&model, &mut asm, &opts, loaded);
        let predicted = predictor(&model, loaded, None, d - loaded.d, tangent.as_ref());
        let step = |asm: &mut Assembly, released: Option<usize>| {
            let mut st = predicted.clone().expect("a predicted state");
            if let Some(k) = released {
                st.active[k] = false;
            }
            model.enforce_constraints(&mut st);
            equilibrate(&model, asm, &mut st, &opts, Hold::NONE)
                .unwrap_or_else(|e| panic!("released {released:?}: {e:?}"));
            st
        };
        let throughout = step(&mut asm, None);
        let grad = asm
            .assemble(&model, &throughout, false)
            .expect("converged")
            .grad;
        let edge = (0..throughout.active.len())
            .rev()
            .find(|&k| throughout.active[k]);
        let node = edge.expect("contact") - 1;
        let put_back = step(&mut asm, Some(node));
        assert_eq!(put_back.active, throughout.active);
        let apart = largest_distance(&throughout, &put_back);
        let [normal, tangential] = [
            model.normal_forces(&throughout, &grad),
            model.tangential_forces(&throughout, &grad),
        ];
        let (n, t) = (normal[node], tangential[node]);
        println!("node {node} (N {n:.3e}, T {t:.3e} G λ): the two steps apart by {apart:.2e} λ");
        assert!(apart < 1e-12, "apart by {apart:.3e} λ");
    }

    /// Releasing the contact edges that are tensile at an unloading step's prediction changes
    /// Newton's path, not the state. Coarse AR 0.3, τ_max/E* 0.1, loaded to a/λ 0.3, then
    /// unloaded through the last seven loading displacements as the unloading branch does
    /// (force-free nodes released at each base, slip committed): at each, the plain displacement
    /// step and the unloading step converge to the same state (measured ≤ 8.1e-14 λ apart,
    /// asserted 1e-12 λ), the unloading step in 38 Newton iterations against 56. Its slip front
    /// held as the plain step's is ([`crate::fe::SlipFront::Held`]), so that the release alone
    /// differs.
    #[test]
    fn releasing_the_tensile_edge_changes_the_path_not_the_state() {
        let (model, mut asm, mut opts, states) = loaded_with_friction();
        opts.steps.slip_front = crate::fe::SlipFront::Held;
        let mut iterations = [0, 0];
        unload_through(&model, &mut asm, &states, 7, |asm, base, d| {
            let (plain, plain_iterations) =
                displacement_step(&model, asm, &opts, base, d, Hold::NONE).expect("the plain step");
            let (st, released_iterations) =
                unloading_step(&model, asm, &opts, base, d).expect("the unloading step");
            let apart = largest_distance(&plain, &st);
            println!(
                "d/λ {d:.5}: apart {apart:.2e} λ, {plain_iterations} against {released_iterations} iterations"
            );
            assert!(apart < 1e-12, "d/λ {d}: apart by {apart:.3e} λ");
            assert_eq!(plain.active, st.active);
            iterations[0] += plain_iterations;
            iterations[1] += released_iterations;
            st
        });
        println!(
            "Newton iterations: {} plain, {} released",
            iterations[0], iterations[1]
        );
        assert!(iterations[1] < iterations[0], "{iterations:?}");
    }
}
