//! The error of a profile's contact-fraction curve, estimated from the same curve on a coarser
//! mesh.
//!
//! At a given mean pressure the FE contact fraction errs by where each patch edge falls between
//! nodes, born and merged patches above all, and that differs from one mesh to the next: the
//! errors of two meshes are uncorrelated point by point, of root-mean-square sizes `e` and
//! `e · ratio^order` (the element sizes' ratio to the convergence order), not one smooth function
//! of the element size as Richardson's extrapolation assumes. Their difference then adds in
//! quadrature, `RMS(c − c_coarse) ≈ e √(1 + ratio^{2·order})`, which gives `e`. (Richardson's
//! `RMS / (ratio^order − 1)` read the same difference as three times the error measured against
//! a four times finer mesh; docs/results.md, two-scale surfaces.)

use crate::fe::CurvePoint;

/// The contact fraction of the curve `points` at the mean pressure `p_over_estar`, linear between
/// the two points around it; `None` outside the curve (below its first point or beyond its last).
/// The points are in loading order, `p̄` non-decreasing.
pub fn contact_fraction_at(points: &[CurvePoint], p_over_estar: f64) -> Option<f64> {
    let k = points
        .windows(2)
        .position(|w| w[0].p_over_estar <= p_over_estar && p_over_estar <= w[1].p_over_estar)?;
    let (a, b) = (&points[k], &points[k + 1]);
    let span = b.p_over_estar - a.p_over_estar;
    let t = if span > 0.0 {
        (p_over_estar - a.p_over_estar) / span
    } else {
        1.0
    };
    Some(a.contact_fraction + t * (b.contact_fraction - a.contact_fraction))
}

/// The root-mean-square relative error of the contact fraction of `fine` over its points whose
/// contact fraction is at least `from` and that the curve `coarse` reaches (a mesh `ratio` times
/// coarser; errors of the convergence `order`): the root mean square of their relative
/// differences from `coarse` over `√(1 + ratio^{2·order})` (module documentation); `None` when
/// no point qualifies.
pub fn contact_fraction_error_estimate(
    fine: &[CurvePoint],
    coarse: &[CurvePoint],
    ratio: f64,
    order: f64,
    from: f64,
) -> Option<f64> {
    let differences: Vec<f64> = fine
        .iter()
        .filter(|p| p.contact_fraction >= from)
        .filter_map(|p| {
            let c = contact_fraction_at(coarse, p.p_over_estar)?;
            Some(p.contact_fraction / c - 1.0)
        })
        .collect();
    if differences.is_empty() {
        return None;
    }
    let rms = (differences.iter().map(|d| d * d).sum::<f64>() / differences.len() as f64).sqrt();
    Some(rms / (1.0 + ratio.powf(2.0 * order)).sqrt())
}

/// A model's contact fraction against an FE curve: relative errors `model / FE − 1` at the FE
/// points with a contact fraction of at least `from` where the model has an answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelErrors {
    /// FE points compared.
    pub points: usize,
    /// Largest |relative error|.
    pub max_rel: f64,
    /// Root mean square of the relative errors.
    pub rms_rel: f64,
    /// Largest |model − FE| of the contact fraction.
    pub max_abs: f64,
}

impl ModelErrors {
    /// Compares `model(p̄/E*)` (`None` where the model has no answer, e.g. beyond its full
    /// contact) with the curve `fe` at its points of contact fraction `≥ from`; `None` when no
    /// point qualifies. The model's errors pass through.
    pub fn against<E>(
        fe: &[CurvePoint],
        from: f64,
        mut model: impl FnMut(f64) -> Result<Option<f64>, E>,
    ) -> Result<Option<ModelErrors>, E> {
        let mut pairs = vec![];
        for p in fe.iter().filter(|p| p.contact_fraction >= from) {
            if let Some(c) = model(p.p_over_estar)? {
                pairs.push((c, p.contact_fraction));
            }
        }
        Ok(Self::of_pairs(pairs))
    }

    /// The errors of `(model, FE)` contact fraction pairs; `None` for none.
    pub fn of_pairs(pairs: impl IntoIterator<Item = (f64, f64)>) -> Option<ModelErrors> {
        let (mut points, mut max_rel, mut sum_sq, mut max_abs) = (0usize, 0.0_f64, 0.0, 0.0_f64);
        for (model, fe) in pairs {
            let rel = model / fe - 1.0;
            points += 1;
            max_rel = max_rel.max(rel.abs());
            sum_sq += rel * rel;
            max_abs = max_abs.max((model - fe).abs());
        }
        (points > 0).then(|| ModelErrors {
            points,
            max_rel,
            rms_rel: (sum_sq / points as f64).sqrt(),
            max_abs,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(p: f64, c: f64) -> CurvePoint {
        CurvePoint {
            a_over_lambda: 0.5 * c,
            p_over_estar: p,
            p_over_estar_reaction: p,
            slab_displacement_over_lambda: p,
            newton_iterations: 1,
            active_nodes: 1,
            contact_fraction: c,
            patches: 1,
            stick_fraction: 0.0,
            stick_half_width_over_lambda: 0.0,
            friction_work_over_estar_lambda2: 0.0,
        }
    }

    #[test]
    fn interpolates_inside_and_refuses_outside() {
        let curve = [point(0.1, 0.2), point(0.3, 0.6)];
        assert!((contact_fraction_at(&curve, 0.2).unwrap() - 0.4).abs() < 1e-15);
        assert_eq!(contact_fraction_at(&curve, 0.05), None);
        assert_eq!(contact_fraction_at(&curve, 0.31), None);
    }

    /// Relative differences of ±5 % at ratio 2 and first order: an error of 5 %/√5.
    #[test]
    fn differences_add_in_quadrature() {
        let fine = [point(0.1, 0.5), point(0.3, 0.5)];
        let coarse = [
            point(0.0, 0.5 / 1.05),
            point(0.15, 0.5 / 1.05),
            point(0.25, 0.5 / 0.95),
            point(0.4, 0.5 / 0.95),
        ];
        let e = contact_fraction_error_estimate(&fine, &coarse, 2.0, 1.0, 0.05).unwrap();
        assert!((e - 0.05 / 5f64.sqrt()).abs() < 1e-12, "{e}");
        assert_eq!(
            contact_fraction_error_estimate(&fine, &coarse, 2.0, 1.0, 0.6),
            None
        );
    }

    /// A model 10 % high at one point and 10 % low at the other, silent at the third.
    #[test]
    fn model_errors_over_the_points_it_answers() {
        let fe = [
            point(0.01, 0.02),
            point(0.1, 0.2),
            point(0.3, 0.5),
            point(0.4, 0.6),
        ];
        let model = |p: f64| -> Result<Option<f64>, ()> {
            Ok(match p {
                p if p < 0.2 => Some(0.22),
                p if p < 0.35 => Some(0.45),
                _ => None,
            })
        };
        let e = ModelErrors::against(&fe, 0.05, model).unwrap().unwrap();
        assert_eq!(e.points, 2);
        assert!(
            (e.max_rel - 0.1).abs() < 1e-12 && (e.rms_rel - 0.1).abs() < 1e-12,
            "{e:?}"
        );
        assert!((e.max_abs - 0.05).abs() < 1e-12, "{e:?}");
        assert_eq!(ModelErrors::against(&fe, 0.7, model).unwrap(), None);
    }
}
