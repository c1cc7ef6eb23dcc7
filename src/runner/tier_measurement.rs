//! One tier's measured error and cost at one case of the speed–accuracy scene, and the Pareto
//! front of a case's tiers.

use crate::accuracy::{relative_errors, ErrorSummary, Tier};

/// One tier's measurement at one case.
pub(super) struct Measurement {
    pub tier: Tier,
    pub errors: Option<ErrorSummary>,
    /// Why there is no error (an FE curve that stops short, an unphysical law value).
    pub status: String,
    pub seconds_per_curve: f64,
    pub seconds_per_point: Option<f64>,
    pub fe: Option<FeCost>,
}

pub(super) struct FeCost {
    pub dofs: usize,
    pub load_steps: usize,
    pub newton_iterations: usize,
}

/// Every tier measured at one case (AR, τ_max in MPa).
pub(super) struct CaseMeasurements {
    pub aspect_ratio: f64,
    pub tau_max_mpa: f64,
    pub reference_uncertainty: f64,
    pub measurements: Vec<Measurement>,
    /// [`pareto_front`] of the measurements.
    pub front: Vec<usize>,
}

/// The Pareto front: indices of the measurements no other one beats in both error and cost,
/// by increasing cost.
pub(super) fn pareto_front(ms: &[Measurement]) -> Vec<usize> {
    let mut ok: Vec<usize> = (0..ms.len()).filter(|&i| ms[i].errors.is_some()).collect();
    ok.sort_by(|&i, &j| {
        ms[i]
            .seconds_per_curve
            .total_cmp(&ms[j].seconds_per_curve)
            .then(
                ms[i]
                    .errors
                    .unwrap()
                    .max
                    .total_cmp(&ms[j].errors.unwrap().max),
            )
    });
    let mut front = vec![];
    let mut best = f64::INFINITY;
    for i in ok {
        let e = ms[i].errors.unwrap().max;
        if e < best {
            best = e;
            front.push(i);
        }
    }
    front
}

impl Measurement {
    /// With the relative errors of `values` against `reference` (none without values).
    pub fn with_errors(self, values: Option<&[f64]>, reference: &[f64]) -> Self {
        Measurement {
            errors: values.map(|v| relative_errors(v, reference)),
            ..self
        }
    }
}
