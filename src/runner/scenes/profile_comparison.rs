//! What the two-scale and many-scale scenes share: a profile's FE contact-fraction curve on a
//! layer mesh graded in depth, loaded to a contact fraction and solved again on a coarser mesh
//! for its error estimate, against models evaluated at mean pressures up to its last point.

use crate::accuracy::contact_fraction::contact_fraction_error_estimate;
use crate::fe::{CurvePoint, Grading, MeshLevel, SolveOptions};
use crate::plot::Series;
use crate::runner::sweep::fe_cases::FeOutcome;
use crate::spec::{SpecError, Validator};
use plotters::style::RGBColor;

/// FE curve colours per τ_max (black, red, …).
pub(crate) const FE_COLORS: [RGBColor; 3] = [
    RGBColor(0, 0, 0),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
];

/// The FE settings of a comparison scene, as its spec states them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ComparisonSettings<'a> {
    /// The scene's table, for the messages (`two_scale`, `many_scale`).
    pub table: &'a str,
    /// Elements along the contact face.
    pub mesh: usize,
    /// `(n, elements)`: the elements along the face, in place of `mesh`, of the profiles whose
    /// finest harmonic has order `n`.
    pub mesh_by_finest_order: &'a [(u32, usize)],
    /// At least this many face elements per wavelength of a profile's finest harmonic (0: none).
    pub elements_per_finest_wavelength: usize,
    /// Elements along the face of the error-estimate mesh (fewer than `mesh`).
    pub error_estimate_mesh: usize,
    /// Elements across the thickness per element along the face.
    pub depth_ratio: f64,
    /// Face spacing at the valley over that at the peak.
    pub peak_ratio: f64,
    /// Row height over column width at which the mesh's columns are coarsened threefold (0:
    /// never; [`crate::fe::Grading::coarsen_at_aspect`]).
    pub coarsen_at_aspect: f64,
    /// Load until the FE contact fraction reaches this, in (0, 1).
    pub until_contact_fraction: f64,
    /// Mean pressures at which each model is evaluated (≥ 2).
    pub model_points: usize,
    /// Order of the FE contact fraction's error in the element size (> 0).
    pub fe_error_order: f64,
    /// FE contact fractions below this are left out of the errors.
    pub error_from_contact_fraction: f64,
}

/// A footer's words for the grading's column coarsening: `, columns coarsened threefold where
/// the rows reach 4× their width`, or nothing.
pub(crate) fn coarsening_footer(coarsen_at_aspect: f64) -> String {
    match coarsen_at_aspect > 0.0 {
        true => format!(
            ", columns coarsened threefold where the rows reach {coarsen_at_aspect}× their width"
        ),
        false => String::new(),
    }
}

impl ComparisonSettings<'_> {
    /// Checks the ranges, naming `<table>.<field>` in the message.
    pub fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        let field = |name: &str| format!("{}.{name}", self.table);
        let refuse = |name: &str, value: String, allowed: String| {
            Err(v.invalid(&field(name), None, value, allowed))
        };
        let ratio = self.depth_ratio;
        if !(ratio.is_finite() && ratio > 0.0 && ratio <= 4.0) {
            return refuse("depth_ratio", ratio.to_string(), "(0, 4]".into());
        }
        let peak = self.peak_ratio;
        if !(peak.is_finite() && peak > 0.0) {
            return refuse("peak_ratio", peak.to_string(), "> 0".into());
        }
        let coarsen = crate::fe::input_ranges::COARSEN_AT_ASPECT;
        if !coarsen.holds(self.coarsen_at_aspect) {
            let value = self.coarsen_at_aspect.to_string();
            return refuse("coarsen_at_aspect", value, coarsen.allowed.into());
        }
        let c = self.until_contact_fraction;
        if !(c > 0.0 && c < 1.0) {
            return refuse("until_contact_fraction", c.to_string(), "(0, 1)".into());
        }
        let order = self.fe_error_order;
        if !(order.is_finite() && order > 0.0) {
            return refuse("fe_error_order", order.to_string(), "> 0".into());
        }
        if self.error_estimate_mesh >= self.mesh {
            let allowed = format!("fewer elements than mesh = {}", self.mesh);
            return refuse(
                "error_estimate_mesh",
                self.error_estimate_mesh.to_string(),
                allowed,
            );
        }
        if self.model_points < 2 {
            return refuse("model_points", self.model_points.to_string(), ">= 2".into());
        }
        Ok(())
    }

    /// The solve options of a curve on `nx` face elements (`depth_ratio` as many across the
    /// thickness, at least 2), graded along the face by `peak_ratio`, loaded to
    /// `until_contact_fraction`.
    pub fn options(&self, nx: usize) -> SolveOptions {
        SolveOptions {
            mesh: MeshLevel::Elements {
                nx,
                ny: ((nx as f64 * self.depth_ratio).round() as usize).max(2),
            },
            grading: Grading {
                peak_ratio: self.peak_ratio,
                coarsen_at_aspect: self.coarsen_at_aspect,
                ..Grading::default()
            },
            until_contact_fraction: Some(self.until_contact_fraction),
            ..SolveOptions::default()
        }
    }

    /// The face elements of a profile whose finest harmonic has order `finest_order`: its entry
    /// in `mesh_by_finest_order`, else `mesh`, or more where that harmonic needs
    /// `elements_per_finest_wavelength` (`finest_order` wavelengths per λ, the face spans λ/2).
    pub fn mesh_for(&self, finest_order: u32) -> usize {
        let stated = self
            .mesh_by_finest_order
            .iter()
            .find(|&&(n, _)| n == finest_order)
            .map_or(self.mesh, |&(_, elements)| elements);
        stated.max((self.elements_per_finest_wavelength * finest_order as usize).div_ceil(2))
    }

    /// The face elements of that profile's error-estimate mesh: `error_estimate_mesh` scaled as
    /// [`Self::mesh_for`] scales `mesh`, so that every profile's two meshes have one ratio.
    pub fn estimate_mesh_for(&self, finest_order: u32) -> usize {
        let grown = self.mesh_for(finest_order) as f64 / self.mesh as f64;
        (self.error_estimate_mesh as f64 * grown).round() as usize
    }

    /// The estimate of the FE curve `fine`'s RMS relative error (over its points with a contact
    /// fraction of at least `error_from_contact_fraction`, [`contact_fraction_error_estimate`])
    /// from the same case on its error-estimate mesh, `coarse`, over the load range both reach
    /// (a coarse curve may stop short); `None` when `fine` is incomplete or they share no point.
    pub fn fe_error_estimate(
        &self,
        fine: &FeOutcome,
        coarse: &FeOutcome,
        finest_order: u32,
    ) -> Option<f64> {
        if fine.failure.is_some() {
            return None;
        }
        let ratio =
            self.mesh_for(finest_order) as f64 / self.estimate_mesh_for(finest_order) as f64;
        contact_fraction_error_estimate(
            &fine.points,
            &coarse.points,
            ratio,
            self.fe_error_order,
            self.error_from_contact_fraction,
        )
    }

    /// `model_points` mean pressures evenly up to `p_max` (p̄/E*), `p_max` the last, exactly
    /// (`p_max · k / n` can round above `p_max`, beyond the FE curve the loads are read on).
    pub fn model_loads(&self, p_max: f64) -> Vec<f64> {
        let n = self.model_points;
        (1..=n).map(|k| p_max * (k as f64 / n as f64)).collect()
    }
}

/// The FE curve of the `t`-th τ_max (MPa) as a series: contact fraction against p̄/E*.
pub(crate) fn fe_series(t: usize, tau_max_mpa: f64, points: &[CurvePoint]) -> Series {
    Series::line(
        Some(format!("FE, τ_max = {tau_max_mpa} MPa")),
        FE_COLORS[t % FE_COLORS.len()],
        2,
        points
            .iter()
            .map(|p| (p.p_over_estar, p.contact_fraction))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The last model load is the FE curve's last mean pressure to the bit, so the last point
    /// is always compared: `p · 30 / 30` rounds above `p` for 37 of these 1000 values.
    #[test]
    fn the_last_model_load_is_the_curves_last_point() {
        let settings = ComparisonSettings {
            table: "many_scale",
            mesh: 48,
            mesh_by_finest_order: &[],
            elements_per_finest_wavelength: 0,
            error_estimate_mesh: 32,
            depth_ratio: 1.0,
            peak_ratio: 1.0,
            coarsen_at_aspect: 0.0,
            until_contact_fraction: 0.5,
            model_points: 30,
            fe_error_order: 1.0,
            error_from_contact_fraction: 0.0,
        };
        for k in 1..=1000 {
            let p_max = 0.01 + 1e-5 * k as f64;
            let loads = settings.model_loads(p_max);
            assert_eq!(loads.len(), 30);
            assert_eq!(loads.last(), Some(&p_max), "p_max {p_max:e}");
            assert!(loads.windows(2).all(|w| w[0] < w[1]));
        }
    }
}
