//! Runs a spec's scene: computes its tables and figure in memory, then writes them atomically.
//!
//! A run computes everything before it writes anything, and every file is written to a
//! temporary file in the target folder and renamed into place, so that a failed or
//! interrupted run never leaves a partial CSV or SVG behind.

pub use crate::atomic_write;
pub mod measured_points;
pub mod requests;
pub mod review;
#[cfg(test)]
mod review_tests;
pub mod scenes;
pub mod sweep;

pub use atomic_write::write_atomic;
pub use scenes::{Scene, SceneContext, SceneResult, Spec};

use crate::models::{ModelKind, ModelLaw};
use crate::spec::{ModelSelection, SpecError};
use crate::table::{CompareError, Comparison, Table};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

/// What a scene produces: its tables, its SVG, and notes for the run's output.
#[derive(Debug, Clone)]
pub struct SceneOutput {
    /// File stem of every output (`figures/<stem>.svg`, `figures/<stem>.csv`, …).
    pub stem: String,
    pub tables: Vec<Table>,
    pub svg: String,
    /// Things the reader must know (missing data, extrapolation), printed by the CLI.
    pub notes: Vec<String>,
    /// FE curves that stopped short of their target (see [`SceneResult::incomplete`]).
    pub incomplete: Vec<String>,
}

/// Why figures that rest on FE curves that stopped short are not what was asked for (their
/// outputs are written, marked INCOMPLETE), or `None` when every curve is complete.
pub fn incomplete_message(outputs: &[SceneOutput]) -> Option<String> {
    let incomplete: Vec<String> = outputs
        .iter()
        .flat_map(|o| o.incomplete.iter().map(move |n| format!("{}: {n}", o.stem)))
        .collect();
    if incomplete.is_empty() {
        return None;
    }
    Some(format!(
        "{} finite-element curve(s) stopped short of their target (the figures say INCOMPLETE):\n  {}",
        incomplete.len(),
        incomplete.join("\n  ")
    ))
}

/// How a run computes expensive cases.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Parallelism, cache folder and shard of finite-element sweeps.
    pub sweep: sweep::SweepOptions,
    /// Replaces every FE section's mesh (tests use a coarse mesh to stay fast).
    pub fe_mesh_override: Option<crate::fe::MeshLevel>,
}

/// Reads, parses and runs the spec at `path`; the output stem is the file stem.
pub fn run_spec_file(path: &Path, opts: &RunOptions) -> Result<SceneOutput> {
    let spec = load_spec(path)?;
    run_spec(
        &spec,
        &stem_of(path)?,
        path.parent().unwrap_or(Path::new(".")),
        opts,
    )
    .with_context(|| path.display().to_string())
}

/// With a shard in `opts`: computes this shard's share of the spec's finite-element cases
/// into the cache and writes no figure. Returns (cases computed, cases already cached).
pub fn compute_share(path: &Path, opts: &RunOptions) -> Result<(usize, usize)> {
    let spec = load_spec(path)?;
    sweep::fe_cases::compute_share(&spec.scene().fe_cases(opts), opts)
}

/// Reads and parses the spec at `path`.
pub fn load_spec(path: &Path) -> Result<Spec> {
    let origin = path.display().to_string();
    let read_error = |message: String| SpecError::Read {
        origin: origin.clone(),
        message,
    };
    let bytes = std::fs::read(path).map_err(|e| read_error(e.to_string()))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let before = String::from_utf8_lossy(&e.as_bytes()[..at]);
        let line = before.matches('\n').count() + 1;
        let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        read_error(format!(
            "not valid UTF-8 at byte {at} (line {line}, column {column})"
        ))
    })?;
    Ok(Spec::parse(&text, &origin)?)
}

fn stem_of(path: &Path) -> Result<String> {
    path.file_stem()
        .and_then(|s| s.to_str())
        .map(String::from)
        .ok_or_else(|| {
            SpecError::Read {
                origin: path.display().to_string(),
                message: "the spec's file name is not valid UTF-8 (it names the outputs)".into(),
            }
            .into()
        })
}

/// Runs a parsed spec. `spec_dir` resolves the spec's relative data paths.
pub fn run_spec(
    spec: &Spec,
    stem: &str,
    spec_dir: &Path,
    opts: &RunOptions,
) -> Result<SceneOutput> {
    let SceneResult {
        tables,
        figure,
        notes,
        incomplete,
    } = spec.scene().run(&SceneContext {
        title: &spec.title,
        spec_dir,
        opts,
    })?;
    let svg = crate::plot::render_svg(&figure)?;
    Ok(SceneOutput {
        stem: stem.into(),
        tables,
        svg,
        notes,
        incomplete,
    })
}

/// Writes a scene's SVG and CSVs into `dir`, each atomically; returns the paths written. Every
/// target is checked before the first is written, so a target that cannot be replaced (a
/// folder in its place) leaves every output as it was.
pub fn write_outputs(out: &SceneOutput, dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<(PathBuf, &[u8])> =
        vec![(dir.join(format!("{}.svg", out.stem)), out.svg.as_bytes())];
    let csvs: Vec<(PathBuf, String)> = out
        .tables
        .iter()
        .map(|t| (dir.join(t.file_name(&out.stem)), t.to_csv()))
        .collect();
    files.extend(csvs.iter().map(|(p, s)| (p.clone(), s.as_bytes())));
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    for (path, _) in &files {
        if path.is_dir() {
            anyhow::bail!(
                "cannot write {}: a folder is in its place (nothing was written)",
                path.display()
            );
        }
    }
    atomic_write::remove_stale_temporaries(dir)?;
    for (path, bytes) in &files {
        write_atomic(path, bytes)?;
    }
    atomic_write::remove_own_temporaries(dir);
    Ok(files.into_iter().map(|(p, _)| p).collect())
}

/// Why a table could not be compared with its golden file.
#[derive(Debug, thiserror::Error)]
pub enum CheckError {
    #[error("cannot read {}: {message}", golden.display())]
    Unreadable { golden: PathBuf, message: String },
    #[error("{}: {error}", golden.display())]
    Mismatch {
        golden: PathBuf,
        #[source]
        error: CompareError,
    },
}

/// A scene's tables compared with their golden files in `expected_dir`.
#[derive(Debug)]
pub struct CheckReport {
    pub stem: String,
    pub tables: Vec<(String, Result<Comparison, CheckError>)>,
    /// FE curves of the recomputation that stopped short of their target: a committed figure
    /// never rests on one, so any fails the check.
    pub incomplete: Vec<String>,
}

impl CheckReport {
    pub fn passed(&self) -> bool {
        self.incomplete.is_empty()
            && self
                .tables
                .iter()
                .all(|(_, r)| matches!(r, Ok(c) if c.failures == 0))
    }
}

/// Recomputes the spec at `path` and compares each table with `expected_dir/<file>.csv`
/// within the spec's `[check]` tolerances.
pub fn check_spec_file(path: &Path, expected_dir: &Path, opts: &RunOptions) -> Result<CheckReport> {
    let spec = load_spec(path)?;
    let out = run_spec(
        &spec,
        &stem_of(path)?,
        path.parent().unwrap_or(Path::new(".")),
        opts,
    )?;
    let (rel, abs) = (spec.check.rel_tol.get(), spec.check.abs_tol.get());
    let tables = out
        .tables
        .iter()
        .map(|t| {
            let file = t.file_name(&out.stem);
            let golden = expected_dir.join(&file);
            let result = std::fs::read_to_string(&golden)
                .map_err(|e| CheckError::Unreadable {
                    golden: golden.clone(),
                    message: e.to_string(),
                })
                .and_then(|text| {
                    t.compare(&text, rel, abs)
                        .map_err(|error| CheckError::Mismatch {
                            golden: golden.clone(),
                            error,
                        })
                })
                .map(|mut c| {
                    let keys = review::ColumnRoles::of(&t.header).keys;
                    for d in &mut c.deviations {
                        d.panel = t.panel_name(d.row - 1, &keys);
                    }
                    c
                });
            (file, result)
        })
        .collect();
    Ok(CheckReport {
        stem: out.stem,
        tables,
        incomplete: out.incomplete,
    })
}

/// The laws a model selection draws at one (AR, τ_max), in the order of `draw`.
pub(crate) fn model_laws(
    sel: &ModelSelection,
    aspect_ratio: f64,
    tau_max_mpa: f64,
) -> Vec<(ModelKind, ModelLaw)> {
    sel.draw
        .iter()
        .map(|&kind| {
            let law = ModelLaw::new(
                kind,
                aspect_ratio,
                tau_max_mpa,
                sel.reading,
                sel.coefficients,
            );
            (kind, law)
        })
        .collect()
}
