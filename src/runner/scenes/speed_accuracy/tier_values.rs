//! What one tier of the speed–accuracy scene answers on the a/λ grid, from its curves or its
//! closed form, with the FE cost of its curves: one FE curve, an extrapolation of several
//! ([`crate::accuracy::extrapolated_tier_values`]), or a closed-form law.

use anyhow::{Context, Result};

use crate::accuracy::{extrapolated_tier_values, Tier};
use crate::fe::{convergence, CurvePoint, MeshLevel};
use crate::models::PressureLaw;
use crate::runner::scenes::speed_accuracy::tier_measurement::FeCost;
use crate::runner::sweep::fe_cases::FeOutcome;

/// The unknowns and the work of an FE curve on the mesh of `nx` elements along the face.
pub(super) fn fe_cost(nx: usize, o: &FeOutcome) -> FeCost {
    FeCost {
        dofs: MeshLevel::along_face(nx).unknowns(),
        load_steps: o.points.len(),
        newton_iterations: o.points.iter().map(|p| p.newton_iterations).sum(),
    }
}

/// What a tier answers on the a/λ grid `xs` (none where it has no curve there), the status
/// that says why not, and the FE cost of its curves (none for a closed form).
pub(super) type TierValues = (Option<Vec<f64>>, String, Option<FeCost>);

/// The FE tier of the curve `o` on `nx` elements along the face: its p̄/E* on `xs`, or where it
/// stopped.
pub(super) fn fe_tier_values(
    xs: &[f64],
    o: &FeOutcome,
    nx: usize,
    tier: &Tier,
    at: &str,
) -> Result<TierValues> {
    let cost = fe_cost(nx, o);
    if let Some(f) = &o.failure {
        let reached = o.last_a_over_lambda();
        let status = format!("stops at a/λ = {reached:.3}: {f}");
        return Ok((None, status, Some(cost)));
    }
    let v: Option<Vec<f64>> = xs
        .iter()
        .map(|&x| convergence::p_at(&o.points, x))
        .collect();
    let v = v.with_context(|| format!("{at}: the curve of {tier} does not cover the a/λ grid"))?;
    Ok((Some(v), "ok".into(), Some(cost)))
}

/// The extrapolating tier of `curves` (each with its elements along the face, coarsest first):
/// the extrapolation on `xs` ([`extrapolated_tier_values`]), or which mesh stopped where. Its
/// cost is the unknowns of the largest system and the work of every curve.
pub(super) fn extrapolated_values(
    xs: &[f64],
    curves: &[(&FeOutcome, usize)],
    tier: &Tier,
    at: &str,
) -> Result<TierValues> {
    let costs: Vec<FeCost> = curves.iter().map(|&(o, nx)| fe_cost(nx, o)).collect();
    let cost = FeCost {
        dofs: costs.iter().map(|c| c.dofs).max().unwrap_or(0),
        load_steps: costs.iter().map(|c| c.load_steps).sum(),
        newton_iterations: costs.iter().map(|c| c.newton_iterations).sum(),
    };
    if let Some((o, nx)) = curves.iter().find(|(o, _)| o.failure.is_some()) {
        let reached = o.last_a_over_lambda();
        let failure = o.failure.as_ref().expect("found by its failure");
        let status = format!("mesh {nx} stops at a/λ = {reached:.3}: {failure}");
        return Ok((None, status, Some(cost)));
    }
    let points: Vec<&[CurvePoint]> = curves.iter().map(|(o, _)| o.points.as_slice()).collect();
    let v = extrapolated_tier_values(tier, &points, xs)
        .with_context(|| format!("{at}: the curves of {tier} do not cover the a/λ grid"))?;
    Ok((Some(v), "ok".into(), Some(cost)))
}

/// A closed-form tier at (AR, τ_max in MPa): its p̄/E* on `xs`, or why it is unphysical there.
pub(super) fn closed_form_values(xs: &[f64], tier: &Tier, ar: f64, tau: f64) -> TierValues {
    let law = tier.law(ar, tau).expect("a closed-form tier has a law");
    match xs
        .iter()
        .map(|&x| law.physical_p_over_estar(x))
        .collect::<Result<Vec<f64>, _>>()
    {
        Ok(v) => (Some(v), "ok".into(), None),
        Err(e) => (None, format!("unphysical: {e}"), None),
    }
}
