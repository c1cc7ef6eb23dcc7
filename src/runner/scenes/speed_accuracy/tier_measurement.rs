//! One tier's measured error and cost at one case of the speed–accuracy scene, and the Pareto
//! front of a case's tiers.

use crate::accuracy::{relative_errors, ErrorSummary, Tier};

/// One tier's measurement at one case.
pub(in crate::runner) struct Measurement {
    pub tier: Tier,
    pub errors: Option<ErrorSummary>,
    /// Why there is no error (an FE curve that stops short, an unphysical law value).
    pub status: String,
    pub seconds_per_curve: f64,
    pub seconds_per_point: Option<f64>,
    pub fe: Option<FeCost>,
}

pub(in crate::runner) struct FeCost {
    pub dofs: usize,
    pub load_steps: usize,
    pub newton_iterations: usize,
}

/// Every tier measured at one case (AR, τ_max in MPa).
pub(in crate::runner) struct CaseMeasurements {
    pub aspect_ratio: f64,
    pub tau_max_mpa: f64,
    pub reference_uncertainty: f64,
    pub measurements: Vec<Measurement>,
    /// [`pareto_front`] of the measurements.
    pub front: Vec<usize>,
}

/// The Pareto front: indices of the measurements no other one beats in both error and cost,
/// by increasing cost.
pub(in crate::runner) fn pareto_front(ms: &[Measurement]) -> Vec<usize> {
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

/// What accuracy costs along a case's finite-strain FE tiers: the exponent `s` of
/// `error ∝ time^s`, fitted by least squares in log–log through the tiers of at least
/// [`TRADE_FROM_ELEMENTS`] elements along the face that have a curve, and the factor of wall time
/// that halves the error, `2^(−1/s)`.
pub(in crate::runner) struct ErrorTimeTrade {
    /// The tiers fitted, in the case's order.
    pub tiers: Vec<Tier>,
    pub exponent: f64,
    pub time_factor_per_halving: f64,
}

/// The coarsest finite-strain mesh of [`error_time_trade`]: below it the coarse meshes do not
/// reach a/λ = 0.45 at every case, and their error is not yet in its asymptotic range.
pub(in crate::runner) const TRADE_FROM_ELEMENTS: usize = 32;

/// The [`ErrorTimeTrade`] of a case's measurements; `None` with fewer than two such tiers or an
/// error that does not fall with the time.
pub(in crate::runner) fn error_time_trade(ms: &[Measurement]) -> Option<ErrorTimeTrade> {
    let fitted: Vec<&Measurement> = ms
        .iter()
        .filter(|m| {
            m.tier.is_finite_fe()
                && m.tier
                    .mesh()
                    .is_some_and(|l| l.counts().0 >= TRADE_FROM_ELEMENTS)
                && m.errors.is_some()
        })
        .collect();
    if fitted.len() < 2 {
        return None;
    }
    let log_time: Vec<f64> = fitted.iter().map(|m| m.seconds_per_curve.ln()).collect();
    let log_error: Vec<f64> = fitted.iter().map(|m| m.errors.unwrap().max.ln()).collect();
    let c = crate::accuracy::extrapolation::polynomial_least_squares(&log_time, &log_error, 1)?;
    let exponent = c[1];
    (exponent < 0.0).then(|| ErrorTimeTrade {
        tiers: fitted.iter().map(|m| m.tier).collect(),
        exponent,
        time_factor_per_halving: 2f64.powf(-1.0 / exponent),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fe(nx: usize, error: Option<f64>, seconds: f64) -> Measurement {
        Measurement {
            tier: format!("fe-finite-{nx}").parse().unwrap(),
            errors: error.map(|e| ErrorSummary { max: e, rms: e }),
            status: String::new(),
            seconds_per_curve: seconds,
            seconds_per_point: None,
            fe: None,
        }
    }

    /// Error ∝ time^(−1/2) gives s = −½ and a factor 4 per halving; tiers below
    /// `TRADE_FROM_ELEMENTS` and tiers without a curve are left out; an error that grows with
    /// the time gives no trade.
    #[test]
    fn the_trade_of_a_power_law_is_recovered() {
        let ms = [
            fe(16, Some(0.5), 0.001),
            fe(32, Some(0.04), 1.0),
            fe(48, None, 2.0),
            fe(64, Some(0.02), 4.0),
            fe(96, Some(0.01), 16.0),
        ];
        let t = error_time_trade(&ms).unwrap();
        assert_eq!(t.tiers.len(), 3);
        assert!((t.exponent + 0.5).abs() < 1e-12, "{}", t.exponent);
        assert!((t.time_factor_per_halving - 4.0).abs() < 1e-9);
        let rising = [fe(32, Some(0.01), 1.0), fe(64, Some(0.02), 4.0)];
        assert!(error_time_trade(&rising).is_none());
    }
}
