//! Random command lines through the parser and the argument checks: nothing panics, a rejected
//! value names its flag, a rejected `eval` writes nothing, and every row it does write is a
//! finite, non-negative pressure. Case count: `WAVY_FUZZ_CASES` (default 10 000; `make fuzz`
//! sets 1 000 000).

use super::input::normalise_negative_numbers;
use crate::{Cli, Command};
use clap::Parser;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseError, TestRunner};
use std::sync::atomic::{AtomicUsize, Ordering};

const VALUES: &[&str] = &[
    "0",
    "-0",
    "0.1",
    "0.18",
    "0.3",
    "0.45",
    "0.5",
    "0.49",
    "1",
    "2",
    "-1",
    "-1e-3",
    "1e-12",
    "1e308",
    "-1e308",
    "1e-320",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "abc",
    "",
    "1,2",
    "0x10",
    "8",
    "4",
    "2048",
    "2049",
    "coarse",
    "fine",
    "default",
    "finite",
    "linear",
    "wnl",
    "westergaard",
    "bracket-2x",
    "literal",
    "ours-literal",
    "nonsense",
];

const EVAL_FLAGS: &[&str] = &[
    "--model",
    "--reading",
    "--coefficients",
    "--ar",
    "--tau-max-mpa",
    "--a-over-lambda",
    "--p-over-estar",
];
const SOLVE_FLAGS: &[&str] = &[
    "--ar",
    "--tau-max-mpa",
    "--mu",
    "--estar-mpa",
    "--kappa-over-g",
    "--thickness-over-lambda",
    "--kinematics",
    "--mesh",
    "--until-a-over-lambda",
];

/// Numbers, mostly: the values a range check must judge.
const NUMBERS: &[&str] = &[
    "0", "-0", "0.1", "0.18", "0.3", "0.45", "0.5", "0.49", "1", "2", "-1", "-1e-3", "1e-12",
    "1e-6", "10", "100", "1e308", "-1e308", "1e-320", "nan", "inf", "-inf",
];

fn command_line() -> impl Strategy<Value = Vec<String>> {
    let flag_value = |flags: &'static [&'static str]| {
        (
            prop::sample::select(flags),
            prop::collection::vec(
                prop_oneof![3 => prop::sample::select(NUMBERS), 1 => prop::sample::select(VALUES)],
                1..3,
            ),
        )
    };
    let number = || prop::sample::select(NUMBERS);
    let eval = (
        prop::sample::select(vec!["wnl", "westergaard"]),
        number(),
        prop::sample::select(vec!["--a-over-lambda", "--p-over-estar"]),
        prop::collection::vec(number(), 1..4),
        prop::collection::vec(flag_value(EVAL_FLAGS), 0..3),
    )
        .prop_map(|(model, ar, input, values, extra)| {
            let mut a = vec!["eval", "--model", model, "--ar", ar, input];
            a.extend(values);
            (a, extra)
        });
    let solve = (
        number(),
        prop::collection::vec(flag_value(SOLVE_FLAGS), 0..4),
    )
        .prop_map(|(ar, extra)| (vec!["solve", "--ar", ar], extra));
    prop_oneof![eval, solve].prop_map(|(base, extra)| {
        let mut args: Vec<String> = std::iter::once("wavy")
            .chain(base)
            .map(String::from)
            .collect();
        for (flag, values) in extra {
            args.push(flag.to_string());
            args.extend(values.into_iter().map(String::from));
        }
        args
    })
}

#[test]
fn random_command_lines_are_answered_or_refused_by_flag() {
    let cases = std::env::var("WAVY_FUZZ_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(10_000);
    let seed = std::env::var("WAVY_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x5eed);
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(seed),
        ..Config::default()
    });
    let [usage, refused, computed] = [(); 3].map(|_| AtomicUsize::new(0));
    runner
        .run(&command_line(), |args| {
            let parsed = Cli::try_parse_from(normalise_negative_numbers(
                args.iter().map(std::ffi::OsString::from),
            ));
            let Ok(cli) = parsed else {
                usage.fetch_add(1, Ordering::Relaxed);
                return Ok(());
            };
            let outcome = match &cli.command {
                Command::Eval(a) => {
                    let mut out = Vec::new();
                    let r = super::eval::eval(a, &mut out);
                    if r.is_err() && !out.is_empty() {
                        return Err(TestCaseError::fail(format!(
                            "{args:?}: wrote before failing"
                        )));
                    }
                    if r.is_ok() {
                        let text = String::from_utf8(out).unwrap();
                        for row in text.lines().skip(1) {
                            let p: f64 = row.split(',').nth(6).unwrap().parse().unwrap();
                            prop_assert!(p.is_finite() && p >= 0.0, "{:?}: {}", args, row);
                        }
                    }
                    r.err()
                }
                Command::Solve(a) => a.setup().err(),
                _ => unreachable!("only eval and solve are generated"),
            };
            match outcome {
                None => {
                    computed.fetch_add(1, Ordering::Relaxed);
                }
                Some(e) => {
                    refused.fetch_add(1, Ordering::Relaxed);
                    let text = format!("{e:#}");
                    // an input error names its flag; a failed computation names its inputs
                    let input = super::input::is_input_error(&e);
                    prop_assert!(
                        text.contains("--"),
                        "{:?}: {} (input error: {})",
                        args,
                        text,
                        input
                    );
                }
            }
            Ok(())
        })
        .unwrap();
    println!(
        "{cases} random command lines: {} usage errors (clap), {} refused by range, {} answered",
        usage.into_inner(),
        refused.into_inner(),
        computed.into_inner()
    );
}
