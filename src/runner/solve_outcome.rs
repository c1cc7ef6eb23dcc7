//! What a `wavy solve` request gave: its rows (one per converged load step) and what they
//! cost; the CSV form of a row.

use crate::fe::{CurvePoint, LoadDirection, MeshLevel, SolveWork};

/// The column after the curve point's columns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExtraColumn {
    None,
    /// `error_estimate` (with `--error-estimate`).
    ErrorEstimate,
    /// `branch`: loading or unloading (with `--unload`).
    Branch,
}

/// One converged load step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveRow {
    pub point: CurvePoint,
    pub branch: LoadDirection,
    /// The Richardson estimate of the relative error of p̄/E* (with `--error-estimate`; `None`
    /// below the coarser curve's first contact point and without it).
    pub error_estimate: Option<f64>,
}

impl SolveRow {
    /// The CSV line of `wavy solve` (numbers in shortest round-trip form).
    pub fn csv_line(&self, extra: ExtraColumn) -> String {
        let row = self.point.csv_row();
        match extra {
            ExtraColumn::None => row,
            ExtraColumn::Branch => format!("{row},{}", self.branch.name()),
            ExtraColumn::ErrorEstimate => format!(
                "{row},{}",
                self.error_estimate.map_or(String::new(), |e| e.to_string())
            ),
        }
    }
}

/// What a solve gave: the converged rows and what they cost (also the converged part of a
/// solve that stopped, `RequestError::Stopped`).
#[derive(Debug, Clone, PartialEq)]
pub struct SolveOutcome {
    pub mesh: MeshLevel,
    /// Nodal displacement unknowns of the mesh, two per node: 2·(nx + 1)·(ny + 1).
    pub unknowns: usize,
    pub extra: ExtraColumn,
    /// Loading rows, then (with `unload`) unloading rows, in the order they converged.
    pub rows: Vec<SolveRow>,
    /// The solver's work counters (zero for a solve that stopped).
    pub work: SolveWork,
}

impl SolveOutcome {
    /// Converged load steps (rows).
    pub fn load_steps(&self) -> usize {
        self.rows.len()
    }

    /// Newton iterations over every converged step.
    pub fn newton_iterations(&self) -> usize {
        self.rows.iter().map(|r| r.point.newton_iterations).sum()
    }
}
