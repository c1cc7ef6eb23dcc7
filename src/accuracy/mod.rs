//! Accuracy tiers: every way wavy answers p̄/E*(a/λ), from Westergaard's closed form to the
//! finite-strain FE on a fine mesh, and how their errors are measured.
//!
//! The errors are relative to a converged reference: the limit of the finite-strain curves on
//! fine meshes, `p(n) = p₀ + c₁/n + c₂/n²` fitted through them ([`extrapolation`];
//! docs/replication.md R11). The `speed_accuracy` scene measures every tier this way;
//! [`measured`] holds the committed measurements and picks the cheapest tier that meets a
//! tolerance.

pub mod contact_fraction;
pub mod extrapolation;
pub mod measured;

use crate::fe::convergence::p_at;
use crate::fe::{CurvePoint, Kinematics, MeshLevel};
use crate::models::{CoefficientSet, ModelKind, ModelLaw, Reading};
use std::fmt;
use std::str::FromStr;

/// One way of computing p̄/E*(a/λ).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tier {
    /// Westergaard's linear, frictionless solution.
    Westergaard,
    /// The WNL law with a coefficient set, in the reading that set belongs to
    /// ([`Tier::reading`]).
    Wnl(CoefficientSet),
    /// Our finite-element solver with `elements_along_face` elements along the contact face
    /// (half as many across the thickness).
    Fe {
        kinematics: Kinematics,
        elements_along_face: usize,
    },
    /// Richardson extrapolation of our finite-strain FE from two meshes, `coarse` < `fine`
    /// elements along the face, at the order [`RICHARDSON_TIER_ORDER`]:
    /// `p_fine + (p_fine − p_coarse) / (fine/coarse − 1)` at each a/λ
    /// ([`richardson_tier_values`]).
    FeRichardson { coarse: usize, fine: usize },
    /// The mesh limit `p₀ + c₁/n + c₂/n²` of our finite-strain FE through three meshes
    /// `n₁ < n₂ < n₃` elements along the face, at each a/λ ([`extrapolated_tier_values`]):
    /// the reference's own form ([`extrapolation::mesh_limit`]) from three cheap meshes, which
    /// removes both the first-order error (the edge rule's, and friction's) and the
    /// second-order one (docs/replication.md R11).
    FeLimit { meshes: [usize; 3] },
}

/// The order of the error that a [`Tier::FeRichardson`] removes: first, the order of the edge
/// rule's residual error, which leads on the meshes the tiers use (docs/replication.md R11: on
/// meshes 48 and 96 first order leaves less error than second in four of the six measured cases).
pub const RICHARDSON_TIER_ORDER: f64 = 1.0;

impl Tier {
    /// The name used in tables, specs and messages: `westergaard`, `wnl-paper-table1`,
    /// `wnl-ours-bracket-sq`, `fe-finite-48`, `fe-linear-48`, ….
    pub fn name(&self) -> String {
        match self {
            Tier::Westergaard => "westergaard".into(),
            Tier::Wnl(set) => format!("wnl-{}", set.name()),
            Tier::Fe {
                kinematics,
                elements_along_face,
            } => format!("fe-{}-{elements_along_face}", kinematics.name()),
            Tier::FeRichardson { coarse, fine } => format!("fe-richardson-{coarse}-{fine}"),
            Tier::FeLimit {
                meshes: [n1, n2, n3],
            } => format!("fe-limit-{n1}-{n2}-{n3}"),
        }
    }

    /// The FE curves a tier computes: its mesh, or an extrapolating tier's meshes (finite
    /// strain, coarsest first); none for a closed form.
    pub fn fe_curves(&self) -> Vec<(Kinematics, usize)> {
        match *self {
            Tier::Fe {
                kinematics,
                elements_along_face,
            } => vec![(kinematics, elements_along_face)],
            Tier::FeRichardson { coarse, fine } => {
                vec![(Kinematics::Finite, coarse), (Kinematics::Finite, fine)]
            }
            Tier::FeLimit { meshes } => meshes.map(|n| (Kinematics::Finite, n)).to_vec(),
            _ => vec![],
        }
    }

    /// The tiers whose wall times make up this tier's: itself, or an extrapolating tier's
    /// meshes (a timings file times those, not the extrapolation).
    pub fn timed_tiers(&self) -> Vec<Tier> {
        match *self {
            Tier::FeRichardson { .. } | Tier::FeLimit { .. } => self
                .fe_curves()
                .into_iter()
                .map(|(kinematics, elements_along_face)| Tier::Fe {
                    kinematics,
                    elements_along_face,
                })
                .collect(),
            _ => vec![*self],
        }
    }

    /// True for the tiers that extrapolate several FE curves ([`extrapolated_tier_values`]).
    pub fn is_extrapolated(&self) -> bool {
        matches!(self, Tier::FeRichardson { .. } | Tier::FeLimit { .. })
    }

    /// True for the closed-form laws (cost per point, no mesh).
    pub fn is_closed_form(&self) -> bool {
        self.fe_curves().is_empty()
    }

    /// True for our finite-strain FE (the paper's physics; the tiers a tolerance picks a mesh
    /// from).
    pub fn is_finite_fe(&self) -> bool {
        matches!(
            self,
            Tier::Fe {
                kinematics: Kinematics::Finite,
                ..
            }
        )
    }

    /// The mesh of an FE tier.
    pub fn mesh(&self) -> Option<MeshLevel> {
        match *self {
            Tier::Fe {
                elements_along_face: nx,
                ..
            } => Some(MeshLevel::along_face(nx)),
            _ => None,
        }
    }

    /// The reading of Eq. 4 a WNL tier uses: a refit set's own reading, the default reading
    /// for the paper's Table 1.
    pub fn reading(&self) -> Reading {
        match self {
            Tier::Wnl(CoefficientSet::OursBracket2x) => Reading::Bracket2x,
            Tier::Wnl(CoefficientSet::OursLiteral) => Reading::Literal,
            _ => Reading::default(),
        }
    }

    /// The closed-form law of this tier at (AR, τ_max in MPa); `None` for an FE tier.
    pub fn law(&self, aspect_ratio: f64, tau_max_mpa: f64) -> Option<ModelLaw> {
        let (kind, set) = match *self {
            Tier::Westergaard => (ModelKind::Westergaard, CoefficientSet::default()),
            Tier::Wnl(set) => (ModelKind::Wnl, set),
            Tier::Fe { .. } | Tier::FeRichardson { .. } | Tier::FeLimit { .. } => return None,
        };
        Some(ModelLaw::new(
            kind,
            aspect_ratio,
            tau_max_mpa,
            self.reading(),
            set,
        ))
    }
}

impl fmt::Display for Tier {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

/// A name that is not a tier.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("value \"{0}\" is not a tier; allowed: westergaard, wnl-<coefficient set> ({sets}), fe-finite-N or fe-linear-N (N elements along the face, {lo} to {hi}), fe-richardson-C-F (meshes C < F in the same range), fe-limit-A-B-C (meshes A < B < C in the same range)", sets = CoefficientSet::names(), lo = MeshLevel::ELEMENTS_ALONG_FACE.start(), hi = MeshLevel::ELEMENTS_ALONG_FACE.end())]
pub struct TierParseError(pub String);

impl FromStr for Tier {
    type Err = TierParseError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || TierParseError(s.into());
        if s == "westergaard" {
            return Ok(Tier::Westergaard);
        }
        if let Some(set) = s.strip_prefix("wnl-") {
            return set.parse().map(Tier::Wnl).map_err(|_| bad());
        }
        let elements = |n: &str| {
            n.parse::<usize>()
                .ok()
                .filter(|n| MeshLevel::ELEMENTS_ALONG_FACE.contains(n))
                .ok_or_else(bad)
        };
        if let Some(meshes) = s.strip_prefix("fe-richardson-") {
            let (coarse, fine) = meshes.split_once('-').ok_or_else(bad)?;
            let (coarse, fine) = (elements(coarse)?, elements(fine)?);
            if coarse >= fine {
                return Err(bad());
            }
            return Ok(Tier::FeRichardson { coarse, fine });
        }
        if let Some(meshes) = s.strip_prefix("fe-limit-") {
            let n: Vec<usize> = meshes.split('-').map(elements).collect::<Result<_, _>>()?;
            return match n[..] {
                [n1, n2, n3] if n1 < n2 && n2 < n3 => Ok(Tier::FeLimit {
                    meshes: [n1, n2, n3],
                }),
                _ => Err(bad()),
            };
        }
        let rest = s.strip_prefix("fe-").ok_or_else(bad)?;
        let (kinematics, n) = rest.rsplit_once('-').ok_or_else(bad)?;
        let kinematics: Kinematics = kinematics.parse().map_err(|_| bad())?;
        let elements_along_face = elements(n)?;
        Ok(Tier::Fe {
            kinematics,
            elements_along_face,
        })
    }
}

/// The largest and the root-mean-square relative error of a curve against a reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorSummary {
    /// max |f − R| / R.
    pub max: f64,
    /// √(mean of ((f − R) / R)²).
    pub rms: f64,
}

/// The relative errors of `values` against `reference` (same abscissae, reference > 0).
///
/// # Panics
/// When the two slices differ in length or are empty.
pub fn relative_errors(values: &[f64], reference: &[f64]) -> ErrorSummary {
    assert!(
        !values.is_empty() && values.len() == reference.len(),
        "one value per reference point"
    );
    let (mut max, mut sq) = (0.0f64, 0.0);
    for (v, r) in values.iter().zip(reference) {
        let e = ((v - r) / r).abs();
        max = max.max(e);
        sq += e * e;
    }
    ErrorSummary {
        max,
        rms: (sq / values.len() as f64).sqrt(),
    }
}

/// Richardson extrapolation from a coarse and a fine value, meshes refined by `ratio`, error
/// of order `order`: `fine + (fine − coarse) / (ratio^order − 1)`.
pub fn richardson(coarse: f64, fine: f64, ratio: f64, order: f64) -> f64 {
    fine + (fine - coarse) / (ratio.powf(order) - 1.0)
}

/// The p̄/E* of a [`Tier::FeRichardson`] at each a/λ of `xs`, from its curves on meshes of
/// `coarse` and `fine` elements along the face ([`p_at`]); `None` if either curve does not
/// cover `xs`.
pub fn richardson_tier_values(
    coarse: (&[CurvePoint], usize),
    fine: (&[CurvePoint], usize),
    xs: &[f64],
) -> Option<Vec<f64>> {
    let ratio = fine.1 as f64 / coarse.1 as f64;
    xs.iter()
        .map(|&x| {
            let (c, f) = (p_at(coarse.0, x)?, p_at(fine.0, x)?);
            Some(richardson(c, f, ratio, RICHARDSON_TIER_ORDER))
        })
        .collect()
}

/// The p̄/E* of an extrapolating tier ([`Tier::is_extrapolated`]) at each a/λ of `xs`, from
/// its curves, one per mesh of [`Tier::fe_curves`] in that order: the Richardson step
/// ([`richardson_tier_values`]) or the mesh limit through three meshes
/// ([`extrapolation::mesh_limit`]). `None` if a curve does not cover `xs`, or for another tier.
pub fn extrapolated_tier_values(
    tier: &Tier,
    curves: &[&[CurvePoint]],
    xs: &[f64],
) -> Option<Vec<f64>> {
    match (*tier, curves) {
        (Tier::FeRichardson { coarse, fine }, &[c, f]) => {
            richardson_tier_values((c, coarse), (f, fine), xs)
        }
        (Tier::FeLimit { meshes }, &[_, _, _]) => xs
            .iter()
            .map(|&x| {
                let values: Vec<f64> = curves.iter().map(|c| p_at(c, x)).collect::<Option<_>>()?;
                extrapolation::mesh_limit(&meshes, &values)
            })
            .collect(),
        _ => None,
    }
}

/// The Richardson estimate of the relative error of `fine`: `|fine − coarse| / (ratio^order − 1)
/// / fine`.
pub fn richardson_relative_error(coarse: f64, fine: f64, ratio: f64, order: f64) -> f64 {
    ((fine - coarse) / (ratio.powf(order) - 1.0) / fine).abs()
}

/// The mesh one refinement step coarser than `mesh` (the named levels step by
/// [`MeshLevel::REFINEMENT_RATIO`]; `N` elements along the face step to `round(N / 1.5)`), and
/// the ratio of their element counts along the face; `None` below 4 elements.
pub fn coarser_level(mesh: MeshLevel) -> Option<(MeshLevel, f64)> {
    let coarser = match mesh {
        MeshLevel::Fine => MeshLevel::Default,
        MeshLevel::Default => MeshLevel::Coarse,
        level => {
            let nx = (level.counts().0 as f64 / MeshLevel::REFINEMENT_RATIO).round() as usize;
            if nx < *MeshLevel::ELEMENTS_ALONG_FACE.start() {
                return None;
            }
            MeshLevel::along_face(nx)
        }
    };
    Some((coarser, mesh.counts().0 as f64 / coarser.counts().0 as f64))
}

/// The Richardson estimate of the relative error of each point of `fine`, from the curve on a
/// mesh `ratio` times coarser and the convergence `order`: `|p − p_c(a)| / (ratio^order − 1) / p`
/// with `p_c` interpolated at the point's a/λ ([`p_at`]); `None` where the coarse curve does
/// not reach (below its first contact point).
pub fn error_estimates(
    fine: &[CurvePoint],
    coarse: &[CurvePoint],
    ratio: f64,
    order: f64,
) -> Vec<Option<f64>> {
    fine.iter()
        .map(|p| {
            let c = p_at(coarse, p.a_over_lambda)?;
            Some(richardson_relative_error(c, p.p_over_estar, ratio, order))
        })
        .collect()
}

pub use crate::fe::convergence::FORMAL_ORDER_RANGE;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tier_names_round_trip() {
        let tiers = [
            Tier::Westergaard,
            Tier::Wnl(CoefficientSet::PaperTable1),
            Tier::Wnl(CoefficientSet::OursBracketSq),
            Tier::Fe {
                kinematics: Kinematics::Finite,
                elements_along_face: 144,
            },
            Tier::Fe {
                kinematics: Kinematics::Linear,
                elements_along_face: 48,
            },
            Tier::FeRichardson {
                coarse: 48,
                fine: 96,
            },
            Tier::FeLimit {
                meshes: [48, 64, 96],
            },
        ];
        for t in tiers {
            assert_eq!(t.name().parse::<Tier>(), Ok(t));
        }
        for bad in [
            "",
            "wnl",
            "wnl-x",
            "fe-finite",
            "fe-finite-3",
            "fe-plastic-48",
            "fe-finite-x",
            "fe-richardson-96-48",
            "fe-richardson-48-48",
            "fe-richardson-48",
            "fe-richardson-3-48",
            "fe-richardson-48-96-128",
            "fe-limit-48-96",
            "fe-limit-48-96-64",
            "fe-limit-48-48-96",
            "fe-limit-3-48-96",
            "fe-limit-48-64-96-128",
        ] {
            assert!(bad.parse::<Tier>().is_err(), "{bad}");
        }
    }

    #[test]
    fn richardson_removes_a_pure_power_error() {
        // f(h) = 2 + 3 h^1.5 on h = 1/64 and 1/96 extrapolates to 2 exactly.
        let f = |n: f64| 2.0 + 3.0 * (1.0 / n).powf(1.5);
        let r = richardson(f(64.0), f(96.0), 1.5, 1.5);
        assert!((r - 2.0).abs() < 1e-14, "{r}");
        let e = richardson_relative_error(f(64.0), f(96.0), 1.5, 1.5);
        assert!((e - (f(96.0) - 2.0) / f(96.0)).abs() < 1e-14);
    }

    #[test]
    fn coarser_levels_step_by_one_and_a_half() {
        assert_eq!(
            coarser_level(MeshLevel::Fine),
            Some((MeshLevel::Default, 1.5))
        );
        assert_eq!(
            coarser_level(MeshLevel::Default),
            Some((MeshLevel::Coarse, 1.5))
        );
        let (m, r) = coarser_level(MeshLevel::Elements { nx: 144, ny: 72 }).unwrap();
        assert_eq!((m, r), (MeshLevel::Elements { nx: 96, ny: 48 }, 1.5));
        assert_eq!(coarser_level(MeshLevel::Elements { nx: 5, ny: 2 }), None);
    }

    /// The curve p̄/E* = `scale`·a² at a/λ = 0.02, 0.04, …, 0.4.
    fn curve(scale: f64) -> Vec<CurvePoint> {
        (1..=20)
            .map(|i| {
                let a = 0.02 * i as f64;
                CurvePoint {
                    a_over_lambda: a,
                    p_over_estar: scale * a * a,
                    p_over_estar_reaction: scale * a * a,
                    slab_displacement_over_lambda: 0.0,
                    newton_iterations: 1,
                    active_nodes: i,
                    contact_fraction: 2.0 * a,
                    patches: 1,
                    stick_fraction: 0.0,
                    stick_half_width_over_lambda: 0.0,
                    friction_work_over_estar_lambda2: 0.0,
                }
            })
            .collect()
    }

    /// Curves p_n = a²(1 + 3/n) on meshes 48 and 96: the first-order Richardson tier removes
    /// the error exactly; a coarse curve that starts late leaves the tier without values.
    #[test]
    fn the_richardson_tier_removes_a_first_order_error() {
        let (coarse, fine) = (curve(1.0 + 3.0 / 48.0), curve(1.0 + 3.0 / 96.0));
        let xs = [0.1, 0.2, 0.4];
        let v = richardson_tier_values((&coarse, 48), (&fine, 96), &xs).unwrap();
        for (x, p) in xs.iter().zip(&v) {
            assert!((p / (x * x) - 1.0).abs() < 1e-12, "{x} {p}");
        }
        assert!(richardson_tier_values((&coarse[6..], 48), (&fine, 96), &xs).is_none());
    }

    /// Curves p_n = a²(1 + 3/n − 40/n²) on meshes 48, 64 and 96: the mesh-limit tier removes
    /// both terms exactly (to round-off), the first-order Richardson tier of two of them only
    /// the first; a curve that starts late leaves the tier without values.
    #[test]
    fn the_mesh_limit_tier_removes_first_and_second_order_errors() {
        let on = |n: f64| curve(1.0 + 3.0 / n - 40.0 / (n * n));
        let (c48, c64, c96) = (on(48.0), on(64.0), on(96.0));
        let tier: Tier = "fe-limit-48-64-96".parse().unwrap();
        let xs = [0.1, 0.2, 0.3];
        let v = extrapolated_tier_values(&tier, &[&c48, &c64, &c96], &xs).unwrap();
        for (x, p) in xs.iter().zip(&v) {
            assert!((p / (x * x) - 1.0).abs() < 1e-12, "{x} {p}");
        }
        let richardson: Tier = "fe-richardson-48-96".parse().unwrap();
        let r = extrapolated_tier_values(&richardson, &[&c48, &c96], &xs).unwrap();
        // what first order leaves of −40/n²: 40/(48·96)
        assert!(
            (r[1] / 0.04 - 1.0 - 40.0 / (48.0 * 96.0)).abs() < 1e-12,
            "{r:?}"
        );
        assert!(extrapolated_tier_values(&tier, &[&c48[6..], &c64, &c96], &xs).is_none());
        assert!(extrapolated_tier_values(&tier, &[&c48, &c96], &xs).is_none());
    }

    #[test]
    fn error_estimates_recover_a_known_error() {
        // p(a) = a² exactly on the coarse mesh, 1 % high on the fine: with ratio 2 and order 1
        // the fine error estimate is |Δ| / (2 − 1) / p = 1/101 of the fine value everywhere
        let (fine, coarse) = (curve(1.01), curve(1.0));
        let e = error_estimates(&fine[5..], &coarse[2..], 2.0, 1.0);
        assert!(
            e.iter().all(|e| (e.unwrap() - 0.01 / 1.01).abs() < 1e-9),
            "{e:?}"
        );
        // below the coarse curve's first point there is no estimate
        assert_eq!(
            error_estimates(&fine[..1], &coarse[2..], 2.0, 1.0),
            vec![None]
        );
    }

    #[test]
    fn relative_errors_are_max_and_rms() {
        let e = relative_errors(&[1.1, 2.0, 2.7], &[1.0, 2.0, 3.0]);
        assert!((e.max - 0.1).abs() < 1e-12);
        assert!((e.rms - (0.02f64 / 3.0).sqrt()).abs() < 1e-12);
    }
}
