//! The start of a load step: the load path's first and second derivatives `∂q/∂d`, `∂²q/∂d²`
//! at a converged state, the predicted state at a new slab displacement (Taylor along the path),
//! and the displacement-controlled step that predicts and equilibrates.
//!
//! The second derivative costs two residual assemblies and a solve with the factorisation the
//! first left: along the path `r(q(d), d) = 0`, so `K q'' = −∂²r[(q', 1), (q', 1)]`, and the
//! right-hand side is the central difference of the residual along `(q', 1)`. Without friction
//! it more than halves the Newton iterations of an edge event at the default mesh
//! (docs/performance.md); with friction the predictor stays first order ([`load_tangent`]).
//!
//! The third-order term costs nothing to solve: the error of the last step's second-order
//! prediction, measured at its converged state, is `q''' dd³/6` to leading order, and the next
//! step, a segment of the same path between its neighbouring events, adds it scaled by the cube of
//! its own increment ([`third_order_term`]). It lowers the Newton iterations of the long steps
//! toward the valley (docs/performance.md, "the third-order term").

use crate::fe::error::StepFail;
use crate::fe::model::{Model, State};
use crate::fe::newton::active_set::{equilibrate, Hold};
use crate::fe::newton::assembly::Assembly;
use crate::fe::{Kinematics, SolveOptions};

/// The difference step of the path's second derivative over the indenter amplitude `Δ`: its
/// central difference has a truncation error of order `ε²` and a round-off of order
/// `10⁻¹⁶ f_e / ε²`. A numerical choice, not tuned: at `10⁻⁴ Δ` the predicted state's residual
/// falls as `dd³` over the steps of a curve (test `the_predictor_is_second_order_along_the_path`).
const CURVATURE_STEP_OVER_AMPLITUDE: f64 = 1e-4;

/// The load path at a converged state: `∂q/∂d` (slot-wise, the load tangent) and, where it
/// could be computed, `∂²q/∂d²`, with the third-order term the last step measured, if any.
/// Dereferences to `∂q/∂d`.
#[derive(Clone, Debug)]
pub(crate) struct LoadTangent {
    rate: Vec<f64>,
    curvature: Option<Vec<f64>>,
    /// `q'''/6` per node position (units `λ⁻²`: times `dd³` a position in units of λ), the last
    /// step's measure of it ([`third_order_term`]); none for the first step, where the
    /// curvature is not computed, and after a release or a landing.
    third_order: Option<Vec<[f64; 2]>>,
}

impl LoadTangent {
    /// `∂²q/∂d²`, where it was computed.
    pub(crate) fn curvature(&self) -> Option<&[f64]> {
        self.curvature.as_deref()
    }

    /// The tangent with the third-order term `third_order` ([`third_order_term`]) for its
    /// predictor.
    pub(crate) fn with_third_order(self, third_order: Option<Vec<[f64; 2]>>) -> Self {
        Self {
            third_order,
            ..self
        }
    }
}

impl std::ops::Deref for LoadTangent {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        &self.rate
    }
}

/// `∂q/∂d` at a converged state, `K ∂q/∂d = −∂r/∂d`, and under finite kinematics without
/// friction `∂²q/∂d²` ([`path_curvature`]); `None` if the state is inverted or the solve fails.
/// Under linear kinematics the frictionless path is straight between two events (the Euler
/// predictor is exact there, and a difference quotient would only add its round-off). With friction the
/// residual depends on the slip history and a stick node's band is a few thousandths of an
/// element wide, so the difference at `d − ε` unloads and the one at `d + ε` may cross a
/// stick–slip switch: the quotient is not the path's curvature, and the Euler predictor is
/// used (measured at AR 0.3, τ_max 0.1 MPa: the second-order one cost 5–20 % more Newton iterations
/// on meshes 48 and 96).
pub(crate) fn load_tangent(model: &Model, asm: &mut Assembly, st: &State) -> Option<LoadTangent> {
    let f = asm.assemble(model, st, true)?;
    let mut rhs = [f.dresid_dd.iter().map(|v| -v).collect::<Vec<f64>>()];
    asm.sys.solve(&mut rhs).ok()?;
    let [rate] = rhs;
    let curvature = match (model.is_potential(), model.kin) {
        (true, Kinematics::Finite) => path_curvature(model, asm, st, &f.resid, &rate),
        _ => None,
    };
    Some(LoadTangent {
        rate,
        curvature,
        third_order: None,
    })
}

/// `∂²q/∂d²` at the converged state `st` (residual `resid`, load tangent `rate`), the matrix
/// of `st` still factored: `K q'' = −(r₊ + r₋ − 2 r₀)/ε²`, `r±` the residuals at
/// `(q ± ε q', d ± ε)` ([`CURVATURE_STEP_OVER_AMPLITUDE`]); `None` where a trial is inverted
/// or the solve fails.
fn path_curvature(
    model: &Model,
    asm: &mut Assembly,
    st: &State,
    resid: &[f64],
    rate: &[f64],
) -> Option<Vec<f64>> {
    let eps = CURVATURE_STEP_OVER_AMPLITUDE * model.indenter.amplitude();
    let mut along = |step: f64| {
        let mut moved = st.clone();
        moved.d = st.d + step;
        model.enforce_constraints(&mut moved);
        let moved = model.updated(&moved, rate, step);
        asm.assemble(model, &moved, false).map(|f| f.resid)
    };
    let (plus, minus) = (along(eps)?, along(-eps)?);
    let second: Vec<f64> = (plus.iter().zip(&minus).zip(resid))
        .map(|((p, m), r)| -(p + m - 2.0 * r) / (eps * eps))
        .collect();
    let mut rhs = [second];
    asm.sys.solve_again(&mut rhs).ok()?;
    let [curvature] = rhs;
    curvature.iter().all(|v| v.is_finite()).then_some(curvature)
}

/// The load tangent of `st` for the predictor if [`StepOptions::tangent_predictor`] is on
/// ([`load_tangent`]).
pub(crate) fn tangent_at(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    st: &State,
) -> Option<LoadTangent> {
    opts.steps
        .tangent_predictor
        .then(|| load_tangent(model, asm, st))
        .flatten()
}

/// Predictor for the slab displacement `cur.d + dd`: the third-order Taylor predictor
/// `q + dd ∂q/∂d + ½ dd² ∂²q/∂d² + dd³ q'''/6` along the load path `tangent` of the converged
/// state (where it carries the third-order term), then the second-order one without the last
/// term, then the tangent (Euler) predictor, else linear extrapolation of the last increment, else
/// a uniform vertical compression. The first that has no inverted element is used.
pub(crate) fn predictor(
    model: &Model,
    cur: &State,
    prev: Option<&State>,
    dd: f64,
    tangent: Option<&LoadTangent>,
) -> Option<State> {
    let h = model.mesh.thickness;
    let mut tries: Vec<State> = Vec::new();
    if let Some(z) = tangent {
        let (euler, second) = taylor(model, cur, dd, z);
        if let (Some(second), Some(term)) = (&second, &z.third_order) {
            tries.push(moved_by(second, term, dd * dd * dd));
        }
        tries.extend(second);
        tries.push(euler);
    }
    if let Some(p) = prev {
        let ddp = cur.d - p.d;
        if ddp > 0.0 {
            let s = dd / ddp;
            let mut st = cur.clone();
            for (xn, (xc, xp)) in st.x.iter_mut().zip(cur.x.iter().zip(&p.x)) {
                xn[0] = xc[0] + s * (xc[0] - xp[0]);
                xn[1] = xc[1] + s * (xc[1] - xp[1]);
            }
            st.d = cur.d + dd;
            tries.push(st);
        }
    }
    let mut st = cur.clone();
    for (xn, xr) in st.x.iter_mut().zip(&model.mesh.nodes) {
        xn[1] -= dd * xr[1] / h;
    }
    st.d = cur.d + dd;
    tries.push(st);
    for mut t in tries {
        model.enforce_constraints(&mut t);
        if model.energy(&t).is_some() {
            return Some(t);
        }
    }
    None
}

/// The Euler and (where `tangent` has the curvature) second-order Taylor states at the slab
/// displacement `cur.d + dd`, constraints not yet enforced on the step.
fn taylor(model: &Model, cur: &State, dd: f64, tangent: &LoadTangent) -> (State, Option<State>) {
    let mut st = cur.clone();
    st.d = cur.d + dd;
    model.enforce_constraints(&mut st);
    let euler = model.updated(&st, tangent, dd);
    let second = (tangent.curvature.as_ref()).map(|w| model.updated(&euler, w, 0.5 * dd * dd));
    (euler, second)
}

/// `st` with every node moved by `scale` times its entry of `term`.
fn moved_by(st: &State, term: &[[f64; 2]], scale: f64) -> State {
    let mut moved = st.clone();
    for (x, t) in moved.x.iter_mut().zip(term) {
        x[0] += scale * t[0];
        x[1] += scale * t[1];
    }
    moved
}

/// The third-order term `q'''/6` of the path per node position, measured on the step from the
/// converged state `from` along its load path `tangent` to the converged state `reached`: the
/// position error of the second-order prediction at `reached.d` over the cube of the increment
/// (module documentation). `None` without the curvature or without an increment.
pub(crate) fn third_order_term(
    model: &Model,
    from: &State,
    tangent: &LoadTangent,
    reached: &State,
) -> Option<Vec<[f64; 2]>> {
    let dd = reached.d - from.d;
    if dd <= 0.0 {
        return None;
    }
    let (_, second) = taylor(model, from, dd, tangent);
    let mut second = second?;
    model.enforce_constraints(&mut second);
    let cube = dd * dd * dd;
    let term = (reached.x.iter().zip(&second.x))
        .map(|(r, p)| [(r[0] - p[0]) / cube, (r[1] - p[1]) / cube])
        .collect();
    Some(term)
}

/// A displacement-controlled step from the converged state `from` to the slab displacement
/// `d` (exactly: `from.d + (d − from.d)` may differ from `d` in the last bit): predicted along
/// the load tangent of `from`, then equilibrated with its active set, the nodes of `hold` kept
/// as they are. Returns the state (slip not committed) and the Newton iterations.
pub(crate) fn displacement_step(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    from: &State,
    d: f64,
    hold: Hold,
) -> Result<(State, usize), StepFail> {
    let tangent = tangent_at(model, asm, opts, from);
    let mut st =
        predictor(model, from, None, d - from.d, tangent.as_ref()).ok_or(StepFail::Inverted {
            iteration: 0,
            residual: f64::NAN,
        })?;
    st.d = d;
    model.enforce_constraints(&mut st);
    let iters = equilibrate(model, asm, &mut st, opts, hold)?;
    Ok((st, iters))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::newton::inf_norm;
    use crate::fe::stepping::test_fixtures::loaded_sinusoid;

    /// The last two converged states of the frictionless AR 0.3 sinusoid on the coarse mesh
    /// loaded to a/λ = 0.2, with the model and its assembly.
    fn loaded() -> (Model, Assembly, State, State) {
        let (model, asm, _, mut states) = loaded_sinusoid(0.3, 0.2);
        let last = states.pop().expect("a point");
        let before = states.pop().expect("two points");
        (model, asm, before, last)
    }

    /// The residual of the state `predictor` gives for `from.d + dd` along `tangent`.
    fn residual_at(
        model: &Model,
        asm: &mut Assembly,
        from: &State,
        dd: f64,
        tangent: &LoadTangent,
    ) -> f64 {
        let st = predictor(model, from, None, dd, Some(tangent)).expect("not inverted");
        inf_norm(&asm.assemble(model, &st, false).expect("not inverted").resid)
    }

    /// The path's curvature makes the predictor second order: halving the step divides the
    /// residual of the predicted state by about 8 (the Euler predictor's by about 4), so at small
    /// steps it is far below the Euler predictor's. Steps: the last event's increment `Δd` halved
    /// three times. Measured: Taylor ratios 8.4, 7.8, 7.9, Euler 4.6, 3.8, 3.9; at `Δd/8` the
    /// residual 2.8e-4 against 4.0e-3 (asserted at the last halving: > 7, < 4.5, 10× smaller).
    #[test]
    fn the_predictor_is_second_order_along_the_path() {
        let (model, mut asm, before, last) = loaded();
        let tangent = load_tangent(&model, &mut asm, &last).expect("a converged state");
        assert!(
            tangent.curvature().is_some(),
            "frictionless: the curvature is computed"
        );
        let euler = LoadTangent {
            rate: tangent.rate.clone(),
            curvature: None,
            third_order: None,
        };
        let dd = last.d - before.d;
        let taylor = [dd, 0.5 * dd, 0.25 * dd, 0.125 * dd]
            .map(|h| residual_at(&model, &mut asm, &last, h, &tangent));
        let first = [dd, 0.5 * dd, 0.25 * dd, 0.125 * dd]
            .map(|h| residual_at(&model, &mut asm, &last, h, &euler));
        println!("residuals: Taylor {taylor:?}, Euler {first:?}");
        assert!(taylor[2] / taylor[3] > 7.0, "Taylor order: {taylor:?}");
        assert!(first[2] / first[3] < 4.5, "Euler order: {first:?}");
        assert!(
            taylor[3] * 10.0 < first[3],
            "Taylor {taylor:?} against Euler {first:?}"
        );
    }

    /// The largest distance (units of λ) of a node of `predicted` from its place in `reached`.
    fn position_error(predicted: &State, reached: &State) -> f64 {
        (predicted.x.iter().zip(&reached.x))
            .map(|(p, r)| (p[0] - r[0]).abs().max((p[1] - r[1]).abs()))
            .fold(0.0, f64::max)
    }

    /// The third-order term measured on one step between events predicts the next, on the coarse
    /// mesh at a/λ 0.2: the next event's nodes lie closer to the prediction with it than without
    /// it (measured: 6.7e-5 λ against 1.1e-4 λ at the farthest node; asserted at 0.75 of it), and a
    /// step predicted with the term measured on itself lands on its own end to round-off (the term
    /// is the whole of the second-order prediction's error there). The residual of the predicted
    /// state is not smaller here (0.19 against 0.12 at its largest entry); what the term saves is
    /// measured on whole curves (docs/performance.md, "the third-order term").
    #[test]
    fn the_third_order_term_measured_on_a_step_predicts_the_next() {
        let (model, mut asm, _, states) = loaded_sinusoid(0.3, 0.2);
        let [first, second, third] = [3, 2, 1].map(|back| states[states.len() - back].clone());
        let tangent_first = load_tangent(&model, &mut asm, &first).expect("a converged state");
        let term = third_order_term(&model, &first, &tangent_first, &second).expect("a term");
        let tangent = load_tangent(&model, &mut asm, &second).expect("a converged state");
        let dd = third.d - second.d;
        let without = predictor(&model, &second, None, dd, Some(&tangent)).expect("not inverted");
        let tangent = tangent.with_third_order(Some(term.clone()));
        let with = predictor(&model, &second, None, dd, Some(&tangent)).expect("not inverted");
        let (error_with, error_without) = (
            position_error(&with, &third),
            position_error(&without, &third),
        );
        println!("next event: {error_with:e} with the term, {error_without:e} without");
        assert!(
            error_with < 0.75 * error_without,
            "{error_with:e} against {error_without:e}"
        );
        let own = tangent_first.with_third_order(Some(term));
        let again =
            predictor(&model, &first, None, second.d - first.d, Some(&own)).expect("not inverted");
        let error_own = position_error(&again, &second);
        assert!(error_own < 1e-12, "its own step: {error_own:e}");
    }
}
