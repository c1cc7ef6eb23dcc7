//! The converged reference curves of the speed–accuracy scene, computed once and committed: the
//! file format.
//!
//! The reference has to be several times tighter than the finest tier it judges (0.1 %), and
//! the meshes that make it so (up to 192 elements along the face) take minutes per curve: more
//! than `make reproduce` should spend. So `wavy refine-reference` (`make reference`,
//! `crate::runner::scenes::speed_accuracy::refine_reference`) solves every case of a speed_accuracy spec on its
//! `reference_meshes`, takes at each a/λ of the grid the limit `p(n) = p₀ + c₁/n + c₂/n²` fitted
//! through them (`crate::accuracy::extrapolation`) and writes
//! `experiments/data/speed_accuracy_reference.csv`; the scene reads it as it reads the measured
//! wall times. The limit does not depend on the discretisation (edge rule, grading),
//! only on the physics, which the file states per row and the scene checks; a change of the
//! physics defaults makes the scene refuse the file until it is recomputed.
//!
//! The file starts with `# key: value` provenance lines ([`REQUIRED_PROVENANCE`]), then CSV:
//! per case and a/λ the limit and its spread (`mesh_limit_with_spread`: how far the limit moves
//! when one mesh is left out, relative).

use crate::accuracy::measured::PHYSICS_COLUMNS;
use anyhow::{bail, Context, Result};
use std::path::Path;

/// Provenance keys every reference file states.
pub const REQUIRED_PROVENANCE: [&str; 3] = ["computed_by", "meshes", "fit"];

/// The columns after the case's (AR, τ_max) and physics columns.
const VALUE_COLUMNS: [&str; 3] = ["a_over_lambda", "p_over_estar", "spread"];

/// The reference of one case at one a/λ.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferencePoint {
    pub aspect_ratio: f64,
    pub tau_max_mpa: f64,
    /// The physics, in the order of [`PHYSICS_COLUMNS`].
    pub physics: [f64; 5],
    pub a_over_lambda: f64,
    /// The limit p̄₀/E*.
    pub p_over_estar: f64,
    /// How far the limit moves when one mesh is left out, relative.
    pub spread: f64,
}

/// A reference file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ReferenceCurves {
    /// (key, value) provenance, in file order.
    pub provenance: Vec<(String, String)>,
    pub points: Vec<ReferencePoint>,
}

fn header() -> Vec<&'static str> {
    let mut h = vec!["aspect_ratio", "tau_max_mpa"];
    h.extend(PHYSICS_COLUMNS);
    h.extend(VALUE_COLUMNS);
    h
}

impl ReferenceCurves {
    /// The meshes the limits were fitted through (provenance `meshes`).
    pub fn meshes(&self) -> Result<Vec<usize>> {
        let v = self
            .provenance
            .iter()
            .find(|(k, _)| k == "meshes")
            .map_or("", |(_, v)| v.as_str());
        v.split_whitespace()
            .map(|n| {
                n.parse()
                    .with_context(|| format!("provenance meshes: `{v}`"))
            })
            .collect()
    }

    /// The reference of the case (AR, τ_max in MPa) with `physics`, in a/λ order.
    pub fn case(
        &self,
        aspect_ratio: f64,
        tau_max_mpa: f64,
        physics: [f64; 5],
    ) -> Vec<&ReferencePoint> {
        self.points
            .iter()
            .filter(|p| {
                p.aspect_ratio == aspect_ratio
                    && p.tau_max_mpa == tau_max_mpa
                    && p.physics == physics
            })
            .collect()
    }

    /// The file's text: provenance lines, header, rows (shortest round-trip numbers).
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        for (k, v) in &self.provenance {
            s.push_str(&format!("# {k}: {v}\n"));
        }
        s.push_str(&header().join(","));
        s.push('\n');
        for p in &self.points {
            let mut row = vec![p.aspect_ratio, p.tau_max_mpa];
            row.extend(p.physics);
            row.extend([p.a_over_lambda, p.p_over_estar, p.spread]);
            let cells: Vec<String> = row.iter().map(|v| v.to_string()).collect();
            s.push_str(&cells.join(","));
            s.push('\n');
        }
        s
    }

    /// Parses a reference file.
    pub fn parse(text: &str) -> Result<Self> {
        let (provenance, body) =
            crate::runner::measured_points::split_provenance(text, &REQUIRED_PROVENANCE)?;
        let mut reader = csv::Reader::from_reader(body.as_bytes());
        let got: Vec<String> = reader.headers()?.iter().map(String::from).collect();
        let want = header();
        if got != want {
            bail!("header {got:?}; expected {want:?}");
        }
        let mut points = vec![];
        for (i, rec) in reader.records().enumerate() {
            let rec = rec?;
            let line = i + 2;
            let mut v = [0.0f64; 10];
            for (j, cell) in v.iter_mut().enumerate() {
                *cell = rec[j]
                    .parse()
                    .with_context(|| format!("data row {line}, {}: `{}`", want[j], &rec[j]))?;
                if !(cell.is_finite() && *cell >= 0.0) {
                    bail!("data row {line}, {}: {cell} (a finite number ≥ 0)", want[j]);
                }
            }
            points.push(ReferencePoint {
                aspect_ratio: v[0],
                tau_max_mpa: v[1],
                physics: [v[2], v[3], v[4], v[5], v[6]],
                a_over_lambda: v[7],
                p_over_estar: v[8],
                spread: v[9],
            });
        }
        Ok(ReferenceCurves { provenance, points })
    }
}

/// Reads a reference file (errors do not repeat the path).
pub fn read(path: &Path) -> Result<ReferenceCurves> {
    let text = std::fs::read_to_string(path).with_context(|| {
        "cannot read the reference curves (compute them with `wavy refine-reference`, make reference)"
    })?;
    ReferenceCurves::parse(&text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_round_trips_and_bad_rows_are_named() {
        let r = ReferenceCurves {
            provenance: vec![
                ("computed_by".into(), "x".into()),
                ("meshes".into(), "64 96 128".into()),
                ("fit".into(), "x".into()),
            ],
            points: vec![ReferencePoint {
                aspect_ratio: 0.18,
                tau_max_mpa: 0.1,
                physics: [1.0, 1.0, 1000.0, 1.0, 0.005],
                a_over_lambda: 0.05,
                p_over_estar: 1.0 / 3.0,
                spread: 1e-5,
            }],
        };
        assert_eq!(ReferenceCurves::parse(&r.to_text()).unwrap(), r);
        assert_eq!(r.meshes().unwrap(), [64, 96, 128]);
        let bad = r.to_text().replace("0.3333333333333333", "-1");
        let e = ReferenceCurves::parse(&bad).unwrap_err().to_string();
        assert!(e.contains("data row 2, p_over_estar"), "{e}");
        let e = ReferenceCurves::parse("a\n").unwrap_err().to_string();
        assert!(e.contains("# computed_by"), "{e}");
    }
}
