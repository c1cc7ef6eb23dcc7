//! `--tolerance`: the cheapest tier whose measured error meets a relative tolerance, read from
//! the committed speed–accuracy measurements (`crate::accuracy::measured`), for `wavy eval`
//! (any tier) and `wavy solve` (the coarsest finite-strain mesh). The choice is returned, not
//! printed: the command line tells it on stderr.

use crate::accuracy::measured::{self, Choice, ChoiceError, Query};
use crate::accuracy::{extrapolated_tier_values, Tier};
use crate::fe::{self, CurvePoint, Kinematics, MeshLevel};
use crate::models::PressureLaw;
use crate::runner::requests::input_checks::{a_over_lambda_in_range, out_of_range, InputError};
use crate::runner::requests::request_error::RequestError;
use crate::runner::sweep::fe_cases::{FeCase, FePhysics};
use rayon::prelude::*;
use std::ops::ControlFlow;

/// The flag of a measured quantity.
fn flag_of(quantity: &str) -> String {
    match quantity {
        "aspect_ratio" => "--ar".into(),
        "friction_coefficient" => "--mu".into(),
        q => format!("--{}", q.replace('_', "-")),
    }
}

/// A tolerance that cannot be served: an input error with the flag, the value and why, or
/// the measurements' own failure.
fn refused(e: ChoiceError, tolerance: f64) -> RequestError {
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
        other => other.into(),
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

/// The line that tells a choice (the command line prints it on stderr).
pub fn announcement(choice: &Choice, tolerance: f64) -> String {
    let cases: Vec<String> = choice
        .cases
        .iter()
        .map(|(a, t)| format!("AR {a}, τ_max {t} MPa"))
        .collect();
    format!(
        "tolerance {tolerance}: tier {} (measured error ≤ {} at {}; {:.3e} s per curve on one thread)",
        choice.tier,
        measured::percent(choice.max_rel_error),
        cases.join(" and "),
        choice.seconds_per_curve
    )
}

/// `wavy eval --tolerance`, first half: the cheapest tier whose measured error at (AR, τ_max
/// in MPa) over the a/λ of `xs` meets `tolerance` (each a/λ checked first).
pub fn eval_tier(
    aspect_ratio: f64,
    tau_max_mpa: f64,
    xs: &[f64],
    tolerance: f64,
) -> Result<Choice, RequestError> {
    check_tolerance(tolerance)?;
    for &x in xs {
        a_over_lambda_in_range("--a-over-lambda", x)?;
    }
    let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let query = Query {
        aspect_ratio,
        tau_max_mpa,
        a_over_lambda: (lo, hi),
        physics: &FePhysics::default().by_column(),
    };
    measured::committed()?
        .choose(tolerance, &query, |_| true)
        .map_err(|e| refused(e, tolerance))
}

/// `wavy eval --tolerance`, second half: the (a/λ, p̄/E*, extrapolated) rows of every a/λ of
/// `xs` by `tier` (a closed form, or its FE curves up to the largest a/λ: one, or a Richardson
/// tier's two).
pub fn eval_with_tier(
    tier: Tier,
    aspect_ratio: f64,
    tau_max_mpa: f64,
    xs: &[f64],
    tolerance: f64,
) -> Result<Vec<(f64, f64, bool)>, RequestError> {
    let inputs = format!(
        "--tolerance {tolerance} (tier {tier}) --ar {aspect_ratio:?} --tau-max-mpa {tau_max_mpa:?}"
    );
    let mut rows = vec![];
    if let Some(law) = tier.law(aspect_ratio, tau_max_mpa) {
        for &x in xs {
            let p = law
                .physical_p_over_estar(x)
                .map_err(|source| RequestError::Unphysical {
                    inputs: format!("{inputs} --a-over-lambda {x:?}"),
                    source,
                })?;
            rows.push((x, p, law.is_extrapolated()));
        }
        return Ok(rows);
    }
    let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    // an extrapolating tier's curves are independent: solved side by side
    let curves: Vec<Vec<CurvePoint>> = (tier.fe_curves().into_par_iter())
        .map(|(kinematics, nx)| {
            let options = fe::SolveOptions {
                until_a_over_lambda: hi,
                mesh: MeshLevel::along_face(nx),
                ..fe::SolveOptions::default()
            };
            let physics = FePhysics {
                kinematics,
                ..FePhysics::default()
            };
            let case = FeCase::new(&physics, aspect_ratio, tau_max_mpa, options);
            fe::solve_curve(&case.problem, &case.options, &mut |_| {
                ControlFlow::Continue(())
            })
            .map(|curve| curve.points)
            .map_err(|f| {
                RequestError::Failed(format!(
                    "{inputs}: the solver stopped on mesh {nx}: {}",
                    f.error
                ))
            })
        })
        .collect::<Result<_, _>>()?;
    let points: Vec<&[CurvePoint]> = curves.iter().map(|c| c.as_slice()).collect();
    let p_at = |x: f64| match tier.is_extrapolated() {
        true => extrapolated_tier_values(&tier, &points, &[x]).map(|v| v[0]),
        false => fe::convergence::p_at(points[0], x),
    };
    for &x in xs {
        let p = p_at(x).ok_or_else(|| {
            RequestError::Failed(format!(
                "{inputs} --a-over-lambda {x:?}: below the first contact point of the FE curve"
            ))
        })?;
        rows.push((x, p, false));
    }
    Ok(rows)
}

/// `wavy solve --tolerance`: the coarsest finite-strain mesh whose measured error at this case
/// is at most `tolerance`, and the choice it came from.
pub fn solve_mesh(
    tolerance: f64,
    aspect_ratio: f64,
    tau_max_mpa: f64,
    physics: &FePhysics,
    until_a_over_lambda: f64,
) -> Result<(MeshLevel, Choice), RequestError> {
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
    Ok((choice.tier.mesh().expect("an FE tier has a mesh"), choice))
}
