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
    /// Newton iterations spent reaching this point: every active-set pass, the event search's
    /// trials and sub-steps, a target retargeted to a node that touched first, the release
    /// searches, and the failed tries before each of them (their last pass); on unloading also
    /// the intermediate steps.
    pub newton_iterations: usize,
    /// Contact-face nodes in contact.
    pub active_nodes: usize,
    /// Total contact length over λ ([`crate::fe::contact::patches`]): `2a/λ` for the single patch of a
    /// sinusoid.
    pub contact_fraction: f64,
    /// Contact patches in the half wavelength `[0, ½]` (a patch that reaches a symmetry line
    /// continues in its mirror image).
    pub patches: usize,
    /// Total stick length over λ ([`crate::fe::contact::stick_zone`]): the part of the contact
    /// fraction where the face sticks to the indenter (0 without friction).
    #[serde(default)]
    pub stick_fraction: f64,
    /// Half-width over λ of the stick zone at the peak: the `x` of its stick–slip front (0
    /// when the peak slips, and without friction).
    #[serde(default)]
    pub stick_half_width_over_lambda: f64,
    /// Work of friction at the contact face along the path up to this point, per unit ridge
    /// length and per wavelength, over `E* λ²`: what the face has done against friction,
    /// sliding along the indenter (0 without friction). On a closed loading–unloading loop,
    /// where the elastic energy is back to zero, it is the loop's work
    /// [`cycle_work_over_estar_lambda2`], the energy the cycle dissipates.
    #[serde(default)]
    pub friction_work_over_estar_lambda2: f64,
}

impl CurvePoint {
    /// Header of the CSV form of curve points ([`CurvePoint::csv_row`]).
    pub const CSV_HEADER: &'static str = "a_over_lambda,p_over_estar,p_over_estar_reaction,slab_displacement_over_lambda,newton_iterations,active_nodes,contact_fraction,patches,stick_fraction,stick_half_width_over_lambda,friction_work_over_estar_lambda2";

    /// One CSV row, numbers in shortest round-trip form (exact: [`FromStr`] reads it back
    /// bit for bit).
    pub fn csv_row(&self) -> String {
        format!(
            "{},{},{},{},{},{},{},{},{},{},{}",
            self.a_over_lambda,
            self.p_over_estar,
            self.p_over_estar_reaction,
            self.slab_displacement_over_lambda,
            self.newton_iterations,
            self.active_nodes,
            self.contact_fraction,
            self.patches,
            self.stick_fraction,
            self.stick_half_width_over_lambda,
            self.friction_work_over_estar_lambda2
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

const CSV_FIELDS: usize = 11;

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
            contact_fraction: f[6].parse().map_err(|_| bad())?,
            patches: f[7].parse().map_err(|_| bad())?,
            stick_fraction: f[8].parse().map_err(|_| bad())?,
            stick_half_width_over_lambda: f[9].parse().map_err(|_| bad())?,
            friction_work_over_estar_lambda2: f[10].parse().map_err(|_| bad())?,
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
    /// Whether each contact-face node is in contact (the active set; the edge node of the
    /// last event touches with zero force, so its pressure is round-off of either sign).
    pub in_contact: Vec<bool>,
    /// Whether each contact-face node sticks to the indenter ([`crate::fe::contact::stick_zone`];
    /// all `false` without friction): an active node not marked sticks slips.
    #[serde(default)]
    pub in_stick: Vec<bool>,
    /// Normal contact pressure `p/E*` per contact-face node: the normal contact force
    /// over the node's tributary length on the deformed face (0 on free nodes).
    pub contact_pressure_over_estar: Vec<f64>,
    /// Tangential contact traction `τ/E*` per contact-face node along the indenter's
    /// tangent `(1, y_s')/w` (the friction traction; 0 when frictionless, on free nodes and
    /// on the symmetry lines).
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
    /// Unit vectors of updated (friction) rows solved for by the Woodbury solve: zero when
    /// the factor's trailing block gives `S⁻¹` on the contact face (`fe::linsys`), one per
    /// friction row and tangent otherwise.
    pub woodbury_unit_solves: usize,
}

/// The direction of the load on a branch of a loading–unloading cycle; named `loading` and
/// `unloading` in CSV files.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LoadDirection {
    /// The slab approaches: the contact grows from first contact to the target.
    Loading,
    /// The slab retracts from the target back to zero load.
    Unloading,
}

impl LoadDirection {
    /// The name in CSV files.
    pub fn name(self) -> &'static str {
        match self {
            LoadDirection::Loading => "loading",
            LoadDirection::Unloading => "unloading",
        }
    }
}

/// A computed load curve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Curve {
    /// Converged points, in loading order.
    pub points: Vec<CurvePoint>,
    /// With unloading ([`super::solve_cycle`]): the converged points of the unloading
    /// branch, from the target back to zero load, in unloading order; empty otherwise.
    #[serde(default)]
    pub unloading: Vec<CurvePoint>,
    /// The contact patches of each loading point (same order as `points`): `[start, end]`
    /// in `[0, ½]` (units of λ, current positions; [`crate::fe::contact::patches`]).
    #[serde(default)]
    pub patch_edges: Vec<Vec<[f64; 2]>>,
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

/// The work `∮ p̄ dδ` of a loading–unloading cycle per unit ridge length and per wavelength,
/// over `E* λ²`: `∫ p̄/E* d(d/λ)` along loading minus along unloading (trapezoid rule on the
/// converged points; the branch from first contact starts at the undeformed state, `p̄ = 0`
/// at `d = 0`, and the unloading branch ends at zero load, so the loop closes on `p̄ = 0`).
/// Positive: the cycle dissipates energy.
pub fn cycle_work_over_estar_lambda2(loading: &[CurvePoint], unloading: &[CurvePoint]) -> f64 {
    let work = |pts: &mut dyn Iterator<Item = (f64, f64)>| {
        let mut w = 0.0;
        let mut last: Option<(f64, f64)> = None;
        for (d, p) in pts {
            if let Some((d0, p0)) = last {
                w += 0.5 * (p + p0) * (d - d0);
            }
            last = Some((d, p));
        }
        w
    };
    let pair = |q: &CurvePoint| (q.slab_displacement_over_lambda, q.p_over_estar);
    // loading from the undeformed state; unloading from the last loading point, where it starts
    let w_load = work(&mut std::iter::once((0.0, 0.0)).chain(loading.iter().map(pair)));
    let w_unload = work(
        &mut loading
            .last()
            .map(pair)
            .into_iter()
            .chain(unloading.iter().map(pair)),
    );
    // unloading runs toward smaller d, so its integral in the direction of travel is −∫ p̄ dd
    w_load + w_unload
}

/// The work of friction at the face over a loading–unloading cycle, over `E* λ²`: the face's
/// work at the cycle's last point ([`CurvePoint::friction_work_over_estar_lambda2`]), 0 for a
/// cycle with no unloading point. Beside [`cycle_work_over_estar_lambda2`], the energy audit
/// of the cycle.
pub fn cycle_friction_work_over_estar_lambda2(unloading: &[CurvePoint]) -> f64 {
    unloading
        .last()
        .map_or(0.0, |p| p.friction_work_over_estar_lambda2)
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
        contact_fraction: 0.6 - 0.0000001,
        patches: 3,
        stick_fraction: 0.1 + 0.7,
        stick_half_width_over_lambda: 0.3 - 1e-16,
        friction_work_over_estar_lambda2: 1.0 / 7e3,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A triangle loop: loading along p̄ = d to (1, 1), unloading straight down to (½, 0)
    /// and along p̄ = 0 back to d = 0 encloses the area ¼.
    #[test]
    fn cycle_work_is_the_area_of_the_loop() {
        let at = |d: f64, p: f64| CurvePoint {
            slab_displacement_over_lambda: d,
            p_over_estar: p,
            ..awkward_point()
        };
        let loading = [at(0.5, 0.5), at(1.0, 1.0)];
        let unloading = [at(0.5, 0.0), at(0.0, 0.0)];
        assert!((cycle_work_over_estar_lambda2(&loading, &unloading) - 0.25).abs() < 1e-15);
        assert!((cycle_work_over_estar_lambda2(&loading, &[]) - 0.5).abs() < 1e-15);
        // the reverse path closes
        let back = [at(0.5, 0.5), at(0.0, 0.0)];
        assert!(cycle_work_over_estar_lambda2(&loading, &back).abs() < 1e-15);
    }

    #[test]
    fn csv_row_round_trips_exactly() {
        let p = awkward_point();
        assert_eq!(p.csv_row().parse::<CurvePoint>(), Ok(p));
        assert_eq!(CurvePoint::CSV_HEADER.split(',').count(), CSV_FIELDS);
        assert!("1,2,3".parse::<CurvePoint>().is_err());
        assert!("1,2,3,4,x,6,7,8,9,10,11".parse::<CurvePoint>().is_err());
    }
}
