//! Input values that cannot be used, named the way the command line names them (`--ar`), with
//! the value and the allowed range: the one definition of these checks and messages, shared by
//! `wavy solve` / `wavy eval` and the Python bindings (whose `ValueError` carries the same text).

use crate::fe::input_ranges::InputRange;
use crate::fe::MeshLevel;
use thiserror::Error;

/// An input value that cannot be used (the command line exits 2; Python raises `ValueError`).
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum InputError {
    /// Outside its physical range.
    #[error("{flag} = {value} is out of range; allowed: {allowed}")]
    OutOfRange {
        flag: String,
        value: String,
        allowed: String,
    },
    /// In range, but the selected model cannot be inverted there.
    #[error("{flag} = {value}: no contact half-width: {reason}")]
    NotInvertible {
        flag: String,
        value: String,
        reason: String,
    },
    /// A valid value that this command cannot serve (a tolerance no measured tier meets, a
    /// point outside the measured region, a spec of another kind).
    #[error("{flag} = {value}: {reason}")]
    Refused {
        flag: String,
        value: String,
        reason: String,
    },
}

/// An [`InputError::OutOfRange`].
pub fn out_of_range(flag: &str, value: impl ToString, allowed: impl ToString) -> InputError {
    InputError::OutOfRange {
        flag: flag.into(),
        value: value.to_string(),
        allowed: allowed.to_string(),
    }
}

/// `Ok` when `value` is in the solver's `range` ([`crate::fe::input_ranges`]), else an error
/// naming `flag` with the range's words.
pub fn within(flag: &str, range: &InputRange, value: f64) -> Result<(), InputError> {
    match range.holds(value) {
        true => Ok(()),
        false => Err(out_of_range(flag, value, range.allowed)),
    }
}

/// `Ok` when `value` is finite and `> 0`, else an error naming `flag`.
pub fn positive(flag: &str, value: f64) -> Result<(), InputError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(out_of_range(flag, value, "> 0"))
    }
}

/// `Ok` when `value` is finite and `>= 0`, else an error naming `flag`.
pub fn non_negative(flag: &str, value: f64) -> Result<(), InputError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(out_of_range(flag, value, ">= 0"))
    }
}

/// `Ok` when `value` is a contact half-width a/λ in `[0, 0.5]`, else an error naming `flag`.
pub fn a_over_lambda_in_range(flag: &str, value: f64) -> Result<(), InputError> {
    if value.is_finite() && (0.0..=0.5).contains(&value) {
        Ok(())
    } else {
        Err(out_of_range(flag, value, "[0, 0.5]"))
    }
}

/// `--mesh`: a named level or an element count along the contact face.
pub fn mesh(text: &str) -> Result<MeshLevel, InputError> {
    text.parse::<MeshLevel>()
        .map_err(|_| out_of_range("--mesh", text, MeshLevel::ALLOWED))
}

/// `--profile`: an even periodic profile as `order:aspect_ratio` pairs ([`crate::profile`]).
pub fn profile(text: &str) -> Result<crate::profile::Profile, InputError> {
    text.parse()
        .map_err(|e: crate::profile::ProfileError| InputError::Refused {
            flag: "--profile".into(),
            value: text.into(),
            reason: e.to_string(),
        })
}

/// `--vtk`: a folder (created if missing), not an existing file.
pub fn vtk_folder(path: &std::path::Path) -> Result<(), InputError> {
    match path.exists() && !path.is_dir() {
        false => Ok(()),
        true => Err(InputError::Refused {
            flag: "--vtk".into(),
            value: path.display().to_string(),
            reason: "is a file; give a folder (created if missing) for the series".into(),
        }),
    }
}
