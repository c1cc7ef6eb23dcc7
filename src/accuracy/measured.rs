//! The measured errors and costs of every tier (the committed output of the `speed_accuracy`
//! scene, `expected/speed_accuracy.csv` and `expected/speed_accuracy_reference.csv`, compiled in
//! by build.rs), and the choice of the cheapest tier that meets a tolerance.
//!
//! A query point is inside the measured region when its aspect ratio and τ_max lie within the
//! measured values, its a/λ within the range the errors were taken over, and its other physical
//! parameters equal the measured ones. A tier's error there is the largest of its errors at the
//! measured cases that bracket the point (up to four: the neighbouring aspect ratios times the
//! neighbouring τ_max), each plus the error estimate of that case's reference, and its cost the
//! largest of their costs: a conservative reading of a table measured at a few points.

use super::Tier;
use crate::csv_text::CsvTable;
use std::sync::OnceLock;

/// One tier at one measured case.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredTier {
    pub tier: Tier,
    pub aspect_ratio: f64,
    pub tau_max_mpa: f64,
    /// Largest relative error of p̄/E* over the measured a/λ range; `None` when the tier could
    /// not produce the curve (an FE mesh too coarse for the case).
    pub max_rel_error: Option<f64>,
    /// Median wall time of one curve on one thread, s.
    pub seconds_per_curve: f64,
}

/// A tier's largest error over one band of a/λ at one case (the error of FE curves is largest
/// at small a/λ, where few elements are in contact: a query at larger a/λ reads its own bands).
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredBand {
    pub tier: Tier,
    pub aspect_ratio: f64,
    pub tau_max_mpa: f64,
    /// The band `[from, to]` of a/λ.
    pub a_over_lambda: (f64, f64),
    /// Largest relative error of p̄/E* in the band; `None` when the tier has no curve.
    pub max_rel_error: Option<f64>,
}

/// What every measured case shares: the parameters it was measured at, and the convergence
/// order observed there.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredCase {
    pub aspect_ratio: f64,
    pub tau_max_mpa: f64,
    /// (name, value) of every other physical parameter, e.g. `("kappa_over_g", 1000.0)`.
    pub physics: Vec<(String, f64)>,
    /// a/λ range of the errors.
    pub a_over_lambda: (f64, f64),
    /// The FE convergence order used for the Richardson reference (observed, limited to
    /// [`super::FORMAL_ORDER_RANGE`]).
    pub order: f64,
    /// The reference's relative uncertainty (its spread over the plausible convergence orders):
    /// added to every tier's measured error when a tier is chosen, so that a choice never
    /// promises more than the reference can tell.
    pub reference_uncertainty: f64,
}

/// The committed measurements.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MeasuredAccuracy {
    pub tiers: Vec<MeasuredTier>,
    pub cases: Vec<MeasuredCase>,
    /// Errors per band of a/λ (may be empty: then the whole-range error counts).
    pub bands: Vec<MeasuredBand>,
}

/// Columns of the reference table that are physical parameters of the FE model.
pub const PHYSICS_COLUMNS: [&str; 5] = [
    "estar_mpa",
    "thickness_over_lambda",
    "kappa_over_g",
    "friction_coefficient",
    "elastic_slip_over_element",
];

/// Where a query is refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ChoiceError {
    #[error("no measured speed–accuracy table is compiled in (expected/speed_accuracy.csv is missing; `make bless` writes it)")]
    NoMeasurements,
    #[error("the committed speed–accuracy table is unreadable: {0}")]
    Unreadable(String),
    #[error("{quantity} = {value} lies outside the measured region ({measured}); the errors of the tiers are known only there")]
    OutsideRegion {
        /// The quantity's name (`aspect_ratio`, `tau_max_mpa`, `a_over_lambda`, or a physics column).
        quantity: String,
        value: f64,
        /// What was measured, in words.
        measured: String,
    },
    #[error("no tier meets the relative tolerance {tolerance} here{}", best.as_ref().map_or(String::new(), |(t, e)| format!(" (the most accurate measured, {t}, has {})", percent(*e))))]
    NoTierMeets {
        tolerance: f64,
        /// The most accurate tier at the point, and its error.
        best: Option<(Tier, f64)>,
    },
}

/// The chosen tier.
#[derive(Debug, Clone, PartialEq)]
pub struct Choice {
    pub tier: Tier,
    /// Its measured error at the point plus the reference's own error estimate (largest over
    /// the bracketing cases).
    pub max_rel_error: f64,
    /// Its measured cost per curve, s (largest over the bracketing cases).
    pub seconds_per_curve: f64,
    /// The measured (AR, τ_max) cases the error was read from.
    pub cases: Vec<(f64, f64)>,
}

/// A point at which a tier is wanted.
#[derive(Debug, Clone, PartialEq)]
pub struct Query<'a> {
    pub aspect_ratio: f64,
    pub tau_max_mpa: f64,
    /// The a/λ range the answer must cover.
    pub a_over_lambda: (f64, f64),
    /// (name, value) of the other physical parameters, named as [`PHYSICS_COLUMNS`]; those
    /// not given are taken to be the measured ones.
    pub physics: &'a [(&'a str, f64)],
}

/// An error as a percentage with three significant digits.
pub fn percent(relative: f64) -> String {
    let v = relative * 100.0;
    let decimals = if v > 0.0 && v.is_finite() {
        (2 - v.log10().floor() as i32).clamp(0, 12) as usize
    } else {
        2
    };
    format!("{v:.decimals$} %")
}

fn bracket(values: &[f64], x: f64) -> Option<Vec<f64>> {
    let lo = values
        .iter()
        .copied()
        .filter(|v| *v <= x)
        .reduce(f64::max)?;
    let hi = values
        .iter()
        .copied()
        .filter(|v| *v >= x)
        .reduce(f64::min)?;
    Some(if lo == hi { vec![lo] } else { vec![lo, hi] })
}

fn distinct(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// A committed table, parsed.
fn table(text: &str) -> Result<CsvTable, ChoiceError> {
    CsvTable::parse(text).map_err(|e| ChoiceError::Unreadable(e.to_string()))
}

/// The rows of `table`, read by column name.
fn named_rows(table: &CsvTable) -> impl Iterator<Item = NamedRow<'_>> {
    (0..table.rows.len()).map(move |row| NamedRow { table, row })
}

/// One row of a committed table.
struct NamedRow<'a> {
    table: &'a CsvTable,
    row: usize,
}

impl NamedRow<'_> {
    fn cell(&self, name: &str) -> Result<&str, ChoiceError> {
        self.table
            .cell(self.row, name)
            .ok_or_else(|| ChoiceError::Unreadable(format!("no column `{name}`")))
    }

    /// A finite number, or `None` for an empty cell.
    fn optional_number(&self, name: &str) -> Result<Option<f64>, ChoiceError> {
        match self.cell(name)? {
            "" => Ok(None),
            cell => cell
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .map(Some)
                .ok_or_else(|| {
                    ChoiceError::Unreadable(format!("column `{name}`: `{cell}` is not a number"))
                }),
        }
    }

    fn number(&self, name: &str) -> Result<f64, ChoiceError> {
        self.optional_number(name)?
            .ok_or_else(|| ChoiceError::Unreadable(format!("column `{name}`: empty")))
    }

    fn tier(&self) -> Result<Tier, ChoiceError> {
        self.cell("tier")?
            .parse()
            .map_err(|e: super::TierParseError| ChoiceError::Unreadable(e.to_string()))
    }
}

impl MeasuredAccuracy {
    /// Parses the scene's main table, its reference table and its table of errors per a/λ band
    /// (CSV text). Columns are found by name; other columns are ignored.
    pub fn parse(
        tiers_csv: &str,
        reference_csv: &str,
        bands_csv: &str,
    ) -> Result<Self, ChoiceError> {
        let tiers = named_rows(&table(tiers_csv)?)
            .map(|r| {
                Ok(MeasuredTier {
                    tier: r.tier()?,
                    aspect_ratio: r.number("aspect_ratio")?,
                    tau_max_mpa: r.number("tau_max_mpa")?,
                    max_rel_error: r.optional_number("max_rel_error")?,
                    seconds_per_curve: r.number("seconds_per_curve")?,
                })
            })
            .collect::<Result<_, ChoiceError>>()?;
        let cases = named_rows(&table(reference_csv)?)
            .map(|r| {
                Ok(MeasuredCase {
                    aspect_ratio: r.number("aspect_ratio")?,
                    tau_max_mpa: r.number("tau_max_mpa")?,
                    physics: PHYSICS_COLUMNS
                        .iter()
                        .map(|n| Ok((n.to_string(), r.number(n)?)))
                        .collect::<Result<_, ChoiceError>>()?,
                    a_over_lambda: (
                        r.number("a_over_lambda_min")?,
                        r.number("a_over_lambda_max")?,
                    ),
                    order: r.number("order_used")?,
                    reference_uncertainty: r.number("reference_uncertainty")?,
                })
            })
            .collect::<Result<_, ChoiceError>>()?;
        let bands = named_rows(&table(bands_csv)?)
            .map(|r| {
                Ok(MeasuredBand {
                    tier: r.tier()?,
                    aspect_ratio: r.number("aspect_ratio")?,
                    tau_max_mpa: r.number("tau_max_mpa")?,
                    a_over_lambda: (
                        r.number("a_over_lambda_from")?,
                        r.number("a_over_lambda_to")?,
                    ),
                    max_rel_error: r.optional_number("max_rel_error")?,
                })
            })
            .collect::<Result<_, ChoiceError>>()?;
        Ok(MeasuredAccuracy {
            tiers,
            cases,
            bands,
        })
    }

    /// The error of `m` over the a/λ range `(lo, hi)`: the largest over the bands that meet the
    /// range, or the whole-range error when the tier has no bands at its case.
    fn error_over(&self, m: &MeasuredTier, (lo, hi): (f64, f64)) -> Option<f64> {
        let mut bands = self
            .bands
            .iter()
            .filter(|b| {
                b.tier == m.tier
                    && b.aspect_ratio == m.aspect_ratio
                    && b.tau_max_mpa == m.tau_max_mpa
            })
            .peekable();
        if bands.peek().is_none() {
            return m.max_rel_error;
        }
        let mut worst: Option<f64> = None;
        for b in bands {
            let (from, to) = b.a_over_lambda;
            if from <= hi && lo <= to {
                let e = b.max_rel_error?;
                worst = Some(worst.map_or(e, |w| w.max(e)));
            }
        }
        worst
    }

    /// The convergence order of the FE error: the smallest order used over the measured cases
    /// (the smaller the order, the larger a Richardson error estimate).
    pub fn fe_order(&self) -> Result<f64, ChoiceError> {
        self.cases
            .iter()
            .map(|c| c.order)
            .reduce(f64::min)
            .ok_or(ChoiceError::NoMeasurements)
    }

    /// The cheapest tier among `candidates` whose measured error at `query` is at most
    /// `tolerance` (relative).
    pub fn choose(
        &self,
        tolerance: f64,
        query: &Query,
        candidates: impl Fn(&Tier) -> bool,
    ) -> Result<Choice, ChoiceError> {
        if self.cases.is_empty() {
            return Err(ChoiceError::NoMeasurements);
        }
        let corners = self.corners(query)?;
        let mut best: Option<(Tier, f64)> = None;
        let mut chosen: Option<Choice> = None;
        let mut names: Vec<Tier> = vec![];
        for m in &self.tiers {
            if !names.contains(&m.tier) {
                names.push(m.tier);
            }
        }
        for tier in names.into_iter().filter(|t| candidates(t)) {
            let Some((error, cost)) = self.over_corners(tier, &corners, query) else {
                continue;
            };
            if best.is_none_or(|(_, e)| error < e) {
                best = Some((tier, error));
            }
            if error <= tolerance && chosen.as_ref().is_none_or(|c| cost < c.seconds_per_curve) {
                chosen = Some(Choice {
                    tier,
                    max_rel_error: error,
                    seconds_per_curve: cost,
                    cases: corners
                        .iter()
                        .map(|c| (c.aspect_ratio, c.tau_max_mpa))
                        .collect(),
                });
            }
        }
        chosen.ok_or(ChoiceError::NoTierMeets { tolerance, best })
    }

    /// The measured cases at the corners of the (AR, τ_max) cell that holds `query`; an error
    /// where the query lies outside the measured region (its AR, τ_max, a/λ range or other
    /// physics).
    fn corners(&self, query: &Query) -> Result<Vec<&MeasuredCase>, ChoiceError> {
        let outside = |quantity: &str, value: f64, values: &[f64]| ChoiceError::OutsideRegion {
            quantity: quantity.into(),
            value,
            measured: if values.len() == 1 {
                format!("{quantity} = {}", values[0])
            } else {
                format!(
                    "{quantity} in [{}, {}]",
                    values[0],
                    values[values.len() - 1]
                )
            },
        };
        let ars = distinct(self.cases.iter().map(|c| c.aspect_ratio).collect());
        let taus = distinct(self.cases.iter().map(|c| c.tau_max_mpa).collect());
        let ar_bracket = bracket(&ars, query.aspect_ratio)
            .ok_or_else(|| outside("aspect_ratio", query.aspect_ratio, &ars))?;
        let tau_bracket = bracket(&taus, query.tau_max_mpa)
            .ok_or_else(|| outside("tau_max_mpa", query.tau_max_mpa, &taus))?;
        let mut corners = vec![];
        for &a in &ar_bracket {
            for &t in &tau_bracket {
                let case = self
                    .cases
                    .iter()
                    .find(|c| c.aspect_ratio == a && c.tau_max_mpa == t)
                    .ok_or_else(|| ChoiceError::OutsideRegion {
                        quantity: "(aspect_ratio, tau_max_mpa)".into(),
                        value: query.aspect_ratio,
                        measured: format!("no measured case at AR {a}, τ_max {t} MPa"),
                    })?;
                let (lo, hi) = case.a_over_lambda;
                for x in [query.a_over_lambda.0, query.a_over_lambda.1] {
                    if !(lo..=hi).contains(&x) {
                        return Err(outside("a_over_lambda", x, &[lo, hi]));
                    }
                }
                for (name, value) in query.physics {
                    if let Some((_, m)) = case.physics.iter().find(|(n, _)| n == name) {
                        if (value - m).abs() > 1e-12 * m.abs() {
                            return Err(outside(name, *value, &[*m]));
                        }
                    }
                }
                corners.push(case);
            }
        }
        Ok(corners)
    }

    /// A tier's largest error (its measured error plus the reference's uncertainty) and largest
    /// cost over `corners`; none unless it was measured at every corner.
    fn over_corners(
        &self,
        tier: Tier,
        corners: &[&MeasuredCase],
        query: &Query,
    ) -> Option<(f64, f64)> {
        let mut error = 0.0f64;
        let mut cost = 0.0f64;
        for c in corners {
            let m = self.tiers.iter().find(|m| {
                m.tier == tier && m.aspect_ratio == c.aspect_ratio && m.tau_max_mpa == c.tau_max_mpa
            })?;
            error = error.max(self.error_over(m, query.a_over_lambda)? + c.reference_uncertainty);
            cost = cost.max(m.seconds_per_curve);
        }
        Some((error, cost))
    }
}

mod committed_text {
    include!(concat!(env!("OUT_DIR"), "/measured_accuracy.rs"));
}

/// The committed measurements (parsed once).
pub fn committed() -> Result<&'static MeasuredAccuracy, ChoiceError> {
    static TABLE: OnceLock<Result<MeasuredAccuracy, ChoiceError>> = OnceLock::new();
    TABLE
        .get_or_init(|| {
            match (
                committed_text::TIERS_CSV,
                committed_text::REFERENCE_CSV,
                committed_text::BANDS_CSV,
            ) {
                (Some(t), Some(r), Some(b)) => MeasuredAccuracy::parse(t, r, b),
                _ => Err(ChoiceError::NoMeasurements),
            }
        })
        .as_ref()
        .map_err(Clone::clone)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::Kinematics;

    const TIERS: &str = "tier,aspect_ratio,tau_max_mpa,max_rel_error,seconds_per_curve
westergaard,0.1,0,0.05,1e-6
westergaard,0.3,0,0.2,1e-6
fe-finite-32,0.1,0,0.004,0.2
fe-finite-32,0.3,0,,0.5
fe-finite-48,0.1,0,0.002,0.4
fe-finite-48,0.3,0,0.003,1.0
";
    const REFERENCE: &str = "aspect_ratio,tau_max_mpa,estar_mpa,thickness_over_lambda,kappa_over_g,friction_coefficient,elastic_slip_over_element,a_over_lambda_min,a_over_lambda_max,order_used,reference_uncertainty
0.1,0,1,1,1000,1,0.005,0.05,0.45,1.5,0
0.3,0,1,1,1000,1,0.005,0.05,0.45,1.25,0.0005
";

    const BANDS: &str =
        "tier,aspect_ratio,tau_max_mpa,a_over_lambda_from,a_over_lambda_to,max_rel_error
fe-finite-32,0.1,0,0.05,0.25,0.004
fe-finite-32,0.1,0,0.25,0.45,0.001
";

    fn table() -> MeasuredAccuracy {
        MeasuredAccuracy::parse(TIERS, REFERENCE, BANDS).unwrap()
    }

    #[test]
    fn a_query_at_large_a_reads_its_own_bands() {
        let t = table();
        let c = t.choose(0.002, &at(0.1, 0.3), |_| true).unwrap();
        assert_eq!(
            (c.tier.name(), c.max_rel_error),
            ("fe-finite-32".into(), 0.001)
        );
        // a range that reaches into the first band takes its error
        let q = Query {
            a_over_lambda: (0.2, 0.3),
            ..at(0.1, 0.3)
        };
        assert_eq!(t.choose(0.005, &q, |_| true).unwrap().max_rel_error, 0.004);
    }

    fn at(ar: f64, a: f64) -> Query<'static> {
        Query {
            aspect_ratio: ar,
            tau_max_mpa: 0.0,
            a_over_lambda: (a, a),
            physics: &[("kappa_over_g", 1000.0)],
        }
    }

    #[test]
    fn picks_the_cheapest_tier_within_tolerance() {
        let t = table();
        let c = t.choose(0.1, &at(0.1, 0.3), |_| true).unwrap();
        assert_eq!(c.tier, Tier::Westergaard);
        let c = t.choose(0.005, &at(0.1, 0.3), |_| true).unwrap();
        assert_eq!(
            c.tier,
            Tier::Fe {
                kinematics: Kinematics::Finite,
                elements_along_face: 32
            }
        );
        // between the measured aspect ratios the worse corner counts, and the 32 mesh, which
        // failed at AR 0.3, is not a candidate
        let c = t.choose(0.005, &at(0.2, 0.3), |_| true).unwrap();
        assert_eq!(c.tier.name(), "fe-finite-48");
        // the AR 0.3 reference's own error (0.0005) counts
        assert!((c.max_rel_error - 0.0035).abs() < 1e-15, "{c:?}");
        assert_eq!(c.seconds_per_curve, 1.0);
        assert_eq!(c.cases, vec![(0.1, 0.0), (0.3, 0.0)]);
        assert_eq!(t.fe_order().unwrap(), 1.25);
    }

    #[test]
    fn refuses_outside_the_region_or_beyond_every_tier() {
        let t = table();
        for (q, quantity) in [
            (at(0.05, 0.3), "aspect_ratio"),
            (at(0.2, 0.47), "a_over_lambda"),
            (
                Query {
                    physics: &[("kappa_over_g", 10.0)],
                    ..at(0.1, 0.3)
                },
                "kappa_over_g",
            ),
            (
                Query {
                    tau_max_mpa: 0.1,
                    ..at(0.1, 0.3)
                },
                "tau_max_mpa",
            ),
        ] {
            match t.choose(0.1, &q, |_| true) {
                Err(ChoiceError::OutsideRegion { quantity: got, .. }) => {
                    assert_eq!(got, quantity)
                }
                other => panic!("{quantity}: {other:?}"),
            }
        }
        match t.choose(1e-7, &at(0.1, 0.3), |_| true) {
            Err(ChoiceError::NoTierMeets { best, .. }) => {
                assert_eq!(best.unwrap().0.name(), "fe-finite-32")
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            MeasuredAccuracy::default().choose(0.1, &at(0.1, 0.3), |_| true),
            Err(ChoiceError::NoMeasurements)
        ));
    }
}
