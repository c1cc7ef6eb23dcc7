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

/// One column of an outcome's rows.
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// Real numbers (a point's measures; `NaN` where an error estimate is empty).
    Real(Vec<f64>),
    /// Counts (iterations, nodes, patches).
    Count(Vec<usize>),
    /// Names (the load branch).
    Name(Vec<&'static str>),
}

/// A curve point's value in one column.
enum PointValue {
    Real(fn(&CurvePoint) -> f64),
    Count(fn(&CurvePoint) -> usize),
}

/// The curve point's columns, in the order of [`CurvePoint::CSV_HEADER`] (a test keeps the two
/// equal).
const POINT_COLUMNS: [(&str, PointValue); 11] = [
    ("a_over_lambda", PointValue::Real(|p| p.a_over_lambda)),
    ("p_over_estar", PointValue::Real(|p| p.p_over_estar)),
    (
        "p_over_estar_reaction",
        PointValue::Real(|p| p.p_over_estar_reaction),
    ),
    (
        "slab_displacement_over_lambda",
        PointValue::Real(|p| p.slab_displacement_over_lambda),
    ),
    (
        "newton_iterations",
        PointValue::Count(|p| p.newton_iterations),
    ),
    ("active_nodes", PointValue::Count(|p| p.active_nodes)),
    ("contact_fraction", PointValue::Real(|p| p.contact_fraction)),
    ("patches", PointValue::Count(|p| p.patches)),
    ("stick_fraction", PointValue::Real(|p| p.stick_fraction)),
    (
        "stick_half_width_over_lambda",
        PointValue::Real(|p| p.stick_half_width_over_lambda),
    ),
    (
        "friction_work_over_estar_lambda2",
        PointValue::Real(|p| p.friction_work_over_estar_lambda2),
    ),
];

/// What a solve gave: the converged rows and what they cost (also the converged part of a
/// solve that stopped, `RequestError::Stopped`).
#[derive(Debug, Clone, PartialEq)]
pub struct SolveOutcome {
    /// The finite-element mesh (`None` for the boundary-element solver).
    pub mesh: Option<MeshLevel>,
    /// The boundary-element grid, points per wavelength (`None` for the finite-element solver).
    pub grid_points: Option<usize>,
    /// Unknowns: of the mesh, two per node (2·(nx + 1)·(ny + 1) where every column reaches
    /// the bonded face); of the grid, one pressure per point.
    pub unknowns: usize,
    pub extra: ExtraColumn,
    /// Loading rows, then (with `unload`) unloading rows, in the order they converged.
    pub rows: Vec<SolveRow>,
    /// The solver's work counters (zero for a solve that stopped).
    pub work: SolveWork,
    /// A boundary-element loop's energy both ways (`None` otherwise).
    pub cycle_energy: Option<CycleEnergy>,
}

/// The energy of a loading–unloading loop, over E* λ² (per unit ridge length, per
/// wavelength).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleEnergy {
    /// `∮ p̄ dδ`: the work the load does over the loop.
    pub cycle_work_over_estar_lambda2: f64,
    /// The work of friction at the face, summed over the increments.
    pub face_dissipation_over_estar_lambda2: f64,
}

impl CycleEnergy {
    /// The energy of a finite-element loop from its rows, loading then unloading: `∮ p̄ dd`
    /// by the trapezoid rule on the converged points
    /// ([`crate::fe::cycle_work_over_estar_lambda2`]), and the face's work of friction at the
    /// last point.
    pub fn of_finite_element_loop(rows: &[SolveRow]) -> Self {
        let branch = |b: LoadDirection| -> Vec<CurvePoint> {
            rows.iter()
                .filter(|r| r.branch == b)
                .map(|r| r.point)
                .collect()
        };
        let (loading, unloading) = (
            branch(LoadDirection::Loading),
            branch(LoadDirection::Unloading),
        );
        Self {
            cycle_work_over_estar_lambda2: crate::fe::cycle_work_over_estar_lambda2(
                &loading, &unloading,
            ),
            face_dissipation_over_estar_lambda2: crate::fe::cycle_friction_work_over_estar_lambda2(
                &unloading,
            ),
        }
    }
}

impl SolveOutcome {
    /// Converged load steps (rows).
    pub fn load_steps(&self) -> usize {
        self.rows.len()
    }

    /// The rows as named columns: the curve point's (as `wavy solve`'s CSV header names them),
    /// `branch` (loading or unloading), and `error_estimate` when estimated. The one list of
    /// columns that the Python bindings return.
    pub fn columns(&self) -> Vec<(&'static str, Column)> {
        let mut columns: Vec<(&'static str, Column)> = POINT_COLUMNS
            .iter()
            .map(|(name, value)| {
                let column = match value {
                    PointValue::Real(f) => {
                        Column::Real(self.rows.iter().map(|r| f(&r.point)).collect())
                    }
                    PointValue::Count(f) => {
                        Column::Count(self.rows.iter().map(|r| f(&r.point)).collect())
                    }
                };
                (*name, column)
            })
            .collect();
        let branches = self.rows.iter().map(|r| r.branch.name()).collect();
        columns.push(("branch", Column::Name(branches)));
        if self.extra == ExtraColumn::ErrorEstimate {
            let estimates = self
                .rows
                .iter()
                .map(|r| r.error_estimate.unwrap_or(f64::NAN));
            columns.push(("error_estimate", Column::Real(estimates.collect())));
        }
        columns
    }

    /// Newton iterations over every converged step.
    pub fn newton_iterations(&self) -> usize {
        self.rows.iter().map(|r| r.point.newton_iterations).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The point columns are the CSV's, in its order.
    #[test]
    fn point_columns_are_the_csv_header() {
        let names: Vec<&str> = POINT_COLUMNS.iter().map(|(n, _)| *n).collect();
        assert_eq!(names.join(","), CurvePoint::CSV_HEADER);
    }
}
