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

/// Flags that take a list of numbers.
const NUMBER_LISTS: [&str; 2] = ["--a-over-lambda", "--p-over-estar"];

/// Rewrites negative numbers in exponent or word form (`-1e-3`, `-inf`) inside the value lists
/// of [`NUMBER_LISTS`] to plain decimals (`-0.001`, `-1e999`), which clap recognises as
/// negative numbers rather than short flags; the value is unchanged (shortest round-trip
/// decimal), so the range check can name the flag, the value and the allowed range.
/// Single-value numeric flags take any hyphenated value directly (`allow_hyphen_values`).
pub fn normalise_negative_numbers(
    args: impl IntoIterator<Item = std::ffi::OsString>,
) -> Vec<std::ffi::OsString> {
    let mut in_list = false;
    args.into_iter()
        .map(|arg| {
            let Some(text) = arg.to_str() else {
                in_list = false;
                return arg;
            };
            if text.starts_with("--") {
                in_list = NUMBER_LISTS.contains(&text);
                return arg;
            }
            match text.parse::<f64>() {
                Ok(v) if in_list && text.starts_with('-') && v.is_finite() => format!("{v}").into(),
                Ok(v) if in_list && text.starts_with('-') && v.is_infinite() => "-1e999".into(),
                _ => arg,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negative_numbers_in_lists_become_plain_decimals_of_the_same_value() {
        let args = [
            "eval",
            "--ar",
            "-1e-3",
            "--a-over-lambda",
            "0.1",
            "-1e-3",
            "-inf",
            "-2",
            "--p-over-estar",
            "-1E+2",
            "--tau-max-mpa",
            "-1e-3",
        ];
        let out: Vec<String> = normalise_negative_numbers(args.map(Into::into))
            .into_iter()
            .map(|a| a.into_string().unwrap())
            .collect();
        assert_eq!(
            out,
            [
                "eval",
                "--ar",
                "-1e-3",
                "--a-over-lambda",
                "0.1",
                "-0.001",
                "-1e999",
                "-2",
                "--p-over-estar",
                "-100",
                "--tau-max-mpa",
                "-1e-3",
            ]
        );
        assert_eq!("-1e999".parse::<f64>(), Ok(f64::NEG_INFINITY));
    }
}
