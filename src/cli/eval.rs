//! `wavy eval`: a closed-form law, forward (a/λ → p̄/E*) or inverse (p̄/E* → a/λ), or with
//! `--profile` the recursive superposition of the law over a profile's harmonics (p̄/E* →
//! contact fraction), as CSV.

use super::input::{non_negative, one_of, positive};
use anyhow::Result;
use std::io::Write;
use wavy::accuracy::Tier;
use wavy::models::{CoefficientSet, ModelKind, Reading};
use wavy::profile::Profile;
use wavy::runner::requests::eval_request::{LawRequest, ProfileRequest};

/// The CSV header of `wavy eval`.
pub const HEADER: &str =
    "model,reading,coefficients,aspect_ratio,tau_max_mpa,a_over_lambda,p_over_estar,extrapolated";

/// The CSV header of `wavy eval --profile`.
pub const PROFILE_HEADER: &str =
    "model,reading,coefficients,profile,tau_max_mpa,p_over_estar,contact_fraction,extrapolated";

/// Arguments of `wavy eval`.
#[derive(Debug, Clone, clap::Args)]
#[command(group(clap::ArgGroup::new("input").required(true).args(["a_over_lambda", "p_over_estar"])))]
pub struct EvalArgs {
    /// Which law: `westergaard` (linear, frictionless, exact) or `wnl` (Westergaard corrected
    /// by the fitted polynomials A and B). Required unless --tolerance chooses.
    #[arg(long, value_parser = one_of::<ModelKind>(ModelKind::ALL.map(ModelKind::key)), required_unless_present = "tolerance", conflicts_with = "tolerance")]
    pub model: Option<ModelKind>,
    /// Instead of --model: the cheapest tier (closed form, finite elements on one mesh, the
    /// Richardson extrapolation of two meshes or the mesh limit of three) whose measured
    /// largest relative error of p̄/E* at this (AR, τ_max) is at most this (e.g. 0.01); the choice,
    /// its measured error and cost go to stderr (measurements: expected/speed_accuracy.csv).
    /// Forward evaluation only.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["p_over_estar", "reading", "coefficients"])]
    pub tolerance: Option<f64>,
    /// Reading of the paper's Eq. 4 (WNL only): bracket-sq p̄_W·[B + x·A·cos²(πx)],
    /// bracket-2x p̄_W·[B + x·A·cos(2πx)], literal p̄_W·B + x·A·cos²(πx).
    #[arg(long, default_value = "bracket-sq", value_parser = one_of::<Reading>(Reading::ALL.map(Reading::name)))]
    pub reading: Reading,
    /// WNL coefficient set: the paper's Table 1, or our refit for one reading (use it with
    /// that reading).
    #[arg(long, default_value = "paper-table1", value_parser = one_of::<CoefficientSet>(CoefficientSet::ALL.map(CoefficientSet::name)))]
    pub coefficients: CoefficientSet,
    /// Aspect ratio Δ/λ (> 0).
    #[arg(long, allow_hyphen_values = true, required_unless_present = "profile")]
    pub ar: Option<f64>,
    /// Instead of --ar: a profile (`order:aspect_ratio` pairs, each order a multiple of the one
    /// before, or `weierstrass:AR0,gamma,D,K`) whose contact fraction at each --p-over-estar
    /// the recursive superposition of --model gives, the law at each harmonic's own aspect
    /// ratio (docs/replication.md R14). Columns: model, reading, coefficients, profile,
    /// tau_max_mpa, p_over_estar, contact_fraction, extrapolated.
    #[arg(long, value_parser = super::input::profile, conflicts_with_all = ["ar", "tolerance", "a_over_lambda"], requires = "p_over_estar")]
    pub profile: Option<Profile>,
    /// Interfacial shear strength τ_max in MPa (≥ 0).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub tau_max_mpa: f64,
    /// Contact half-widths a/λ ∈ [0, 0.5] (forward evaluation).
    #[arg(long, num_args = 1.., allow_negative_numbers = true)]
    pub a_over_lambda: Vec<f64>,
    /// Mean pressures p̄/E* ≥ 0 (inverse evaluation).
    #[arg(long, num_args = 1.., allow_negative_numbers = true)]
    pub p_over_estar: Vec<f64>,
}

/// Runs `wavy eval`, writing CSV to `out`; an input error names the flag. The evaluation is the
/// library's (`wavy::runner::requests::eval_request`, `wavy::runner::requests::tolerance_choice`).
pub fn eval(args: &EvalArgs, out: &mut impl Write) -> Result<()> {
    if let Some(profile) = args.profile {
        return eval_profile(args, profile, out);
    }
    let ar = args.ar.expect("clap requires --ar without --profile");
    positive("--ar", ar)?;
    non_negative("--tau-max-mpa", args.tau_max_mpa)?;
    if let Some(tolerance) = args.tolerance {
        let e = super::tolerance::eval(ar, args.tau_max_mpa, &args.a_over_lambda, tolerance)?;
        let (reading, coefficients) = match e.tier {
            Tier::Wnl(set) => (e.tier.reading().name(), set.name()),
            _ => ("", ""),
        };
        return write_rows(
            out,
            &e.tier.to_string(),
            reading,
            coefficients,
            (ar, args.tau_max_mpa),
            &e.rows,
        );
    }
    let model = args
        .model
        .expect("clap requires --model without --tolerance");
    let request = LawRequest {
        model,
        ar,
        tau_max_mpa: args.tau_max_mpa,
        reading: args.reading,
        coefficients: args.coefficients,
    };
    let (reading, coefficients) = request.reading_and_coefficients();
    // every input is checked before the first row is written
    let mut rows = request.forward(&args.a_over_lambda)?;
    rows.extend(request.inverse(&args.p_over_estar)?);
    let rows: Vec<(f64, f64, bool)> = rows
        .iter()
        .map(|r| (r.a_over_lambda, r.p_over_estar, r.extrapolated))
        .collect();
    write_rows(
        out,
        model.key(),
        reading,
        coefficients,
        (ar, args.tau_max_mpa),
        &rows,
    )
}

/// Writes the CSV of `wavy eval`: [`HEADER`], then one line per (a/λ, p̄/E*, extrapolated) of
/// `rows`, evaluated by `law` (a model key or a tier name) at (AR, τ_max).
fn write_rows(
    out: &mut impl Write,
    law: &str,
    reading: &str,
    coefficients: &str,
    (ar, tau_max_mpa): (f64, f64),
    rows: &[(f64, f64, bool)],
) -> Result<()> {
    writeln!(out, "{HEADER}")?;
    for (x, p, extrapolated) in rows {
        writeln!(
            out,
            "{law},{reading},{coefficients},{},{},{x},{p},{extrapolated}",
            ar, tau_max_mpa
        )?;
    }
    Ok(())
}

/// `wavy eval --profile`: the contact fraction of the recursive superposition at each
/// --p-over-estar (`wavy::runner::requests::eval_request::ProfileRequest`), as CSV.
fn eval_profile(args: &EvalArgs, profile: Profile, out: &mut impl Write) -> Result<()> {
    non_negative("--tau-max-mpa", args.tau_max_mpa)?;
    let model = args
        .model
        .expect("clap requires --model without --tolerance");
    let request = ProfileRequest {
        model,
        profile,
        tau_max_mpa: args.tau_max_mpa,
        reading: args.reading,
        coefficients: args.coefficients,
    };
    let rows = request.contact_fractions(&args.p_over_estar)?;
    let (reading, coefficients) = LawRequest {
        model,
        ar: profile.aspect_ratio,
        tau_max_mpa: args.tau_max_mpa,
        reading: args.reading,
        coefficients: args.coefficients,
    }
    .reading_and_coefficients();
    writeln!(out, "{PROFILE_HEADER}")?;
    for r in rows {
        writeln!(
            out,
            "{},{reading},{coefficients},\"{profile}\",{},{},{},{}",
            model.key(),
            args.tau_max_mpa,
            r.p_over_estar,
            r.contact_fraction,
            r.extrapolated
        )?;
    }
    Ok(())
}
