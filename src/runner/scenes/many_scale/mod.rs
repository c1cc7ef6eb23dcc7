//! Scene `many_scale` (beyond the paper, docs/replication.md R14): Weierstrass profiles of
//! K = 1, 2, … scales by direct finite elements (finite strain, frictionless and with friction),
//! against the recursive superposition of single-scale laws (Westergaard's, as Ciavarella et al.
//! 2000 use it, and the paper's WNL) and against the boundary-element solution of the same layer
//! in the linear limit.
//!
//! Per profile: the contact fraction against p̄/E* of each source; per profile, τ_max and model:
//! the model's relative error against the FE at the model's mean pressures (the FE curve, one
//! point per node event, read between its points), with the FE's own error estimated from the
//! same case on a coarser mesh. The last panel draws the models' RMS errors against K.

mod scale_panels;

use crate::bem::{self, ElasticBody};
use crate::fe::MeshLevel;
use crate::models::{profile_contact, CoefficientSet, ModelKind, ModelLaw, Reading};
use crate::profile::{Profile, Weierstrass};
use crate::runner::requests::bem_solve::{self, default_grid_points};
use crate::runner::scenes::profile_comparison::{coarsening_footer, ComparisonSettings};
use crate::runner::scenes::scene_output::{Layout, Remarks};
use crate::runner::scenes::{Scene, SceneContext, SceneResult};
use crate::runner::sweep::fe_cases::{FeCase, FePhysics, SolvedCases};
use crate::runner::RunOptions;
use crate::spec::{Bounded, NonNegative, SpecError, Validator};
use anyhow::Result;
use plotters::style::RGBColor;

/// A Weierstrass family (R14): its profiles of K = 1 … `scales` scales are solved.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Family {
    /// The big wave's aspect ratio AR₀.
    pub ar0: f64,
    /// The order ratio γ of successive scales (an integer ≥ 2).
    pub gamma: u32,
    /// The fractal dimension D ∈ (1, 2): AR_k = AR₀ γ^{(D−1)k}.
    pub dimension: f64,
    /// The most scales K solved.
    pub scales: u32,
}

/// The `[many_scale]` section.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManyScaleScene {
    /// The Weierstrass families; a profile two families share (K = 1 of equal AR₀) is solved
    /// once.
    pub families: Vec<Family>,
    /// τ_max values, MPa, at the default E* (1 MPa): τ_max/E*; the first must be 0 (the
    /// frictionless models are compared with its curves first).
    pub tau_max_mpa: Vec<Bounded<NonNegative>>,
    /// Elements along the contact face, at least.
    pub mesh: usize,
    /// At least this many face elements per wavelength of the finest scale (the face spans
    /// λ/2): a profile that needs more than `mesh` gets them, its `error_estimate_mesh` grown
    /// alike.
    pub elements_per_finest_wavelength: usize,
    /// Elements across the layer's thickness per element along the face (graded from one face
    /// spacing, as in the two-scale scenes).
    pub depth_ratio: f64,
    /// Face spacing at the valley over that at the peak (1: uniform, the small waves lie
    /// everywhere).
    pub peak_ratio: f64,
    /// Where the rows, growing with depth, reach this many times their column width, the
    /// columns are coarsened threefold (a conforming transition row; 0, the default: every
    /// column to the bonded face). Below the small waves' reach this costs the contact fraction
    /// a small part of the FE error (docs/results.md, two-scale surfaces).
    #[serde(default)]
    pub coarsen_at_aspect: f64,
    /// Load until the FE contact fraction reaches this, in (0, 1).
    pub until_contact_fraction: f64,
    /// Mean pressures, evenly up to the FE curve's last, at which every model is evaluated and
    /// compared with the FE.
    pub model_points: usize,
    /// FE contact fractions below this are left out of the relative errors.
    pub error_from_contact_fraction: f64,
    /// Elements along the face of the coarser mesh on which each case is solved again for its
    /// FE error estimate (fewer than `mesh`).
    pub error_estimate_mesh: usize,
    /// Order of the FE contact fraction's error in the element size, for its estimate
    /// (`crate::accuracy::contact_fraction`).
    pub fe_error_order: f64,
    /// Reading of the paper's Eq. 4 for WNL (default `bracket-sq`).
    #[serde(default)]
    pub reading: Reading,
    /// WNL coefficient set (default `paper-table1`).
    #[serde(default)]
    pub coefficients: CoefficientSet,
}

/// A source compared with the FE.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Model {
    /// The recursion (R14) with Westergaard's law at every scale (frictionless).
    RecursionWestergaard,
    /// The recursion with the WNL law at every scale, at the curve's τ_max.
    RecursionWnl,
    /// The boundary-element solution of the same layer, linear kinematics, frictionless.
    BemLinear,
}

impl Model {
    const ALL: [Model; 3] = [
        Model::RecursionWestergaard,
        Model::RecursionWnl,
        Model::BemLinear,
    ];

    /// The name in the tables.
    fn name(self) -> &'static str {
        match self {
            Model::RecursionWestergaard => "recursion-westergaard",
            Model::RecursionWnl => "recursion-wnl",
            Model::BemLinear => "bem-linear",
        }
    }

    fn color(self) -> RGBColor {
        match self {
            Model::RecursionWestergaard => RGBColor(31, 119, 180),
            Model::RecursionWnl => RGBColor(44, 160, 44),
            Model::BemLinear => RGBColor(127, 127, 127),
        }
    }

    /// Whether its curve does not depend on τ_max (computed and drawn once).
    fn frictionless(self) -> bool {
        self != Model::RecursionWnl
    }
}

/// One profile of the scene: its family's parameters at K scales.
#[derive(Debug, Clone)]
struct ScaleCase {
    weierstrass: Weierstrass,
    profile: Profile,
}

impl ScaleCase {
    /// The profile's command-line text.
    fn name(&self) -> String {
        let w = &self.weierstrass;
        format!(
            "weierstrass:{},{},{},{}",
            w.aspect_ratio_0, w.gamma, w.dimension, w.scales
        )
    }
}

impl ManyScaleScene {
    /// Every family's profiles, K = 1 … scales, family by family; a profile equal to one before
    /// (K = 1 of the same AR₀) left out.
    fn scale_cases(&self) -> Result<Vec<ScaleCase>, crate::profile::ProfileError> {
        let mut cases: Vec<ScaleCase> = vec![];
        for f in &self.families {
            for k in 1..=f.scales {
                let weierstrass = Weierstrass::new(f.ar0, f.gamma, f.dimension, k)?;
                let profile = weierstrass.profile();
                if cases.iter().all(|c| c.profile != profile) {
                    cases.push(ScaleCase {
                        weierstrass,
                        profile,
                    });
                }
            }
        }
        Ok(cases)
    }

    fn cases_validated(&self) -> Vec<ScaleCase> {
        self.scale_cases().expect("validated")
    }

    /// The face elements of `case`'s FE mesh ([`ComparisonSettings::mesh_for`]).
    fn mesh_of(&self, case: &ScaleCase) -> usize {
        self.settings().mesh_for(case.profile.max_order())
    }

    /// The FE mesh the scene solves `profile` on (its face elements grown for the finest
    /// harmonic, `depth_ratio` as many across the thickness).
    pub fn fe_mesh(&self, profile: &Profile) -> MeshLevel {
        let nx = self.settings().mesh_for(profile.max_order());
        self.settings().options(nx).mesh
    }

    /// The face elements of `case`'s error-estimate mesh.
    fn estimate_mesh_of(&self, case: &ScaleCase) -> usize {
        self.settings().estimate_mesh_for(case.profile.max_order())
    }

    /// The FE settings the comparison scenes share.
    fn settings(&self) -> ComparisonSettings<'static> {
        ComparisonSettings {
            table: "many_scale",
            mesh: self.mesh,
            mesh_by_finest_order: &[],
            elements_per_finest_wavelength: self.elements_per_finest_wavelength,
            error_estimate_mesh: self.error_estimate_mesh,
            depth_ratio: self.depth_ratio,
            peak_ratio: self.peak_ratio,
            coarsen_at_aspect: self.coarsen_at_aspect,
            until_contact_fraction: self.until_contact_fraction,
            model_points: self.model_points,
            fe_error_order: self.fe_error_order,
            error_from_contact_fraction: self.error_from_contact_fraction,
        }
    }

    /// The FE case of `case` at τ_max on its mesh (`coarse`: its error-estimate mesh).
    fn fe_case(&self, case: &ScaleCase, tau: f64, coarse: bool) -> FeCase {
        let nx = match coarse {
            true => self.estimate_mesh_of(case),
            false => self.mesh_of(case),
        };
        FeCase::for_profile(
            &FePhysics::default(),
            &case.profile,
            tau,
            self.settings().options(nx),
        )
    }

    /// Every FE case: each profile at each τ_max, on its mesh and its error-estimate mesh.
    fn all_fe_cases(&self) -> Vec<FeCase> {
        let mut all = vec![];
        for case in &self.cases_validated() {
            for tau in self.tau_max_mpa.iter().map(|t| t.get()) {
                all.push(self.fe_case(case, tau, false));
                all.push(self.fe_case(case, tau, true));
            }
        }
        all
    }

    fn law(&self, kind: ModelKind, aspect_ratio: f64, tau: f64) -> ModelLaw {
        ModelLaw::new(kind, aspect_ratio, tau, self.reading, self.coefficients)
    }

    /// The contact fraction of the recursion with `kind`'s law at every scale for `profile` at
    /// τ_max and p̄/E*; `None` at or beyond the big wave's full contact, where the recursion has
    /// no answer (any other failure is an error).
    fn recursion_fraction(
        &self,
        kind: ModelKind,
        profile: &Profile,
        tau: f64,
        p: f64,
    ) -> Result<Option<f64>> {
        match profile_contact(profile, |ar| self.law(kind, ar, tau), p) {
            Ok(c) => Ok(Some(c.contact_fraction)),
            Err(e) if e.is_beyond_big_full_contact() => Ok(None),
            Err(e) => Err(e.into()),
        }
    }

    /// The boundary-element contact fraction of `profile` on the FE's layer (h/λ and ν of the
    /// default physics), linear kinematics, frictionless, at each of `loads` (p̄/E*).
    fn bem_fractions(profile: &Profile, loads: &[f64]) -> Result<Vec<f64>> {
        use rayon::prelude::*;
        let physics = FePhysics::default();
        let body = ElasticBody::Layer {
            thickness: physics.thickness_over_lambda,
            poisson: crate::fe::poisson_ratio(physics.kappa_over_g),
        };
        let grid = default_grid_points(profile);
        loads
            .par_iter()
            .map(|&p| {
                let contact = bem::solve_on(profile, body, p, grid, bem_solve::TOLERANCE)?;
                Ok(contact.contact_fraction)
            })
            .collect()
    }
}

impl Scene for ManyScaleScene {
    fn fe_cases(&self, _opts: &RunOptions) -> Vec<FeCase> {
        self.all_fe_cases()
    }

    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        run(ctx.title, self, ctx.opts)
    }

    fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        v.non_empty("many_scale.families", self.families.len())?;
        v.non_empty("many_scale.tau_max_mpa", self.tau_max_mpa.len())?;
        let first_tau = self.tau_max_mpa[0].get();
        if first_tau != 0.0 {
            return Err(v.invalid(
                "many_scale.tau_max_mpa",
                None,
                format!("{first_tau} first"),
                "0 first (the frictionless models are drawn with the first curves)".into(),
            ));
        }
        self.settings().validate(v)?;
        self.validate_profiles(v)
    }
}

impl ManyScaleScene {
    /// Each family's parameters, and each profile's FE problem on both its meshes
    /// (`crate::fe::validate`: mesh resolution, slope under finite strain).
    fn validate_profiles(&self, v: &Validator) -> Result<(), SpecError> {
        let field = "many_scale.families";
        for f in &self.families {
            if f.scales == 0 {
                return Err(v.invalid(field, None, format!("{f:?}"), "scales >= 1".into()));
            }
        }
        let cases = self
            .scale_cases()
            .map_err(|e| v.invalid(field, None, format!("{:?}", self.families), e.to_string()))?;
        for case in &cases {
            let problem = crate::fe::LayerProblem {
                finer_harmonics: case.profile.finer,
                ..crate::defaults::layer_problem(case.profile.aspect_ratio)
            };
            for coarse in [false, true] {
                let opts = self.fe_case(case, 0.0, coarse).options;
                crate::fe::validate(&problem, &opts)
                    .map_err(|e| v.invalid(field, None, case.name(), e.to_string()))?;
            }
        }
        Ok(())
    }
}

/// The figure's footer line on the FE and the BEM.
fn footer(s: &ManyScaleScene) -> Vec<String> {
    let fe = format!(
        "FE: finite strain, neo-Hookean, h/λ = 1, at least {} elements along the face or {} per wavelength of the finest scale (peak ratio {}), {} across the thickness per face element{}, node events; E* = 1 MPa;",
        s.mesh,
        s.elements_per_finest_wavelength,
        s.peak_ratio,
        s.depth_ratio,
        coarsening_footer(s.coarsen_at_aspect)
    );
    let estimate = format!(
        "its error estimated against {}/{} times the elements at order {}. BEM: the same layer, linear kinematics, frictionless. Models: docs/replication.md R14.",
        s.error_estimate_mesh, s.mesh, s.fe_error_order
    );
    vec![fe, estimate]
}

/// The footer line counting, and the note naming, the profiles where the WNL law of some scale
/// is evaluated outside the domain its coefficients were fitted on (at some τ_max); none when
/// every law lies inside.
fn extrapolation_note(s: &ManyScaleScene, cases: &[ScaleCase]) -> Option<(String, String)> {
    let outside: Vec<String> = cases
        .iter()
        .filter(|c| {
            c.profile.harmonics().any(|h| {
                s.tau_max_mpa.iter().any(|t| {
                    s.law(ModelKind::Wnl, h.aspect_ratio, t.get())
                        .is_extrapolated()
                })
            })
        })
        .map(ScaleCase::name)
        .collect();
    (!outside.is_empty()).then(|| {
        let count = format!(
            "WNL is extrapolated beyond its fit domain at some scale of {} of the {} profiles",
            outside.len(),
            cases.len()
        );
        let names = format!("{count}: {}.", outside.join(", "));
        (format!("{count} (the run's notes name them)."), names)
    })
}

fn run(title: &str, s: &ManyScaleScene, opts: &RunOptions) -> Result<SceneResult> {
    let solved = SolvedCases::solve(s.all_fe_cases(), opts)?;
    let mut tables = scale_panels::Tables::new();
    let mut remarks = Remarks::with_footer(footer(s));
    if let Some((footer, note)) = extrapolation_note(s, &s.cases_validated()) {
        remarks.footer.push(footer);
        remarks.notes.push(note);
    }
    let mut panels = vec![];
    for case in &s.cases_validated() {
        panels.push(scale_panels::profile_panel(
            s,
            case,
            &solved,
            &mut tables,
            &mut remarks,
        )?);
    }
    panels.push(scale_panels::error_panel(s, &tables.records));
    remarks.count_incomplete("their curves end where the solver stopped; see the run's notes");
    let cols = 3;
    let layout = Layout {
        grid: (panels.len().div_ceil(cols), cols),
        panel_px: (520, 420),
        margin_px: 120,
        font_px: 14,
    };
    Ok(remarks.finish(title, layout, panels, tables.into_vec()))
}
