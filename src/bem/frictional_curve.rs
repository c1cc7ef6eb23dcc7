//! A frictional load curve on the boundary-element solver: increments of the mean pressure from
//! first contact to a target, each from the last committed state ([`FrictionalContact`]), then,
//! if asked, back down through the same pressures with the slip history carried through; and
//! the loop's energy both ways, `∮ p̄ dδ` against the work of friction at the face.
//!
//! The loading pressures: `n` points `p̄_j = p̄₀ (j/n)²` (`j = 1 … n`; even steps of the contact
//! half-width for a parabolic crest, where `p̄ ∝ a²`), `p̄₀` the frictionless pressure at the
//! target (history-free, so found by bisection on [`super::solve_on`]); friction stiffens the
//! contact, so the curve goes on in steps of the last increment until it passes the target,
//! and the step that passes it is solved again from the same committed state at the pressure
//! that lands on it (regula falsi, to `1e-9` of the target).

use super::frictional_contact::{FrictionalContact, FrictionalProblem, Increment};
use super::BemError;
use std::ops::ControlFlow;

/// Where loading stops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LoadTarget {
    /// The outermost patch edge `a/λ` (the half-width of a sinusoid's contact), in `(0, ½)`.
    ContactHalfWidth(f64),
    /// The contact fraction (total contact length over λ), in `(0, 1)`.
    ContactFraction(f64),
    /// The mean pressure `p̄/E*`, `> 0`.
    MeanPressure(f64),
}

impl LoadTarget {
    /// The measure the target is stated in, of an increment.
    fn measure(self, inc: &Increment) -> f64 {
        match self {
            LoadTarget::ContactHalfWidth(_) => outermost_edge(inc),
            LoadTarget::ContactFraction(_) => inc.contact_fraction,
            LoadTarget::MeanPressure(_) => inc.p_over_estar,
        }
    }

    fn value(self) -> f64 {
        match self {
            LoadTarget::ContactHalfWidth(v)
            | LoadTarget::ContactFraction(v)
            | LoadTarget::MeanPressure(v) => v,
        }
    }
}

/// The end of the outermost contact patch in `[0, ½]` (`a/λ` of a sinusoid).
pub fn outermost_edge(inc: &Increment) -> f64 {
    inc.patches.last().map_or(0.0, |p| p[1])
}

/// A computed curve: the increments of each branch, in the order they were solved.
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionalCurve {
    pub loading: Vec<Increment>,
    /// Back through the loading pressures to the first (empty without unloading).
    pub unloading: Vec<Increment>,
}

impl FrictionalCurve {
    /// `∮ p̄ dδ` over E* λ² (trapezoid rule): loading from `(0, 0)`, unloading back to the first
    /// loading pressure and on to `(0, 0)`; with friction, the work the loop dissipates.
    pub fn cycle_work_over_estar_lambda2(&self) -> f64 {
        let origin = (0.0, 0.0);
        let path = std::iter::once(origin)
            .chain(
                self.loading
                    .iter()
                    .chain(&self.unloading)
                    .map(|i| (i.approach_over_lambda, i.p_over_estar)),
            )
            .chain(std::iter::once(origin));
        let points: Vec<(f64, f64)> = path.collect();
        points
            .windows(2)
            .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
            .sum()
    }

    /// The work of friction at the face over every increment (`Σ |q| |Δu_x| / N`), over E* λ².
    pub fn face_dissipation_over_estar_lambda2(&self) -> f64 {
        self.loading
            .iter()
            .chain(&self.unloading)
            .map(|i| i.dissipation_over_estar_lambda2)
            .sum()
    }
}

/// The curve of `problem` through given mean pressures (p̄/E*, each `> 0`): `loading` then
/// `unloading`, every increment committed, so that the slip history is that of another solver's
/// load path (the finite elements' node events, for instance) and both solve the same
/// backward-Euler problem of friction.
pub fn follow_pressures(
    problem: &FrictionalProblem,
    loading: &[f64],
    unloading: &[f64],
) -> Result<FrictionalCurve, BemError> {
    let mut contact = FrictionalContact::new(problem)?;
    let mut branch = |pressures: &[f64]| -> Result<Vec<Increment>, BemError> {
        pressures
            .iter()
            .map(|&p| {
                let inc = contact.increment(p)?;
                contact.commit(&inc);
                Ok(inc)
            })
            .collect()
    };
    let loading = branch(loading)?;
    let unloading = branch(unloading)?;
    Ok(FrictionalCurve { loading, unloading })
}

/// What the curve is asked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveRequest {
    pub target: LoadTarget,
    /// Loading points up to the frictionless pressure at the target (≥ 2).
    pub points: usize,
    pub unload: bool,
}

/// The most loading increments past the planned ones before a target is declared out of reach.
const MAX_EXTRA_STEPS: usize = 400;

/// What sees each committed increment with its branch (`false` loading, `true` unloading);
/// `Break` stops the curve ([`BemError::Stopped`]).
pub type OnIncrement<'a> = dyn FnMut(bool, &Increment) -> ControlFlow<()> + 'a;

/// Solves the curve of `problem` as `request` says; `on_increment` sees each converged
/// increment as soon as it is committed.
pub fn solve_curve(
    problem: &FrictionalProblem,
    request: &CurveRequest,
    on_increment: &mut OnIncrement,
) -> Result<FrictionalCurve, BemError> {
    check_request(request)?;
    let mut contact = FrictionalContact::new(problem)?;
    let p_end = frictionless_pressure_at(problem, request.target)?;
    let mut loading: Vec<Increment> = vec![];
    let n = request.points;
    let mut p_last = 0.0;
    for step in 1..=n + MAX_EXTRA_STEPS {
        let p = if step <= n {
            p_end * (step as f64 / n as f64).powi(2)
        } else {
            p_last + p_end * (1.0 - ((n - 1) as f64 / n as f64).powi(2))
        };
        let trial = contact.increment(p)?;
        let reached = request.target.measure(&trial) >= request.target.value();
        let inc = if reached {
            let below = (
                p_last,
                loading.last().map_or(0.0, |i| request.target.measure(i)),
            );
            land_on_target(&mut contact, request.target, below, p, trial)?
        } else {
            trial
        };
        contact.commit(&inc);
        let flow = on_increment(false, &inc);
        p_last = inc.p_over_estar;
        loading.push(inc);
        if flow.is_break() {
            return Err(BemError::Stopped {
                increments: loading.len(),
            });
        }
        if reached {
            let unloading = unload(&mut contact, &loading, request.unload, on_increment)?;
            return Ok(FrictionalCurve { loading, unloading });
        }
    }
    Err(BemError::TargetOutOfReach {
        target: request.target.value(),
        reached: loading.last().map_or(0.0, |i| request.target.measure(i)),
        increments: loading.len(),
    })
}

/// The ranges of a curve request.
fn check_request(request: &CurveRequest) -> Result<(), BemError> {
    let (value, ok, field, allowed) = match request.target {
        LoadTarget::ContactHalfWidth(a) => (a, a > 0.0 && a < 0.5, "target a/λ", "(0, ½)"),
        LoadTarget::ContactFraction(c) => {
            (c, c > 0.0 && c < 1.0, "target contact fraction", "(0, 1)")
        }
        LoadTarget::MeanPressure(p) => (p, p > 0.0 && p.is_finite(), "target p̄/E*", "finite, > 0"),
    };
    if !ok {
        return Err(BemError::InvalidInput {
            field,
            value,
            allowed,
        });
    }
    if request.points < 2 {
        return Err(BemError::InvalidInput {
            field: "loading points",
            value: request.points as f64,
            allowed: "≥ 2",
        });
    }
    Ok(())
}

/// The frictionless mean pressure at `target` (the target itself for a pressure), by bisection
/// on the history-free frictionless solution.
fn frictionless_pressure_at(
    problem: &FrictionalProblem,
    target: LoadTarget,
) -> Result<f64, BemError> {
    if let LoadTarget::MeanPressure(p) = target {
        return Ok(p);
    }
    let full = super::full_contact_pressure_on(problem.profile, problem.body)?;
    let measure = |p: f64| -> Result<f64, BemError> {
        let s = super::solve_on(
            problem.profile,
            problem.body,
            p,
            problem.points_per_wavelength,
            problem.tol,
        )?;
        Ok(match target {
            LoadTarget::ContactHalfWidth(_) => s.patches.last().map_or(0.0, |p| p[1]),
            _ => s.contact_fraction,
        })
    };
    let (mut lo, mut hi) = (0.0, full);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if measure(mid)? < target.value() {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-6 * hi {
            break;
        }
    }
    Ok(hi)
}

/// The increment from the committed state that lands on `target`, between `below` (the
/// committed pressure and its measure, short of the target) and the pressure `p_above` (whose
/// `trial` passes it): regula falsi (Illinois) on the target's measure, to `1e-9` of the target
/// or 60 solves.
fn land_on_target(
    contact: &mut FrictionalContact,
    target: LoadTarget,
    below: (f64, f64),
    p_above: f64,
    trial: Increment,
) -> Result<Increment, BemError> {
    if let LoadTarget::MeanPressure(p) = target {
        return if trial.p_over_estar == p {
            Ok(trial)
        } else {
            contact.increment(p)
        };
    }
    let goal = target.value();
    let (mut lo, mut f_lo) = (below.0, below.1 - goal);
    let (mut hi, mut f_hi) = (p_above, target.measure(&trial) - goal);
    let mut best = trial;
    let mut side = 0i8;
    for _ in 0..60 {
        if f_hi.abs() <= 1e-9 * goal {
            break;
        }
        let p = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
        let p = if p > lo && p < hi { p } else { 0.5 * (lo + hi) };
        let inc = contact.increment(p)?;
        let f = target.measure(&inc) - goal;
        if f >= 0.0 {
            (hi, f_hi) = (p, f);
            best = inc;
            if side == 1 {
                f_lo *= 0.5;
            }
            side = 1;
        } else {
            (lo, f_lo) = (p, f);
            if side == -1 {
                f_hi *= 0.5;
            }
            side = -1;
        }
        if hi - lo <= 1e-14 * hi {
            break;
        }
    }
    Ok(best)
}

/// The unloading branch: the loading pressures in reverse down to the first, each an increment
/// from the last.
fn unload(
    contact: &mut FrictionalContact,
    loading: &[Increment],
    unload: bool,
    on_increment: &mut OnIncrement,
) -> Result<Vec<Increment>, BemError> {
    if !unload {
        return Ok(vec![]);
    }
    let mut out = vec![];
    for p in loading.iter().rev().skip(1).map(|i| i.p_over_estar) {
        let inc = contact.increment(p)?;
        contact.commit(&inc);
        let flow = on_increment(true, &inc);
        out.push(inc);
        if flow.is_break() {
            return Err(BemError::Stopped {
                increments: loading.len() + out.len(),
            });
        }
    }
    Ok(out)
}
