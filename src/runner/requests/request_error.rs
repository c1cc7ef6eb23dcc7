//! Why a single evaluation or solve asked for by `wavy eval`, `wavy solve` or the Python
//! bindings gave no answer: an input that cannot be used (exit 2, `ValueError`) or a
//! computation that failed (exit 1, `RuntimeError` / `wavy.SolveError`).

use crate::accuracy::measured::ChoiceError;
use crate::fe::SolveError;
use crate::models::{InverseError, UnphysicalPressure};
use crate::runner::requests::input_checks::InputError;
use crate::runner::requests::solve_outcome::SolveOutcome;
use thiserror::Error;

/// Why a request gave no answer. `Display` is the message the command line prints after
/// `error: `, with the sources appended as `: source` (see [`full_message`]).
#[derive(Debug, Error)]
pub enum RequestError {
    /// An input value that cannot be used.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The committed speed–accuracy measurements (behind `--tolerance` and `--error-estimate`)
    /// are missing or unreadable.
    #[error(transparent)]
    Measurements(#[from] ChoiceError),
    /// A law gave no physical pressure at a point; `inputs` names the law and the point.
    #[error("{inputs}")]
    Unphysical {
        inputs: String,
        #[source]
        source: UnphysicalPressure,
    },
    /// The inverse of a law failed numerically; `inputs` names the law and the pressure.
    #[error("{inputs}")]
    Inverse {
        inputs: String,
        #[source]
        source: InverseError,
    },
    /// A computation that failed, the whole message (which inputs, what stopped).
    #[error("{0}")]
    Failed(String),
    /// The solve would need more memory than the caller allows or the machine has available
    /// (`cost_estimate`); the message names the estimate. Python: `MemoryError`.
    #[error("{0}")]
    Memory(String),
    /// The solver stopped before the target; `partial` holds the points converged before.
    #[error("the solver stopped: {error}")]
    Stopped {
        error: SolveError,
        partial: Box<SolveOutcome>,
    },
    /// The caller's step callback asked to stop (Ctrl-C in Python); `partial` holds the points
    /// converged before.
    #[error("the solve was interrupted after {} converged points", partial.rows.len())]
    Interrupted { partial: Box<SolveOutcome> },
}

impl RequestError {
    /// True for an input that cannot be used (exit 2), false for a failed computation.
    pub fn is_input(&self) -> bool {
        matches!(self, RequestError::Input(_))
    }
}

/// `error` and its sources joined by `": "`: what the command line prints after `error: `
/// (anyhow's alternate form), for callers that print errors without anyhow.
pub fn full_message(error: &dyn std::error::Error) -> String {
    let mut message = error.to_string();
    let mut source = error.source();
    while let Some(s) = source {
        message.push_str(": ");
        message.push_str(&s.to_string());
        source = s.source();
    }
    message
}
