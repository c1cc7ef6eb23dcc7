//! Newton's method with line search, the contact active-set loop and adaptive load
//! stepping with step cutting.
//!
//! * Newton: consistent tangent of the reduced problem, sparse Cholesky (`L D Lᵀ`,
//!   then the pivoting `L B Lᵀ` if the tangent is not positive definite, see
//!   [`super::linsys`]; symbolic factorisations reused; LU with friction), backtracking line search on
//!   the energy `Π` (Armijo,
//!   `c = 10⁻⁴`); if the Newton direction is not a descent direction the residual norm
//!   is used instead. Inverted trial configurations (`J ≤ 0`) have `Π = +∞` and are
//!   backtracked. Convergence: `‖r‖∞ ≤ rtol · f_e + atol`, `f_e` the largest
//!   element-level nodal force (the round-off scale of the assembled residual) and
//!   `atol = residual_atol · (G + κ) λ`; an iteration whose correction is below
//!   `increment_atol` (round-off of the positions) also ends the iteration.
//! * Active set: after each converged Newton solve, release nodes with `λ < 0`,
//!   activate penetrating nodes (moved to their closest point on the indenter),
//!   repeat (see [`super::contact`]). Passes whose active set may still change are
//!   converged loosely, the confirming pass tightly.
//! * Load stepping in the slab displacement `d`, from one edge event to the next (see
//!   [`trace`]). Each event is first solved by the bordered Newton method
//!   ([`newton_edge`], `d` an unknown); if that fails, a secant/regula-falsi search on
//!   `d` with ordinary Newton solves takes over, and a failed trial load (Newton
//!   divergence, inversion, active-set cycling) is retried from the last converged
//!   state with half the increment, up to `max_step_cuts` times. Predictor: tangent
//!   (Euler) step from the last converged state, to the load at which the target node
//!   closes along that tangent (scaled by the previous event's ratio of actual to
//!   extrapolated increment). Nodes left touching with a vanishing force at the last
//!   event enter the next step active.

use super::error::{CurveFailure, SolveError};
use super::model::{Model, State};
use super::{Curve, CurvePoint, DeformedState, EdgeRule, Kinematics, SolveOptions};

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

/// Solve the assembled tangent for each right-hand side in place: Cholesky (`L D Lᵀ`,
/// `L B Lᵀ`, then LU as fallbacks) for the symmetric frictionless tangent, LU with
/// friction.
fn linear_solve(
    model: &mut Model,
    rhs: &mut [Vec<f64>],
) -> Result<(), super::linsys::LinSolveError> {
    if model.is_potential() {
        model.sys.solve_symmetric_multi(rhs)
    } else {
        model.sys.lu_solve_multi(rhs)
    }
}

fn l2_norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
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
        let scale = f.force_scale;
        last_res = res;
        let atol = opts.residual_atol * (model.mat.g + model.mat.kappa);
        if res <= rtol * scale + atol {
            return Ok(it);
        }
        if it == opts.max_newton_iterations || !res.is_finite() {
            break;
        }
        let f = model
            .assemble(st, true)
            .expect("state assembled above is not inverted");
        let mut rhs = vec![f.resid.iter().map(|r| -r).collect::<Vec<f64>>()];
        if let Err(e) = linear_solve(model, &mut rhs) {
            return Err(StepFail::Linear {
                iteration: it,
                message: e.to_string(),
            });
        }
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
        let e0 = f.energy;
        let res2 = l2_norm(&f.resid);
        let mut alpha = 1.0;
        let mut accepted = None;
        for _ in 0..opts.max_line_search {
            let trial = model.updated(st, &dq, alpha);
            if slope < 0.0 && model.is_potential() {
                // energy and forces: the forces of the accepted state are cached for
                // the next convergence check
                if let Some(e) = model.assemble(&trial, false).map(|f| f.energy) {
                    if e <= e0 + 1e-4 * alpha * slope + 1e-13 * e0.abs() {
                        accepted = Some(trial);
                        break;
                    }
                }
            } else if let Some(ft) = model.assemble(&trial, false) {
                if l2_norm(&ft.resid) < (1.0 - 1e-4 * alpha) * res2 {
                    accepted = Some(trial);
                    break;
                }
            }
            alpha *= 0.5;
        }
        match accepted {
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

/// Newton iterations for the edge event on node `k` at a fixed active set: the slab
/// displacement `d` is an extra unknown and the extra equation is the gap of node `k`
/// (held free), `c(q) = 0`. Bordered solve with one factorisation:
///
/// ```text
/// K z₁ = −r,   K z₂ = −∂r/∂d,   δd = −(c + ∇c·z₁)/(∇c·z₂),   δq = z₁ + z₂ δd
/// ```
///
/// Line search on the merit `‖r‖∞ + |∂r/∂d|∞ |c|` (forces), backtracking also on
/// inversion.
pub(crate) fn newton_edge(
    model: &mut Model,
    st: &mut State,
    opts: &SolveOptions,
    k: usize,
    gap_tol: f64,
    rtol: f64,
) -> Result<usize, StepFail> {
    let mut last_res = f64::NAN;
    let mut kscale = 0.0;
    for it in 0..=opts.max_newton_iterations {
        // convergence check on the forces alone (cached after the line search), the
        // matrix only when another iteration follows
        let Some(f) = model.assemble(st, false) else {
            return Err(StepFail::Inverted {
                iteration: it,
                residual: last_res,
            });
        };
        let (c, _) = model.edge_constraint(st, k);
        let res = inf_norm(&f.resid);
        last_res = res;
        let atol = opts.residual_atol * (model.mat.g + model.mat.kappa);
        let gtol = if rtol > opts.residual_rtol {
            100.0 * gap_tol
        } else {
            gap_tol
        };
        if res <= rtol * f.force_scale + atol && c.abs() <= gtol {
            return Ok(it);
        }
        if it == opts.max_newton_iterations || !res.is_finite() || !c.is_finite() {
            break;
        }
        let f = model
            .assemble(st, true)
            .expect("state assembled above is not inverted");
        if it == 0 {
            kscale = inf_norm(&f.dresid_dd);
        }
        let merit = res + kscale * c.abs();
        if !merit.is_finite() {
            break;
        }
        let mut rhs = vec![
            f.resid.iter().map(|r| -r).collect::<Vec<f64>>(),
            f.dresid_dd.iter().map(|r| -r).collect::<Vec<f64>>(),
        ];
        if let Err(e) = linear_solve(model, &mut rhs) {
            return Err(StepFail::Linear {
                iteration: it,
                message: e.to_string(),
            });
        }
        let (z1, z2) = (&rhs[0], &rhs[1]);
        let den = gap_rate(model, st, k, z2);
        if den.abs() < 1e-300 {
            return Err(StepFail::Diverged {
                iteration: it,
                residual: res,
                reason: "edge constraint insensitive to the slab displacement".into(),
            });
        }
        let dd = -(c + gap_rate(model, st, k, z1)) / den;
        let dq: Vec<f64> = z1.iter().zip(z2).map(|(a, b)| a + b * dd).collect();
        let mut alpha = 1.0;
        let mut accepted = None;
        for _ in 0..opts.max_edge_line_search {
            let mut trial = st.clone();
            trial.d += alpha * dd;
            model.enforce_constraints(&mut trial);
            let trial = model.updated(&trial, &dq, alpha);
            if let Some(ft) = model.assemble(&trial, false) {
                let (ct, _) = model.edge_constraint(&trial, k);
                let m = inf_norm(&ft.resid) + kscale * ct.abs();
                if m < (1.0 - 1e-4 * alpha) * merit
                    || (model.kin == Kinematics::Linear && model.is_potential())
                {
                    accepted = Some(trial);
                    break;
                }
            }
            alpha *= 0.5;
        }
        match accepted {
            Some(t) => *st = t,
            None => {
                return Err(StepFail::Diverged {
                    iteration: it,
                    residual: res,
                    reason: "edge line search found no acceptable step".into(),
                })
            }
        }
    }
    Err(StepFail::Diverged {
        iteration: opts.max_newton_iterations,
        residual: last_res,
        reason: "maximum Newton iterations reached (edge solve)".into(),
    })
}

/// Converge one load step: Newton + active-set updates. `exclude` names a contact-face
/// node that is never activated (the target of the edge search). Returns the total
/// number of Newton iterations.
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
            (Some(tol), Some(k)) => newton_edge(model, st, opts, k, 0.5 * tol, rtol)?,
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
        let lam_scale = lam.iter().fold(0.0_f64, |m, l| m.max(l.abs())).max(1e-300);
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

/// Contact half-width at an edge event on node `k` (rule documented at [`trace`]).
fn edge_position(model: &Model, st: &State, k: usize, rule: EdgeRule) -> f64 {
    let b = &model.mesh.bottom;
    let x = |i: usize| st.x[b[i]][0];
    let lo = x(k.saturating_sub(1));
    let hi = x(k);
    if let EdgeRule::Fraction(phi) = rule {
        return lo + phi * (hi - lo);
    }
    if k + 2 < b.len() {
        let gaps = model.gaps(st);
        let (g1, g2) = (gaps[k + 1], gaps[k + 2]);
        if g1 > 0.0 && g2 > g1 {
            return match rule {
                EdgeRule::GapPower => {
                    let r = (g1 / g2).powf(2.0 / 3.0);
                    ((x(k + 1) - r * x(k + 2)) / (1.0 - r)).clamp(lo, hi)
                }
                EdgeRule::PeriodicGap => periodic_gap_fit(x(k + 1), x(k + 2), g1 / g2, lo, hi),
                EdgeRule::Fraction(_) => unreachable!("handled above"),
            };
        }
    }
    0.5 * (lo + hi)
}

/// Gap shape of the periodic (Westergaard) contact beyond the edge `a`, up to a
/// constant factor (units of λ, `a < x ≤ ½`):
///
/// ```text
/// g'(x) ∝ cos πx √(sin²πx − sin²πa)
/// G(x; a) = ½ [ s √(s² − c²) − c² ln((s + √(s² − c²))/c) ],  s = sin πx, c = sin πa
/// ```
///
/// (`∝ (s − c)^{3/2}` near the edge). Exact in the linear limit.
fn periodic_gap_shape(x: f64, a: f64) -> f64 {
    let pi = std::f64::consts::PI;
    let (s, c) = ((pi * x).sin(), (pi * a).sin());
    if s <= c {
        return 0.0;
    }
    if c <= 0.0 {
        return 0.5 * s * s;
    }
    let r = (s * s - c * c).sqrt();
    0.5 * (s * r - c * c * ((s + r) / c).ln())
}

/// The `a ∈ [lo, hi]` with `G(x₁; a)/G(x₂; a) = ratio` ([`periodic_gap_shape`]; the
/// ratio decreases with `a`), clamped to the interval; bisection.
fn periodic_gap_fit(x1: f64, x2: f64, ratio: f64, lo: f64, hi: f64) -> f64 {
    let r = |a: f64| periodic_gap_shape(x1, a) / periodic_gap_shape(x2, a);
    if r(lo) <= ratio {
        return lo;
    }
    if r(hi) >= ratio {
        return hi;
    }
    let (mut l, mut h) = (lo, hi);
    for _ in 0..60 {
        let m = 0.5 * (l + h);
        if r(m) > ratio {
            l = m;
        } else {
            h = m;
        }
    }
    0.5 * (l + h)
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
    // p̄ from the contact tractions: the vertical components of the contact forces, which
    // at equilibrium are the internal forces ∂Π/∂y of the active nodes.
    let lam = model.multipliers(st, &f.grad);
    let half = 0.5;
    let p_tr = lam.iter().sum::<f64>() / half / estar;
    let p_re = model.slab_reaction(&f.grad) / half / estar;
    (
        CurvePoint {
            a_over_lambda: edge_position(model, st, edge, rule),
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
        contact_pressure_over_estar: (0..n).map(|k| normal[k] / trib(k) / estar).collect(),
        contact_shear_over_estar: (0..n).map(|k| tangential[k] / trib(k) / estar).collect(),
    }
}

/// `∂q/∂d` at a converged state: `K ∂q/∂d = −∂r/∂d` (the tangent is positive definite
/// there); `None` if the state is inverted or the solve fails.
fn load_tangent(model: &mut Model, st: &State) -> Option<Vec<f64>> {
    let f = model.assemble(st, true)?;
    let mut rhs = [f.dresid_dd.iter().map(|v| -v).collect::<Vec<f64>>()];
    linear_solve(model, &mut rhs).ok()?;
    let [z] = rhs;
    Some(z)
}

/// Change `∇g_k · z` of the gap of the free contact-face node `k` along the slot vector
/// `z`: with the load tangent `z` ([`load_tangent`]) the rate `∂g_k/∂d` at which it
/// closes.
fn gap_rate(model: &Model, st: &State, k: usize, z: &[f64]) -> f64 {
    let node = model.mesh.bottom[k];
    let (_, dc) = model.edge_constraint(st, k);
    dc[0] * z[2 * node] + dc[1] * z[2 * node + 1]
}

/// Predictor for the load `cur.d + dd`: the tangent (Euler) predictor
/// `q + dd · ∂q/∂d` along the load tangent `tangent` of the converged state, else
/// linear extrapolation of the last increment, else a uniform vertical compression.
/// The first that has no inverted element is used.
fn predictor(
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

/// Trace the load curve up to `opts.until_a_over_lambda`.
///
/// Curve points are *edge events*: the load `d` at which a chosen contact-face node
/// `k` (by default the first free node; see `da_target`) touches the indenter with
/// zero contact force. Node `k` is kept free, the extra equation `g_k = 0` fixes `d`
/// (bordered Newton, [`newton_edge`]; secant/regula-falsi (Illinois) search on `d` as
/// fallback), and the other nodes follow the active-set rules.
///
/// Contact-edge location at an event (rule, see [`edge_position`] and
/// [`EdgeRule`]): the discrete solution has zero gap up to `x_k`, but its nodal forces
/// are the work-equivalent integrals `∫ p N_i dx`, so zero force on node `k` means the
/// pressure vanishes beyond `x_{k−1}`: the edge lies in `[x_{k−1}, x_k]` (current
/// positions). The default rule puts it at the fixed fraction
/// [`super::DISCRETE_EDGE_FRACTION`] of that interval, calibrated on Westergaard's
/// solution. Measured (AR = 0.01, linear, a/λ ≈ 0.11): `a = x_k` errs by −5 % in `p̄`
/// and the midpoint by +2 % (48×24 mesh). Gap fits through the next free nodes
/// ([`EdgeRule::GapPower`], [`EdgeRule::PeriodicGap`]) converge only at first order
/// at AR = 0.3 (Richardson error of the default mesh 0.6–0.9 %), the fixed fraction
/// there and at AR = 0.1 is within 0.2 % (`tests/fe_convergence.rs`).
pub(crate) fn trace(
    model: &mut Model,
    opts: &SolveOptions,
    estar: f64,
    on_step: &mut dyn FnMut(&CurvePoint),
) -> Result<Curve, Box<CurveFailure>> {
    let amp = model.indenter.amplitude;
    let nb = model.mesh.bottom.len();
    let mut cur = model.initial_state();
    let mut prev: Option<State> = None;
    let mut dd_guess = opts.first_step_over_amplitude * amp;
    let mut event_ratio = 1.0;
    let mut a_cur = 0.0;
    let mut points: Vec<CurvePoint> = Vec::new();
    let mut step = 1;
    let mut last_grad = vec![0.0; 2 * model.num_nodes()];
    let fail =
        |error: SolveError, points: Vec<CurvePoint>| Box::new(CurveFailure { error, points });
    while a_cur < opts.until_a_over_lambda {
        if step > opts.max_steps {
            return Err(fail(
                SolveError::TooManySteps {
                    steps: opts.max_steps,
                    a_over_lambda: a_cur,
                },
                points,
            ));
        }
        let xs: Vec<f64> = model.mesh.bottom.iter().map(|&n| cur.x[n][0]).collect();
        let c = (0..nb).rev().find(|&i| cur.active[i]).unwrap_or(0);
        if c + 1 >= nb {
            break; // full contact
        }
        // target: the first node at least `da_target` beyond the edge with a clearly
        // open gap (a node released with a vanishing multiplier sits at gap 0)
        let gaps_now = model.gaps(&cur);
        let open_tol = 1e-9 * amp;
        let mut k = c + 1;
        while k + 2 < nb && (xs[k] < a_cur + opts.da_target || gaps_now[k] <= open_tol) {
            k += 1;
        }
        if k + 1 >= nb {
            // the next edge node would be the valley node (x = λ/2): full contact
            break;
        }
        // Nodes skipped above touch with a vanishing force (released at the last event):
        // they carry load as soon as the load grows, so they enter the step active (left
        // free, they penetrate deeply and their late activation stalls the edge solve).
        let touching: Vec<usize> = (c + 1..k).filter(|&i| gaps_now[i] <= open_tol).collect();
        if !touching.is_empty() {
            for i in touching {
                model.activate(&mut cur, i);
            }
            model.enforce_constraints(&mut cur);
        }
        let gap_k = |m: &Model, st: &State| m.gaps(st)[k];
        let g0 = gap_k(model, &cur);
        let tol = (opts.edge_gap_rtol * g0.abs()).max(1e-15 * amp);
        let mut lo = (cur.clone(), g0);
        let mut lo_prev: Option<(State, f64)> = prev.as_ref().map(|p| (p.clone(), gap_k(model, p)));
        let mut hi: Option<(State, f64)> = None;
        let mut iters = 0;
        let mut cuts = 0;
        let mut evals = 0;
        let mut illinois_side = 0i32;
        let tangent_at = |model: &mut Model, st: &State| {
            opts.tangent_predictor
                .then(|| load_tangent(model, st))
                .flatten()
        };
        // First trial increment: the load at which node k closes, extrapolated along the
        // load tangent and scaled by the ratio of actual to extrapolated increment of the
        // previous event (the gap closes faster as the edge approaches).
        let mut z_base = tangent_at(model, &cur);
        let extrapolated = z_base.as_ref().and_then(|z| {
            let rate = gap_rate(model, &cur, k, z);
            (rate < 0.0).then(|| g0 / -rate)
        });
        let dd_first = extrapolated.map_or(dd_guess, |e| e * event_ratio);
        let mut trial = cur.d + dd_first;
        let bordered =
            |model: &mut Model, base: &State, base_prev: Option<&State>, z: Option<&[f64]>, dd| {
                predictor(model, base, base_prev, dd, z).and_then(|mut st| {
                    let it = equilibrate(model, &mut st, opts, Some(k), Some(tol)).ok()?;
                    let g = gap_k(model, &st);
                    (g.abs() <= tol && st.d > cur.d).then_some((st, it))
                })
            };
        let fast = if !opts.bordered_edge_solve {
            None
        } else if model.is_potential() {
            bordered(model, &cur, prev.as_ref(), z_base.as_deref(), dd_first)
        } else {
            // With friction the step is path dependent: when the event cannot be reached in
            // one increment, advance by converged, committed sub-steps (half the trial
            // increment, the target node held free) and retry from there.
            let mut base = cur.clone();
            let mut base_prev = prev.clone();
            let mut dd = dd_first;
            let mut spent = 0;
            let mut out = None;
            for _ in 0..=opts.max_step_cuts {
                if let Some((st, it)) =
                    bordered(model, &base, base_prev.as_ref(), z_base.as_deref(), dd)
                {
                    out = Some((st, it + spent));
                    break;
                }
                dd *= 0.5;
                let sub = predictor(model, &base, base_prev.as_ref(), dd, z_base.as_deref())
                    .and_then(|mut st| {
                        let it = equilibrate(model, &mut st, opts, Some(k), None).ok()?;
                        Some((st, it))
                    });
                if let Some((mut st, it)) = sub {
                    spent += it;
                    if gap_k(model, &st) > tol {
                        model.commit_slip(&mut st);
                        base_prev = Some(std::mem::replace(&mut base, st));
                        z_base = tangent_at(model, &base);
                    }
                }
            }
            out
        };
        let found = loop {
            if let Some((st, it)) = fast.clone() {
                iters += it;
                break st;
            }
            evals += 1;
            if evals > opts.max_edge_iterations {
                return Err(fail(
                    SolveError::EdgeSearch {
                        step,
                        node: k,
                        gap: lo.1,
                    },
                    points,
                ));
            }
            let base_d = lo.0.d;
            let z_lo = tangent_at(model, &lo.0);
            let attempt = match predictor(
                model,
                &lo.0,
                lo_prev.as_ref().map(|p| &p.0),
                trial - base_d,
                z_lo.as_deref(),
            ) {
                Some(mut st) => equilibrate(model, &mut st, opts, Some(k), None).map(|it| (st, it)),
                None => Err(StepFail::Inverted {
                    iteration: 0,
                    residual: f64::NAN,
                }),
            };
            match attempt {
                Err(f) => {
                    cuts += 1;
                    if cuts > opts.max_step_cuts {
                        return Err(fail(f.into_error(step, trial), points));
                    }
                    trial = base_d + 0.5 * (trial - base_d);
                }
                Ok((st, it)) => {
                    iters += it;
                    let g = gap_k(model, &st);
                    if g.abs() <= tol {
                        break st;
                    }
                    if g > 0.0 {
                        let old = std::mem::replace(&mut lo, (st, g));
                        lo_prev = Some(old);
                        if illinois_side == 1 {
                            if let Some(h) = hi.as_mut() {
                                h.1 *= 0.5;
                            }
                        }
                        illinois_side = 1;
                    } else {
                        if illinois_side == -1 {
                            lo.1 *= 0.5;
                        }
                        illinois_side = -1;
                        hi = Some((st, g));
                    }
                    trial = match &hi {
                        Some((hs, hg)) => {
                            let t = lo.1 / (lo.1 - hg);
                            lo.0.d + t.clamp(0.02, 0.98) * (hs.d - lo.0.d)
                        }
                        None => {
                            let span = match &lo_prev {
                                Some((ps, pg)) if pg > &lo.1 && lo.0.d > ps.d => {
                                    lo.1 * (lo.0.d - ps.d) / (pg - lo.1)
                                }
                                _ => 2.0 * (lo.0.d - cur.d).max(dd_guess),
                            };
                            let grow = opts.max_step_growth * (lo.0.d - cur.d).max(dd_guess);
                            lo.0.d + span.clamp(1e-3 * grow, grow)
                        }
                    };
                }
            }
        };
        if found.d <= cur.d {
            return Err(fail(
                SolveError::EdgeSearch {
                    step,
                    node: k,
                    gap: g0,
                },
                points,
            ));
        }
        let mut st = found;
        model.activate(&mut st, k);
        model.enforce_constraints(&mut st);
        match equilibrate(model, &mut st, opts, None, None) {
            Ok(it) => iters += it,
            Err(f) => return Err(fail(f.into_error(step, st.d), points)),
        }
        model.commit_slip(&mut st);
        let (mut pt, grad) = measure(model, &st, estar, k, opts.edge_rule);
        pt.newton_iterations = iters;
        a_cur = pt.a_over_lambda;
        on_step(&pt);
        points.push(pt);
        last_grad = grad;
        dd_guess = st.d - cur.d;
        if let Some(e) = extrapolated {
            // bounded so that one odd event (a node released and re-touching) cannot
            // throw the next prediction far off
            event_ratio = (dd_guess / e).clamp(0.5, 4.0);
        }
        prev = Some(std::mem::replace(&mut cur, st));
        step += 1;
    }
    let final_state = deformed_state(model, &cur, &last_grad, estar);
    Ok(Curve {
        points,
        final_state,
    })
}
