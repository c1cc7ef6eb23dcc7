//! Command-line values that cannot be used, and the parsers that name the flag, the value and
//! the allowed range.

use clap::builder::{PossibleValuesParser, TypedValueParser};
use std::str::FromStr;
use thiserror::Error;
use wavy::fe::MeshLevel;

/// A command-line value that cannot be used (exit code 2).
#[derive(Debug, Error)]
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
}

/// An [`InputError::OutOfRange`].
pub fn out_of_range(flag: &str, value: impl ToString, allowed: impl ToString) -> InputError {
    InputError::OutOfRange {
        flag: flag.into(),
        value: value.to_string(),
        allowed: allowed.to_string(),
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

/// A parser that accepts exactly `names` (listed in `--help` and in clap's error) and turns
/// the chosen one into its library type.
pub fn one_of<T>(names: impl IntoIterator<Item = &'static str>) -> impl TypedValueParser<Value = T>
where
    T: FromStr + Clone + Send + Sync + 'static,
    T::Err: std::fmt::Debug,
{
    PossibleValuesParser::new(names)
        .map(|name: String| name.parse::<T>().expect("every listed name parses"))
}

/// `--mesh`: a named level or an element count along the contact face.
pub fn mesh(s: &str) -> Result<MeshLevel, String> {
    s.parse::<MeshLevel>().map_err(|_| {
        format!(
            "--mesh = {s} is out of range; allowed: {}",
            MeshLevel::ALLOWED
        )
    })
}
