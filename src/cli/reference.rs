//! `wavy refine-reference`: solve every case of a speed_accuracy spec on its reference meshes and
//! write the limit its scene measures the tiers against (see `runner::reference_curves`).

use super::specs::SweepArgs;
use anyhow::{Context, Result};
use std::io::Write;
use std::path::PathBuf;
use wavy::runner::scenes::speed_accuracy::refine_reference;
use wavy::runner::{load_spec, write_atomic};

/// Arguments of `wavy refine-reference`.
#[derive(Debug, Clone, clap::Args)]
pub struct RefineReferenceArgs {
    /// The speed_accuracy spec whose cases are refined (its `reference_meshes`).
    #[arg(default_value = "experiments/speed_accuracy.toml")]
    pub spec: PathBuf,
    /// The reference file to write (replaced atomically when every case has its limit); by
    /// default the spec's `reference`.
    #[arg(long)]
    pub out: Option<PathBuf>,
    #[command(flatten)]
    pub sweep: SweepArgs,
}

/// Runs `wavy refine-reference`: the written path on stdout.
pub fn refine_reference(args: &RefineReferenceArgs, out: &mut impl Write) -> Result<()> {
    let opts = args.sweep.run_options()?;
    let spec = load_spec(&args.spec)?;
    let scene = super::timing::speed_accuracy_scene(&spec, &args.spec)?;
    let path = match &args.out {
        Some(p) => p.clone(),
        None => args
            .spec
            .parent()
            .unwrap_or_else(|| std::path::Path::new("."))
            .join(&scene.reference),
    };
    let curves = refine_reference::compute(scene, &opts)
        .with_context(|| format!("{}: the reference", args.spec.display()))?;
    write_atomic(&path, curves.to_text().as_bytes()).with_context(|| path.display().to_string())?;
    writeln!(out, "wrote {}", path.display())?;
    Ok(())
}
