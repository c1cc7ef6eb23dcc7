//! `--tolerance` on the command line: the choice is the library's
//! (`wavy::runner::requests::tolerance_choice`); this module tells it on stderr.

use anyhow::Result;
use wavy::accuracy::measured::Choice;
use wavy::accuracy::Tier;
use wavy::runner::requests::tolerance_choice;

/// The choice, told on stderr.
pub fn announce(choice: &Choice, tolerance: f64) {
    eprintln!("{}", tolerance_choice::announcement(choice, tolerance));
}

/// What `wavy eval --tolerance` evaluated: the tier chosen and its (a/λ, p̄/E*, extrapolated)
/// rows.
pub struct TierEvaluation {
    pub tier: Tier,
    pub rows: Vec<(f64, f64, bool)>,
}

/// `wavy eval --tolerance`: the forward evaluation at (AR, τ_max in MPa) of every a/λ of `xs` by
/// the cheapest tier whose measured error meets `tolerance`.
pub fn eval(
    aspect_ratio: f64,
    tau_max_mpa: f64,
    xs: &[f64],
    tolerance: f64,
) -> Result<TierEvaluation> {
    let choice = tolerance_choice::eval_tier(aspect_ratio, tau_max_mpa, xs, tolerance)?;
    announce(&choice, tolerance);
    let rows =
        tolerance_choice::eval_with_tier(choice.tier, aspect_ratio, tau_max_mpa, xs, tolerance)?;
    Ok(TierEvaluation {
        tier: choice.tier,
        rows,
    })
}
