//! The inverse of a finite-element curve: the contact width a/λ at which it carries a mean
//! pressure, never extrapolated beyond its last point.

use crate::fe::CurvePoint;
use crate::numfmt::sig_digits;

/// Where a mean pressure falls on an FE curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum FeInverse {
    /// At or below the curve's last point: a/λ there.
    Within(f64),
    /// Above the curve's last point (a/λ = `last_a_over_lambda`): the FE says only that the
    /// contact is at least that wide.
    Beyond { last_a_over_lambda: f64 },
}

/// a/λ at which an FE curve carries p̄/E* = `p_over_estar` (≥ 0): linear in √p̄ between the
/// origin (no load, no contact) and the curve's points, whose p̄ must not decrease. Points that
/// repeat an edge position (within 10⁻⁶, as in `fe::convergence::p_at`) are skipped. Above the last point the
/// answer is [`FeInverse::Beyond`], never an extrapolation.
pub(crate) fn fe_a_over_lambda_at(
    points: &[CurvePoint],
    p_over_estar: f64,
) -> Result<FeInverse, String> {
    let mut nodes = vec![(0.0, 0.0)];
    for p in points {
        let &(a, s) = nodes.last().expect("starts with the origin");
        if p.a_over_lambda <= a + 1e-6 {
            continue;
        }
        let root = p.p_over_estar.max(0.0).sqrt();
        if root < s {
            return Err(format!(
                "the FE curve's p̄/E* decreases to {} at a/λ = {}: no unique contact width",
                sig_digits(p.p_over_estar, 6),
                sig_digits(p.a_over_lambda, 4)
            ));
        }
        nodes.push((p.a_over_lambda, root));
    }
    let target = p_over_estar.max(0.0).sqrt();
    let &(last_a, last_s) = nodes.last().expect("starts with the origin");
    if target > last_s {
        return Ok(FeInverse::Beyond {
            last_a_over_lambda: last_a,
        });
    }
    let k = nodes
        .iter()
        .position(|&(_, s)| s >= target)
        .expect("target ≤ the last node's");
    if k == 0 {
        return Ok(FeInverse::Within(0.0));
    }
    let ((a0, s0), (a1, s1)) = (nodes[k - 1], nodes[k]);
    let t = if s1 > s0 {
        (target - s0) / (s1 - s0)
    } else {
        1.0
    };
    Ok(FeInverse::Within(a0 + t * (a1 - a0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(a: f64, p: f64) -> CurvePoint {
        CurvePoint {
            a_over_lambda: a,
            p_over_estar: p,
            p_over_estar_reaction: p,
            slab_displacement_over_lambda: 0.0,
            newton_iterations: 1,
            active_nodes: 1,
            contact_fraction: 2.0 * a,
            patches: 1,
            stick_fraction: 0.0,
            stick_half_width_over_lambda: 0.0,
            friction_work_over_estar_lambda2: 0.0,
        }
    }

    #[test]
    fn fe_inverse_interpolates_and_never_extrapolates() {
        let pts = [
            point(0.1, 0.01),
            point(0.2, 0.04),
            point(0.2, 0.04),
            point(0.3, 0.09),
        ];
        // p = x² exactly: linear in √p reproduces it
        for (p, a) in [
            (0.0, 0.0),
            (0.0025, 0.05),
            (0.01, 0.1),
            (0.0625, 0.25),
            (0.09, 0.3),
        ] {
            match fe_a_over_lambda_at(&pts, p) {
                Ok(FeInverse::Within(x)) => assert!((x - a).abs() < 1e-12, "{p}: {x} ≠ {a}"),
                other => panic!("{p}: {other:?}"),
            }
        }
        assert_eq!(
            fe_a_over_lambda_at(&pts, 0.1),
            Ok(FeInverse::Beyond {
                last_a_over_lambda: 0.3
            })
        );
        let turning = [point(0.1, 0.02), point(0.2, 0.01)];
        assert!(fe_a_over_lambda_at(&turning, 0.005).is_err());
    }
}
