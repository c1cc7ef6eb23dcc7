//! The converged reference of the speed–accuracy scene (docs/replication.md R11): the
//! Richardson extrapolation of the two finest finite-strain meshes, with the order observed on
//! those two and the mesh ρ times coarser, and what that reference itself may be off by.

use crate::accuracy::{richardson, FORMAL_ORDER_RANGE};
use crate::fe::{convergence, CurvePoint};
use anyhow::{bail, Context, Result};

/// The reference p̄/E* of one case on the a/λ grid, and its own error.
#[derive(Debug, Clone)]
pub(crate) struct Reference {
    /// p̄/E* at each a/λ of the grid.
    pub p_over_estar: Vec<f64>,
    /// The order observed on the three meshes.
    pub observed_order: f64,
    /// The order extrapolated with: the observed one within `FORMAL_ORDER_RANGE`.
    pub order_used: f64,
    /// The Richardson estimate of the finest mesh's error, largest relative value over the grid.
    pub error_estimate: f64,
    /// The reference's spread over the plausible orders, largest relative value over the grid.
    pub uncertainty: f64,
}

impl Reference {
    /// From the curves on `meshes` (elements along the face, coarse to fine, each `ratio` times
    /// the last) on the a/λ grid `xs`; `case` names the case in errors.
    pub fn of(
        curves: [&[CurvePoint]; 3],
        meshes: [usize; 3],
        ratio: f64,
        xs: &[f64],
        case: &str,
    ) -> Result<Self> {
        let table = convergence::convergence_table(curves, ratio, xs).with_context(|| {
            format!(
                "{case}: the reference curves do not cover a/λ ∈ [{}, {}]",
                xs[0],
                xs[xs.len() - 1]
            )
        })?;
        let q = table.observed_order;
        let q_used = q.clamp(FORMAL_ORDER_RANGE.0, FORMAL_ORDER_RANGE.1);
        let reference: Vec<f64> = table
            .rows
            .iter()
            .map(|r| richardson(r.p_over_estar[1], r.p_over_estar[2], ratio, q_used))
            .collect();
        // The reference's own error: the Richardson estimate of the finest mesh's error, with
        // the observed order where it is below the formal range (a pre-asymptotic sequence,
        // where the formal order would understate it).
        if q.is_nan() || q <= 0.0 {
            let [coarsest, coarse, fine] = meshes;
            bail!("{case}: the finite-strain curves on meshes {coarsest}, {coarse}, {fine} do not converge (observed order {q})");
        }
        let q_error = q.min(q_used);
        let mut error_estimate = 0.0f64;
        let mut uncertainty = 0.0f64;
        for (r, &rv) in table.rows.iter().zip(&reference) {
            let [_, p_coarse, p_fine] = r.p_over_estar;
            let finest_error = (p_fine - p_coarse) / (ratio.powf(q_error) - 1.0);
            error_estimate = error_estimate.max((finest_error / rv).abs());
            // the reference's uncertainty: its spread over the plausible orders, from the
            // smaller of the observed and the formal lower order to the formal upper one
            let spread = richardson(p_coarse, p_fine, ratio, q_error.min(FORMAL_ORDER_RANGE.0))
                - richardson(p_coarse, p_fine, ratio, FORMAL_ORDER_RANGE.1);
            uncertainty = uncertainty.max((spread / rv).abs());
        }
        Ok(Reference {
            p_over_estar: reference,
            observed_order: q,
            order_used: q_used,
            error_estimate,
            uncertainty,
        })
    }
}
