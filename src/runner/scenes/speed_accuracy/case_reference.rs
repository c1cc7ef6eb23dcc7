//! The reference of one case of the speed–accuracy scene (docs/replication.md R11): the
//! committed limit of the fine meshes on the a/λ grid (`crate::runner::scenes::speed_accuracy::reference_curves`), how far it
//! may be off, and the order of the FE error observed on three meshes refined by a constant
//! ratio, which the error estimates of single curves use.

use crate::accuracy::FORMAL_ORDER_RANGE;
use crate::fe::{convergence, CurvePoint};
use crate::runner::scenes::speed_accuracy::reference_curves::ReferencePoint;
use anyhow::{bail, Context, Result};

/// The reference p̄/E* of one case on the a/λ grid, its uncertainty and the observed order.
#[derive(Debug, Clone)]
pub(crate) struct Reference {
    /// p̄/E* at each a/λ of the grid.
    pub p_over_estar: Vec<f64>,
    /// The order observed on the three order meshes.
    pub observed_order: f64,
    /// The order error estimates use: the observed one within `FORMAL_ORDER_RANGE`.
    pub order_used: f64,
    /// The reference's own uncertainty: the largest relative spread of the limit over the grid.
    pub uncertainty: f64,
}

impl Reference {
    /// From the curves on the order `meshes` (elements along the face, coarse to fine, each
    /// `ratio` times the last) and the committed `limit` of the case, on the a/λ grid `xs`;
    /// `case` names the case in errors.
    pub fn of(
        curves: [&[CurvePoint]; 3],
        meshes: [usize; 3],
        ratio: f64,
        xs: &[f64],
        limit: &[&ReferencePoint],
        case: &str,
    ) -> Result<Self> {
        let grid_matches = limit.len() == xs.len()
            && limit
                .iter()
                .zip(xs)
                .all(|(p, &x)| (p.a_over_lambda - x).abs() <= 1e-12);
        if !grid_matches {
            bail!(
                "{case}: the reference file has no limit on this a/λ grid and physics ({} points there, {} asked): recompute it with `wavy refine-reference` (make reference)",
                limit.len(),
                xs.len()
            );
        }
        let table = convergence::convergence_table(curves, ratio, xs).with_context(|| {
            format!(
                "{case}: the curves of the observed order do not cover a/λ ∈ [{}, {}]",
                xs[0],
                xs[xs.len() - 1]
            )
        })?;
        let q = table.observed_order;
        if q.is_nan() || q <= 0.0 {
            let [coarsest, coarse, fine] = meshes;
            bail!("{case}: the finite-strain curves on meshes {coarsest}, {coarse}, {fine} do not converge (observed order {q})");
        }
        Ok(Reference {
            p_over_estar: limit.iter().map(|p| p.p_over_estar).collect(),
            observed_order: q,
            order_used: q.clamp(FORMAL_ORDER_RANGE.0, FORMAL_ORDER_RANGE.1),
            uncertainty: limit.iter().map(|p| p.spread).fold(0.0, f64::max),
        })
    }
}
