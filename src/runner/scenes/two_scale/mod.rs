//! Scene `two_scale` (beyond the paper, docs/replication.md R13): two-scale wavy surfaces by
//! direct finite elements, against the paper's proposal of superposing single-scale solutions
//! (`crate::models::superposition`) and against the big wave's WNL law alone.
//!
//! Per profile (the big wave and one finer harmonic) and τ_max: the FE curve of the contact
//! fraction against p̄/E* (node events, `crate::fe::stepping::node_events`), the superposition with
//! Westergaard's law and with the WNL law for both scales, and the WNL law of the big wave alone
//! (`2a₁/λ`); a table of each model's error against the FE; two contact maps (where the patches
//! lie as the load grows).

mod panels;

use panels::{contact_map, profile_panel};

use crate::fe::SolveOptions;
use crate::models::superposition::superposed_contact;
use crate::models::{a_over_lambda_at, CoefficientSet, InverseError, ModelKind, ModelLaw, Reading};
use crate::profile::Profile;
use crate::runner::scenes::profile_comparison::{coarsening_footer, ComparisonSettings};
use crate::runner::scenes::scene_output::{Layout, Remarks};
use crate::runner::scenes::{Scene, SceneContext, SceneResult};
use crate::runner::sweep::fe_cases::{FeCase, FePhysics, SolvedCases};
use crate::runner::RunOptions;
use crate::spec::{Bounded, NonNegative, SpecError, Validator};
use crate::table::Table;
use anyhow::Result;
use plotters::style::RGBColor;

/// The `[two_scale]` section.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TwoScaleScene {
    /// Two-scale profiles, each `[[1, AR₁], [n, AR₂]]`: (order, aspect ratio) pairs as
    /// `wavy solve --profile` takes them (docs/replication.md R13).
    pub profiles: Vec<Vec<(u32, f64)>>,
    /// τ_max values, MPa, at the default E* (1 MPa): τ_max/E*.
    pub tau_max_mpa: Vec<Bounded<NonNegative>>,
    /// Elements along the contact face.
    pub mesh: usize,
    /// `[[n, elements], …]`: the elements along the face, in place of `mesh`, of the profiles
    /// whose finer harmonic has order `n` (`elements_per_small_wavelength` still applies). Where
    /// the superposition errs most, at small `n`, a coarser mesh keeps the FE's error a small
    /// fraction of the error it judges (docs/results.md, two-scale surfaces).
    #[serde(default)]
    pub mesh_by_order: Vec<(u32, usize)>,
    /// Elements across the layer's thickness per element along the face (the meshes of
    /// `wavy solve --mesh N` take ½; the depth grows geometrically from one face spacing at the
    /// face, so fewer layers cost little accuracy: docs/results.md, two-scale surfaces).
    pub depth_ratio: f64,
    /// At least this many face elements per wavelength of the finer harmonic: a profile that needs
    /// more than `mesh` gives them (`error_estimate_mesh` grows with it). 0: `mesh` for every
    /// profile.
    #[serde(default)]
    pub elements_per_small_wavelength: usize,
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
    /// Mean pressures at which each model curve is evaluated.
    pub model_points: usize,
    /// FE contact fractions below this are left out of the relative errors (a relative error of
    /// a vanishing contact says little).
    pub error_from_contact_fraction: f64,
    /// Elements along the face of the coarser mesh on which each case is solved again for its FE
    /// error estimate (fewer than `mesh`).
    pub error_estimate_mesh: usize,
    /// Order of the FE contact fraction's error in the element size, with which each case's FE
    /// error is estimated from the same case on `error_estimate_mesh` (`crate::accuracy::contact_fraction`; the order
    /// observed by mesh convergence: docs/results.md, two-scale surfaces).
    pub fe_error_order: f64,
    /// The profiles (indices into `profiles`, frictionless) whose contact maps are drawn.
    pub contact_maps: Vec<usize>,
    /// Reading of the paper's Eq. 4 for WNL (default `bracket-sq`).
    #[serde(default)]
    pub reading: Reading,
    /// WNL coefficient set (default `paper-table1`).
    #[serde(default)]
    pub coefficients: CoefficientSet,
}

/// A model compared with the FE.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Model {
    /// The superposition (R13) with Westergaard's law for both scales (frictionless).
    SuperpositionWestergaard,
    /// The superposition with the WNL law for both scales.
    SuperpositionWnl,
    /// The big wave's WNL law alone: `2a₁/λ`.
    BigWaveWnl,
}

impl Model {
    const ALL: [Model; 3] = [
        Model::SuperpositionWestergaard,
        Model::SuperpositionWnl,
        Model::BigWaveWnl,
    ];

    /// The name in the tables.
    fn name(self) -> &'static str {
        match self {
            Model::SuperpositionWestergaard => "superposition-westergaard",
            Model::SuperpositionWnl => "superposition-wnl",
            Model::BigWaveWnl => "big-wave-wnl",
        }
    }

    fn color(self) -> RGBColor {
        match self {
            Model::SuperpositionWestergaard => RGBColor(31, 119, 180),
            Model::SuperpositionWnl => RGBColor(44, 160, 44),
            Model::BigWaveWnl => RGBColor(127, 127, 127),
        }
    }

    /// Whether its curve does not depend on τ_max (drawn once).
    fn frictionless(self) -> bool {
        self == Model::SuperpositionWestergaard
    }
}

impl TwoScaleScene {
    fn profile(&self, i: usize) -> Profile {
        Profile::from_pairs(&self.profiles[i]).expect("validated")
    }

    /// The face elements of profile `i`'s FE case ([`ComparisonSettings::mesh_for`]).
    fn mesh_of(&self, i: usize) -> usize {
        self.settings().mesh_for(self.profile(i).max_order())
    }

    /// The face elements of profile `i`'s error-estimate case.
    fn estimate_mesh_of(&self, i: usize) -> usize {
        self.settings()
            .estimate_mesh_for(self.profile(i).max_order())
    }

    /// The FE settings the comparison scenes share.
    fn settings(&self) -> ComparisonSettings<'_> {
        ComparisonSettings {
            table: "two_scale",
            mesh: self.mesh,
            mesh_by_finest_order: &self.mesh_by_order,
            elements_per_finest_wavelength: self.elements_per_small_wavelength,
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

    /// The solve options of profile `i`.
    fn options(&self, i: usize) -> SolveOptions {
        self.settings().options(self.mesh_of(i))
    }

    /// The FE cases ([`Self::cases`]) and, after them, each on `error_estimate_mesh`, for the FE
    /// error estimates.
    fn all_cases(&self) -> Vec<FeCase> {
        let cases = self.cases();
        let n = self.profiles.len();
        let coarse: Vec<FeCase> = cases
            .iter()
            .enumerate()
            .map(|(c, case)| self.coarse_case(c % n, case))
            .collect();
        cases.into_iter().chain(coarse).collect()
    }

    /// `case`, of profile `i`, on its error-estimate mesh ([`Self::estimate_mesh_of`]).
    fn coarse_case(&self, i: usize, case: &FeCase) -> FeCase {
        let mut coarse = case.clone();
        coarse.options.mesh = self.settings().options(self.estimate_mesh_of(i)).mesh;
        coarse
    }

    /// One FE case per (τ_max, profile), τ_max outer.
    fn cases(&self) -> Vec<FeCase> {
        let mut cases = vec![];
        for tau in self.tau_max_mpa.iter().map(|t| t.get()) {
            for i in 0..self.profiles.len() {
                let profile = self.profile(i);
                cases.push(FeCase::for_profile(
                    &FePhysics::default(),
                    &profile,
                    tau,
                    self.options(i),
                ));
            }
        }
        cases
    }

    /// Each entry of `mesh_by_order` names the order of some profile's finer harmonic, once,
    /// with at least one element. Checked before the profiles' meshes are (a profile that
    /// cannot be read has no order here; its own check names it).
    fn validate_mesh_by_order(&self, v: &Validator) -> Result<(), SpecError> {
        let orders: Vec<u32> = (self.profiles.iter())
            .filter_map(|p| Profile::from_pairs(p).ok())
            .map(|p| p.max_order())
            .collect();
        for (k, &(n, elements)) in self.mesh_by_order.iter().enumerate() {
            let allowed = if !orders.contains(&n) {
                Some(format!(
                    "orders of the profiles' finer harmonics ({orders:?})"
                ))
            } else if self.mesh_by_order[..k].iter().any(|&(m, _)| m == n) {
                Some("each order once".into())
            } else if elements == 0 {
                Some("at least one element".into())
            } else {
                None
            };
            if let Some(allowed) = allowed {
                let value = format!("[{n}, {elements}]");
                return Err(v.invalid("two_scale.mesh_by_order", None, value, allowed));
            }
        }
        Ok(())
    }

    fn wnl(&self, aspect_ratio: f64, tau_max_mpa: f64) -> ModelLaw {
        ModelLaw::new(
            ModelKind::Wnl,
            aspect_ratio,
            tau_max_mpa,
            self.reading,
            self.coefficients,
        )
    }

    /// The contact fraction of `model` for `profile` at τ_max and p̄/E*; `None` at or beyond
    /// the big wave's full contact, where the model has no answer (any other failure is an
    /// error).
    fn model_fraction(
        &self,
        model: Model,
        profile: &Profile,
        tau: f64,
        p: f64,
    ) -> Result<Option<f64>> {
        let fine = profile.finer.iter().next().expect("two-scale");
        let big_ar = profile.aspect_ratio;
        let westergaard = |ar| {
            ModelLaw::new(
                ModelKind::Westergaard,
                ar,
                0.0,
                self.reading,
                self.coefficients,
            )
        };
        let superposed = |big: &ModelLaw, small: &ModelLaw| match superposed_contact(
            big, small, fine.order, p,
        ) {
            Ok(c) => Ok(Some(c.contact_fraction)),
            Err(e) if e.is_beyond_big_full_contact() => Ok(None),
            Err(e) => Err(e.into()),
        };
        match model {
            Model::SuperpositionWestergaard => {
                superposed(&westergaard(big_ar), &westergaard(fine.aspect_ratio))
            }
            Model::SuperpositionWnl => {
                superposed(&self.wnl(big_ar, tau), &self.wnl(fine.aspect_ratio, tau))
            }
            Model::BigWaveWnl => match a_over_lambda_at(&self.wnl(big_ar, tau), p) {
                Ok(a) => Ok(Some(2.0 * a)),
                Err(InverseError::AboveFullContact { .. }) => Ok(None),
                Err(e) => Err(e.into()),
            },
        }
    }
}

impl Scene for TwoScaleScene {
    fn fe_cases(&self, _opts: &RunOptions) -> Vec<FeCase> {
        self.all_cases()
    }

    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        run(ctx.title, self, ctx.opts)
    }

    fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        v.non_empty("two_scale.profiles", self.profiles.len())?;
        v.non_empty("two_scale.tau_max_mpa", self.tau_max_mpa.len())?;
        self.settings().validate(v)?;
        self.validate_mesh_by_order(v)?;
        let field = "two_scale.profiles";
        for (i, p) in self.profiles.iter().enumerate() {
            let text = format!("{p:?}");
            let profile = Profile::from_pairs(p)
                .map_err(|e| v.invalid(field, None, text.clone(), e.to_string()))?;
            if p.len() != 2 {
                return Err(v.invalid(
                    field,
                    None,
                    text,
                    "two harmonics: [[1, AR₁], [n, AR₂]]".into(),
                ));
            }
            let problem = crate::fe::LayerProblem {
                finer_harmonics: profile.finer,
                ..crate::defaults::layer_problem(profile.aspect_ratio)
            };
            let coarse = self.settings().options(self.estimate_mesh_of(i));
            for opts in [self.options(i), coarse] {
                crate::fe::validate(&problem, &opts)
                    .map_err(|e| v.invalid(field, None, text.clone(), e.to_string()))?;
            }
        }
        if let Some(&i) = self
            .contact_maps
            .iter()
            .find(|&&i| i >= self.profiles.len())
        {
            return Err(v.invalid(
                "two_scale.contact_maps",
                None,
                i.to_string(),
                "indices into profiles".into(),
            ));
        }
        // a contact map draws the profile's curve at the first τ_max, which must be frictionless
        let first_tau = self.tau_max_mpa[0].get();
        if !self.contact_maps.is_empty() && first_tau != 0.0 {
            return Err(v.invalid(
                "two_scale.tau_max_mpa",
                None,
                format!("{first_tau} first"),
                "0 first when contact_maps are drawn (the maps show the frictionless curves)"
                    .into(),
            ));
        }
        Ok(())
    }
}

/// The figure's footer line on the FE: its meshes, the error-estimate meshes (each profile's,
/// grown with its face mesh) and the order assumed.
fn fe_footer(s: &TwoScaleScene) -> String {
    let estimate_meshes: std::collections::BTreeSet<usize> = (0..s.profiles.len())
        .map(|i| s.estimate_mesh_of(i))
        .collect();
    let estimate_meshes: Vec<String> = estimate_meshes.iter().map(usize::to_string).collect();
    format!(
        "FE: finite strain, neo-Hookean, h/λ = 1, mesh {} elements along the face{}{} (peak ratio {}), {} across the thickness per face element{}, node events; E* = 1 MPa; its error estimated against mesh {} at order {}. Models: docs/replication.md R13.",
        s.mesh,
        by_order_footer(&s.mesh_by_order),
        match s.elements_per_small_wavelength {
            0 => String::new(),
            e => format!(" or {e} per wavelength of the finer harmonic, whichever is more"),
        },
        s.peak_ratio,
        s.depth_ratio,
        coarsening_footer(s.coarsen_at_aspect),
        estimate_meshes.join(" or "),
        s.fe_error_order
    )
}

/// `mesh_by_order` for the footer: ` (n = 4: 96, n = 8: 128)`, or nothing.
fn by_order_footer(mesh_by_order: &[(u32, usize)]) -> String {
    if mesh_by_order.is_empty() {
        return String::new();
    }
    let entries: Vec<String> = mesh_by_order
        .iter()
        .map(|(n, elements)| format!("n = {n}: {elements}"))
        .collect();
    format!(" ({})", entries.join(", "))
}

fn run(title: &str, s: &TwoScaleScene, opts: &RunOptions) -> Result<SceneResult> {
    let cases = s.cases();
    let solved = SolvedCases::solve(s.all_cases(), opts)?;
    let mut curves = Table::new(
        "",
        &[
            "profile",
            "tau_max_mpa",
            "source",
            "p_over_estar",
            "contact_fraction",
            "patches",
        ],
    );
    let mut errors = Table::new(
        "errors",
        &[
            "profile",
            "tau_max_mpa",
            "model",
            "fe_points",
            "max_rel_error",
            "rms_rel_error",
            "max_abs_error",
            "fe_rms_error_estimate",
            "fe_error_over_model_error",
        ],
    );
    let mut remarks = Remarks::with_footer(vec![fe_footer(s)]);
    let mut panels = vec![];
    for i in 0..s.profiles.len() {
        let tables = (&mut curves, &mut errors);
        panels.push(profile_panel(s, i, &cases, &solved, tables, &mut remarks)?);
    }
    for &i in &s.contact_maps {
        let case = &cases[i];
        let fe = solved.outcome(case).expect("solved");
        panels.push(contact_map(&s.profile(i).to_string(), fe));
    }
    remarks.count_incomplete("their curves end where the solver stopped; see the run's notes");
    let n = panels.len();
    let cols = 3;
    let layout = Layout {
        grid: (n.div_ceil(cols), cols),
        panel_px: (520, 420),
        margin_px: 120,
        font_px: 14,
    };
    Ok(remarks.finish(title, layout, panels, vec![curves, errors]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed figures' footers name the meshes their specs solve: each profile's
    /// error-estimate mesh is two thirds of its own (n = 4 on 96, n = 8 on 128, n = 16 on 192
    /// and n = 32 on 320 elements along the face).
    #[test]
    fn the_committed_footers_are_their_specs() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        for (stem, meshes) in [
            ("two_scale", "(n = 8: 128)"),
            ("two_scale", "mesh 85 or 128 at"),
            ("two_scale_separation", "(n = 4: 96, n = 8: 128)"),
            ("two_scale_separation", "mesh 64 or 85 or 128 or 213 at"),
        ] {
            let spec = crate::runner::load_spec(&root.join(format!("experiments/{stem}.toml")))
                .expect("the committed spec");
            let scene = spec.two_scale.as_ref().expect("a two_scale spec");
            let footer = fe_footer(scene);
            assert!(footer.contains(meshes), "{stem}: {footer}");
            let svg = std::fs::read_to_string(root.join(format!("figures/{stem}.svg")))
                .expect("the committed figure");
            assert!(svg.contains(&footer), "figures/{stem}.svg lacks: {footer}");
        }
    }
}
