//! `wavy time-tiers`: measure the wall time of every tier of a speed_accuracy spec (one thread,
//! median of runs) and write the timings file the scene reads (see `runner::tier_timings`).

use super::input::InputError;
use anyhow::{Context, Result};
use std::io::Write;
use std::path::{Path, PathBuf};
use wavy::runner::scenes::speed_accuracy::SpeedAccuracyScene;
use wavy::runner::Spec;
use wavy::runner::{load_spec, write_atomic};

/// Arguments of `wavy time-tiers`.
#[derive(Debug, Clone, clap::Args)]
pub struct TimeTiersArgs {
    /// The speed_accuracy spec whose tiers and cases are timed.
    #[arg(default_value = "experiments/speed_accuracy.toml")]
    pub spec: PathBuf,
    /// Runs per tier and case (≥ 1); the median is kept.
    #[arg(long, default_value_t = 3)]
    pub runs: usize,
    /// The timings file to write (replaced atomically when every tier is timed).
    #[arg(long, default_value = "experiments/data/speed_accuracy_timings.csv")]
    pub out: PathBuf,
}

/// The `[speed_accuracy]` section of the spec read from `path`, or an input error naming it.
pub(super) fn speed_accuracy_scene<'a>(
    spec: &'a Spec,
    path: &Path,
) -> Result<&'a SpeedAccuracyScene, InputError> {
    spec.speed_accuracy
        .as_ref()
        .ok_or_else(|| InputError::Refused {
            flag: "SPEC".into(),
            value: path.display().to_string(),
            reason: "not a [speed_accuracy] spec".into(),
        })
}

/// The processor's name, for the provenance of the timings.
fn machine() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find_map(|l| l.strip_prefix("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string())
}

/// Runs `wavy time-tiers`: a progress line per tier and case on stderr, the written path on
/// stdout.
pub fn time_tiers(args: &TimeTiersArgs, out: &mut impl Write) -> Result<()> {
    if args.runs == 0 {
        return Err(super::input::out_of_range("--runs", 0, ">= 1").into());
    }
    let spec = load_spec(&args.spec)?;
    let scene = speed_accuracy_scene(&spec, &args.spec)?;
    let timings = wavy::runner::scenes::speed_accuracy::time_tiers::measure(
        scene,
        args.runs,
        &machine(),
        &mut |line| eprintln!("{line}"),
    )?;
    write_atomic(&args.out, timings.to_text().as_bytes())
        .with_context(|| args.out.display().to_string())?;
    writeln!(out, "wrote {}", args.out.display())?;
    Ok(())
}
