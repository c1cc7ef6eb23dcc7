//! The start of a load step: the load path's first and second derivatives `∂q/∂d`, `∂²q/∂d²`
//! at a converged state, and the predicted state at a new slab displacement (Taylor along the path;
//! the step that predicts and equilibrates is [`crate::fe::stepping::displacement_step`]).
//!
//! The second derivative costs two residual assemblies and a solve with the factorisation the
//! first left: along the path `r(q(d), d) = 0`, so `K q'' = −∂²r[(q', 1), (q', 1)]`, and the
//! right-hand side is the central difference of the residual along `(q', 1)`, with friction on the
//! smooth pieces of the law ([`SmoothPieces`]). Without friction it more than halves the Newton
//! iterations of an edge event at the default mesh; with friction it saves 10–29 % of them on the
//! Fig. 3 curves at AR 0.3 (docs/performance.md, "friction's predictor"), and under exact stick the
//! predictor stays first order ([`load_tangent`]).
//!
//! The third-order term costs nothing to solve: the error of the last step's second-order
//! prediction, measured at its converged state, is `q''' dd³/6` to leading order, and the next
//! step, a segment of the same path between its neighbouring events, adds it scaled by the cube of
//! its own increment ([`third_order_term`]; frictionless only). It lowers the Newton iterations of
//! the long steps toward the valley (docs/performance.md, "the third-order term").

use crate::fe::contact::friction::Branch;
use crate::fe::model::{Model, State};
use crate::fe::newton::assembly::Assembly;
use crate::fe::stepping::slip_front::{piecewise_rate, SlipFront};
use crate::fe::stepping::touched_hold::{TouchedHold, TouchedNodes};
use crate::fe::{Kinematics, SolveOptions};

/// The difference step of the path's second derivative over the indenter amplitude `Δ`: its
/// central difference has a truncation error of order `ε²` and a round-off of order
/// `10⁻¹⁶ f_e / ε²`. A numerical choice, not tuned: at `10⁻⁴ Δ` the predicted state's residual
/// falls as `dd³` over the steps of a curve (test `the_predictor_is_second_order_along_the_path`).
const CURVATURE_STEP_OVER_AMPLITUDE: f64 = 1e-4;

/// The step of the slab displacement over which the path's derivatives are taken as
/// difference quotients ([`CURVATURE_STEP_OVER_AMPLITUDE`] times the amplitude `Δ`).
fn difference_step(model: &Model) -> f64 {
    CURVATURE_STEP_OVER_AMPLITUDE * model.indenter.amplitude()
}

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

    /// The tangent alone, without the path's curvature and third-order term: its predictor is
    /// the Euler one.
    pub(crate) fn first_order(self) -> Self {
        Self {
            curvature: None,
            third_order: None,
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

/// `∂q/∂d` at a converged state, `K ∂q/∂d = −∂r/∂d`, and under finite kinematics
/// `∂²q/∂d²` ([`path_curvature`]), with friction on the pieces of the law the state lies on
/// ([`SmoothPieces`]) and the nodes that have just touched as `touched` says ([`TouchedHold`]:
/// held, both derivatives taken along the held path); `None` if the state is inverted or the
/// solve fails. Under linear kinematics the frictionless path is straight between two events
/// (the Euler predictor is exact there, and a difference quotient would only add its
/// round-off). Under exact stick the Euler predictor is used: the second-order one cost more
/// Newton iterations there (AR 0.3, τ_max 0.1 MPa, mesh 48: 17.3 to 25.6 per point at μ 1,
/// 13.3 to 16.9 at μ 10⁻⁶; docs/performance.md). With `slip_front_step`, an unloading step of
/// that many λ, and no node held: where stuck nodes start to slide in that step, the secant of the
/// piecewise-linear path through them instead, without curvature ([`piecewise_rate`]).
pub(crate) fn load_tangent(
    model: &Model,
    asm: &mut Assembly,
    st: &State,
    touched: TouchedNodes,
    slip_front_step: Option<f64>,
) -> Option<LoadTangent> {
    let f = asm.assemble(model, st, true)?;
    let hold = TouchedHold::at(model, st, touched);
    let load_column: Vec<f64> = f.dresid_dd.iter().map(|v| -v).collect();
    let mut rhs = vec![load_column.clone()];
    rhs.extend(hold.unit_loads(load_column.len()));
    asm.sys.solve(&mut rhs).ok()?;
    let mut rate = rhs.remove(0);
    if let Some(dd) = slip_front_step.filter(|_| hold.is_empty()) {
        if let Some(rate) = piecewise_rate(model, asm, &load_column, &rate, dd) {
            return Some(LoadTangent {
                rate,
                curvature: None,
                third_order: None,
            });
        }
    }
    let eps = difference_step(model);
    let hold = (hold.with_responses(rhs)).limited_by_friction(model, asm, (st, &rate), eps)?;
    hold.hold_rate(&mut rate);
    let exact_stick = model.friction.is_some_and(|law| law.exact_stick());
    let curvature = match (model.kin, exact_stick) {
        (Kinematics::Finite, false) => path_curvature(model, asm, st, &rate).map(|mut w| {
            hold.hold_curvature(&mut w);
            w
        }),
        _ => None,
    };
    Some(LoadTangent {
        rate,
        curvature,
        third_order: None,
    })
}

/// `∂²q/∂d²` at the converged state `st` (load tangent `rate`), the matrix of `st` still
/// factored: `K q'' = −(r₊ + r₋ − 2 r₀)/ε²`, `r±` the residuals at `(q ± ε q', d ± ε)`
/// ([`CURVATURE_STEP_OVER_AMPLITUDE`]), with friction on the smooth pieces of the law
/// ([`SmoothPieces`]); `None` where a trial is inverted or the solve fails.
fn path_curvature(model: &Model, asm: &mut Assembly, st: &State, rate: &[f64]) -> Option<Vec<f64>> {
    let pieces = SmoothPieces::of(model, asm, st);
    curvature_on(model, asm, &pieces, rate)
}

/// [`path_curvature`] with the difference quotient evaluated on `pieces`.
fn curvature_on(
    model: &Model,
    asm: &mut Assembly,
    pieces: &SmoothPieces,
    rate: &[f64],
) -> Option<Vec<f64>> {
    let eps = difference_step(model);
    let mut along = |step: f64| {
        let moved = model.along(&pieces.state, rate, step);
        pieces.residual(model, asm, &moved)
    };
    let (here, plus, minus) = (along(0.0)?, along(eps)?, along(-eps)?);
    let second: Vec<f64> = (plus.iter().zip(&minus).zip(&here))
        .map(|((p, m), r)| -(p + m - 2.0 * r) / (eps * eps))
        .collect();
    let mut rhs = [second];
    asm.sys.solve_again(&mut rhs).ok()?;
    let [curvature] = rhs;
    curvature.iter().all(|v| v.is_finite()).then_some(curvature)
}

/// What the path's difference quotient evaluates under the penalty friction law: the friction
/// forces on the pieces of the law that the state lies on, continued smoothly a little either
/// way along the path. Two pieces are not smooth there. A sliding node sits at the edge of its
/// stick band once its step is committed (`e = ±e_c`), so the trial a little back along the path
/// would put it on the stick spring: its committed elastic slip is moved one band width further
/// along its slip ([`SmoothPieces::state`]). A stuck node's force `−L e*/e_c` has the second
/// derivative `2 L′ e*′/e_c` (and more) along the path, the curvature of a band a few thousandths of
/// an element wide that a load step crosses: its row takes the equilibrium part `c·g` alone
/// ([`SmoothPieces::stuck`]). Taken as they are, both make the quotient the band's, not the path's,
/// which kept the frictional predictor first order; at μ 10⁻⁶ the frictional curve then took 2.5
/// times the Newton iterations of the frictionless one (docs/performance.md, "friction's
/// predictor").
struct SmoothPieces {
    /// The state, each sliding node's committed elastic slip moved beyond its band's edge.
    state: State,
    /// The equations (slots) and contact-face indices of the stuck nodes.
    stuck: Vec<(usize, usize)>,
}

impl SmoothPieces {
    /// The smooth pieces at `st`, read off the friction rows of its tangent (assembled last in
    /// `asm`); without friction, `st` itself.
    fn of(model: &Model, asm: &Assembly, st: &State) -> Self {
        let mut state = st.clone();
        let mut stuck = Vec::new();
        if let Some(law) = model.friction {
            for row in &asm.friction_rows {
                match row.at.slip {
                    Branch::Stick => stuck.push((row.row, row.face)),
                    slide => state.slip[row.face].elastic += slide.sign() * law.slip_c,
                }
            }
        }
        Self { state, stuck }
    }

    /// The residual of `trial` with the stuck nodes' friction forces left out; `None` where
    /// an element is inverted.
    fn residual(&self, model: &Model, asm: &mut Assembly, trial: &State) -> Option<Vec<f64>> {
        let forces = asm.assemble(model, trial, false)?;
        let mut resid = forces.resid;
        if let Some(law) = model.friction {
            let iterate = model.iterate_forces(trial, &forces.grad);
            let forces = (forces.grad.as_slice(), iterate.as_deref());
            for &(row, face) in &self.stuck {
                resid[row] -= model.friction_eval(trial, face, forces, &law).force;
            }
        }
        Some(resid)
    }
}

/// The load tangent of `st` for the predictor if [`StepOptions::tangent_predictor`] is on
/// ([`load_tangent`]).
pub(crate) fn tangent_at(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    st: &State,
) -> Option<LoadTangent> {
    tangent_with(model, asm, opts, st, None)
}

/// [`tangent_at`] for an unloading step of `dd` (units of λ): with the slip front followed
/// ([`StepOptions::slip_front`]), where stuck nodes start to slide in the step, the secant of the
/// piecewise-linear path through them ([`piecewise_rate`]), without the path's curvature.
pub(crate) fn unloading_tangent_at(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    st: &State,
    dd: f64,
) -> Option<LoadTangent> {
    let slip_front_step = (opts.steps.slip_front == SlipFront::Followed).then_some(dd);
    tangent_with(model, asm, opts, st, slip_front_step)
}

/// [`load_tangent`] with the options' touched nodes, if [`StepOptions::tangent_predictor`] is on.
fn tangent_with(
    model: &Model,
    asm: &mut Assembly,
    opts: &SolveOptions,
    st: &State,
    slip_front_step: Option<f64>,
) -> Option<LoadTangent> {
    let touched = opts.steps.touched_nodes;
    (opts.steps.tangent_predictor)
        .then(|| load_tangent(model, asm, st, touched, slip_front_step))
        .flatten()
}

/// Predictor for the slab displacement `cur.d + dd`: the Taylor prediction along the load path
/// `tangent` of the converged state ([`taylor_prediction`]), else linear extrapolation of the last
/// increment, else a uniform vertical compression ([`crude_prediction`]). The first that has no
/// inverted element is used.
pub(crate) fn predictor(
    model: &Model,
    cur: &State,
    prev: Option<&State>,
    dd: f64,
    tangent: Option<&LoadTangent>,
) -> Option<State> {
    let taylor = tangent.and_then(|z| taylor_prediction(model, cur, dd, z));
    taylor
        .map(|(st, _)| st)
        .or_else(|| crude_prediction(model, cur, prev, dd))
}

/// Which terms a Taylor prediction kept ([`taylor_prediction`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TaylorOrder {
    /// The tangent alone (Euler).
    First,
    /// The tangent and the path's curvature, with the third-order term where the tangent
    /// carries it.
    Curved,
}

/// The Taylor prediction at the slab displacement `cur.d + dd` along the load path `z` of the
/// converged state: `q + dd ∂q/∂d + ½ dd² ∂²q/∂d² + dd³ q'''/6` where the tangent carries the
/// third-order term, then the second-order one without it, then the tangent (Euler) one; the
/// first that has no inverted element, constraints enforced, with the terms it kept; `None` when
/// every one inverts an element. The predictions also predict the element pressures, from the
/// path's own derivatives, to the order of their positions' curvature
/// ([`Model::predicted_pressure`]): Newton's first tangent starts from them.
pub(crate) fn taylor_prediction(
    model: &Model,
    cur: &State,
    dd: f64,
    z: &LoadTangent,
) -> Option<(State, TaylorOrder)> {
    let (euler, second) = taylor(model, cur, dd, z);
    let (first_order, second_order) = match model.predicted_pressure(cur, z, z.curvature(), dd) {
        Some(p) => (Some(p.first_order), p.second_order),
        None => (None, None),
    };
    let mut tries = Vec::new();
    if let (Some(second), Some(term)) = (&second, &z.third_order) {
        let third = moved_by(second, term, dd * dd * dd).with_pressure(second_order.clone());
        tries.push((third, TaylorOrder::Curved));
    }
    tries.extend(second.map(|second| (second.with_pressure(second_order), TaylorOrder::Curved)));
    tries.push((euler.with_pressure(first_order), TaylorOrder::First));
    (tries.into_iter()).find_map(|(st, order)| admissible(model, st).map(|st| (st, order)))
}

/// The predictions that need no load tangent, at the slab displacement `cur.d + dd`: linear
/// extrapolation of the increment from `prev`, else a uniform vertical compression of the layer;
/// the first that has no inverted element, constraints enforced.
pub(crate) fn crude_prediction(
    model: &Model,
    cur: &State,
    prev: Option<&State>,
    dd: f64,
) -> Option<State> {
    let extrapolated = prev.filter(|p| cur.d - p.d > 0.0).map(|p| {
        let s = dd / (cur.d - p.d);
        let mut st = cur.clone();
        for (xn, (xc, xp)) in st.x.iter_mut().zip(cur.x.iter().zip(&p.x)) {
            xn[0] = xc[0] + s * (xc[0] - xp[0]);
            xn[1] = xc[1] + s * (xc[1] - xp[1]);
        }
        st.d = cur.d + dd;
        st
    });
    let h = model.mesh.thickness;
    let mut compressed = cur.clone();
    for (xn, xr) in compressed.x.iter_mut().zip(&model.mesh.nodes) {
        xn[1] -= dd * xr[1] / h;
    }
    compressed.d = cur.d + dd;
    (extrapolated.into_iter().chain([compressed])).find_map(|st| admissible(model, st))
}

/// `st` with its constraints enforced, if it has no inverted element.
fn admissible(model: &Model, mut st: State) -> Option<State> {
    model.enforce_constraints(&mut st);
    model.energy(&st).is_some().then_some(st)
}

/// The Euler and (where `tangent` has the curvature) second-order Taylor states at the slab
/// displacement `cur.d + dd`, constraints not yet enforced on the step.
fn taylor(model: &Model, cur: &State, dd: f64, tangent: &LoadTangent) -> (State, Option<State>) {
    let euler = model.along(cur, tangent, dd);
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
/// (module documentation). `None` without the curvature, without an increment, and with
/// friction: a step's pieces of the law change where it crosses a stick band or a threshold's
/// crossover, the prediction's error is then not the path's third-order term, and carried to
/// the next step it cost more Newton iterations (AR 0.3, τ_max 0.1 MPa, mesh 48: 15.2 against 9.8
/// per point at μ 1, 8.9 against 7.6 at μ 0.2; docs/performance.md, "friction's predictor").
pub(crate) fn third_order_term(
    model: &Model,
    from: &State,
    tangent: &LoadTangent,
    reached: &State,
) -> Option<Vec<[f64; 2]>> {
    let dd = reached.d - from.d;
    if dd <= 0.0 || !model.is_potential() {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::newton::inf_norm;
    use crate::fe::stepping::test_fixtures::{
        largest_distance, loaded_sinusoid, loaded_sinusoid_with,
    };
    use crate::fe::Interface;

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
        let tangent = load_tangent(&model, &mut asm, &last, TouchedNodes::Held, None)
            .expect("a converged state");
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

    /// With friction the path's curvature is taken on the law's smooth pieces, so that as the
    /// friction coefficient vanishes it is the frictionless path's: at μ 10⁻⁶ (penalty stick,
    /// coarse AR 0.3 to a/λ 0.2) the two at the same converged state differ by a small part of
    /// the largest entry (measured 3.8e-6 of it; asserted 1e-5), where the raw difference quotient,
    /// whose trial back along the path puts every sliding node on its stick spring, differs by
    /// 5.6 times it (asserted above 1).
    #[test]
    fn the_frictional_curvature_tends_to_the_frictionless_one() {
        let interface = Interface::coulomb_orowan(1e-6, 0.1, 0.005);
        let (model, mut asm, _, states) = loaded_sinusoid_with(0.3, 0.2, interface);
        let last = states.last().expect("a point");
        let mut frictionless = model.clone();
        frictionless.friction = None;
        let mut frictionless_asm = Assembly::new(&frictionless);
        let curvature = |model: &Model, asm: &mut Assembly| {
            let tangent = load_tangent(model, asm, last, TouchedNodes::Held, None)
                .expect("a converged state");
            tangent.curvature().expect("finite kinematics").to_vec()
        };
        let reference = curvature(&frictionless, &mut frictionless_asm);
        let scale = inf_norm(&reference);
        let apart = |c: &[f64]| {
            let gap = c.iter().zip(&reference).map(|(a, b)| (a - b).abs());
            gap.fold(0.0, f64::max) / scale
        };
        let smooth = apart(&curvature(&model, &mut asm));
        let rate = load_tangent(&model, &mut asm, last, TouchedNodes::Held, None)
            .expect("converged")
            .rate;
        let as_they_are = SmoothPieces {
            state: last.clone(),
            stuck: Vec::new(),
        };
        let raw = apart(&curvature_on(&model, &mut asm, &as_they_are, &rate).expect("a curvature"));
        println!(
            "curvature apart from the frictionless one: smooth pieces {smooth:e}, raw {raw:e}"
        );
        assert!(smooth < 1e-5, "smooth pieces: {smooth:e}");
        assert!(raw > 1.0, "the raw quotient: {raw:e}");
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
        let tangent_first = load_tangent(&model, &mut asm, &first, TouchedNodes::Held, None)
            .expect("a converged state");
        let term = third_order_term(&model, &first, &tangent_first, &second).expect("a term");
        let tangent = load_tangent(&model, &mut asm, &second, TouchedNodes::Held, None)
            .expect("a converged state");
        let dd = third.d - second.d;
        let without = predictor(&model, &second, None, dd, Some(&tangent)).expect("not inverted");
        let tangent = tangent.with_third_order(Some(term.clone()));
        let with = predictor(&model, &second, None, dd, Some(&tangent)).expect("not inverted");
        let (error_with, error_without) = (
            largest_distance(&with, &third),
            largest_distance(&without, &third),
        );
        println!("next event: {error_with:e} with the term, {error_without:e} without");
        assert!(
            error_with < 0.75 * error_without,
            "{error_with:e} against {error_without:e}"
        );
        let own = tangent_first.with_third_order(Some(term));
        let again =
            predictor(&model, &first, None, second.d - first.d, Some(&own)).expect("not inverted");
        let error_own = largest_distance(&again, &second);
        assert!(error_own < 1e-12, "its own step: {error_own:e}");
    }
}
