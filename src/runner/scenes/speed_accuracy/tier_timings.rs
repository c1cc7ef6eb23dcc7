//! The measured wall times of the tiers: the cost axis of the `speed_accuracy` scene.
//!
//! Times are measured data, like the fingertip measurements: `wavy time-tiers` (`make
//! bench-tiers`) runs every tier of a speed_accuracy spec `runs` times on one thread and writes
//! `experiments/data/speed_accuracy_timings.csv`, which is committed; the scene reads it, so that
//! `make reproduce` stays byte-identical while the errors are recomputed every run. The file
//! starts with `# key: value` provenance lines (`measured_by`, `machine`, `threads`, `runs`),
//! then CSV with [`HEADER`]. The measurement itself is `crate::runner::scenes::speed_accuracy::time_tiers`.

use crate::accuracy::Tier;
use anyhow::{bail, Context, Result};
use std::path::Path;

/// Columns of a timings file.
pub const HEADER: [&str; 6] = [
    "tier",
    "aspect_ratio",
    "tau_max_mpa",
    "runs",
    "median_seconds_per_curve",
    "points_per_curve",
];

/// Provenance keys every timings file states.
pub const REQUIRED_PROVENANCE: [&str; 4] = ["measured_by", "machine", "threads", "runs"];

/// The timing of one tier at one case.
#[derive(Debug, Clone, PartialEq)]
pub struct TierTiming {
    pub tier: Tier,
    pub aspect_ratio: f64,
    pub tau_max_mpa: f64,
    pub runs: usize,
    /// Median wall time of one curve, s.
    pub median_seconds_per_curve: f64,
    /// Points of the curve (the a/λ grid for a closed form; the load steps for FE).
    pub points_per_curve: usize,
}

/// A timings file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Timings {
    /// (key, value) provenance, in file order.
    pub provenance: Vec<(String, String)>,
    pub rows: Vec<TierTiming>,
}

impl Timings {
    /// The timing of `tier` at (AR, τ_max in MPa).
    pub fn get(&self, tier: &Tier, aspect_ratio: f64, tau_max_mpa: f64) -> Option<&TierTiming> {
        self.rows.iter().find(|r| {
            r.tier == *tier && r.aspect_ratio == aspect_ratio && r.tau_max_mpa == tau_max_mpa
        })
    }

    fn provenance(&self, key: &str) -> &str {
        self.provenance
            .iter()
            .find(|(k, _)| k == key)
            .map_or("", |(_, v)| v.as_str())
    }

    /// The provenance in a few words, for a figure's footer; the optional `conditions` line
    /// (what else ran during the measurement) follows on a line of its own.
    pub fn describe(&self) -> Vec<String> {
        let mut lines = vec![format!(
            "median of {} runs on {} thread(s), {}.",
            self.provenance("runs"),
            self.provenance("threads"),
            self.provenance("machine")
        )];
        let conditions = self.provenance("conditions");
        if !conditions.is_empty() {
            lines.push(format!("Conditions: {conditions}."));
        }
        lines
    }

    /// The file's text: provenance lines, header, rows (times in shortest round-trip form).
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        for (k, v) in &self.provenance {
            s.push_str(&format!("# {k}: {v}\n"));
        }
        s.push_str(&HEADER.join(","));
        s.push('\n');
        for r in &self.rows {
            s.push_str(&format!(
                "{},{},{},{},{},{}\n",
                r.tier,
                r.aspect_ratio,
                r.tau_max_mpa,
                r.runs,
                r.median_seconds_per_curve,
                r.points_per_curve
            ));
        }
        s
    }

    /// Parses a timings file.
    pub fn parse(text: &str) -> Result<Self> {
        let (provenance, body) =
            crate::runner::measured_points::split_provenance(text, &REQUIRED_PROVENANCE)?;
        let mut reader = csv::Reader::from_reader(body.as_bytes());
        let header: Vec<String> = reader.headers()?.iter().map(String::from).collect();
        if header != HEADER {
            bail!("header {header:?}; expected {HEADER:?}");
        }
        let mut rows = vec![];
        for (i, rec) in reader.records().enumerate() {
            let rec = rec?;
            let line = i + 2;
            let num = |j: usize| -> Result<f64> {
                let v: f64 = rec[j]
                    .parse()
                    .with_context(|| format!("data row {line}, {}: `{}`", HEADER[j], &rec[j]))?;
                if !(v.is_finite() && v >= 0.0) {
                    bail!("data row {line}, {}: {v} (a finite number ≥ 0)", HEADER[j]);
                }
                Ok(v)
            };
            let count = |j: usize| -> Result<usize> {
                rec[j]
                    .parse()
                    .with_context(|| format!("data row {line}, {}: `{}`", HEADER[j], &rec[j]))
            };
            let seconds = num(4)?;
            if seconds <= 0.0 {
                bail!("data row {line}, median_seconds_per_curve: {seconds} (> 0)");
            }
            rows.push(TierTiming {
                tier: rec[0]
                    .parse()
                    .with_context(|| format!("data row {line}, tier"))?,
                aspect_ratio: num(1)?,
                tau_max_mpa: num(2)?,
                runs: count(3)?,
                median_seconds_per_curve: seconds,
                points_per_curve: count(5)?,
            });
        }
        Ok(Timings { provenance, rows })
    }
}

/// Reads a timings file (errors do not repeat the path).
pub fn read(path: &Path) -> Result<Timings> {
    let text = std::fs::read_to_string(path).with_context(|| {
        "cannot read the measured wall times (write them with `wavy time-tiers`, make bench-tiers)"
    })?;
    Timings::parse(&text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_round_trips_and_bad_rows_are_named() {
        let t = Timings {
            provenance: REQUIRED_PROVENANCE
                .iter()
                .map(|k| (k.to_string(), "x".to_string()))
                .collect(),
            rows: vec![TierTiming {
                tier: "fe-finite-48".parse().unwrap(),
                aspect_ratio: 0.18,
                tau_max_mpa: 0.1,
                runs: 3,
                median_seconds_per_curve: 1.0 / 3.0,
                points_per_curve: 41,
            }],
        };
        assert_eq!(Timings::parse(&t.to_text()).unwrap(), t);
        let bad = t.to_text().replace("0.3333333333333333", "-1");
        let e = Timings::parse(&bad).unwrap_err().to_string();
        assert!(e.contains("data row 2, median_seconds_per_curve"), "{e}");
        let e = Timings::parse("tier\n").unwrap_err().to_string();
        assert!(e.contains("# measured_by"), "{e}");
    }
}
