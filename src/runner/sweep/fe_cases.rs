//! Finite-element curves as sweep cases: what identifies one, and how it is cached.

use crate::fe::{self, CurvePoint, Kinematics, LayerProblem, MeshLevel, SolveOptions};
use crate::runner::sweep::{self, Cacheable, SweepCase};
use crate::runner::RunOptions;
use crate::spec::FeSection;
use anyhow::Result;
use std::ops::ControlFlow;

/// The FE cases of a section: one per (τ_max, AR), τ_max outer, at the run's mesh override
/// if it has one. Scenes that list the same section and aspect ratios share their cache files.
pub fn section_cases(fe: &FeSection, aspect_ratios: &[f64], opts: &RunOptions) -> Vec<FeCase> {
    let mut cases = vec![];
    for tau in fe.tau_max_mpa.iter().map(|t| t.get()) {
        for &ar in aspect_ratios {
            cases.push(FeCase::new(
                &FePhysics::from(fe),
                ar,
                tau,
                fe.options(aspect_ratios, opts.fe_mesh_override),
            ));
        }
    }
    cases
}

/// The cases of the error estimates of `cases`: each on the next coarser mesh
/// (`crate::accuracy::coarser_level`), with the ratio of the element counts; `None` for a mesh
/// with no coarser level.
pub fn coarser_cases(cases: &[FeCase]) -> Vec<Option<(FeCase, f64)>> {
    cases
        .iter()
        .map(|c| {
            let (mesh, ratio) = crate::accuracy::coarser_level(c.options.mesh)?;
            let mut coarse = c.clone();
            coarse.options.mesh = mesh;
            Some((coarse, ratio))
        })
        .collect()
}

/// `cases`, followed, when `error_estimate` is set, by each of them on the next coarser mesh
/// (those that have one, [`coarser_cases`]).
pub fn with_coarser_cases(mut cases: Vec<FeCase>, error_estimate: bool) -> Vec<FeCase> {
    if error_estimate {
        let coarse = coarser_cases(&cases);
        cases.extend(coarse.into_iter().flatten().map(|(c, _)| c));
    }
    cases
}

/// Every case's curve, from the cache or computed (in parallel, whatever the run's shard).
pub fn solve_all(cases: &[FeCase], opts: &RunOptions) -> Result<Vec<FeOutcome>> {
    let unsharded = sweep::SweepOptions {
        shard: None,
        ..opts.sweep.clone()
    };
    let swept = sweep::run(cases, &unsharded, FeCase::solve)?;
    Ok(swept
        .results
        .into_iter()
        .map(|r| r.expect("an unsharded sweep computes every case"))
        .collect())
}

/// FE cases and their curves, in the cases' order.
#[derive(Debug, Clone)]
pub struct SolvedCases {
    pub cases: Vec<FeCase>,
    pub outcomes: Vec<FeOutcome>,
}

impl SolvedCases {
    /// Every case's curve, from the cache or computed ([`solve_all`]).
    pub fn solve(cases: Vec<FeCase>, opts: &RunOptions) -> Result<Self> {
        let outcomes = solve_all(&cases, opts)?;
        Ok(SolvedCases { cases, outcomes })
    }

    /// The curve of `case`, one of the cases (equal in every field).
    pub fn outcome(&self, case: &FeCase) -> Option<&FeOutcome> {
        self.cases
            .iter()
            .zip(&self.outcomes)
            .find(|(c, _)| *c == case)
            .map(|(_, o)| o)
    }
}

/// This shard's share of `cases`, computed into the cache: (computed, already cached).
pub fn compute_share(cases: &[FeCase], opts: &RunOptions) -> Result<(usize, usize)> {
    let r = sweep::run(cases, &opts.sweep, FeCase::solve)?;
    Ok((r.computed, r.from_cache))
}

/// How a figure names the rigid surface of a case: `AR = 0.3` for a sinusoid, `profile
/// 1:0.1,8:0.05` for a profile.
pub fn surface_label(profile: &crate::profile::Profile) -> String {
    if profile.is_sinusoid() {
        format!("AR = {}", profile.aspect_ratio)
    } else {
        format!("profile {profile}")
    }
}

/// Fingerprint of the solver's source (build.rs): a changed solver never reads old results.
pub const FE_SOURCE_SHA256: &str = env!("WAVY_FE_SOURCE_SHA256");

/// The files [`FE_SOURCE_SHA256`] hashes, comma-separated, relative to the crate root: `src/fe/`
/// and every module it reaches through `crate::` paths (build.rs).
pub const FE_SOURCE_FILES: &str = env!("WAVY_FE_SOURCE_FILES");

/// The physical parameters of an FE curve other than its aspect ratio and shear strength:
/// what a spec's FE section and `wavy solve`'s flags both state (docs/replication.md R7).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FePhysics {
    /// Plane-strain modulus E*, MPa: turns τ_max in MPa into the solver's τ_max/E*.
    pub estar_mpa: f64,
    /// Layer thickness over wavelength h/λ.
    pub thickness_over_lambda: f64,
    /// Bulk over shear modulus κ/G.
    pub kappa_over_g: f64,
    /// Friction coefficient μ.
    pub friction_coefficient: f64,
    /// Elastic slip at the friction threshold over the mean face element length.
    pub elastic_slip_over_element: f64,
    pub kinematics: Kinematics,
}

impl FePhysics {
    /// The numeric parameters by the names of the measured tables' columns
    /// (`accuracy::measured::PHYSICS_COLUMNS`, in that order).
    pub fn by_column(&self) -> [(&'static str, f64); 5] {
        let [e, h, k, mu, slip] = crate::accuracy::measured::PHYSICS_COLUMNS;
        [
            (e, self.estar_mpa),
            (h, self.thickness_over_lambda),
            (k, self.kappa_over_g),
            (mu, self.friction_coefficient),
            (slip, self.elastic_slip_over_element),
        ]
    }
}

impl Default for FePhysics {
    /// Every parameter at its default (`crate::defaults`), finite kinematics.
    fn default() -> Self {
        use crate::defaults;
        FePhysics {
            estar_mpa: defaults::fe_estar_mpa(),
            thickness_over_lambda: defaults::thickness_over_lambda(),
            kappa_over_g: defaults::kappa_over_g(),
            friction_coefficient: defaults::friction_coefficient(),
            elastic_slip_over_element: defaults::elastic_slip_over_element(),
            kinematics: Kinematics::Finite,
        }
    }
}

impl From<&FeSection> for FePhysics {
    fn from(fe: &FeSection) -> Self {
        FePhysics {
            estar_mpa: fe.estar_mpa.get(),
            thickness_over_lambda: fe.thickness_over_lambda.get(),
            kappa_over_g: fe.kappa_over_g.get(),
            friction_coefficient: fe.friction_coefficient.get(),
            elastic_slip_over_element: fe.elastic_slip_over_element.get(),
            kinematics: fe.kinematics,
        }
    }
}

impl FeSection {
    /// The solver options of this section's curves at `aspect_ratios` (its mesh, or the mesh its
    /// tolerance needs there), at `mesh_override` when a run sets one.
    ///
    /// # Panics
    /// When the tolerance cannot be met: `Validator::fe_section` refuses such a spec.
    pub fn options(&self, aspect_ratios: &[f64], mesh_override: Option<MeshLevel>) -> SolveOptions {
        let mesh = mesh_override.unwrap_or_else(|| {
            self.mesh_for(aspect_ratios)
                .expect("a validated FE section's tolerance has a mesh")
        });
        SolveOptions {
            until_a_over_lambda: self.until_a_over_lambda.get(),
            mesh,
            ..SolveOptions::default()
        }
    }
}

/// One FE curve: the physical problem, the numerical options, and the modulus that turns
/// τ_max in MPa into τ_max/E*.
#[derive(Debug, Clone, PartialEq)]
pub struct FeCase {
    pub problem: LayerProblem,
    pub options: SolveOptions,
    pub estar_mpa: f64,
    pub tau_max_mpa: f64,
    pub friction_coefficient: f64,
    /// Also unload from the target back to zero load (`fe::solve_cycle`).
    pub unload: bool,
}

impl FeCase {
    /// The case of the rigid `profile` at shear strength τ_max (MPa) ([`FeCase::new`] with the
    /// profile's finer harmonics).
    pub fn for_profile(
        physics: &FePhysics,
        profile: &crate::profile::Profile,
        tau_max_mpa: f64,
        options: SolveOptions,
    ) -> Self {
        let mut case = Self::new(physics, profile.aspect_ratio, tau_max_mpa, options);
        case.problem.finer_harmonics = profile.finer;
        case
    }

    /// The case at aspect ratio Δ/λ and shear strength τ_max (MPa): the one place where a
    /// layer problem is built from physical parameters.
    pub fn new(
        physics: &FePhysics,
        aspect_ratio: f64,
        tau_max_mpa: f64,
        options: SolveOptions,
    ) -> Self {
        let problem = LayerProblem {
            aspect_ratio,
            finer_harmonics: crate::profile::FinerHarmonics::NONE,
            thickness_over_lambda: physics.thickness_over_lambda,
            kappa_over_g: physics.kappa_over_g,
            kinematics: physics.kinematics,
            interface: fe::Interface::coulomb_orowan(
                physics.friction_coefficient,
                tau_max_mpa / physics.estar_mpa,
                physics.elastic_slip_over_element,
            ),
        };
        FeCase {
            problem,
            options,
            estar_mpa: physics.estar_mpa,
            tau_max_mpa,
            friction_coefficient: physics.friction_coefficient,
            unload: false,
        }
    }

    /// This case as a loading–unloading cycle: loaded to its target, then unloaded to zero
    /// load.
    pub fn with_unloading(self) -> Self {
        FeCase {
            unload: true,
            ..self
        }
    }

    /// Runs the solver.
    pub fn solve(&self) -> FeOutcome {
        let result = match self.unload {
            true => fe::solve_cycle(&self.problem, &self.options, &mut |_, _| {
                ControlFlow::Continue(())
            }),
            false => fe::solve_curve(&self.problem, &self.options, &mut |_| {
                ControlFlow::Continue(())
            }),
        };
        match result {
            Ok(curve) => FeOutcome {
                points: curve.points,
                unloading: curve.unloading,
                patch_edges: curve.patch_edges,
                failure: None,
            },
            Err(f) => FeOutcome {
                points: f.points.clone(),
                unloading: f.unloading.clone(),
                patch_edges: Vec::new(),
                failure: Some(f.error.to_string()),
            },
        }
    }
}

impl SweepCase for FeCase {
    fn key_text(&self) -> String {
        // Debug prints every field, floats in shortest round-trip form: exact.
        let kind = if self.unload { "cycle" } else { "curve" };
        format!(
            "wavy fe {kind}\nsolver source sha256 {FE_SOURCE_SHA256}\nproblem {:?}\noptions {:?}\nestar_mpa {:?} tau_max_mpa {:?} friction_coefficient {:?}",
            self.problem, self.options, self.estar_mpa, self.tau_max_mpa, self.friction_coefficient
        )
    }

    fn label(&self) -> String {
        let cycle = if self.unload {
            ", loading–unloading"
        } else {
            ""
        };
        let shape = if self.problem.finer_harmonics.is_empty() {
            format!("AR = {}", self.problem.aspect_ratio)
        } else {
            format!("profile {}", self.problem.profile())
        };
        format!("{shape}, τ_max = {} MPa{cycle}", self.tau_max_mpa)
    }

    /// The time of a curve grows with the element count, the aspect ratio and friction (the
    /// times per curve: docs/performance.md); only the order of the cases matters.
    fn cost_hint(&self) -> f64 {
        let (nx, ny) = self.options.mesh.counts();
        let friction = match self.problem.interface {
            fe::Interface::Frictionless => 1.0,
            fe::Interface::CoulombOrowan(_) => 3.0,
        };
        (nx * ny) as f64 * self.problem.aspect_ratio * friction
    }
}

/// A computed curve, complete or not.
#[derive(Debug, Clone, PartialEq)]
pub struct FeOutcome {
    /// The loading branch.
    pub points: Vec<CurvePoint>,
    /// The unloading branch of a cycle ([`FeCase::with_unloading`]); empty otherwise.
    pub unloading: Vec<CurvePoint>,
    /// The contact patches of each point of a complete loading branch (`fe::Curve::patch_edges`);
    /// empty for an incomplete curve.
    pub patch_edges: Vec<Vec<[f64; 2]>>,
    /// The solver's error when it stopped before the target a/λ.
    pub failure: Option<String>,
}

impl FeOutcome {
    /// The a/λ of the curve's last point (0 for an empty curve).
    pub fn last_a_over_lambda(&self) -> f64 {
        self.points.last().map_or(0.0, |p| p.a_over_lambda)
    }

    /// `complete`, or `incomplete at a/λ = …: <reason>` for a curve that stopped short.
    pub fn status(&self) -> String {
        match &self.failure {
            None => "complete".into(),
            Some(f) => format!(
                "incomplete at a/λ = {}: {f}",
                crate::numfmt::sig_digits(self.last_a_over_lambda(), 4)
            ),
        }
    }
}

/// The line of the cache text between the loading and the unloading rows.
const UNLOADING_LINE: &str = "unloading";

/// The line of the cache text before the patch rows (one per loading point: the edges of its
/// patches, space-separated, `start end start end …`).
const PATCHES_LINE: &str = "patches";

impl Cacheable for FeOutcome {
    fn to_cache_text(&self) -> String {
        let mut s = String::from("status ");
        s.push_str(
            self.failure
                .as_deref()
                .map_or("ok".into(), |f| format!("failed: {}", f.replace('\n', " ")))
                .as_str(),
        );
        s.push('\n');
        s.push_str(CurvePoint::CSV_HEADER);
        s.push('\n');
        for p in &self.points {
            s.push_str(&p.csv_row());
            s.push('\n');
        }
        if !self.unloading.is_empty() {
            s.push_str(UNLOADING_LINE);
            s.push('\n');
            for p in &self.unloading {
                s.push_str(&p.csv_row());
                s.push('\n');
            }
        }
        if !self.patch_edges.is_empty() {
            s.push_str(PATCHES_LINE);
            s.push('\n');
            for patches in &self.patch_edges {
                let edges: Vec<String> = patches
                    .iter()
                    .flat_map(|p| [p[0].to_string(), p[1].to_string()])
                    .collect();
                s.push_str(&edges.join(" "));
                s.push('\n');
            }
        }
        s
    }

    fn from_cache_text(text: &str) -> Option<Self> {
        let mut lines = text.lines();
        let status = lines.next()?.strip_prefix("status ")?;
        let failure = match status {
            "ok" => None,
            f => Some(f.strip_prefix("failed: ")?.to_string()),
        };
        if lines.next()? != CurvePoint::CSV_HEADER {
            return None;
        }
        let all: Vec<&str> = lines.collect();
        let (rows, patch_rows) = match all.iter().position(|&l| l == PATCHES_LINE) {
            Some(i) => (&all[..i], &all[i + 1..]),
            None => (&all[..], &[][..]),
        };
        let patch_edges = patch_rows
            .iter()
            .map(|l| {
                let x: Vec<f64> = l
                    .split_whitespace()
                    .map(|v| v.parse().ok())
                    .collect::<Option<_>>()?;
                x.len()
                    .is_multiple_of(2)
                    .then(|| x.chunks(2).map(|c| [c[0], c[1]]).collect())
            })
            .collect::<Option<Vec<Vec<[f64; 2]>>>>()?;
        let (loading, unloading) = match rows.iter().position(|&l| l == UNLOADING_LINE) {
            Some(i) => (&rows[..i], &rows[i + 1..]),
            None => (rows, &[][..]),
        };
        let parse = |rows: &[&str]| {
            rows.iter()
                .map(|l| l.parse().ok())
                .collect::<Option<Vec<CurvePoint>>>()
        };
        Some(FeOutcome {
            points: parse(loading)?,
            unloading: parse(unloading)?,
            patch_edges,
            failure,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cache_text_round_trips_exactly() {
        let p = crate::fe::curve::awkward_point();
        for failure in [None, Some("Newton diverged at load step 3".to_string())] {
            for unloading in [vec![], vec![p]] {
                let o = FeOutcome {
                    points: vec![p, p],
                    unloading,
                    patch_edges: vec![vec![[0.0, 0.1 + 0.2]], vec![[0.0, 0.3], [1.0 / 3.0, 0.5]]],
                    failure: failure.clone(),
                };
                assert_eq!(FeOutcome::from_cache_text(&o.to_cache_text()), Some(o));
            }
        }
        assert_eq!(
            FeOutcome::from_cache_text("status ok\nwrong header\n"),
            None
        );
    }
}
