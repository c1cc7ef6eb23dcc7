//! `wavy run`, `wavy reproduce` and `wavy check`: experiment specs in, figures, tables and
//! check reports out.

use super::input::{out_of_range, InputError};
use anyhow::{Context, Result};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use wavy::runner::sweep::{Shard, DEFAULT_CACHE_DIR};
use wavy::runner::{self, CheckReport, RunOptions, SceneOutput};

/// Sweep flags shared by `run`, `reproduce` and `check`.
#[derive(Debug, Clone, clap::Args)]
pub struct SweepArgs {
    /// Worker threads for finite-element cases (≥ 1; default: all cores).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Folder of cached finite-element results (shared by the shards of a split sweep).
    #[arg(long, default_value = DEFAULT_CACHE_DIR)]
    pub cache: PathBuf,
}

impl SweepArgs {
    /// The run options these flags ask for.
    pub fn run_options(&self) -> Result<RunOptions, InputError> {
        let mut opts = RunOptions::default();
        if let Some(j) = self.jobs {
            if j == 0 {
                return Err(out_of_range("--jobs", 0, ">= 1"));
            }
            opts.sweep.jobs = j;
        }
        opts.sweep.cache_dir = self.cache.clone();
        Ok(opts)
    }
}

/// `wavy run SPEC`: one spec's figure and tables; with a shard, only its share of the FE cases.
pub fn run(
    spec: &Path,
    out_dir: &Path,
    sweep: &SweepArgs,
    shard: Option<Shard>,
    out: &mut impl Write,
) -> Result<()> {
    let mut opts = sweep.run_options()?;
    if let Some(shard) = shard {
        opts.sweep.shard = Some(shard);
        let (computed, cached) = runner::compute_share(spec, &opts)?;
        writeln!(
            out,
            "shard {}/{}: computed {computed} case(s); {cached} of the spec's cases are in the cache",
            shard.index, shard.count
        )?;
        return Ok(());
    }
    let output = runner::run_spec_file(spec, &opts)?;
    let written = runner::write_outputs(&output, out_dir)?;
    report(&output, &written, out)?;
    refuse_incomplete(std::slice::from_ref(&output))
}

/// Exit 1 when a figure rests on incomplete FE curves: the outputs are written, marked
/// INCOMPLETE, but they are not what was asked for.
fn refuse_incomplete(outputs: &[SceneOutput]) -> Result<()> {
    match runner::incomplete_message(outputs) {
        None => Ok(()),
        Some(message) => anyhow::bail!("{message}"),
    }
}

/// `wavy reproduce`: every spec of a folder, all parsed before anything is computed or written.
pub fn reproduce(
    experiments: &Path,
    out_dir: &Path,
    sweep: &SweepArgs,
    out: &mut impl Write,
) -> Result<()> {
    let opts = sweep.run_options()?;
    let specs = spec_files(experiments)?;
    for s in &specs {
        runner::load_spec(s)?;
    }
    let outputs = specs
        .iter()
        .map(|s| runner::run_spec_file(s, &opts))
        .collect::<Result<Vec<_>>>()?;
    for o in &outputs {
        let written = runner::write_outputs(o, out_dir)?;
        report(o, &written, out)?;
    }
    refuse_incomplete(&outputs)
}

/// `wavy check`: recompute every spec and compare with the golden tables; exit 1 on a regression.
pub fn check(
    experiments: &Path,
    expected: &Path,
    sweep: &SweepArgs,
    out: &mut impl Write,
) -> Result<ExitCode> {
    let opts = sweep.run_options()?;
    let mut all_passed = true;
    for s in spec_files(experiments)? {
        let r = runner::check_spec_file(&s, expected, &opts)?;
        write!(out, "{}", format_check_report(&r, 5))?;
        all_passed &= r.passed();
    }
    writeln!(
        out,
        "{}",
        if all_passed {
            "check: all tables within tolerance"
        } else {
            "check: REGRESSION"
        }
    )?;
    Ok(if all_passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// What a run wrote, and the notes the reader must see.
fn report(output: &SceneOutput, written: &[PathBuf], out: &mut impl Write) -> Result<()> {
    for p in written {
        writeln!(out, "wrote {}", p.display())?;
    }
    for n in &output.notes {
        writeln!(out, "note ({}): {n}", output.stem)?;
    }
    for n in &output.incomplete {
        writeln!(out, "INCOMPLETE ({}): {n}", output.stem)?;
    }
    Ok(())
}

/// The `*.toml` specs of a folder, sorted by name.
fn spec_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut specs: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("cannot list {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    specs.sort();
    if specs.is_empty() {
        anyhow::bail!("no *.toml spec in {}", dir.display());
    }
    Ok(specs)
}

/// A check report as text: per table, the worst `worst` deviations.
fn format_check_report(r: &CheckReport, worst: usize) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    for n in &r.incomplete {
        let _ = writeln!(s, "FAIL {}: incomplete finite-element curve: {n}", r.stem);
    }
    for (file, result) in &r.tables {
        match result {
            Err(e) => {
                let _ = writeln!(s, "FAIL {file}: {e}");
            }
            Ok(c) => {
                let verdict = if c.failures == 0 { "ok  " } else { "FAIL" };
                let _ = writeln!(
                    s,
                    "{verdict} {file}: {} cells, {} numbers, {} outside tolerance",
                    c.deviations.len(),
                    c.numbers,
                    c.failures
                );
                let _ = writeln!(
                    s,
                    "     {:>6}  {:<36} {:<28} {:>14} {:>14} {:>11}",
                    "row", "panel", "column", "expected", "computed", "rel. dev."
                );
                for d in c.deviations.iter().take(worst) {
                    let _ = writeln!(
                        s,
                        "     {:>6}  {:<36} {:<28} {:>14} {:>14} {:>11.3e}{}",
                        d.row,
                        d.panel,
                        d.column,
                        d.expected,
                        d.found,
                        d.relative,
                        if d.pass { "" } else { "  <- outside tolerance" }
                    );
                }
            }
        }
    }
    s
}
