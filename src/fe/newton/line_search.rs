//! The backtracking line search of a Newton step: the trial states `α = 1, ½, ¼, …` along the
//! step, and what each must decrease (the energy, Armijo, or a residual merit).

use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::{Assembly, Forces};

/// Sufficient-decrease constant `c` of the backtracking line search, in the energy
/// Armijo test `Π(α) ≤ Π₀ + c α r·δ` and in the merit test `m(α) < (1 − c α) m₀`: the
/// customary value (Nocedal & Wright, *Numerical Optimization*, §3.1), small enough that
/// the full Newton step passes wherever Newton converges.
const ARMIJO_C: f64 = 1e-4;

/// Slack of the energy Armijo test relative to `|Π₀|`. Round-off argument: `Π` is a sum
/// of ~10³ element energies (1152 on the default mesh), each exact to about one ulp, so it
/// carries a relative error up to `N ε ≈ 10⁻¹³`; near convergence the energy change of a
/// correct step drops below that and would be rejected without the slack.
const ENERGY_ROUNDOFF_SLACK: f64 = 1e-13;

/// Step-length factor per backtracking step (halving: [`crate::fe::NewtonOptions::max_line_search`]
/// and [`crate::fe::NewtonOptions::max_edge_line_search`] count halvings).
const LINE_SEARCH_BACKTRACK: f64 = 0.5;

/// What a line-search trial must decrease.
pub(crate) enum Decrease<'a> {
    /// The energy, Armijo: `Π(α) ≤ Π₀ + c α slope + ε |Π₀|` with `slope = r·δ < 0`
    /// ([`ARMIJO_C`], [`ENERGY_ROUNDOFF_SLACK`]).
    Energy {
        /// `Π₀`.
        initial: f64,
        /// Directional derivative `r·δ` of the energy along the step.
        slope: f64,
    },
    /// A merit `m(trial, forces)`: `m(α) < (1 − c α) m₀`.
    Merit {
        /// `m₀`.
        initial: f64,
        /// The merit of a trial state given its forces.
        merit: &'a dyn Fn(&Model, &State, &Forces) -> f64,
    },
    /// Nothing: the step is exact (quadratic energy); the first non-inverted trial is
    /// taken.
    Exact,
}

impl Decrease<'_> {
    fn accepts(&self, model: &Model, trial: &State, forces: &Forces, alpha: f64) -> bool {
        match self {
            Decrease::Energy { initial, slope } => {
                forces.energy
                    <= initial + ARMIJO_C * alpha * slope + ENERGY_ROUNDOFF_SLACK * initial.abs()
            }
            Decrease::Merit { initial, merit } => {
                merit(model, trial, forces) < (1.0 - ARMIJO_C * alpha) * initial
            }
            Decrease::Exact => true,
        }
    }
}

/// Backtracking line search: the first of the trial states `trial_at(α)`,
/// `α = 1, ½, ¼, …` (at most `max_trials`), that is not inverted and satisfies
/// `decrease`; `None` if there is none. The forces of the accepted state stay cached in
/// the model for the next convergence check.
pub(crate) fn line_search(
    model: &Model,
    asm: &mut Assembly,
    max_trials: usize,
    trial_at: impl Fn(&Model, f64) -> State,
    decrease: Decrease<'_>,
) -> Option<State> {
    let mut alpha = 1.0;
    for _ in 0..max_trials {
        let trial = trial_at(model, alpha);
        if let Some(f) = asm.assemble(model, &trial, false) {
            if decrease.accepts(model, &trial, &f, alpha) {
                return Some(trial);
            }
        }
        alpha *= LINE_SEARCH_BACKTRACK;
    }
    None
}
