//! The unloading branch of a loading–unloading cycle: from the loaded state back to zero
//! load, with the friction history carried through.

use crate::fe::contact::measure::{measure_between_events, Measured};
use crate::fe::error::{CurveFailure, SolveError};
use crate::fe::model::Model;
use crate::fe::newton::active_set::Hold;
use crate::fe::newton::assembly::Assembly;
use crate::fe::stepping::load_path::LoadPath;
use crate::fe::stepping::loading::loading_branch;
use crate::fe::stepping::predictor::displacement_step;
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
/// states and the two branches can be compared point by point. Each step predicts along the
/// load tangent, equilibrates (nodes whose normal force turns tensile are released, the
/// return mapping carries the slip history, committed after every step;
/// [`displacement_step`]) and is measured with the edge in the last loaded element, as at the
/// loading events ([`measure_between_events`]). A step that fails is approached through
/// intermediate displacements (the remaining increment halved, at most `max_step_cuts` times
/// in a row and never below the first event's increment cut as often, [`StepCuts`]) that serve as initial guesses only: the slip history is committed,
/// and points are recorded, at the scheduled displacements alone, so that the discrete load
/// path, and with it the dissipated energy, does not depend on where Newton needed help
/// (where the cuts fall moves with the round-off of the linear solves); a point's Newton
/// iterations count those of the intermediate steps and failed tries that led to it (of a failed
/// try, its last active-set pass: [`crate::fe::error::StepFail::iterations`]). When contact remains
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
    let event_displacements = retraced_displacements(path, opts.steps.unloading_substeps);
    let d_max = path.cur.d;
    let retract_increment = event_displacements.first().copied().unwrap_or(d_max);
    // targets as a stack, the next one last: scheduled displacements (committed and recorded) and
    // intermediate ones (initial guesses for the next target only)
    let mut targets: Vec<(f64, bool)> = vec![(0.0, true)];
    targets.extend(
        event_displacements
            .iter()
            .take(event_displacements.len().saturating_sub(1))
            .map(|&d| (d, true)),
    );
    let mut points: Vec<CurvePoint> = Vec::new();
    let fail = |path: &LoadPath, points: Vec<CurvePoint>, error: SolveError| {
        Box::new(CurveFailure {
            error,
            points: path.points.clone(),
            unloading: points,
        })
    };
    let mut cuts = unloading_cuts(opts, retract_increment);
    let mut steps = 0;
    let mut cur_p = path.points.last().map_or(0.0, |p| p.p_over_estar);
    // zero load: the round-off of p̄ relative to the largest load of the cycle
    let p_max = cur_p;
    // where the next step starts: the last committed state, or an intermediate one past it
    let mut base = path.cur.clone();
    // Newton iterations of the intermediate steps and failed tries since the last point
    let mut spent = 0;
    loop {
        let Some(&(target, scheduled)) = targets.last() else {
            // at d = 0 or beyond: done when no contact force is left
            let active = path.cur.active.iter().filter(|&&b| b).count();
            if cur_p <= opts.newton.residual_rtol * p_max || active == 0 {
                break;
            }
            let next = path.cur.d - retract_increment;
            if next < -d_max {
                let error = SolveError::ContactPersists {
                    slab_displacement_over_lambda: path.cur.d,
                    p_over_estar: cur_p,
                    active_nodes: active,
                };
                return Err(fail(path, points, error));
            }
            targets.push((next, true));
            continue;
        };
        steps += 1;
        if steps > opts.steps.max_steps {
            let error = SolveError::TooManySteps {
                steps: opts.steps.max_steps,
                a_over_lambda: path.a,
            };
            return Err(fail(path, points, error));
        }
        // exactly the target, so that a reversible cycle revisits the loading displacements
        match displacement_step(model, asm, opts, &base, target, Hold::NONE) {
            Ok((mut st, iters)) if scheduled => {
                asm.commit_slip(model, &mut st);
                let Measured {
                    mut point, grad, ..
                } = measure_between_events(model, asm, &st, estar, opts);
                point.newton_iterations = spent + iters;
                spent = 0;
                let at = Converged {
                    model,
                    state: &st,
                    grad: &grad,
                };
                let flow = on_step(&point, at);
                cur_p = point.p_over_estar;
                path.a = point.a_over_lambda;
                path.grad = grad;
                base = st.clone();
                path.prev = Some(std::mem::replace(&mut path.cur, st));
                points.push(point);
                if flow.is_break() {
                    let error = SolveError::Stopped {
                        points: path.points.len() + points.len(),
                    };
                    return Err(fail(path, points, error));
                }
                targets.pop();
                cuts.reset();
            }
            Ok((st, iters)) => {
                spent += iters;
                base = st;
                targets.pop();
                cuts.reset();
            }
            Err(f) => match cuts.cut(base.d, target) {
                Some(intermediate) => {
                    spent += f.iterations();
                    targets.push((intermediate, false));
                }
                None => {
                    let error = SolveError::UnloadingStalled {
                        slab_displacement_over_lambda: base.d,
                        target,
                        cuts: cuts.made(),
                        reason: f.into_error(steps, target).to_string(),
                    };
                    return Err(fail(path, points, error));
                }
            },
        }
    }
    Ok(points)
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
