//! Typed errors of the finite-element solver.

/// Why a curve could not be completed (or started).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// The caller's step callback asked to stop (`ControlFlow::Break`), after `points`
    /// converged points: an ordinary return, not a numerical failure.
    #[error("stopped by the caller after {points} converged points")]
    Stopped {
        /// Converged points handed to the callback, the last one included.
        points: usize,
    },
    /// An input is outside its allowed range.
    #[error("invalid input: {field} = {value} (allowed: {allowed})")]
    InvalidInput {
        /// Field name.
        field: &'static str,
        /// Offending value.
        value: f64,
        /// Allowed range, in words.
        allowed: &'static str,
    },
    /// Newton's method did not converge even after the maximum number of step cuts.
    #[error("Newton diverged at load step {step} (slab displacement d/λ = {slab_displacement_over_lambda:.6e}), iteration {iteration}, residual norm {residual:.3e}: {reason}")]
    NewtonDiverged {
        /// Load step (1-based) that failed.
        step: usize,
        /// Newton iteration at which it gave up.
        iteration: usize,
        /// Residual norm (∞-norm, units `G λ`) at that iteration.
        residual: f64,
        /// Trial slab displacement.
        slab_displacement_over_lambda: f64,
        /// What went wrong in the last attempt.
        reason: String,
    },
    /// Every trial configuration had an inverted element (J ≤ 0) even after the
    /// maximum number of step cuts.
    #[error("element inversion (J <= 0) at load step {step}, iteration {iteration}, residual norm {residual:.3e}")]
    Inverted {
        /// Load step (1-based).
        step: usize,
        /// Newton iteration.
        iteration: usize,
        /// Residual norm at the last valid iterate.
        residual: f64,
    },
    /// The contact active set did not settle.
    #[error("contact active set did not settle at load step {step} after {iterations} updates")]
    ActiveSetCycling {
        /// Load step (1-based).
        step: usize,
        /// Active-set updates performed.
        iterations: usize,
    },
    /// The slab displacement at which the next contact-face node touches could not be found.
    #[error(
        "edge search did not converge at load step {step} (node {node}, remaining gap {gap:.3e})"
    )]
    EdgeSearch {
        /// Load step.
        step: usize,
        /// Contact-face node index (from the peak).
        node: usize,
        /// Smallest positive gap reached (units of λ).
        gap: f64,
    },
    /// The sparse factorisation failed.
    #[error("sparse solve failed at load step {step}, iteration {iteration}: {message}")]
    LinearSolve {
        /// Load step.
        step: usize,
        /// Newton iteration.
        iteration: usize,
        /// faer's message.
        message: String,
    },
    /// Every contact-face node is in contact (the valley node touched) before the contact
    /// half-width reached its target: the mesh cannot resolve a larger one.
    #[error("the contact is complete at a/λ = {a_over_lambda:.4}, short of the target {target:.4}: the valley node touched, and this mesh resolves no contact edge beyond its last element; refine the mesh (more elements along the face) or lower the target")]
    TargetBeyondMesh {
        /// Contact half-width reached (the edge in the last element).
        a_over_lambda: f64,
        /// The requested `until_a_over_lambda`.
        target: f64,
    },
    /// Every contact-face node is in contact before the contact fraction reached its target.
    #[error("the contact is complete at a contact fraction of {contact_fraction:.4}, short of the target {target:.4}: every contact-face node touched; lower the target")]
    ContactFractionBeyondMesh {
        /// Contact fraction reached.
        contact_fraction: f64,
        /// The requested `until_contact_fraction`.
        target: f64,
    },
    /// A profile harmonic that the mesh resolves with too few elements.
    #[error("profile harmonic {order} (wavelength λ/{order}) spans {elements_per_wavelength:.1} face elements where the mesh is coarsest; at least {min} are needed: refine the mesh (more elements along the face) or drop the harmonic")]
    ProfileUnresolved {
        /// The harmonic's order.
        order: u32,
        /// Face elements per its wavelength at the largest face spacing.
        elements_per_wavelength: f64,
        /// The least allowed.
        min: f64,
    },
    /// A profile whose slopes the solver cannot follow.
    #[error("profile slopes up to Σ 2π AR_k = {slope_bound:.3} exceed {limit:.3} (the steepest sinusoid the solver is verified on); harmonic {steepest_order} contributes most ({steepest_slope:.3}): lower its aspect ratio")]
    ProfileTooSteep {
        /// `Σ 2π AR_k`.
        slope_bound: f64,
        /// The largest allowed.
        limit: f64,
        /// The harmonic contributing most.
        steepest_order: u32,
        /// Its `2π AR_k`.
        steepest_slope: f64,
    },
    /// An unloading step failed even after the maximum number of step cuts.
    #[error("unloading stopped at slab displacement d/λ = {slab_displacement_over_lambda:.6e} (next target {target:.6e}) after {cuts} step cuts: {reason}")]
    UnloadingStalled {
        /// Slab displacement of the last converged unloading state.
        slab_displacement_over_lambda: f64,
        /// The slab displacement the failed step aimed at (units of λ).
        target: f64,
        /// Step cuts tried.
        cuts: usize,
        /// The last attempt's failure.
        reason: String,
    },
    /// Contact persisted with a positive mean pressure while the slab retracted as far
    /// beyond its starting position as it had been pressed in.
    #[error("unloading: contact persists at d/λ = {slab_displacement_over_lambda:.6e} with p̄/E* = {p_over_estar:.3e} ({active_nodes} nodes in contact)")]
    ContactPersists {
        /// Slab displacement reached.
        slab_displacement_over_lambda: f64,
        /// Mean pressure there.
        p_over_estar: f64,
        /// Contact-face nodes still in contact.
        active_nodes: usize,
    },
    /// The contact half-width reached its limit before the mean pressure reached its
    /// target ([`super::SolveOptions::until_p_over_estar`]).
    #[error("the contact half-width reached its limit a/λ = {a_over_lambda:.4} at p̄/E* = {p_over_estar:.4}, short of the target p̄/E* = {target:.4}; {}", pressure_limit_advice(*a_over_lambda))]
    PressureTargetBeyondLimit {
        /// Contact half-width reached.
        a_over_lambda: f64,
        /// Mean pressure reached.
        p_over_estar: f64,
        /// The requested `until_p_over_estar`.
        target: f64,
    },
    /// A profile reached full contact (every face node in contact) before the mean pressure
    /// reached its target ([`super::SolveOptions::until_p_over_estar`]): no contact state of the
    /// mesh carries more.
    #[error("full contact was reached at p̄/E* = {p_over_estar:.4}, short of the target p̄/E* = {target:.4}: lower the target below full contact")]
    PressureTargetBeyondFullContact {
        /// Mean pressure at full contact.
        p_over_estar: f64,
        /// The requested `until_p_over_estar`.
        target: f64,
    },
    /// The load-step budget was exhausted before reaching the target contact width.
    #[error("maximum number of load steps ({steps}) reached at a/λ = {a_over_lambda:.4}")]
    TooManySteps {
        /// Steps taken.
        steps: usize,
        /// Contact half-width reached.
        a_over_lambda: f64,
    },
}

/// A failed curve: the error and the points converged before it.
#[derive(Debug, Clone, thiserror::Error)]
#[error("{error} (after {} converged points)", points.len())]
pub struct CurveFailure {
    /// What stopped the solve.
    #[source]
    pub error: SolveError,
    /// Points converged so far (loading branch).
    pub points: Vec<super::CurvePoint>,
    /// Points converged on the unloading branch before the failure (empty when it failed
    /// while loading, or when no unloading was asked for).
    pub unloading: Vec<super::CurvePoint>,
}

/// One attempt at a load step that failed: why, and the Newton iterations it spent.
#[derive(Debug, Clone)]
pub(crate) struct StepFail {
    cause: FailCause,
    /// Newton iterations the attempt spent: every active-set pass and every try it made.
    iterations: usize,
}

/// What stopped an attempt at a load step.
#[derive(Debug, Clone)]
pub(crate) enum FailCause {
    /// No convergence within the pass's iterations (`iteration`: the pass's, where it stopped).
    Diverged {
        iteration: usize,
        residual: f64,
        reason: String,
    },
    Inverted {
        iteration: usize,
        residual: f64,
    },
    /// The active set still changed after `updates` updates.
    Cycling {
        updates: usize,
    },
    Linear {
        iteration: usize,
        message: String,
    },
}

impl From<FailCause> for StepFail {
    /// A failure within one Newton pass: the attempt spent the pass's iterations so far (a
    /// caller that spent more before it adds them, [`StepFail::after`]).
    fn from(cause: FailCause) -> Self {
        let iterations = match &cause {
            FailCause::Diverged { iteration, .. }
            | FailCause::Inverted { iteration, .. }
            | FailCause::Linear { iteration, .. } => *iteration,
            FailCause::Cycling { .. } => 0,
        };
        StepFail { cause, iterations }
    }
}

/// The advice of [`SolveError::PressureTargetBeyondLimit`]: one the caller can follow. At
/// a/λ ≈ ½ no larger `until_a_over_lambda` is allowed.
fn pressure_limit_advice(a_over_lambda: f64) -> &'static str {
    if a_over_lambda >= 0.4995 {
        "no larger until_a_over_lambda exists (it must stay below 0.5): lower the target"
    } else {
        "raise until_a_over_lambda (below 0.5) or lower the target"
    }
}

impl StepFail {
    /// The active set did not settle in `updates` updates, after `iterations` Newton iterations.
    pub(crate) fn cycling(updates: usize, iterations: usize) -> Self {
        StepFail {
            cause: FailCause::Cycling { updates },
            iterations,
        }
    }

    /// The same failure, after `earlier` Newton iterations spent before it on the same attempt
    /// (earlier active-set passes, an earlier try).
    pub(crate) fn after(self, earlier: usize) -> Self {
        StepFail {
            iterations: self.iterations + earlier,
            ..self
        }
    }

    /// The Newton iterations the failed attempt spent, all of them.
    pub(crate) fn iterations(&self) -> usize {
        self.iterations
    }

    pub(crate) fn into_error(self, step: usize, d: f64) -> SolveError {
        match self.cause {
            FailCause::Diverged {
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
            FailCause::Inverted {
                iteration,
                residual,
            } => SolveError::Inverted {
                step,
                iteration,
                residual,
            },
            FailCause::Cycling { updates } => SolveError::ActiveSetCycling {
                step,
                iterations: updates,
            },
            FailCause::Linear { iteration, message } => SolveError::LinearSolve {
                step,
                iteration,
                message,
            },
        }
    }
}
