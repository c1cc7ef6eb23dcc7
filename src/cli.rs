//! Argument types and the validation behind the `wavy` command line (kept in the library so
//! that tests can drive it without a process).

use crate::coefficient_sets;
use crate::models::{a_over_lambda_at, ModelLaw, PressureLaw, Reading, Westergaard, Wnl};
use crate::runner::CheckReport;
use anyhow::{Context, Result};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// A command-line value that cannot be used.
#[derive(Debug, Error)]
pub enum InputError {
    /// Outside its physical range.
    #[error("{flag} = {value} is out of range; allowed: {allowed}")]
    OutOfRange {
        flag: String,
        value: String,
        allowed: String,
    },
    /// In range, but the selected model cannot be inverted there.
    #[error("{flag} = {value}: no contact half-width: {reason}")]
    NotInvertible {
        flag: String,
        value: String,
        reason: String,
    },
}

fn input_error(flag: &str, value: impl ToString, allowed: impl ToString) -> InputError {
    InputError::OutOfRange {
        flag: flag.into(),
        value: value.to_string(),
        allowed: allowed.to_string(),
    }
}

/// Which law `wavy eval` evaluates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum EvalModel {
    Westergaard,
    Wnl,
}

/// Arguments of `wavy eval`.
#[derive(Debug, Clone, clap::Args)]
#[command(group(clap::ArgGroup::new("input").required(true).args(["a_over_lambda", "p_over_estar"])))]
pub struct EvalArgs {
    #[arg(long, value_enum)]
    pub model: EvalModel,
    /// Reading of Eq. 4 (WNL only): bracket-sq, bracket-2x, literal.
    #[arg(long, default_value = "bracket-sq")]
    pub reading: Reading,
    /// WNL coefficient set.
    #[arg(long, default_value = "paper-table1")]
    pub coefficients: String,
    /// Aspect ratio Δ/λ (> 0).
    #[arg(long, allow_negative_numbers = true)]
    pub ar: f64,
    /// Interfacial shear strength τ_max in MPa (≥ 0).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub tau_max_mpa: f64,
    /// Contact half-widths a/λ ∈ [0, 0.5] (forward evaluation).
    #[arg(long, num_args = 1.., allow_negative_numbers = true)]
    pub a_over_lambda: Vec<f64>,
    /// Mean pressures p̄/E* ≥ 0 (inverse evaluation).
    #[arg(long, num_args = 1.., allow_negative_numbers = true)]
    pub p_over_estar: Vec<f64>,
}

/// Runs `wavy eval`: the CSV text it prints, or an [`InputError`] naming the flag.
pub fn eval(args: &EvalArgs) -> Result<String> {
    if !(args.ar.is_finite() && args.ar > 0.0) {
        return Err(input_error("--ar", args.ar, "> 0").into());
    }
    if !(args.tau_max_mpa.is_finite() && args.tau_max_mpa >= 0.0) {
        return Err(input_error("--tau-max-mpa", args.tau_max_mpa, ">= 0").into());
    }
    let law = match args.model {
        EvalModel::Westergaard => ModelLaw::Westergaard(Westergaard::new(args.ar)),
        EvalModel::Wnl => {
            let c = coefficient_sets::by_name(&args.coefficients).ok_or_else(|| {
                input_error(
                    "--coefficients",
                    &args.coefficients,
                    coefficient_sets::NAMES.join(", "),
                )
            })?;
            ModelLaw::Wnl(Wnl::new(args.ar, args.tau_max_mpa, args.reading, c))
        }
    };
    let (model, reading, coefficients) = match args.model {
        EvalModel::Westergaard => ("westergaard", "", ""),
        EvalModel::Wnl => ("wnl", args.reading.name(), args.coefficients.as_str()),
    };
    let mut out = String::from(
        "model,reading,coefficients,aspect_ratio,tau_max_mpa,a_over_lambda,p_over_estar,extrapolated\n",
    );
    let mut row = |x: f64, p: f64| {
        let _ = writeln!(
            out,
            "{model},{reading},{coefficients},{},{},{x},{p},{}",
            args.ar,
            args.tau_max_mpa,
            law.is_extrapolated()
        );
    };
    for &x in &args.a_over_lambda {
        if !(x.is_finite() && (0.0..=0.5).contains(&x)) {
            return Err(input_error("--a-over-lambda", x, "[0, 0.5]").into());
        }
        row(x, law.p_over_estar(x));
    }
    for &p in &args.p_over_estar {
        let full = law.full_contact_p_over_estar();
        let x = a_over_lambda_at(&law, p).map_err(|e| match e {
            crate::models::InverseError::NegativeOrNotFinite { .. } => {
                input_error("--p-over-estar", p, ">= 0")
            }
            crate::models::InverseError::AboveFullContact { .. } => input_error(
                "--p-over-estar",
                p,
                format!("[0, {full}] (the full-contact pressure of this model)"),
            ),
            other => InputError::NotInvertible {
                flag: "--p-over-estar".into(),
                value: p.to_string(),
                reason: other.to_string(),
            },
        })?;
        row(x, p);
    }
    Ok(out)
}

/// The `*.toml` specs of a folder, sorted by name.
pub fn spec_files(dir: &Path) -> Result<Vec<PathBuf>> {
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
pub fn format_check_report(r: &CheckReport, worst: usize) -> String {
    let mut s = String::new();
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
                    "     {:>6}  {:<28} {:>14} {:>14} {:>11}",
                    "row", "column", "expected", "computed", "rel. dev."
                );
                for d in c.deviations.iter().take(worst) {
                    let _ = writeln!(
                        s,
                        "     {:>6}  {:<28} {:>14} {:>14} {:>11.3e}{}",
                        d.row,
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

/// Mesh resolution on the command line: a named level or a number of elements along the face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeshArg(pub crate::fe::MeshLevel);

impl std::str::FromStr for MeshArg {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        use crate::fe::MeshLevel;
        match s {
            "coarse" => Ok(MeshArg(MeshLevel::Coarse)),
            "default" => Ok(MeshArg(MeshLevel::Default)),
            "fine" => Ok(MeshArg(MeshLevel::Fine)),
            n => match n.parse::<usize>() {
                Ok(nx) if (4..=2048).contains(&nx) => Ok(MeshArg(MeshLevel::Elements { nx, ny: (nx / 2).max(2) })),
                _ => Err(format!(
                    "--mesh = {s} is out of range; allowed: coarse, default, fine, or N elements along the face (4 to 2048; N/2 across the thickness)"
                )),
            },
        }
    }
}

/// Kinematics on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum KinematicsArg {
    Finite,
    Linear,
}

/// Arguments of `wavy solve`.
#[derive(Debug, Clone, clap::Args)]
pub struct SolveArgs {
    /// Aspect ratio Δ/λ (> 0).
    #[arg(long, allow_negative_numbers = true)]
    pub ar: f64,
    /// Interfacial shear strength τ_max in MPa (≥ 0; 0 = frictionless).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub tau_max_mpa: f64,
    /// Friction coefficient μ of the Coulomb–Orowan law (≥ 0; R7 default 1; 0 = frictionless).
    #[arg(long, default_value_t = crate::defaults::friction_coefficient(), allow_negative_numbers = true)]
    pub mu: f64,
    /// Plane-strain modulus E* in MPa (> 0): τ_max/E* is what the physics sees (R7 default 1).
    #[arg(long, default_value_t = crate::defaults::fe_estar_mpa(), allow_negative_numbers = true)]
    pub estar_mpa: f64,
    /// Bulk over shear modulus κ/G (> 0; R7 default 1000).
    #[arg(long, default_value_t = crate::defaults::kappa_over_g(), allow_negative_numbers = true)]
    pub kappa_over_g: f64,
    /// Layer thickness over wavelength h/λ (> 0; R7 default 1).
    #[arg(long, default_value_t = crate::defaults::thickness_over_lambda(), allow_negative_numbers = true)]
    pub thickness_over_lambda: f64,
    #[arg(long, value_enum, default_value = "finite")]
    pub kinematics: KinematicsArg,
    /// coarse, default, fine, or N elements along the contact face.
    #[arg(long, default_value = "default")]
    pub mesh: MeshArg,
    /// Load until the contact half-width a/λ reaches this value (in (0, 0.5)).
    #[arg(long, default_value_t = 0.45, allow_negative_numbers = true)]
    pub until_a_over_lambda: f64,
}

/// The solver's problem and options for `wavy solve`, or an [`InputError`] naming the flag.
pub fn solve_setup(
    args: &SolveArgs,
) -> Result<(crate::fe::LayerProblem, crate::fe::SolveOptions), InputError> {
    use crate::fe::{Interface, Kinematics, LayerProblem, SolveOptions};
    let positive = |flag: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(input_error(flag, v, "> 0"))
        }
    };
    positive("--ar", args.ar)?;
    positive("--estar-mpa", args.estar_mpa)?;
    positive("--kappa-over-g", args.kappa_over_g)?;
    positive("--thickness-over-lambda", args.thickness_over_lambda)?;
    if !(args.tau_max_mpa.is_finite() && args.tau_max_mpa >= 0.0) {
        return Err(input_error("--tau-max-mpa", args.tau_max_mpa, ">= 0"));
    }
    if !(args.mu.is_finite() && args.mu >= 0.0) {
        return Err(input_error("--mu", args.mu, ">= 0"));
    }
    let x = args.until_a_over_lambda;
    if !(x.is_finite() && x > 0.0 && x < 0.5) {
        return Err(input_error("--until-a-over-lambda", x, "(0, 0.5)"));
    }
    let problem = LayerProblem {
        aspect_ratio: args.ar,
        thickness_over_lambda: args.thickness_over_lambda,
        kappa_over_g: args.kappa_over_g,
        kinematics: match args.kinematics {
            KinematicsArg::Finite => Kinematics::Finite,
            KinematicsArg::Linear => Kinematics::Linear,
        },
        interface: Interface::coulomb_orowan(
            args.mu,
            args.tau_max_mpa / args.estar_mpa,
            crate::defaults::elastic_slip_over_element(),
        ),
    };
    let opts = SolveOptions {
        until_a_over_lambda: x,
        mesh: args.mesh.0,
        ..SolveOptions::default()
    };
    Ok((problem, opts))
}

/// Header of `wavy solve`'s CSV.
pub const SOLVE_HEADER: &str =
    "a_over_lambda,p_over_estar,p_over_estar_reaction,slab_displacement_over_lambda,newton_iterations,active_nodes";

/// One CSV row of `wavy solve` (numbers in shortest round-trip form).
pub fn solve_row(p: &crate::fe::CurvePoint) -> String {
    format!(
        "{},{},{},{},{},{}",
        p.a_over_lambda,
        p.p_over_estar,
        p.p_over_estar_reaction,
        p.slab_displacement_over_lambda,
        p.newton_iterations,
        p.active_nodes
    )
}

/// Sweep flags shared by `run`, `reproduce` and `check`.
#[derive(Debug, Clone, clap::Args)]
pub struct SweepArgs {
    /// Worker threads for finite-element cases (≥ 1; default: all cores).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Folder of cached finite-element results (shared by the shards of a split sweep).
    #[arg(long, default_value = ".wavy-cache")]
    pub cache: PathBuf,
}

impl SweepArgs {
    /// The run options these flags ask for.
    pub fn run_options(&self) -> Result<crate::runner::RunOptions, InputError> {
        let mut opts = crate::runner::RunOptions::default();
        if let Some(j) = self.jobs {
            if j == 0 {
                return Err(input_error("--jobs", 0, ">= 1"));
            }
            opts.sweep.jobs = j;
        }
        opts.sweep.cache_dir = self.cache.clone();
        Ok(opts)
    }
}
