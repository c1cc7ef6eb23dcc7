//! Paper Table 1 re-derived: the twelve WNL coefficients fitted to our FE curves, once per
//! reading of Eq. 4, beside the paper's; and the paper's own coefficients scored against the
//! same curves.

use crate::fit::{self, CurveSample, Refit};
use crate::models::wnl::{quadratic_surface, Correction};
use crate::models::{Coefficients, FitDomain, Reading};
use crate::numfmt::sig_digits;
use crate::plot::{padded_range, palette, LegendPosition, Panel, Series};
use crate::runner::scenes::scene_output::{Layout, Remarks};
use crate::runner::scenes::{Scene, SceneContext, SceneResult};
use crate::runner::sweep::fe_cases::{self, FeCase};
use crate::runner::RunOptions;
use crate::spec::{Bounded, FeSection, Grid, Positive, SpecError, Validator};
use crate::table::{Cell, Table};
use anyhow::{Context, Result};
use serde::Deserialize;

/// Paper Table 1 re-derived: the twelve WNL coefficients fitted by least squares in p̄/E* to our
/// FE curves, once per reading of Eq. 4 (R5), beside the paper's.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Table1RefitScene {
    /// Aspect ratios Δ/λ of the FE curves (at least three: the polynomials are quadratic).
    pub aspect_ratios: Vec<Bounded<Positive>>,
    /// τ_max grid (MPa) on which the fitted A and B are drawn against the paper's.
    pub tau_max_mpa: Grid,
    /// The FE curves; `fe.tau_max_mpa` (at least three values) are the fitted shear strengths.
    pub fe: FeSection,
}

impl Scene for Table1RefitScene {
    /// One case per (τ_max, AR) of the FE section, τ_max outer.
    fn fe_cases(&self, opts: &RunOptions) -> Vec<FeCase> {
        let ars: Vec<f64> = self.aspect_ratios.iter().map(|a| a.get()).collect();
        fe_cases::section_cases(&self.fe, &ars, opts)
    }

    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        run(ctx.title, self, ctx.opts)
    }

    fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        v.at_least(
            "table1_refit.aspect_ratios",
            self.aspect_ratios.iter().map(|a| a.get()),
            3,
        )?;
        let ars: Vec<f64> = self.aspect_ratios.iter().map(|a| a.get()).collect();
        v.fe_section("table1_refit.fe", &self.fe, None, &ars)?;
        v.at_least(
            "table1_refit.fe.tau_max_mpa",
            self.fe.tau_max_mpa.iter().map(|t| t.get()),
            3,
        )?;
        v.grid(
            "table1_refit.tau_max_mpa",
            &self.tau_max_mpa,
            (0.0, f64::INFINITY),
            true,
        )?;
        Ok(())
    }
}

/// One fitted reading: our refit and the paper's coefficients scored on the same samples.
pub struct ReadingFit {
    pub refit: Refit,
    pub paper_mse: f64,
}

/// Fits every reading to the FE points of `samples`.
pub fn fit_readings(samples: &[CurveSample], domain: FitDomain) -> Result<Vec<ReadingFit>> {
    Reading::ALL
        .iter()
        .map(|&reading| {
            let refit = fit::refit(samples, reading, domain)
                .with_context(|| format!("refit of reading {reading}"))?;
            let paper_mse = fit::mse(samples, reading, Coefficients::PAPER_TABLE1);
            Ok(ReadingFit { refit, paper_mse })
        })
        .collect()
}

fn run(title: &str, s: &Table1RefitScene, opts: &RunOptions) -> Result<SceneResult> {
    let cases = s.fe_cases(opts);
    let outcomes = fe_cases::solve_all(&cases, opts)?;
    let mut remarks = Remarks::default();
    let mut samples = vec![];
    for (case, outcome) in cases.iter().zip(&outcomes) {
        let label = format!(
            "AR = {}, τ_max = {} MPa",
            case.problem.aspect_ratio, case.tau_max_mpa
        );
        remarks.stopped_curve(&label, outcome);
        samples.extend(outcome.points.iter().map(|p| CurveSample {
            aspect_ratio: case.problem.aspect_ratio,
            tau_max_mpa: case.tau_max_mpa,
            a_over_lambda: p.a_over_lambda,
            p_over_estar: p.p_over_estar,
        }));
    }
    let fits = fit_readings(&samples, fitted_domain(&cases))?;
    let best = best_reading(&fits);
    remarks.notes.push(best.clone());
    let (nx, ny) = cases
        .first()
        .map(|c| c.options.mesh.counts())
        .unwrap_or((0, 0));
    let ars: Vec<f64> = s.aspect_ratios.iter().map(|a| a.get()).collect();
    remarks.footer = vec![
        format!(
            "Least squares in p̄/E* over {} FE points (AR ∈ {:?}, τ_max ∈ {:?} MPa, mesh {nx}×{ny}); solid: ours, dashed: paper Table 1.",
            samples.len(),
            ars,
            s.fe.tau_max_mpa.iter().map(|t| t.get()).collect::<Vec<_>>()
        ),
        best,
    ];
    remarks.count_incomplete("the fit uses their converged points");
    let layout = Layout {
        grid: (fits.len(), 2),
        panel_px: (500, 380),
        margin_px: 140,
        font_px: 16,
    };
    let tables = vec![coefficients_table(&fits), quality_table(&fits)];
    Ok(remarks.finish(title, layout, figure_panels(s, &fits), tables))
}

/// The (AR, τ_max) span of the fitted curves.
fn fitted_domain(cases: &[FeCase]) -> FitDomain {
    let span = |v: &mut dyn Iterator<Item = f64>| {
        v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        })
    };
    let (ar_lo, ar_hi) = span(&mut cases.iter().map(|c| c.problem.aspect_ratio));
    let (tau_lo, tau_hi) = span(&mut cases.iter().map(|c| c.tau_max_mpa));
    FitDomain {
        aspect_ratio_min: ar_lo,
        aspect_ratio_max: ar_hi,
        tau_max_mpa_min: tau_lo,
        tau_max_mpa_max: tau_hi,
    }
}

/// The reading that fits our FE curves best, and how the others compare, in words.
fn best_reading(fits: &[ReadingFit]) -> String {
    let best = fits
        .iter()
        .min_by(|x, y| x.refit.mse.total_cmp(&y.refit.mse))
        .expect("three readings");
    format!(
        "best reading of Eq. 4 on our FE curves: {} (MSE {}; {})",
        best.refit.reading,
        sig_digits(best.refit.mse, 3),
        fits.iter()
            .filter(|f| f.refit.reading != best.refit.reading)
            .map(|f| format!("{} {}", f.refit.reading, sig_digits(f.refit.mse, 3)))
            .collect::<Vec<_>>()
            .join(", ")
    )
}

/// The coefficients beside the paper's: one row per coefficient, one column per reading.
fn coefficients_table(fits: &[ReadingFit]) -> Table {
    let mut header = vec!["coefficient".to_string(), "paper".to_string()];
    header.extend(
        fits.iter()
            .map(|f| format!("ours_{}", f.refit.reading.name().replace('-', "_"))),
    );
    let mut table = Table::new("", &header.iter().map(String::as_str).collect::<Vec<_>>());
    let paper = Coefficients::PAPER_TABLE1;
    for correction in Correction::BOTH {
        for i in 0..6 {
            let get = |c: &Coefficients| correction.of(c)[i];
            let mut row: Vec<Cell> = vec![
                format!("{}{i}", correction.letter()).into(),
                get(&paper).into(),
            ];
            row.extend(fits.iter().map(|f| Cell::Num(get(&f.refit.coefficients))));
            table.push(row);
        }
    }
    table
}

/// How well each reading fits, and how well the paper's coefficients do on our curves.
fn quality_table(fits: &[ReadingFit]) -> Table {
    let mut table = Table::new(
        "fit",
        &[
            "reading",
            "samples",
            "mse_ours",
            "mse_paper_table1",
            "relative_optimality",
            "condition_number",
        ],
    );
    for f in fits {
        table.push(vec![
            f.refit.reading.name().into(),
            (f.refit.samples as f64).into(),
            f.refit.mse.into(),
            f.paper_mse.into(),
            f.refit.relative_optimality.into(),
            f.refit.condition_number.into(),
        ]);
    }
    table
}

/// Per reading, A and B against τ_max at the FE aspect ratios, ours against the paper's.
fn figure_panels(s: &Table1RefitScene, fits: &[ReadingFit]) -> Vec<Panel> {
    let taus = s.tau_max_mpa.values();
    let ars: Vec<f64> = s.aspect_ratios.iter().map(|a| a.get()).collect();
    let paper = Coefficients::PAPER_TABLE1;
    let mut panels = vec![];
    for f in fits {
        for correction in Correction::BOTH {
            let name = correction.name();
            let mut series = vec![];
            for (k, &ar) in ars.iter().enumerate() {
                let color = palette::CYCLE[k % palette::CYCLE.len()];
                let surface = |c: &Coefficients| -> Vec<(f64, f64)> {
                    let coeffs = correction.of(c);
                    taus.iter()
                        .map(|&t| (t, quadratic_surface(coeffs, ar, t)))
                        .collect()
                };
                series.push(Series::line(
                    Some(format!("ours, AR = {ar}")),
                    color,
                    2,
                    surface(&f.refit.coefficients),
                ));
                series.push(Series::dashed(
                    Some(format!("paper, AR = {ar}")),
                    color,
                    1,
                    surface(&paper),
                ));
            }
            let y = padded_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
            panels.push(Panel {
                title: format!("{name}(AR, τ_max), reading {}", f.refit.reading),
                x_label: "τ_max (MPa)".into(),
                y_label: name.into(),
                x_range: (taus[0], taus[taus.len() - 1]),
                y_range: y,
                series,
                notes: vec![
                    format!("MSE ours {}", sig_digits(f.refit.mse, 2)),
                    format!("MSE paper {}", sig_digits(f.paper_mse, 2)),
                ],
                // A falls with τ_max and AR, B rises: keep the legend off the lines
                log_scale: (false, false),
                legend: Some(if correction == Correction::A {
                    LegendPosition::LowerLeft
                } else {
                    LegendPosition::UpperLeft
                }),
            });
        }
    }
    panels
}
