//! `wavy`: the command line over the library.
//!
//! Exit codes: 0 success (also when the reader of stdout closed the pipe early); 1 a
//! computation failed or `check` found a regression; 2 invalid input (a flag or spec value
//! out of range, an unreadable spec, a usage error).

mod cli;

use clap::{Parser, Subcommand};
use cli::output::{is_closed_pipe, Stdout};
use std::path::PathBuf;
use std::process::ExitCode;

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
        /// The experiment spec (a TOML file such as experiments/fig3_fe_vs_model.toml).
        spec: PathBuf,
        /// Folder the SVG and CSV files are written to.
        #[arg(long, default_value = "figures")]
        out: PathBuf,
        #[command(flatten)]
        sweep: cli::specs::SweepArgs,
        /// Compute only the cases with index ≡ i (mod n) into the cache (0 <= i < n).
        #[arg(long)]
        shard: Option<wavy::runner::sweep::Shard>,
    },
    /// Run every experiments/*.toml (all specs are parsed before anything is written).
    Reproduce {
        /// Folder of the experiment specs (*.toml).
        #[arg(long, default_value = "experiments")]
        experiments: PathBuf,
        /// Folder the SVG and CSV files are written to.
        #[arg(long, default_value = "figures")]
        out: PathBuf,
        #[command(flatten)]
        sweep: cli::specs::SweepArgs,
    },
    /// Recompute every spec and compare its tables with expected/ within the spec's tolerances.
    Check {
        /// Folder of the experiment specs (*.toml).
        #[arg(long, default_value = "experiments")]
        experiments: PathBuf,
        /// Folder of the golden CSV tables.
        #[arg(long, default_value = "expected")]
        expected: PathBuf,
        #[command(flatten)]
        sweep: cli::specs::SweepArgs,
    },
    /// Solve the finite-element contact problem: one CSV row per converged load step on stdout,
    /// from first contact until a/λ reaches the target (non-zero exit, after the converged rows,
    /// when the solver cannot go on).
    Solve(Box<cli::solve::SolveArgs>),
    /// Compare the figures' tables with a git revision: review/<figure>.svg overlays (base grey
    /// and dashed) and review/summary.md, what moved per panel; exit 1 when something moved
    /// beyond a spec's [check] tolerances.
    Diff(cli::diff::DiffArgs),
    /// Evaluate a model law, forward (a/λ → p̄/E*) or inverse (p̄/E* → a/λ), or with --profile
    /// its recursive superposition (p̄/E* → contact fraction); CSV on stdout, numbers in
    /// shortest round-trip form.
    Eval(Box<cli::eval::EvalArgs>),
    /// Measure the wall time of every tier of a speed_accuracy spec (one thread, median of
    /// runs) and write the timings file its figure reads (make bench-tiers).
    TimeTiers(cli::timing::TimeTiersArgs),
    /// Solve every case of a speed_accuracy spec on its reference meshes and write the limit of
    /// those curves that its figure measures the tiers against (make reference).
    RefineReference(cli::reference::RefineReferenceArgs),
}

fn main() -> ExitCode {
    let args = cli::input::normalise_negative_numbers(std::env::args_os());
    let cli = match Cli::try_parse_from(args) {
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
    let mut out = Stdout::lock();
    match run(cli, &mut out) {
        Ok(code) => code,
        Err(e) if is_closed_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            if cli::input::is_input_error(&e) {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}

fn run(cli: Cli, out: &mut Stdout) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Run {
            spec,
            out: dir,
            sweep,
            shard,
        } => cli::specs::run(&spec, &dir, &sweep, shard, out).map(|()| ExitCode::SUCCESS),
        Command::Reproduce {
            experiments,
            out: dir,
            sweep,
        } => cli::specs::reproduce(&experiments, &dir, &sweep, out).map(|()| ExitCode::SUCCESS),
        Command::Check {
            experiments,
            expected,
            sweep,
        } => cli::specs::check(&experiments, &expected, &sweep, out),
        Command::Solve(args) => cli::solve::solve(&args, out),
        Command::Eval(args) => cli::eval::eval(&args, out).map(|()| ExitCode::SUCCESS),
        Command::Diff(args) => cli::diff::diff(&args, out),
        Command::TimeTiers(args) => cli::timing::time_tiers(&args, out).map(|()| ExitCode::SUCCESS),
        Command::RefineReference(args) => {
            cli::reference::refine_reference(&args, out).map(|()| ExitCode::SUCCESS)
        }
    }
}
