//! `--tolerance`: the cheapest tier whose measured error meets a relative tolerance, read from
//! the committed speed–accuracy measurements (`wavy::accuracy::measured`), for `wavy eval`
//! (any tier) and `wavy solve` (the coarsest finite-strain mesh).

use super::input::{out_of_range, InputError};
use anyhow::{Context, Result};
use wavy::accuracy::measured::{self, percent, Choice, ChoiceError, Query};
use wavy::accuracy::Tier;
use wavy::fe::{self, Kinematics, MeshLevel};
use wavy::models::PressureLaw;
use wavy::runner::fe_cases::{FeCase, FePhysics};

/// The flag of a measured quantity.
fn flag_of(quantity: &str) -> String {
    match quantity {
        "aspect_ratio" => "--ar".into(),
        "friction_coefficient" => "--mu".into(),
        q => format!("--{}", q.replace('_', "-")),
    }
}

/// A tolerance that cannot be served: exit 2 with the flag, the value and why.
fn refused(e: ChoiceError, tolerance: f64) -> anyhow::Error {
    match e {
        ChoiceError::OutsideRegion {
            ref quantity,
            value,
            ..
        } => InputError::Refused {
            flag: flag_of(quantity),
            value: format!("{value:?}"),
            reason: e.to_string(),
        }
        .into(),
        ChoiceError::NoTierMeets { .. } => InputError::Refused {
            flag: "--tolerance".into(),
            value: format!("{tolerance:?}"),
            reason: e.to_string(),
        }
        .into(),
        other => anyhow::Error::new(other),
    }
}

fn check_tolerance(tolerance: f64) -> Result<(), InputError> {
    if !(tolerance.is_finite() && tolerance > 0.0 && tolerance < 1.0) {
        return Err(out_of_range(
            "--tolerance",
            tolerance,
            "(0, 1), a relative error",
        ));
    }
    Ok(())
}

/// The choice, told on stderr.
fn announce(choice: &Choice, tolerance: f64) {
    let cases: Vec<String> = choice
        .cases
        .iter()
        .map(|(a, t)| format!("AR {a}, τ_max {t} MPa"))
        .collect();
    eprintln!(
        "tolerance {tolerance}: tier {} (measured error ≤ {} at {}; {:.3e} s per curve on one thread)",
        choice.tier,
        percent(choice.max_rel_error),
        cases.join(" and "),
        choice.seconds_per_curve
    );
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
    check_tolerance(tolerance)?;
    for &x in xs {
        if !(x.is_finite() && (0.0..=0.5).contains(&x)) {
            return Err(out_of_range("--a-over-lambda", x, "[0, 0.5]").into());
        }
    }
    let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let physics = FePhysics::default();
    let query = Query {
        aspect_ratio,
        tau_max_mpa,
        a_over_lambda: (lo, hi),
        physics: &physics.by_column(),
    };
    let table = measured::committed()?;
    let choice = table
        .choose(tolerance, &query, |_| true)
        .map_err(|e| refused(e, tolerance))?;
    announce(&choice, tolerance);
    let tier = choice.tier;
    let inputs = format!(
        "--tolerance {tolerance} (tier {tier}) --ar {aspect_ratio:?} --tau-max-mpa {tau_max_mpa:?}"
    );
    let mut rows = vec![];
    if let Some(law) = tier.law(aspect_ratio, tau_max_mpa) {
        for &x in xs {
            let p = law
                .physical_p_over_estar(x)
                .with_context(|| format!("{inputs} --a-over-lambda {x:?}"))?;
            rows.push((x, p, law.is_extrapolated()));
        }
    } else {
        let options = fe::SolveOptions {
            until_a_over_lambda: hi,
            mesh: tier.mesh().expect("an FE tier has a mesh"),
            ..fe::SolveOptions::default()
        };
        let physics = FePhysics {
            kinematics: match tier {
                Tier::Fe { kinematics, .. } => kinematics,
                _ => Kinematics::Finite,
            },
            ..physics
        };
        let case = FeCase::new(&physics, aspect_ratio, tau_max_mpa, options);
        let curve = fe::solve_curve(&case.problem, &case.options, &mut |_| {})
            .map_err(|f| anyhow::anyhow!("{inputs}: the solver stopped: {}", f.error))?;
        for &x in xs {
            let p = curve.p_at(x).with_context(|| {
                format!(
                    "{inputs} --a-over-lambda {x:?}: below the first contact point of the FE curve"
                )
            })?;
            rows.push((x, p, false));
        }
    }
    Ok(TierEvaluation { tier, rows })
}

/// `wavy solve --tolerance`: the coarsest finite-strain mesh whose measured error at this case
/// is at most `tolerance`.
pub fn solve_mesh(
    tolerance: f64,
    aspect_ratio: f64,
    tau_max_mpa: f64,
    physics: &FePhysics,
    until_a_over_lambda: f64,
) -> Result<MeshLevel> {
    check_tolerance(tolerance)?;
    if physics.kinematics != Kinematics::Finite {
        return Err(InputError::Refused {
            flag: "--kinematics".into(),
            value: physics.kinematics.name().into(),
            reason: "the measured mesh errors are of the finite-strain solution".into(),
        }
        .into());
    }
    let query = Query {
        aspect_ratio,
        tau_max_mpa,
        a_over_lambda: (until_a_over_lambda, until_a_over_lambda),
        physics: &physics.by_column(),
    };
    let choice = measured::committed()?
        .choose(tolerance, &query, |t| t.is_finite_fe())
        .map_err(|e| refused(e, tolerance))?;
    announce(&choice, tolerance);
    Ok(choice.tier.mesh().expect("an FE tier has a mesh"))
}
