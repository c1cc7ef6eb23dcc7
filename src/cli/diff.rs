//! `wavy diff`: what moved in the figures' numbers between a git revision and the working tree,
//! for reviewing a change of results in a pull request. The base tables are read with
//! `git show REV:path` (never a checkout); the comparison and the overlays are
//! `wavy::runner::review`'s.

use anyhow::{bail, Context, Result};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use wavy::runner::review::{self, CsvTable, Presence, TableChange};
use wavy::runner::{load_spec, write_atomic};

/// Arguments of `wavy diff`.
#[derive(Debug, Clone, clap::Args)]
pub struct DiffArgs {
    /// The git revision to compare with (a branch, tag or commit; default: `origin/main` when
    /// it exists, else `HEAD`).
    #[arg(long)]
    pub base: Option<String>,
    /// Folder of the figures' CSV tables, in the working tree and at the same path in the base.
    #[arg(long, default_value = "figures")]
    pub figures: PathBuf,
    /// Folder of the experiment specs: each table's spec gives the `[check]` tolerances that
    /// decide what counts as moved.
    #[arg(long, default_value = "experiments")]
    pub experiments: PathBuf,
    /// Folder the review is written to: `<stem>.svg` overlays and `summary.md`.
    #[arg(long, default_value = "review")]
    pub out: PathBuf,
}

fn git(args: &[&str]) -> Result<std::process::Output> {
    Command::new("git")
        .args(args)
        .output()
        .context("cannot run git (wavy diff reads the base revision with git show)")
}

/// The revision `--base` names, or the default one.
fn base_revision(asked: Option<&str>) -> Result<String> {
    let exists = |rev: &str| -> Result<bool> {
        Ok(git(&[
            "rev-parse",
            "--verify",
            "--quiet",
            &format!("{rev}^{{commit}}"),
        ])?
        .status
        .success())
    };
    match asked {
        Some(rev) if exists(rev)? => Ok(rev.to_string()),
        Some(rev) => bail!("--base = {rev} is not a revision of this repository"),
        None if exists("origin/main")? => Ok("origin/main".into()),
        None => Ok("HEAD".into()),
    }
}

/// The CSV file names under `dir` at revision `rev` (none when the folder is not there).
fn base_files(rev: &str, dir: &Path) -> Result<Vec<String>> {
    let o = git(&[
        "ls-tree",
        "--name-only",
        rev,
        &format!("{}/", dir.display()),
    ])?;
    Ok(String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter_map(|l| Path::new(l).file_name()?.to_str().map(String::from))
        .filter(|f| f.ends_with(".csv"))
        .collect())
}

fn base_text(rev: &str, path: &Path) -> Result<String> {
    let o = git(&["show", &format!("{rev}:./{}", path.display())])?;
    if !o.status.success() {
        bail!(
            "git show {rev}:./{}: {}",
            path.display(),
            String::from_utf8_lossy(&o.stderr).trim()
        );
    }
    String::from_utf8(o.stdout).with_context(|| format!("{}: not UTF-8", path.display()))
}

/// The spec stem a table file belongs to (`fig3_fe_vs_model_mse.csv` → `fig3_fe_vs_model`):
/// the longest stem the file name starts with.
fn stem_of<'a>(file: &str, stems: &'a [String]) -> Option<&'a String> {
    stems
        .iter()
        .filter(|s| file == format!("{s}.csv") || file.starts_with(&format!("{s}_")))
        .max_by_key(|s| s.len())
}

/// A table compared between the base and the working tree: its file name, both sides and what
/// changed.
type Compared = (String, CsvTable, CsvTable, TableChange);

/// The tables of one spec: those that changed, those on one side only, and those that did not
/// change (drawn too: the overlay shows the whole figure).
#[derive(Default)]
struct SpecTables {
    changed: Vec<Compared>,
    one_side: Vec<(String, Presence)>,
    unchanged: Vec<Compared>,
}

/// Runs `wavy diff`; exit 1 when something moved beyond a spec's `[check]` tolerances.
pub fn diff(args: &DiffArgs, out: &mut impl Write) -> Result<ExitCode> {
    let rev = base_revision(args.base.as_deref())?;
    let tolerances = spec_tolerances(&args.experiments)?;
    let by_stem = compare_tables(args, &rev, &tolerances)?;
    clear_review_folder(&args.out)?;
    write_review(args, &rev, &by_stem, out)
}

/// The `[check]` tolerances `(rel, abs)` of every spec in `experiments`, by its file stem.
fn spec_tolerances(experiments: &Path) -> Result<BTreeMap<String, (f64, f64)>> {
    let mut specs = BTreeMap::new();
    for e in std::fs::read_dir(experiments)
        .with_context(|| format!("cannot list {}", experiments.display()))?
        .flatten()
    {
        let p = e.path();
        if p.extension().is_some_and(|x| x == "toml") {
            let spec = load_spec(&p)?;
            let stem = p.file_stem().and_then(|s| s.to_str()).unwrap_or_default();
            specs.insert(
                stem.to_string(),
                (spec.check.rel_tol.get(), spec.check.abs_tol.get()),
            );
        }
    }
    Ok(specs)
}

/// Every figure table, in the working tree or at `rev`, compared and grouped by its spec (the
/// tables of no spec are left out: they are not figures of this project).
fn compare_tables(
    args: &DiffArgs,
    rev: &str,
    tolerances: &BTreeMap<String, (f64, f64)>,
) -> Result<BTreeMap<String, SpecTables>> {
    let stems: Vec<String> = tolerances.keys().cloned().collect();
    let mut files: Vec<String> = std::fs::read_dir(&args.figures)
        .with_context(|| format!("cannot list {}", args.figures.display()))?
        .flatten()
        .filter_map(|e| e.file_name().to_str().map(String::from))
        .filter(|f| f.ends_with(".csv"))
        .collect();
    let in_base = base_files(rev, &args.figures)?;
    files.extend(in_base.iter().cloned());
    files.sort();
    files.dedup();

    let mut by_stem: BTreeMap<String, SpecTables> = BTreeMap::new();
    for file in &files {
        let Some(stem) = stem_of(file, &stems) else {
            continue;
        };
        let (rel, abs) = tolerances[stem];
        let entry = by_stem.entry(stem.clone()).or_default();
        let path = args.figures.join(file);
        let new_text = std::fs::read_to_string(&path).ok();
        let base = if in_base.contains(file) {
            Some(base_text(rev, &path)?)
        } else {
            None
        };
        match (base, new_text) {
            (Some(b), Some(n)) => {
                let parse = |t: &str, side: &str| {
                    CsvTable::parse(t).with_context(|| format!("{file} ({side}): not CSV"))
                };
                let (bt, nt) = (parse(&b, rev)?, parse(&n, "working tree")?);
                let change = review::compare(file, &bt, &nt, rel, abs);
                let target = if b == n {
                    &mut entry.unchanged
                } else {
                    &mut entry.changed
                };
                target.push((file.clone(), bt, nt, change));
            }
            (None, Some(_)) => entry.one_side.push((file.clone(), Presence::Added)),
            (Some(_), None) => entry.one_side.push((file.clone(), Presence::Removed)),
            (None, None) => {}
        }
    }
    Ok(by_stem)
}

/// Creates the review folder and removes the overlays and summary of an earlier run: it holds
/// only this run's files.
fn clear_review_folder(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    for e in std::fs::read_dir(dir)?.flatten() {
        let p = e.path();
        if p.extension().is_some_and(|x| x == "svg") || p.ends_with("summary.md") {
            std::fs::remove_file(&p).with_context(|| format!("cannot remove {}", p.display()))?;
        }
    }
    Ok(())
}

/// Writes `summary.md` and an overlay per changed figure; the exit code says whether a table
/// moved beyond its spec's tolerances (or appeared or disappeared).
fn write_review(
    args: &DiffArgs,
    rev: &str,
    by_stem: &BTreeMap<String, SpecTables>,
    out: &mut impl Write,
) -> Result<ExitCode> {
    let mut md = format!(
        "# What moved: figures/ at `{rev}` against the working tree\n\n\
         Largest changes per panel (named by its parameters) and column; **moved** marks a change \
         beyond the spec's `[check]` tolerances. Overlays: `review/<figure>.svg` (base grey and dashed).\n\n"
    );
    let mut moved_tables = 0;
    let mut changed_figures = 0;
    for (stem, tables) in by_stem {
        if tables.changed.is_empty() && tables.one_side.is_empty() {
            continue;
        }
        changed_figures += 1;
        let changes: Vec<TableChange> = tables.changed.iter().map(|c| c.3.clone()).collect();
        moved_tables += changes.iter().filter(|c| c.moved()).count() + tables.one_side.len();
        md.push_str(&review::summary(stem, &changes, &tables.one_side));
        let drawn: Vec<Compared> = (tables.changed.iter().chain(&tables.unchanged))
            .cloned()
            .collect();
        if let Some(fig) = review::overlay(stem, &drawn) {
            let svg = wavy::plot::render_svg(&fig)?;
            let path = args.out.join(format!("{stem}.svg"));
            write_atomic(&path, svg.as_bytes())?;
            writeln!(out, "wrote {}", path.display())?;
        }
    }
    if changed_figures == 0 {
        md.push_str("No figure table differs.\n");
    }
    write_atomic(&args.out.join("summary.md"), md.as_bytes())?;
    writeln!(out, "wrote {}", args.out.join("summary.md").display())?;
    writeln!(
        out,
        "diff against {rev}: {changed_figures} figure(s) changed, {moved_tables} table(s) moved beyond tolerance"
    )?;
    Ok(if moved_tables == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
