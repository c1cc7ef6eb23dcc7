//! Landing on a mean-pressure target ([`SolveOptions::until_p_over_estar`]) between the last
//! converged state and the edge event that overshoots it.

use super::assembly::Assembly;
use super::loading::LoadPath;
use super::measure::{mean_pressure_over_estar, measure_between_events};
use super::model::{Model, State};
use super::newton::StepFail;
use super::predictor::displacement_step;
use super::step_control::{RegulaFalsi, StepCuts, Trial};
use super::{CurvePoint, SolveOptions};

/// Relative tolerance on `p̄/E*` of the landing on a pressure target
/// ([`SolveOptions::until_p_over_estar`]): far below the solver's other errors (the
/// discretisation's ~10⁻³), far above the round-off of the summed contact forces.
pub(crate) const PRESSURE_TARGET_RTOL: f64 = 1e-9;

/// Most trial displacements of the landing on a pressure target (regula falsi on a monotone
/// `p̄(d)` converges in a handful; a safeguard).
const MAX_PRESSURE_TRIALS: usize = 40;

/// The state at which `p̄/E*` equals `target`, between the last converged state of `path`
/// (below the target) and the edge event `(d, p̄/E*)` (above it): regula falsi on the slab
/// displacement (Illinois variant), each trial a displacement-controlled step with the
/// friction history of the last converged state, equilibrated with its active set and the
/// event's `node` kept free ([`displacement_step`]); a trial that fails is halved (at most
/// `max_step_cuts` times). Returns the state (slip committed), its point
/// ([`measure_between_events`]), its forces and the Newton iterations spent.
pub(crate) fn land_on_pressure(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    estar: f64,
    path: &LoadPath,
    node: usize,
    event: (f64, f64),
    target: f64,
) -> Result<(State, CurvePoint, Vec<f64>, usize), StepFail> {
    // the residual of the regula falsi: how far a trial's p̄/E* lies below the target;
    // each trial starts from the converged trial nearest below the target (its friction
    // history is still the last converged state's: only the starting point moves)
    let below_p = path.points.last().map_or(0.0, |p| p.p_over_estar);
    let mut search = RegulaFalsi::new(
        Trial {
            x: path.cur.d,
            f: target - below_p,
            at: path.cur.clone(),
        },
        None,
    );
    search.beyond = Some((event.0, target - event.1));
    let mut iters = 0;
    let mut cuts = StepCuts::new(opts.max_step_cuts);
    let mut next = search.next(0.0, 1.0).expect("bracketed by the event");
    for _ in 0..MAX_PRESSURE_TRIALS {
        let d = next;
        let start = &search.below.at;
        // the event's node touches only at the event: below it, it stays free (as in the
        // event search)
        let (st, it) = match displacement_step(model, asm, opts, start, d, Some(node)) {
            Ok(converged) => converged,
            Err(f) => {
                next = cuts.cut(start.d, d).ok_or(f)?;
                continue;
            }
        };
        iters += it;
        let f = asm
            .assemble(model, &st, false)
            .expect("converged state is not inverted");
        let p = mean_pressure_over_estar(model, &st, &f.grad, estar);
        if (p - target).abs() <= PRESSURE_TARGET_RTOL * target {
            let mut st = st;
            model.commit_slip(&mut st);
            let (point, grad) = measure_between_events(model, asm, &st, estar, opts);
            return Ok((st, point, grad, iters));
        }
        search.insert(Trial {
            x: d,
            f: target - p,
            at: st,
        });
        next = search.next(0.0, 1.0).expect("bracketed by the event");
    }
    Err(StepFail::Diverged {
        iteration: iters,
        residual: f64::NAN,
        reason: format!(
            "the slab displacement with p̄/E* = {target} was not found in {MAX_PRESSURE_TRIALS} trials"
        ),
    })
}
