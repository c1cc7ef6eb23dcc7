//! Command-line values that cannot be used (the checks and messages are the library's,
//! `wavy::runner::requests::input_checks`), and the clap parsers that name the flag, the value and the allowed range.

use clap::builder::{PossibleValuesParser, TypedValueParser};
use std::str::FromStr;
use wavy::fe::MeshLevel;
pub use wavy::runner::requests::input_checks::{non_negative, out_of_range, positive, InputError};
use wavy::runner::requests::request_error::RequestError;

/// True when `e` is (or was caused by) an input that cannot be used, an unusable request or an
/// invalid spec: exit 2.
pub fn is_input_error(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.is::<InputError>()
            || c.is::<wavy::spec::SpecError>()
            || c.downcast_ref::<RequestError>()
                .is_some_and(RequestError::is_input)
    })
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

/// `--mesh`: a named level or an element count along the contact face (the library's check,
/// its message for clap).
pub fn mesh(s: &str) -> Result<MeshLevel, String> {
    wavy::runner::requests::input_checks::mesh(s).map_err(|e| e.to_string())
}

/// An even periodic profile, `order:aspect_ratio` pairs or `weierstrass:AR0,gamma,D,K`
/// (`wavy::profile`; the library's check,
/// the profile's own message for clap, which names the flag itself).
pub fn profile(s: &str) -> Result<wavy::profile::Profile, String> {
    wavy::runner::requests::input_checks::profile(s).map_err(|e| match e {
        InputError::Refused { reason, .. } => reason,
        other => other.to_string(),
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
