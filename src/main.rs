//! `wavy`: the command line over the library.
//!
//! Exit codes: 0 success; 1 a computation failed or `check` found a regression;
//! 2 invalid input (a flag or spec value out of range, an unreadable spec, a usage error).

use anyhow::Result;
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;
use wavy::cli::{self, InputError};

#[derive(Parser)]
#[command(
    name = "wavy",
    version,
    about = "Contact area of a soft solid on a rigid wavy surface: Westergaard, WNL, finite elements"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run one experiment spec: write <out>/<stem>.svg and its CSV tables.
    Run {
        spec: PathBuf,
        #[arg(long, default_value = "figures")]
        out: PathBuf,
    },
    /// Run every experiments/*.toml (all specs are parsed before anything is written).
    Reproduce {
        #[arg(long, default_value = "experiments")]
        experiments: PathBuf,
        #[arg(long, default_value = "figures")]
        out: PathBuf,
    },
    /// Recompute every spec and compare its tables with expected/ within the spec's tolerances.
    Check {
        #[arg(long, default_value = "experiments")]
        experiments: PathBuf,
        #[arg(long, default_value = "expected")]
        expected: PathBuf,
    },
    /// Evaluate a model law, forward (a/λ → p̄/E*) or inverse (p̄/E* → a/λ); CSV on stdout,
    /// numbers in shortest round-trip form.
    Eval(cli::EvalArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            if is_input_error(&e) {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}

fn is_input_error(e: &anyhow::Error) -> bool {
    e.chain()
        .any(|c| c.is::<InputError>() || c.is::<wavy::spec::SpecError>())
}

fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Run { spec, out } => {
            let output = wavy::runner::run_spec_file(&spec)?;
            report(&output, &wavy::runner::write_outputs(&output, &out)?);
            Ok(ExitCode::SUCCESS)
        }
        Command::Reproduce { experiments, out } => {
            let specs = cli::spec_files(&experiments)?;
            for s in &specs {
                wavy::runner::load_spec(s)?;
            }
            let outputs = specs
                .iter()
                .map(|s| wavy::runner::run_spec_file(s))
                .collect::<Result<Vec<_>>>()?;
            for o in &outputs {
                report(o, &wavy::runner::write_outputs(o, &out)?);
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Check {
            experiments,
            expected,
        } => {
            let mut all_passed = true;
            for s in cli::spec_files(&experiments)? {
                let r = wavy::runner::check_spec_file(&s, &expected)?;
                print!("{}", cli::format_check_report(&r, 5));
                all_passed &= r.passed();
            }
            println!(
                "{}",
                if all_passed {
                    "check: all tables within tolerance"
                } else {
                    "check: REGRESSION"
                }
            );
            Ok(if all_passed {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            })
        }
        Command::Eval(args) => {
            print!("{}", cli::eval(&args)?);
            Ok(ExitCode::SUCCESS)
        }
    }
}

fn report(output: &wavy::runner::SceneOutput, written: &[PathBuf]) {
    for p in written {
        println!("wrote {}", p.display());
    }
    for n in &output.notes {
        println!("note ({}): {n}", output.stem);
    }
}
