//! Newton's method with line search, the contact active-set loop and the load stepping
//! from one contact-edge event to the next.
//!
//! * Newton: consistent tangent of the reduced problem, solved by [`super::linsys`]
//!   (the factorisations are described there), one backtracking `line_search` on the
//!   energy `Π` (Armijo) or, if the Newton direction is not a descent direction or the
//!   problem has friction, on the residual norm. Inverted trial configurations
//!   (`J ≤ 0`) are backtracked. Convergence: `‖r‖∞ ≤ rtol · f_e + atol`, `f_e` the
//!   largest element-level nodal force (the round-off scale of the assembled residual)
//!   and `atol = residual_atol · (G + κ) λ`; an iteration whose correction is below
//!   `increment_atol` (round-off of the positions) also ends the iteration.
//! * Active set: after each converged Newton solve, release nodes with `λ < 0` (with
//!   friction: normal force `N < 0`), activate penetrating nodes (moved to their closest
//!   point on the indenter), repeat (see [`super::contact`]). Passes whose active set
//!   may still change are converged loosely, the confirming pass tightly.
//! * Load stepping in the slab displacement `d`, from one edge event to the next
//!   (`trace`; the event search is in [`super::edge`]). Predictor: tangent (Euler) step
//!   from the last converged state, to the load at which the target node closes along
//!   that tangent (scaled by the previous event's ratio of actual to extrapolated
//!   increment). Nodes left touching with a vanishing force at the last event enter the
//!   next step active.

use super::edge::{self, newton_edge, EventSearch};
use super::error::{CurveFailure, SolveError};
use super::model::{Forces, Model, State};
use super::{Curve, CurvePoint, DeformedState, EdgeRule, Kinematics, LoadDirection, SolveOptions};

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

/// Step-length factor per backtracking step (halving: [`SolveOptions::max_line_search`]
/// and [`SolveOptions::max_edge_line_search`] count halvings).
const LINE_SEARCH_BACKTRACK: f64 = 0.5;

/// Floor of the multiplier scale `max|λ|` of the release test
/// `λ < −multiplier_rtol · max|λ|`: when every multiplier vanishes the test stays a
/// comparison with a (tiny) negative number. Safeguard, far below any force of the
/// problem and above the underflow threshold of doubles.
const MULTIPLIER_SCALE_FLOOR: f64 = 1e-300;

/// Bounds of the ratio of actual to tangent-extrapolated load increment that scales the
/// next event's first trial. Safeguard, not tuned: one odd event (a node released and
/// re-touching) cannot throw the next prediction far off.
const EVENT_RATIO_MIN: f64 = 0.5;

/// Upper bound of the event ratio ([`EVENT_RATIO_MIN`]).
const EVENT_RATIO_MAX: f64 = 4.0;

/// Why one attempt at a load step failed.
#[derive(Debug, Clone)]
pub(crate) enum StepFail {
    Diverged {
        iteration: usize,
        residual: f64,
        reason: String,
    },
    Inverted {
        iteration: usize,
        residual: f64,
    },
    Cycling {
        iterations: usize,
    },
    Linear {
        iteration: usize,
        message: String,
    },
}

impl StepFail {
    pub(crate) fn into_error(self, step: usize, d: f64) -> SolveError {
        match self {
            StepFail::Diverged {
                iteration,
                residual,
                reason,
            } => SolveError::NewtonDiverged {
                step,
                iteration,
                residual,
                slab_displacement_over_lambda: d,
                reason,
            },
            StepFail::Inverted {
                iteration,
                residual,
            } => SolveError::Inverted {
                step,
                iteration,
                residual,
            },
            StepFail::Cycling { iterations } => SolveError::ActiveSetCycling { step, iterations },
            StepFail::Linear { iteration, message } => SolveError::LinearSolve {
                step,
                iteration,
                message,
            },
        }
    }
}

/// The linear solve ([`Model::solve_newton`]) of a Newton system at iteration
/// `iteration`, `direction` mapping its solutions to the step; a failure ends the Newton
/// solve.
pub(crate) fn solve_newton_system(
    model: &mut Model,
    opts: &SolveOptions,
    rhs: &mut [Vec<f64>],
    iteration: usize,
    direction: impl Fn(&[Vec<f64>]) -> Vec<f64>,
) -> Result<(), StepFail> {
    model
        .solve_newton(rhs, opts.semismooth_friction, direction)
        .map_err(|e| StepFail::Linear {
            iteration,
            message: e.to_string(),
        })
}

/// Residual bound of Newton convergence, `rtol · f_e + residual_atol · (G + κ)`, with
/// `force_scale = f_e` the largest element-level nodal force.
pub(crate) fn residual_tolerance(
    model: &Model,
    opts: &SolveOptions,
    rtol: f64,
    force_scale: f64,
) -> f64 {
    let atol = opts.residual_atol * (model.mat.g + model.mat.kappa);
    rtol * force_scale + atol
}

pub(crate) fn l2_norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

pub(crate) fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

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
    model: &mut Model,
    max_trials: usize,
    trial_at: impl Fn(&Model, f64) -> State,
    decrease: Decrease<'_>,
) -> Option<State> {
    let mut alpha = 1.0;
    for _ in 0..max_trials {
        let trial = trial_at(model, alpha);
        if let Some(f) = model.assemble(&trial, false) {
            if decrease.accepts(model, &trial, &f, alpha) {
                return Some(trial);
            }
        }
        alpha *= LINE_SEARCH_BACKTRACK;
    }
    None
}

/// Newton iterations at a fixed active set. Returns the number of iterations.
pub(crate) fn newton(
    model: &mut Model,
    st: &mut State,
    opts: &SolveOptions,
    rtol: f64,
) -> Result<usize, StepFail> {
    let mut last_res = f64::NAN;
    for it in 0..=opts.max_newton_iterations {
        // convergence check on the forces alone (cached after the line search), the
        // matrix only when another iteration follows
        let Some(f) = model.assemble(st, false) else {
            return Err(StepFail::Inverted {
                iteration: it,
                residual: last_res,
            });
        };
        let res = inf_norm(&f.resid);
        last_res = res;
        if res <= residual_tolerance(model, opts, rtol, f.force_scale) {
            return Ok(it);
        }
        if it == opts.max_newton_iterations || !res.is_finite() {
            break;
        }
        let f = model
            .assemble(st, true)
            .expect("state assembled above is not inverted");
        let mut rhs = vec![f.resid.iter().map(|r| -r).collect::<Vec<f64>>()];
        solve_newton_system(model, opts, &mut rhs, it, |x| x[0].clone())?;
        let dq = rhs.pop().expect("one right-hand side");
        if inf_norm(&dq) <= opts.increment_atol {
            // correction below the round-off of the positions: converged
            *st = model.updated(st, &dq, 1.0);
            return Ok(it + 1);
        }
        if model.kin == Kinematics::Linear && model.is_potential() {
            // quadratic energy: the Newton step is exact
            *st = model.updated(st, &dq, 1.0);
            continue;
        }
        let slope: f64 = f.resid.iter().zip(&dq).map(|(r, d)| r * d).sum();
        let residual_norm = |_: &Model, _: &State, ft: &Forces| l2_norm(&ft.resid);
        let decrease = if slope < 0.0 && model.is_potential() {
            Decrease::Energy {
                initial: f.energy,
                slope,
            }
        } else {
            Decrease::Merit {
                initial: l2_norm(&f.resid),
                merit: &residual_norm,
            }
        };
        let trial_at = |m: &Model, alpha: f64| m.updated(st, &dq, alpha);
        match line_search(model, opts.max_line_search, trial_at, decrease) {
            Some(t) => *st = t,
            None => {
                return Err(StepFail::Diverged {
                    iteration: it,
                    residual: res,
                    reason: "line search found no acceptable step".into(),
                })
            }
        }
    }
    Err(StepFail::Diverged {
        iteration: opts.max_newton_iterations,
        residual: last_res,
        reason: "maximum Newton iterations reached".into(),
    })
}

/// Converge one load step: Newton + active-set updates. `exclude` names a contact-face
/// node that is never activated (the target of the edge search); with `edge_tol` (the
/// event's gap tolerance) the load `d` is an unknown too and node `exclude` is brought
/// to the surface ([`newton_edge`]). Returns the total number of Newton iterations.
pub(crate) fn equilibrate(
    model: &mut Model,
    st: &mut State,
    opts: &SolveOptions,
    exclude: Option<usize>,
    edge_tol: Option<f64>,
) -> Result<usize, StepFail> {
    let mut total = 0;
    // Passes whose active set may still change are converged loosely
    // (`loose_residual_rtol`); the pass that confirms the set is converged tightly.
    let mut loose = true;
    for _ in 0..opts.max_active_set_updates {
        let rtol = if loose {
            opts.loose_residual_rtol
        } else {
            opts.residual_rtol
        };
        total += match (edge_tol, exclude) {
            (Some(tol), Some(k)) => newton_edge(model, st, opts, k, tol, rtol)?,
            _ => newton(model, st, opts, rtol)?,
        };
        let f = model.assemble(st, false).ok_or(StepFail::Inverted {
            iteration: total,
            residual: f64::NAN,
        })?;
        // Release test: the vertical multiplier λ = ∂Π/∂y without friction (the same sign as
        // the normal force at equilibrium, and insensitive to the tangential residual left by
        // loose passes: testing N there doubled the Newton iterations); the normal force N
        // with friction, where λ = (N + y_s' T)/w can differ in sign from N.
        let lam = if model.is_potential() {
            model.multipliers(st, &f.grad)
        } else {
            model.normal_forces(st, &f.grad)
        };
        let gaps = model.gaps(st);
        let lam_scale = lam
            .iter()
            .fold(0.0_f64, |m, l| m.max(l.abs()))
            .max(MULTIPLIER_SCALE_FLOOR);
        let gap_tol = opts.gap_tolerance_over_amplitude * model.indenter.amplitude;
        let mut changed = false;
        for k in 0..st.active.len() {
            if st.active[k] {
                if lam[k] < -opts.multiplier_rtol * lam_scale {
                    st.active[k] = false;
                    changed = true;
                }
            } else if gaps[k] < -gap_tol && exclude != Some(k) {
                model.activate(st, k);
                changed = true;
            }
        }
        if !changed {
            if !loose {
                return Ok(total);
            }
            loose = false;
        }
        model.enforce_constraints(st);
    }
    Err(StepFail::Cycling {
        iterations: opts.max_active_set_updates,
    })
}

/// The modelled width, half a wavelength (units of λ): the mean pressure is a force over it.
const HALF_WAVELENGTH: f64 = 0.5;

/// `p̄/E*` from the contact tractions: the vertical components of the contact forces, which
/// at equilibrium are the internal forces `∂Π/∂y` of the active nodes, over half a wavelength.
fn mean_pressure_over_estar(model: &Model, st: &State, grad: &[f64], estar: f64) -> f64 {
    model.multipliers(st, grad).iter().sum::<f64>() / HALF_WAVELENGTH / estar
}

/// Measured quantities of a converged state whose contact edge is node `edge`.
pub(crate) fn measure(
    model: &mut Model,
    st: &State,
    estar: f64,
    edge: usize,
    rule: EdgeRule,
) -> (CurvePoint, Vec<f64>) {
    let f = model
        .assemble(st, false)
        .expect("converged state is not inverted");
    let p_tr = mean_pressure_over_estar(model, st, &f.grad, estar);
    let p_re = model.slab_reaction(&f.grad) / HALF_WAVELENGTH / estar;
    (
        CurvePoint {
            a_over_lambda: edge::edge_position(model, st, edge, rule),
            p_over_estar: p_tr,
            p_over_estar_reaction: p_re,
            slab_displacement_over_lambda: st.d,
            newton_iterations: 0,
            active_nodes: st.active.iter().filter(|&&b| b).count(),
        },
        f.grad,
    )
}

/// The deformed state and its contact tractions: normal and tangential nodal contact
/// forces ([`Model::normal_forces`], [`Model::tangential_forces`]) over each node's
/// tributary length on the deformed face.
fn deformed_state(model: &Model, st: &State, grad: &[f64], estar: f64) -> DeformedState {
    let normal = model.normal_forces(st, grad);
    let tangential = model.tangential_forces(st, grad);
    let b = &model.mesh.bottom;
    let n = b.len();
    let pos = |k: usize| st.x[b[k]];
    let seg = |k: usize| {
        let (p, q) = (pos(k), pos(k + 1));
        ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt()
    };
    let trib = |k: usize| {
        0.5 * (if k > 0 { seg(k - 1) } else { 0.0 } + if k + 1 < n { seg(k) } else { 0.0 })
    };
    DeformedState {
        nodes: st.x.clone(),
        quads: model.mesh.quads.clone(),
        bottom: b.clone(),
        in_contact: st.active.clone(),
        contact_pressure_over_estar: (0..n).map(|k| normal[k] / trib(k) / estar).collect(),
        contact_shear_over_estar: (0..n).map(|k| tangential[k] / trib(k) / estar).collect(),
    }
}

/// `∂q/∂d` at a converged state: `K ∂q/∂d = −∂r/∂d` (the tangent is positive definite
/// there); `None` if the state is inverted or the solve fails.
pub(crate) fn load_tangent(model: &mut Model, st: &State) -> Option<Vec<f64>> {
    let f = model.assemble(st, true)?;
    let mut rhs = [f.dresid_dd.iter().map(|v| -v).collect::<Vec<f64>>()];
    model.sys.solve(&mut rhs).ok()?;
    let [z] = rhs;
    Some(z)
}

/// The load tangent of `st` for the predictor if [`SolveOptions::tangent_predictor`] is on
/// ([`load_tangent`]).
pub(crate) fn tangent_at(model: &mut Model, opts: &SolveOptions, st: &State) -> Option<Vec<f64>> {
    opts.tangent_predictor
        .then(|| load_tangent(model, st))
        .flatten()
}

/// Predictor for the load `cur.d + dd`: the tangent (Euler) predictor
/// `q + dd · ∂q/∂d` along the load tangent `tangent` of the converged state, else
/// linear extrapolation of the last increment, else a uniform vertical compression.
/// The first that has no inverted element is used.
pub(crate) fn predictor(
    model: &mut Model,
    cur: &State,
    prev: Option<&State>,
    dd: f64,
    tangent: Option<&[f64]>,
) -> Option<State> {
    let h = model.mesh.thickness;
    let mut tries: Vec<State> = Vec::new();
    if let Some(z) = tangent {
        let mut st = cur.clone();
        st.d = cur.d + dd;
        model.enforce_constraints(&mut st);
        tries.push(model.updated(&st, z, dd));
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

/// What the load stepping carries from one edge event to the next.
struct LoadPath {
    /// Converged state of the last event, and of the one before.
    cur: State,
    prev: Option<State>,
    /// Contact half-width `a/λ` of the last event.
    a: f64,
    /// Load increment of the last event (units of λ; before the first, the first trial).
    last_increment: f64,
    /// Ratio of the actual to the tangent-extrapolated increment of the last event.
    event_ratio: f64,
    /// Points converged so far.
    points: Vec<CurvePoint>,
    /// Internal forces `∂Π/∂x` of `cur`.
    grad: Vec<f64>,
}

impl LoadPath {
    /// The undeformed state with the peak node in contact.
    fn start(model: &Model, opts: &SolveOptions) -> Self {
        Self {
            cur: model.initial_state(),
            prev: None,
            a: 0.0,
            last_increment: opts.first_step_over_amplitude * model.indenter.amplitude,
            event_ratio: 1.0,
            points: Vec::new(),
            grad: vec![0.0; 2 * model.num_nodes()],
        }
    }

    /// Move on to the converged event `st` with its point and forces; `extrapolated` is
    /// the increment the load tangent predicted for it.
    fn advance(&mut self, st: State, point: CurvePoint, grad: Vec<f64>, extrapolated: Option<f64>) {
        self.a = point.a_over_lambda;
        self.points.push(point);
        self.grad = grad;
        self.last_increment = st.d - self.cur.d;
        if let Some(e) = extrapolated {
            self.event_ratio = (self.last_increment / e).clamp(EVENT_RATIO_MIN, EVENT_RATIO_MAX);
        }
        self.prev = Some(std::mem::replace(&mut self.cur, st));
    }

    /// The failure `error` with the points converged so far.
    fn fail(self, error: SolveError) -> Box<CurveFailure> {
        Box::new(CurveFailure {
            error,
            points: self.points,
            unloading: Vec::new(),
        })
    }

    /// The curve: the loading points, `unloading`, and the last converged state.
    fn finish(self, model: &Model, estar: f64, unloading: Vec<CurvePoint>) -> Curve {
        Curve {
            final_state: deformed_state(model, &self.cur, &self.grad, estar),
            points: self.points,
            unloading,
            work: model.work(),
        }
    }
}

/// Trace the load curve up to `opts.until_a_over_lambda`, one edge event per point (see
/// [`super::edge`] for the events and the contact-edge location).
pub(crate) fn trace(
    model: &mut Model,
    opts: &SolveOptions,
    estar: f64,
    on_step: &mut dyn FnMut(&CurvePoint),
) -> Result<Curve, Box<CurveFailure>> {
    let path = load(model, opts, estar, on_step)?;
    Ok(path.finish(model, estar, Vec::new()))
}

/// Trace the loading branch as [`trace`], then unload back to zero load with the friction
/// history carried through ([`unload`]); `on_step` sees every converged point with its
/// branch.
pub(crate) fn trace_cycle(
    model: &mut Model,
    opts: &SolveOptions,
    estar: f64,
    on_step: &mut dyn FnMut(LoadDirection, &CurvePoint),
) -> Result<Curve, Box<CurveFailure>> {
    let mut path = load(model, opts, estar, &mut |p| {
        on_step(LoadDirection::Loading, p)
    })?;
    let unloading = unload(model, opts, estar, &mut path, &mut |p| {
        on_step(LoadDirection::Unloading, p)
    })?;
    Ok(path.finish(model, estar, unloading))
}

/// The loading branch: from first contact, one edge event per point, until the contact
/// half-width reaches `opts.until_a_over_lambda` (or, with `opts.until_p_over_estar`, until
/// the mean pressure reaches that: the event that would overshoot it is replaced by the
/// state on the target, [`land_on_pressure`]).
fn load(
    model: &mut Model,
    opts: &SolveOptions,
    estar: f64,
    on_step: &mut dyn FnMut(&CurvePoint),
) -> Result<LoadPath, Box<CurveFailure>> {
    let mut path = LoadPath::start(model, opts);
    let mut step = 1;
    // reached when loading landed on it (within its tolerance, so possibly a hair below)
    let pressure_reached = |path: &LoadPath| match (opts.until_p_over_estar, path.points.last()) {
        (Some(target), Some(p)) => p.p_over_estar >= target * (1.0 - PRESSURE_TARGET_RTOL),
        _ => false,
    };
    while path.a < opts.until_a_over_lambda && !pressure_reached(&path) {
        if step > opts.max_steps {
            let error = SolveError::TooManySteps {
                steps: opts.max_steps,
                a_over_lambda: path.a,
            };
            return Err(path.fail(error));
        }
        // the next edge node; nodes skipped because they touch enter the step active
        let Some(k) = edge::next_target(model, &path.cur, path.a, opts.da_target) else {
            break; // full contact
        };
        edge::activate_touching(model, &mut path.cur, k);
        // predict: the load at which node k closes along the load tangent, scaled by
        // the previous event's ratio of actual to extrapolated increment
        let gap0 = model.gaps(&path.cur)[k];
        let tangent = tangent_at(model, opts, &path.cur);
        let extrapolated = tangent
            .as_deref()
            .and_then(|z| edge::closing_increment(model, &path.cur, k, gap0, z));
        let search = EventSearch {
            opts,
            from: &path.cur,
            before: path.prev.as_ref(),
            node: k,
            gap0,
            gap_tol: edge::event_gap_tolerance(model, opts, gap0),
            tangent,
            first_increment: extrapolated.map_or(path.last_increment, |e| e * path.event_ratio),
            last_increment: path.last_increment,
        };
        // the event: node k touches with zero force
        let (mut st, mut iters) = match search.find(model, step) {
            Ok(found) => found,
            Err(error) => return Err(path.fail(error)),
        };
        // node k enters contact; equilibrate, commit the slip and measure
        model.activate(&mut st, k);
        model.enforce_constraints(&mut st);
        match equilibrate(model, &mut st, opts, None, None) {
            Ok(it) => iters += it,
            Err(f) => return Err(path.fail(f.into_error(step, st.d))),
        }
        model.commit_slip(&mut st);
        let (mut point, grad) = measure(model, &st, estar, k, opts.edge_rule);
        point.newton_iterations = iters;
        if let Some(target) = opts.until_p_over_estar.filter(|&t| point.p_over_estar > t) {
            // the event overshoots the pressure target: land on it between the last
            // converged state and this event instead
            let event = (st.d, point.p_over_estar);
            match land_on_pressure(model, opts, estar, &path, k, event, target) {
                Ok((st, mut point, grad, it)) => {
                    point.newton_iterations = iters + it;
                    on_step(&point);
                    path.advance(st, point, grad, None);
                    break;
                }
                Err(f) => return Err(path.fail(f.into_error(step, event.0))),
            }
        }
        on_step(&point);
        path.advance(st, point, grad, extrapolated);
        step += 1;
    }
    if let Some(target) = opts.until_p_over_estar {
        if !pressure_reached(&path) && path.a >= opts.until_a_over_lambda {
            let error = SolveError::PressureTargetBeyondLimit {
                a_over_lambda: path.a,
                p_over_estar: path.points.last().map_or(0.0, |p| p.p_over_estar),
                target,
            };
            return Err(path.fail(error));
        }
    }
    if path.a < opts.until_a_over_lambda && !pressure_reached(&path) {
        let error = SolveError::TargetBeyondMesh {
            a_over_lambda: path.a,
            target: opts.until_a_over_lambda,
        };
        return Err(path.fail(error));
    }
    Ok(path)
}

/// A displacement-controlled step from the converged state `from` to the slab displacement
/// `d` (exactly: `from.d + (d − from.d)` may differ from `d` in the last bit): predicted along
/// the load tangent of `from`, then equilibrated with its active set, node `exclude` kept
/// free. Returns the state (slip not committed) and the Newton iterations.
fn displacement_step(
    model: &mut Model,
    opts: &SolveOptions,
    from: &State,
    d: f64,
    exclude: Option<usize>,
) -> Result<(State, usize), StepFail> {
    let tangent = tangent_at(model, opts, from);
    let mut st =
        predictor(model, from, None, d - from.d, tangent.as_deref()).ok_or(StepFail::Inverted {
            iteration: 0,
            residual: f64::NAN,
        })?;
    st.d = d;
    model.enforce_constraints(&mut st);
    let iters = equilibrate(model, &mut st, opts, exclude, None)?;
    Ok((st, iters))
}

/// [`measure`] for a converged state that is not an edge event: the edge in the last loaded
/// element ([`edge::loaded_edge_node`]).
fn measure_between_events(
    model: &mut Model,
    st: &State,
    estar: f64,
    opts: &SolveOptions,
) -> (CurvePoint, Vec<f64>) {
    let f = model
        .assemble(st, false)
        .expect("converged state is not inverted");
    let edge = edge::loaded_edge_node(model, st, &f.grad, opts.multiplier_rtol);
    measure(model, st, estar, edge, opts.edge_rule)
}

/// Relative tolerance on `p̄/E*` of the landing on a pressure target
/// ([`SolveOptions::until_p_over_estar`]): far below the solver's other errors (the
/// discretisation's ~10⁻³), far above the round-off of the summed contact forces.
const PRESSURE_TARGET_RTOL: f64 = 1e-9;

/// Most trial loads of the landing on a pressure target (regula falsi on a monotone
/// `p̄(d)` converges in a handful; a safeguard).
const MAX_PRESSURE_TRIALS: usize = 40;

/// The state at which `p̄/E*` equals `target`, between the last converged state of `path`
/// (below the target) and the edge event `(d, p̄/E*)` (above it): regula falsi on the slab
/// displacement (Illinois variant), each trial a displacement-controlled step with the
/// friction history of the last converged state, equilibrated with its active set and the
/// event's `node` kept free ([`displacement_step`]); a trial that fails is halved (at most
/// `max_step_cuts` times). Returns the state (slip committed), its point
/// ([`measure_between_events`]), its forces and the Newton iterations spent.
fn land_on_pressure(
    model: &mut Model,
    opts: &SolveOptions,
    estar: f64,
    path: &LoadPath,
    node: usize,
    event: (f64, f64),
    target: f64,
) -> Result<(State, CurvePoint, Vec<f64>, usize), StepFail> {
    let below = (
        path.cur.d,
        path.points.last().map_or(0.0, |p| p.p_over_estar),
    );
    let (mut lo, mut hi) = (below, event);
    // each trial starts from the converged trial nearest below the target (its friction
    // history is still the last converged state's: only the starting point moves)
    let mut start = path.cur.clone();
    let mut iters = 0;
    let mut cuts = 0;
    let mut side = 0; // Illinois: which end stayed put last time
    let mut next = lo.0 + (target - lo.1) * (hi.0 - lo.0) / (hi.1 - lo.1);
    for _ in 0..MAX_PRESSURE_TRIALS {
        let d = next;
        // the event's node touches only at the event: below it, it stays free (as in the
        // event search)
        let (st, it) = match displacement_step(model, opts, &start, d, Some(node)) {
            Ok(converged) => converged,
            Err(f) => {
                // halve the step from the start, as often as a load step may be cut
                if cuts == opts.max_step_cuts {
                    return Err(f);
                }
                cuts += 1;
                next = 0.5 * (start.d + d);
                continue;
            }
        };
        iters += it;
        let f = model
            .assemble(&st, false)
            .expect("converged state is not inverted");
        let p = mean_pressure_over_estar(model, &st, &f.grad, estar);
        if (p - target).abs() <= PRESSURE_TARGET_RTOL * target {
            let mut st = st;
            model.commit_slip(&mut st);
            let (point, grad) = measure_between_events(model, &st, estar, opts);
            return Ok((st, point, grad, iters));
        }
        if p < target {
            lo = (d, p);
            start = st;
            if side == -1 {
                hi.1 = target + 0.5 * (hi.1 - target);
            }
            side = -1;
        } else {
            hi = (d, p);
            if side == 1 {
                lo.1 = target - 0.5 * (target - lo.1);
            }
            side = 1;
        }
        next = lo.0 + (target - lo.1) * (hi.0 - lo.0) / (hi.1 - lo.1);
    }
    Err(StepFail::Diverged {
        iteration: iters,
        residual: f64::NAN,
        reason: format!(
            "the load with p̄/E* = {target} was not found in {MAX_PRESSURE_TRIALS} trials"
        ),
    })
}

/// The unloading branch from the loaded state of `path` back to zero load.
///
/// Displacement-controlled: the slab retracts through the loads of the loading events in
/// reverse, then to `d = 0`, so that a frictionless (reversible) cycle revisits the loading
/// states and the two branches can be compared point by point. Each step predicts along the
/// load tangent, equilibrates (nodes whose normal force turns tensile are released, the
/// return mapping carries the slip history, committed after every step;
/// [`displacement_step`]) and is measured with the edge in the last loaded element, as at the
/// loading events ([`measure_between_events`]). A step that fails is approached through
/// intermediate loads (the remaining increment halved, at most `max_step_cuts` times in a
/// row) that serve as initial guesses only: the slip history is committed, and points are
/// recorded, at the scheduled loads alone, so that the discrete load path, and with it the
/// dissipated energy, does not depend on where Newton needed help (it did: the step cuts
/// moved with the round-off of the linear solves, and the dissipation at AR 0.3 with them,
/// by up to 0.6 %). When contact
/// remains at `d = 0` with a positive mean pressure (slip locked in by friction; "positive"
/// meaning above `residual_rtol` times the largest load, the round-off of the summed contact
/// forces), the slab goes on retracting by the first event's increment until the last node
/// lets go; contact still held once the slab is as far out as it had been
/// pressed in is an error.
fn unload(
    model: &mut Model,
    opts: &SolveOptions,
    estar: f64,
    path: &mut LoadPath,
    on_step: &mut dyn FnMut(&CurvePoint),
) -> Result<Vec<CurvePoint>, Box<CurveFailure>> {
    let loads: Vec<f64> = path
        .points
        .iter()
        .map(|p| p.slab_displacement_over_lambda)
        .collect();
    let d_max = path.cur.d;
    let retract_increment = loads.first().copied().unwrap_or(d_max);
    // targets as a stack, the next one last: scheduled loads (committed and recorded) and
    // intermediate ones (initial guesses for the next target only)
    let mut targets: Vec<(f64, bool)> = vec![(0.0, true)];
    targets.extend(
        loads
            .iter()
            .take(loads.len().saturating_sub(1))
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
    let mut cuts = 0;
    let mut steps = 0;
    let mut cur_p = path.points.last().map_or(0.0, |p| p.p_over_estar);
    // zero load: the round-off of p̄ relative to the largest load of the cycle
    let p_max = cur_p;
    // where the next step starts: the last committed state, or an intermediate one past it
    let mut base = path.cur.clone();
    loop {
        let Some(&(target, scheduled)) = targets.last() else {
            // at d = 0 or beyond: done when no contact force is left
            let active = path.cur.active.iter().filter(|&&b| b).count();
            if cur_p <= opts.residual_rtol * p_max || active == 0 {
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
        if steps > opts.max_steps {
            let error = SolveError::TooManySteps {
                steps: opts.max_steps,
                a_over_lambda: path.a,
            };
            return Err(fail(path, points, error));
        }
        // exactly the target load, so that a reversible cycle revisits the loading branch's loads
        match displacement_step(model, opts, &base, target, None) {
            Ok((mut st, iters)) if scheduled => {
                model.commit_slip(&mut st);
                let (mut point, grad) = measure_between_events(model, &st, estar, opts);
                point.newton_iterations = iters;
                on_step(&point);
                cur_p = point.p_over_estar;
                path.a = point.a_over_lambda;
                path.grad = grad;
                base = st.clone();
                path.prev = Some(std::mem::replace(&mut path.cur, st));
                points.push(point);
                targets.pop();
                cuts = 0;
            }
            Ok((st, _)) => {
                base = st;
                targets.pop();
                cuts = 0;
            }
            Err(_) if cuts < opts.max_step_cuts => {
                cuts += 1;
                targets.push((0.5 * (base.d + target), false));
            }
            Err(f) => {
                let error = SolveError::UnloadingStalled {
                    slab_displacement_over_lambda: base.d,
                    target,
                    cuts,
                    reason: f.into_error(steps, target).to_string(),
                };
                return Err(fail(path, points, error));
            }
        }
    }
    Ok(points)
}
