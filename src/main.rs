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
    /// Run one experiment spec: write <out>/<stem>.svg and its CSV tables. With --shard i/n,
    /// compute only this shard's finite-element cases into the cache and write no figure.
    Run {
        spec: PathBuf,
        #[arg(long, default_value = "figures")]
        out: PathBuf,
        #[command(flatten)]
        sweep: cli::SweepArgs,
        /// Compute only the cases with index ≡ i (mod n) into the cache (0 <= i < n).
        #[arg(long)]
        shard: Option<wavy::runner::sweep::Shard>,
    },
    /// Run every experiments/*.toml (all specs are parsed before anything is written).
    Reproduce {
        #[arg(long, default_value = "experiments")]
        experiments: PathBuf,
        #[arg(long, default_value = "figures")]
        out: PathBuf,
        #[command(flatten)]
        sweep: cli::SweepArgs,
    },
    /// Recompute every spec and compare its tables with expected/ within the spec's tolerances.
    Check {
        #[arg(long, default_value = "experiments")]
        experiments: PathBuf,
        #[arg(long, default_value = "expected")]
        expected: PathBuf,
        #[command(flatten)]
        sweep: cli::SweepArgs,
    },
    /// Solve the finite-element contact problem: one CSV row per converged load step on stdout,
    /// from first contact until a/λ reaches the target (non-zero exit, after the converged rows,
    /// when the solver cannot go on).
    Solve(cli::SolveArgs),
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
        Command::Run {
            spec,
            out,
            sweep,
            shard,
        } => {
            let mut opts = sweep.run_options()?;
            if let Some(shard) = shard {
                opts.sweep.shard = Some(shard);
                let (computed, cached) = wavy::runner::compute_share(&spec, &opts)?;
                println!(
                    "shard {}/{}: computed {computed} case(s); {cached} of the spec's cases are in the cache",
                    shard.index, shard.count
                );
                return Ok(ExitCode::SUCCESS);
            }
            let output = wavy::runner::run_spec_file(&spec, &opts)?;
            report(&output, &wavy::runner::write_outputs(&output, &out)?);
            Ok(ExitCode::SUCCESS)
        }
        Command::Reproduce {
            experiments,
            out,
            sweep,
        } => {
            let opts = sweep.run_options()?;
            let specs = cli::spec_files(&experiments)?;
            for s in &specs {
                wavy::runner::load_spec(s)?;
            }
            let outputs = specs
                .iter()
                .map(|s| wavy::runner::run_spec_file(s, &opts))
                .collect::<Result<Vec<_>>>()?;
            for o in &outputs {
                report(o, &wavy::runner::write_outputs(o, &out)?);
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Check {
            experiments,
            expected,
            sweep,
        } => {
            let opts = sweep.run_options()?;
            let mut all_passed = true;
            for s in cli::spec_files(&experiments)? {
                let r = wavy::runner::check_spec_file(&s, &expected, &opts)?;
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
        Command::Solve(args) => solve(&args),
        Command::Eval(args) => {
            print!("{}", cli::eval(&args)?);
            Ok(ExitCode::SUCCESS)
        }
    }
}

fn solve(args: &cli::SolveArgs) -> Result<ExitCode> {
    use std::io::{IsTerminal, Write};
    let (problem, opts) = cli::solve_setup(args)?;
    let bar = std::io::stderr().is_terminal().then(|| {
        let b = indicatif::ProgressBar::new_spinner();
        b.set_style(
            indicatif::ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
                .expect("valid template"),
        );
        b
    });
    let mut out = std::io::stdout().lock();
    writeln!(out, "{}", cli::SOLVE_HEADER)?;
    let mut write_error = None;
    let result = wavy::fe::solve_curve(&problem, &opts, &mut |p| {
        if let Some(b) = &bar {
            b.set_message(format!(
                "a/λ = {:.4}, p̄/E* = {:.5}",
                p.a_over_lambda, p.p_over_estar
            ));
            b.tick();
        }
        if write_error.is_none() {
            if let Err(e) = writeln!(out, "{}", cli::solve_row(p)) {
                write_error = Some(e);
            }
        }
    });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if let Some(e) = write_error {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            return Ok(ExitCode::SUCCESS);
        }
        return Err(e.into());
    }
    match result {
        Ok(_) => Ok(ExitCode::SUCCESS),
        Err(failure) => {
            eprintln!("error: the solver stopped: {}", failure.error);
            Ok(ExitCode::from(1))
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
