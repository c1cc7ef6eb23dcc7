//! Landing on a mean-pressure target ([`SolveOptions::until_p_over_estar`]) between the last
//! converged state and the edge event that overshoots it.

use crate::fe::contact::measure::{mean_pressure_over_estar, measure_between_events, Measured};
use crate::fe::error::{FailCause, StepFail};
use crate::fe::model::{Model, State};
use crate::fe::newton::active_set::Hold;
use crate::fe::newton::assembly::Assembly;
use crate::fe::stepping::displacement_step::displacement_step;
use crate::fe::stepping::step_control::{RegulaFalsi, StepCuts, Trial};
use crate::fe::SolveOptions;

/// Relative tolerance on `p̄/E*` of the landing on a pressure target
/// ([`SolveOptions::until_p_over_estar`]): far below the solver's other errors (the
/// discretisation's ~10⁻³), far above the round-off of the summed contact forces.
pub(crate) const PRESSURE_TARGET_RTOL: f64 = 1e-9;

/// Most trial displacements of the landing on a pressure target (regula falsi on a monotone
/// `p̄(d)` converges in a handful; a safeguard).
const MAX_PRESSURE_TRIALS: usize = 40;

/// An edge event that overshoots a pressure target, and the converged state before it.
pub(crate) struct Overshoot<'a> {
    /// The last converged state, below the target.
    pub below: &'a State,
    /// Its `p̄/E*`.
    pub below_p_over_estar: f64,
    /// The event's node: it touches only at the event, so below it the node stays free.
    pub node: usize,
    /// The event's slab displacement (units of λ) and `p̄/E*`, beyond the target.
    pub event: (f64, f64),
}

/// The state at which `p̄/E*` equals `target`, between the state `below` the target and
/// the edge event beyond it ([`Overshoot`]): regula falsi on the slab
/// displacement (Illinois variant), each trial a displacement-controlled step with the
/// friction history of the last converged state, equilibrated with its active set and the
/// event's `node` kept free ([`displacement_step`]); a trial that fails is halved (at most
/// `max_step_cuts` times). Returns the state (slip committed), what
/// [`measure_between_events`] finds in it (point, forces, patches) and the Newton iterations
/// spent.
pub(crate) fn land_on_pressure(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    estar: f64,
    overshoot: Overshoot<'_>,
    target: f64,
) -> Result<(State, Measured, usize), StepFail> {
    // the residual of the regula falsi: how far a trial's p̄/E* lies below the target;
    // each trial starts from the converged trial nearest below the target (its friction
    // history is still the last converged state's: only the starting point moves)
    let Overshoot {
        below,
        below_p_over_estar,
        node,
        event,
    } = overshoot;
    let mut search = RegulaFalsi::new(
        Trial {
            x: below.d,
            f: target - below_p_over_estar,
            at: below.clone(),
        },
        None,
    );
    search.beyond = Some((event.0, target - event.1));
    let mut iters = 0;
    let mut cuts = StepCuts::new(opts.steps.max_step_cuts);
    let mut next = search.next(0.0, 1.0).expect("bracketed by the event");
    for _ in 0..MAX_PRESSURE_TRIALS {
        let d = next;
        let start = &search.below.at;
        // the event's node touches only at the event: below it, it stays free (as in the
        // event search)
        let (st, it) = match displacement_step(model, asm, opts, start, d, Hold::free(Some(node))) {
            Ok(converged) => converged,
            Err(f) => {
                next = cuts.after_failure((start.d, d), f, &mut iters)?;
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
            asm.commit_slip(model, &mut st);
            let measured = measure_between_events(model, asm, &st, estar, opts);
            return Ok((st, measured, iters));
        }
        search.insert(Trial {
            x: d,
            f: target - p,
            at: st,
        });
        next = search.next(0.0, 1.0).expect("bracketed by the event");
    }
    Err(StepFail::from(FailCause::Diverged {
        iteration: iters,
        residual: f64::NAN,
        reason: format!(
            "the slab displacement with p̄/E* = {target} was not found in {MAX_PRESSURE_TRIALS} trials"
        ),
    }))
}
