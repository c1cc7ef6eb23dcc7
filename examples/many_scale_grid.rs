//! The finite-element side of issue 44's grid, as far as the solver's cost allows (docs/results.md,
//! "Many-scale surfaces"): Weierstrass profiles `weierstrass:AR0,γ,D,K`, γ ∈ {3, 4, 8},
//! D ∈ {1.3, 1.5, 1.7}, K = 2 … 4, at the AR₀ and with every setting of
//! `experiments/many_scale.toml` (finite strain, frictionless and τ_max 0.1 MPa, the FE error from
//! a coarser mesh, the recursion with both laws and the linear BEM against it). Per (γ, D) the
//! scene runs on the largest K that the spec's validation admits (the finite-strain slope limit,
//! the mesh resolution) and whose frictionless curve the cost model estimates
//! (`runner::requests::cost_estimate`, to a/λ 0.45 on one core) within `BUDGET_S` seconds
//! (default 300); the K beyond are listed with the refusal or the estimate. One markdown row per
//! (γ, D, K): the mesh, RMS relative errors of the contact fraction against the FE, and the wall
//! time of the (γ, D) run (all its K, both τ_max, both meshes, the models and the BEM; 2 cores
//! share it).
//!
//! `cargo run --release --example many_scale_grid` (`BUDGET_S=…` to go further)

use std::path::Path;
use wavy::fe::MeshLevel;
use wavy::profile::Profile;
use wavy::runner::requests::cost_estimate::CostEstimate;
use wavy::runner::{run_spec, RunOptions, Spec};
use wavy::table::Table;

/// The spec text with its families replaced by the one family (AR₀, γ, D, K).
fn spec_text(template: &str, ar0: f64, gamma: u32, d: f64, k: u32) -> String {
    let start = template.find("families = [").expect("the spec's families");
    let end = start + template[start..].find("\n]\n").expect("the families' end") + 3;
    format!(
        "{}families = [{{ ar0 = {ar0}, gamma = {gamma}, dimension = {d}, scales = {k} }}]\n{}",
        &template[..start],
        &template[end..]
    )
}

/// The FE mesh the spec's scene solves `profile` on.
fn mesh_of(spec: &Spec, profile: &Profile) -> MeshLevel {
    let scene = spec.many_scale.as_ref().expect("a many-scale spec");
    scene.fe_mesh(profile)
}

/// Why K scales are not solved (the finite-strain slope limit first, then the spec's other
/// checks, then the cost), or `None` when they are affordable.
fn not_solved(template: &str, ar0: f64, gamma: u32, d: f64, k: u32, budget: f64) -> Option<String> {
    let text = spec_text(template, ar0, gamma, d, k);
    let profile: Profile = format!("weierstrass:{ar0},{gamma},{d},{k}")
        .parse()
        .expect("valid parameters");
    let slopes = profile.slope_bound();
    if slopes > wavy::fe::PROFILE_SLOPE_LIMIT {
        return Some(format!(
            "refused: slopes up to Σ 2π AR_k = {slopes:.3} > {:.3}, the finite-strain limit",
            wavy::fe::PROFILE_SLOPE_LIMIT
        ));
    }
    match Spec::parse(&text, "many_scale.toml") {
        Err(e) => Some(format!("refused: {}", e.to_string().replace('\n', " "))),
        Ok(spec) => {
            let cost = CostEstimate::of(mesh_of(&spec, &profile));
            (cost.seconds > budget).then(|| format!("beyond the budget: {}", cost.describe()))
        }
    }
}

/// The `column` of the errors row (profile, τ_max, model), as text.
fn cell(errors: &Table, profile: &str, tau: &str, model: &str, column: &str) -> String {
    let col = |name: &str| errors.header.iter().position(|h| h == name).unwrap();
    errors
        .rows
        .iter()
        .find(|r| {
            r[col("profile")].to_string() == profile
                && r[col("tau_max_mpa")].to_string() == tau
                && r[col("model")].to_string() == model
        })
        .map(|r| r[col(column)].to_string())
        .unwrap_or_default()
}

/// `x` (a fraction, as text) in per cent to two significant digits.
fn percent(x: &str) -> String {
    match x.parse::<f64>() {
        Ok(v) => format!("{} %", wavy::numfmt::sig_digits(100.0 * v, 2)),
        Err(_) => "—".into(),
    }
}

fn main() -> anyhow::Result<()> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let template = std::fs::read_to_string(root.join("experiments/many_scale.toml"))?;
    let budget: f64 = std::env::var("BUDGET_S").map_or(Ok(300.0), |s| s.parse())?;
    let ar0 = 0.03;
    let cache = tempfile::tempdir()?;
    let mut opts = RunOptions::default();
    opts.sweep.cache_dir = cache.path().to_path_buf();
    println!("| profile | mesh | recursion, Westergaard | recursion, WNL | WNL, τ_max 0.1 MPa | linear BEM | FE's own error | run |");
    println!("|---|---|---|---|---|---|---|---|");
    for gamma in [3u32, 4, 8] {
        for d in [1.3, 1.5, 1.7] {
            let solved = (2..=4)
                .take_while(|&k| not_solved(&template, ar0, gamma, d, k, budget).is_none())
                .last();
            if let Some(k_max) = solved {
                let text = spec_text(&template, ar0, gamma, d, k_max);
                let spec = Spec::parse(&text, "many_scale.toml")?;
                let started = std::time::Instant::now();
                let out = run_spec(&spec, "many_scale", root, &opts)?;
                let seconds = started.elapsed().as_secs_f64();
                let errors = &out.tables[1];
                for k in 2..=k_max {
                    let name = format!("weierstrass:{ar0},{gamma},{d},{k}");
                    let (nx, ny) = mesh_of(&spec, &name.parse()?).counts();
                    let at = |tau, model, column| percent(&cell(errors, &name, tau, model, column));
                    let run = match k {
                        2 => format!("{seconds:.0} s for K ≤ {k_max}"),
                        _ => String::new(),
                    };
                    println!(
                        "| `{name}` | {nx} × {ny} | {} | {} | {} | {} | {} | {run} |",
                        at("0", "recursion-westergaard", "rms_rel_error"),
                        at("0", "recursion-wnl", "rms_rel_error"),
                        at("0.1", "recursion-wnl", "rms_rel_error"),
                        at("0", "bem-linear", "rms_rel_error"),
                        at("0", "bem-linear", "fe_rms_error_estimate"),
                    );
                }
            }
            for k in solved.map_or(2, |k| k + 1)..=4 {
                let why = not_solved(&template, ar0, gamma, d, k, budget).unwrap_or_default();
                println!("| `weierstrass:{ar0},{gamma},{d},{k}` | {why} ||||||");
            }
        }
    }
    Ok(())
}
