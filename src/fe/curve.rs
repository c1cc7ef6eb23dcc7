//! The computed load curve: its converged points, the last deformed state, and the CSV row
//! format of a point (the format of `wavy solve` and of the sweep cache).

use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

use super::convergence::p_at;

/// One converged point of the load curve.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CurvePoint {
    /// Contact half-width `a/λ` (current configuration).
    pub a_over_lambda: f64,
    /// Mean pressure from the contact forces: `Σ_i λ_i / (λ/2) / E*`.
    pub p_over_estar: f64,
    /// Mean pressure from the slab reaction: `−Σ_top ∂Π/∂y / (λ/2) / E*`.
    pub p_over_estar_reaction: f64,
    /// Slab displacement `d/λ`.
    pub slab_displacement_over_lambda: f64,
    /// Newton iterations spent on this step (all active-set passes).
    pub newton_iterations: usize,
    /// Contact-face nodes in contact.
    pub active_nodes: usize,
}

impl CurvePoint {
    /// Header of the CSV form of curve points ([`CurvePoint::csv_row`]).
    pub const CSV_HEADER: &'static str = "a_over_lambda,p_over_estar,p_over_estar_reaction,slab_displacement_over_lambda,newton_iterations,active_nodes";

    /// One CSV row, numbers in shortest round-trip form (exact: [`FromStr`] reads it back
    /// bit for bit).
    pub fn csv_row(&self) -> String {
        format!(
            "{},{},{},{},{},{}",
            self.a_over_lambda,
            self.p_over_estar,
            self.p_over_estar_reaction,
            self.slab_displacement_over_lambda,
            self.newton_iterations,
            self.active_nodes
        )
    }
}

/// A CSV row that is not a curve point.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("not a curve point row ({CSV_FIELDS} comma-separated numbers expected): `{row}`")]
pub struct CurvePointParseError {
    /// The offending row.
    pub row: String,
}

const CSV_FIELDS: usize = 6;

impl FromStr for CurvePoint {
    type Err = CurvePointParseError;
    /// Reads a row written by [`CurvePoint::csv_row`].
    fn from_str(row: &str) -> Result<Self, Self::Err> {
        let bad = || CurvePointParseError { row: row.into() };
        let f: Vec<&str> = row.split(',').collect();
        if f.len() != CSV_FIELDS {
            return Err(bad());
        }
        Ok(CurvePoint {
            a_over_lambda: f[0].parse().map_err(|_| bad())?,
            p_over_estar: f[1].parse().map_err(|_| bad())?,
            p_over_estar_reaction: f[2].parse().map_err(|_| bad())?,
            slab_displacement_over_lambda: f[3].parse().map_err(|_| bad())?,
            newton_iterations: f[4].parse().map_err(|_| bad())?,
            active_nodes: f[5].parse().map_err(|_| bad())?,
        })
    }
}

impl fmt::Display for CurvePoint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.csv_row())
    }
}

/// Deformed mesh of the last converged state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DeformedState {
    /// Current node positions (units of λ).
    pub nodes: Vec<[f64; 2]>,
    /// Quads (node ids, counter-clockwise).
    pub quads: Vec<[usize; 4]>,
    /// Contact-face node ids in order of increasing reference `X`.
    pub bottom: Vec<usize>,
    /// Normal contact pressure `p/E*` per contact-face node: the normal contact force
    /// over the node's tributary length on the deformed face (0 on free nodes).
    pub contact_pressure_over_estar: Vec<f64>,
    /// Tangential contact traction `τ/E*` per contact-face node along the indenter's
    /// tangent `(1, y_s')/w` (the friction traction; 0 when frictionless and on free
    /// nodes).
    pub contact_shear_over_estar: Vec<f64>,
}

/// The work a curve took, counted by the solver (deterministic, unlike its wall time).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct SolveWork {
    /// Tangent assemblies: Newton iterations of every attempt (failed bordered attempts
    /// and sub-steps included) and load tangents of the predictor.
    pub tangent_assemblies: usize,
    /// Numeric factorisations of the tangent, of any kind (a failed Cholesky counts, as
    /// does the `L D Lᵀ` that follows it).
    pub factorisations: usize,
}

/// A computed load curve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Curve {
    /// Converged points, in loading order.
    pub points: Vec<CurvePoint>,
    /// Last converged state.
    pub final_state: DeformedState,
    /// What the curve cost.
    #[serde(default)]
    pub work: SolveWork,
}

impl Curve {
    /// `p̄/E*` interpolated at `a/λ` (see [`p_at`]).
    pub fn p_at(&self, a_over_lambda: f64) -> Option<f64> {
        p_at(&self.points, a_over_lambda)
    }
}

/// A point whose numbers need every digit of the round-trip form (test fixture).
#[cfg(test)]
pub(crate) fn awkward_point() -> CurvePoint {
    CurvePoint {
        a_over_lambda: 0.1 + 0.2,
        p_over_estar: std::f64::consts::PI / 7.0,
        p_over_estar_reaction: 1.0 / 3.0,
        slab_displacement_over_lambda: -1e-17,
        newton_iterations: 4,
        active_nodes: 17,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_row_round_trips_exactly() {
        let p = awkward_point();
        assert_eq!(p.csv_row().parse::<CurvePoint>(), Ok(p));
        assert_eq!(CurvePoint::CSV_HEADER.split(',').count(), CSV_FIELDS);
        assert!("1,2,3".parse::<CurvePoint>().is_err());
        assert!("1,2,3,4,x,6".parse::<CurvePoint>().is_err());
    }
}
