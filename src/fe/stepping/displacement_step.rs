//! A displacement-controlled load step: from a converged state to a slab displacement, predicted
//! along the load path ([`crate::fe::stepping::predictor`]) and equilibrated with its active set.
//! The loading curve's steps between events and the searches take it as it is
//! ([`displacement_step`]); the unloading branch's steps are predicted through their slip front,
//! first let go of the tensile contact edges of their prediction, and are cut instead of started
//! from a crude guess ([`unloading_step`]).

use crate::fe::error::{FailCause, StepFail};
use crate::fe::model::{Model, State};
use crate::fe::newton::active_set::{equilibrate, release_tensile_edges, Hold};
use crate::fe::newton::assembly::Assembly;
use crate::fe::stepping::predictor::{
    crude_prediction, tangent_at, taylor_prediction, unloading_tangent_at, LoadTangent, TaylorOrder,
};
use crate::fe::SolveOptions;

/// A displacement-controlled step from the converged state `from` to the slab displacement
/// `d` (exactly: `from.d + (d − from.d)` may differ from `d` in the last bit): predicted along
/// the load tangent of `from` (where every Taylor prediction inverts an element, from a crude
/// one, [`crude_prediction`]), then equilibrated with its active set, the nodes of `hold` kept
/// as they are. With friction, a step that fails from the second-order prediction is tried
/// again from the first-order one: at μ 100 the second-order predictor stopped two unloading
/// branches at mesh 96 (a line search that found no step, the residual at 7·10⁻⁷) that the
/// first-order one completes (docs/performance.md, "friction's predictor"). Returns the state
/// (slip not committed) and the Newton iterations, a failed first try's included; a failure
/// counts the iterations of both tries.
pub(crate) fn displacement_step(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    from: &State,
    d: f64,
    hold: Hold,
) -> Result<(State, usize), StepFail> {
    Step {
        from,
        d,
        hold,
        direction: Direction::Loading,
    }
    .taken(model, asm, opts)
}

/// An unloading step from the converged state `from` to the slab displacement `d`: a
/// [`displacement_step`] whose predicted state first lets go of the contact patches' edge nodes
/// that are tensile there ([`release_tensile_edges`], the forces of its predicted pressures), as
/// the contact recedes from its edges, instead of holding them through a first active-set pass. A
/// node so released that the step puts back keeps its history ([`Model::activate`]), so the release
/// changes Newton's path (−11 to −29 % of the unloading's iterations on the mesh-48 loops), not the
/// state it converges to, wherever the step has one state; where it has two (at μ 100 an edge node
/// in contact with a small force, or free and clear of the indenter) it may find the other
/// (docs/performance.md, "the tensile edge released at the prediction"). Its prediction follows the
/// stuck nodes that start to slide in the step ([`unloading_tangent_at`],
/// [`crate::fe::stepping::slip_front`]). A step whose every Taylor prediction inverts an element
/// fails at once, unsolved, and the unloading branch cuts it: Newton from a crude guess spent 30
/// iterations and failed there (docs/performance.md, "an unloading step without a Taylor prediction
/// is cut").
pub(crate) fn unloading_step(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    from: &State,
    d: f64,
) -> Result<(State, usize), StepFail> {
    Step {
        from,
        d,
        hold: Hold::NONE,
        direction: Direction::Unloading,
    }
    .taken(model, asm, opts)
}

/// The branch a displacement step belongs to, which decides what it does besides predicting
/// along the load tangent and equilibrating.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Direction {
    /// A step of the loading curve or a search: its prediction is the load tangent's, from a
    /// crude one where every Taylor prediction inverts an element ([`crude_prediction`]), and the
    /// active-set passes release what turns tensile.
    Loading,
    /// A step of the unloading branch ([`unloading_step`]): predicted through its slip front
    /// ([`unloading_tangent_at`]), its contact edges tensile at the prediction released, and
    /// failed unsolved ([`FailCause::Inverted`], no iteration spent) where every Taylor
    /// prediction inverts an element.
    Unloading,
}

/// A displacement-controlled step: from the converged state `from` to the slab displacement `d`,
/// the nodes of `hold` kept as they are, as its `direction` does ([`displacement_step`],
/// [`unloading_step`]).
struct Step<'a> {
    from: &'a State,
    d: f64,
    hold: Hold,
    direction: Direction,
}

impl Step<'_> {
    /// The step from its prediction; with friction, where that prediction kept the path's
    /// curvature and failed, again from the first-order one (the same prediction otherwise, so
    /// not tried twice).
    fn taken(
        &self,
        model: &Model,
        asm: &mut Assembly,
        opts: &SolveOptions,
    ) -> Result<(State, usize), StepFail> {
        let tangent = match self.direction {
            Direction::Loading => tangent_at(model, asm, opts, self.from),
            Direction::Unloading => {
                unloading_tangent_at(model, asm, opts, self.from, self.d - self.from.d)
            }
        };
        let (st, order) = self.predicted(model, tangent.as_ref())?;
        let first = self.equilibrated(model, asm, opts, st);
        match (first, tangent) {
            (Err(failed), Some(z))
                if !model.is_potential() && order == Some(TaylorOrder::Curved) =>
            {
                let first_order = z.first_order();
                let spent = failed.iterations();
                let (st, iterations) = self
                    .predicted(model, Some(&first_order))
                    .and_then(|(st, _)| self.equilibrated(model, asm, opts, st))
                    .map_err(|retry| retry.after(spent))?;
                Ok((st, iterations + spent))
            }
            (result, _) => result,
        }
    }

    /// The predicted state at `d` along `tangent` ([`taylor_prediction`]), with the terms it kept;
    /// without a tangent, or loading where every Taylor prediction inverts, a crude one (no
    /// terms, `None`).
    fn predicted(
        &self,
        model: &Model,
        tangent: Option<&LoadTangent>,
    ) -> Result<(State, Option<TaylorOrder>), StepFail> {
        let dd = self.d - self.from.d;
        let crude = || crude_prediction(model, self.from, None, dd).map(|st| (st, None));
        let predicted = match (tangent, self.direction) {
            (None, _) => crude(),
            (Some(z), direction) => match taylor_prediction(model, self.from, dd, z) {
                Some((st, order)) => Some((st, Some(order))),
                None if direction == Direction::Loading => crude(),
                None => None,
            },
        };
        let (mut st, order) = predicted.ok_or(StepFail::from(FailCause::Inverted {
            iteration: 0,
            residual: f64::NAN,
        }))?;
        st.d = self.d;
        model.enforce_constraints(&mut st);
        Ok((st, order))
    }

    /// The predicted state `st` (unloading, the contact edges it holds in tension released)
    /// equilibrated, with its Newton iterations.
    fn equilibrated(
        &self,
        model: &Model,
        asm: &mut Assembly,
        opts: &SolveOptions,
        mut st: State,
    ) -> Result<(State, usize), StepFail> {
        if self.direction == Direction::Unloading {
            release_tensile_edges(model, asm, opts, &mut st);
        }
        let iters = equilibrate(model, asm, &mut st, opts, self.hold)?;
        Ok((st, iters))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::error::SolveError;
    use crate::fe::newton::active_set::release_forces;
    use crate::fe::stepping::test_fixtures::{loaded_sinusoid_with, unload_through};
    use crate::fe::Interface;

    /// The coarse AR 0.3 sinusoid with τ_max/E* 0.1 and μ 1, loaded to a/λ 0.3 event by event:
    /// the model, its assembly, the options and the converged state of every event.
    fn loaded_states() -> (Model, Assembly, SolveOptions, Vec<State>) {
        let interface = Interface::coulomb_orowan(1.0, 0.1, 0.005);
        loaded_sinusoid_with(0.3, 0.3, interface)
    }

    /// [`loaded_states`]' model, assembly and options, with its loaded state and the one before
    /// it.
    fn loaded() -> (Model, Assembly, SolveOptions, State, State) {
        let (model, asm, opts, mut states) = loaded_states();
        let loaded = states.pop().expect("a loaded state");
        let before = states.pop().expect("a state before it");
        (model, asm, opts, loaded, before)
    }

    /// The release test of an unloading step's prediction, on the forces of the prediction's
    /// element pressures, finds edges that the displacement method's forces there hold
    /// compressive, and releases none that the step does not release. The sinusoid of
    /// [`loaded_states`] unloaded through its last seven loading displacements as the unloading
    /// branch does: at 3 of them the displacement method's force of the edge released there is
    /// compressive, and at each the nodes released at the prediction are free where the plain
    /// displacement step (nothing released at the prediction) converges.
    #[test]
    fn the_predicted_pressures_release_what_the_step_releases() {
        let (model, mut asm, opts, states) = loaded_states();
        let mut found_by_pressures = 0;
        unload_through(&model, &mut asm, &states, 7, |asm, base, d| {
            let step = Step {
                from: base,
                d,
                hold: Hold::NONE,
                direction: Direction::Unloading,
            };
            let tangent = unloading_tangent_at(&model, asm, &opts, base, d - base.d);
            let (mut st, _) = step
                .predicted(&model, tangent.as_ref())
                .expect("a prediction");
            let grad = asm.assemble(&model, &st, false).expect("not inverted").grad;
            let displacement_method = release_forces(&model, &st, &grad);
            let active = st.active.clone();
            release_tensile_edges(&model, asm, &opts, &mut st);
            let released: Vec<usize> = (0..active.len())
                .filter(|&k| active[k] && !st.active[k])
                .collect();
            let (plain, _) =
                displacement_step(&model, asm, &opts, base, d, Hold::NONE).expect("the plain step");
            println!("d/λ {d:.5}: released {released:?}");
            for &k in &released {
                assert!(!plain.active[k], "d/λ {d}: node {k} in contact");
                found_by_pressures += usize::from(displacement_method[k] >= 0.0);
            }
            unloading_step(&model, asm, &opts, base, d)
                .expect("the unloading step")
                .0
        });
        assert_eq!(found_by_pressures, 3);
    }

    /// A failed step counts every Newton iteration it spent: both tries, the curved prediction's
    /// and the first-order one's. Newton allowed one iteration per pass: the unloading step to
    /// the loading displacement before the loaded one fails in the first pass of each try, and
    /// reports 2 iterations (the failed retry's alone, 1, before).
    #[test]
    fn a_failed_step_counts_both_tries() {
        let (model, mut asm, mut opts, loaded, before) = loaded();
        opts.newton.max_iterations = 1;
        let failed = unloading_step(&model, &mut asm, &opts, &loaded, before.d)
            .expect_err("one Newton iteration is not enough");
        assert_eq!(failed.iterations(), 2);
    }

    /// An unloading step whose every Taylor prediction inverts an element fails unsolved, for
    /// the branch to cut, where a step of the loading branch starts Newton from a crude guess:
    /// the slab pulled up by a whole wavelength from the loaded state.
    #[test]
    fn an_unloading_step_whose_predictions_invert_fails_unsolved() {
        let (model, mut asm, opts, loaded, _) = loaded();
        let d = loaded.d - 1.0;
        let tangent = tangent_at(&model, &mut asm, &opts, &loaded).expect("a load tangent");
        assert!(taylor_prediction(&model, &loaded, d - loaded.d, &tangent).is_none());
        let failed = unloading_step(&model, &mut asm, &opts, &loaded, d)
            .expect_err("no prediction to start from");
        assert_eq!(failed.iterations(), 0);
        let error = failed.into_error(1, d);
        assert!(
            matches!(error, SolveError::Inverted { iteration: 0, .. }),
            "{error}"
        );
        let crude = displacement_step(&model, &mut asm, &opts, &loaded, d, Hold::NONE);
        let spent = crude.map_or_else(|f| f.iterations(), |(_, iterations)| iterations);
        assert!(spent > 0, "the crude guess was solved from");
    }
}
