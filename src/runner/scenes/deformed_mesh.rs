//! The deformed finite-element mesh at the end of loading, with the indenter and the contact
//! pressure along the contact face: the picture that shows what the solver does at large
//! aspect ratio (material sliding along the indenter, the valley closing).

use crate::fe;
use crate::fe::{CurvePoint, DeformedState};
use crate::plot::{palette, LegendPosition, Panel, Series};
use crate::profile::Profile;
use crate::runner::scenes::scene_output::{Layout, Remarks};
use crate::runner::scenes::{Scene, SceneContext, SceneResult};
use crate::runner::sweep::fe_cases::{surface_label, FeCase, FePhysics};
use crate::runner::RunOptions;
use crate::spec::{Bounded, FeSection, Positive, SpecError, Validator};
use crate::table::Table;
use anyhow::{anyhow, Result};
use serde::Deserialize;
use std::ops::ControlFlow;

/// The deformed finite-element mesh and its contact pressure at the end of loading.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DeformedMeshScene {
    /// Aspect ratio Δ/λ of a sinusoid; or, instead, `profile`.
    pub aspect_ratio: Option<Bounded<Positive>>,
    /// A profile of cosine harmonics `[[1, AR₁], [n, AR₂], …]` (docs/replication.md R13) or the
    /// command line's text for one (`"weierstrass:AR0,gamma,D,K"`, R14), instead of
    /// `aspect_ratio`.
    pub profile: Option<crate::spec::ProfileField>,
    /// The FE model; `tau_max_mpa` must hold exactly one value.
    pub fe: FeSection,
}

impl Scene for DeformedMeshScene {
    fn run(&self, ctx: &SceneContext) -> Result<SceneResult> {
        run(ctx.title, self, ctx.opts)
    }

    fn validate(&self, v: &Validator) -> Result<(), SpecError> {
        let surface = v.fe_surface(
            "deformed_mesh",
            &self.fe,
            self.aspect_ratio.map(|a| a.get()),
            self.profile.as_ref(),
        )?;
        v.fe_section("deformed_mesh.fe", &self.fe, None, &[surface.aspect_ratio])?;
        if self.fe.tau_max_mpa.len() != 1 {
            return Err(v.invalid(
                "deformed_mesh.fe.tau_max_mpa",
                None,
                format!("{} values", self.fe.tau_max_mpa.len()),
                "exactly one value".into(),
            ));
        }
        Ok(())
    }
}

impl DeformedMeshScene {
    /// The rigid surface: the sinusoid of `aspect_ratio` or the `profile` (validated: exactly
    /// one of them).
    fn surface(&self) -> Profile {
        crate::spec::validated_surface(self.aspect_ratio.map(|a| a.get()), self.profile.as_ref())
    }
}

fn run(title: &str, s: &DeformedMeshScene, opts: &RunOptions) -> Result<SceneResult> {
    let surface = s.surface();
    let tau = s.fe.tau_max_mpa[0].get();
    let case = FeCase::for_profile(
        &FePhysics::from(&s.fe),
        &surface,
        tau,
        s.fe.options(&[surface.aspect_ratio], opts.fe_mesh_override),
    );
    // one case, not cached: its progress as the sweeps show theirs
    let bar = crate::runner::sweep::progress_bar(1);
    let solved = fe::solve_curve(&case.problem, &case.options, &mut |p| {
        if let Some(b) = &bar {
            b.set_message(format!("deformed mesh: a/λ = {:.4}", p.a_over_lambda));
        }
        ControlFlow::Continue(())
    });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let curve =
        solved.map_err(|f| anyhow!("the FE solve for the deformed mesh stopped: {}", f.error))?;
    let last = *curve
        .points
        .last()
        .ok_or_else(|| anyhow!("the FE solve converged no load step"))?;
    let state = &curve.final_state;
    let mut table = Table::new(
        "",
        &["node", "x_over_lambda", "y_over_lambda", "p_over_estar"],
    );
    for (k, &id) in state.bottom.iter().enumerate() {
        let [x, y] = state.nodes[id];
        table.push(vec![
            (id as f64).into(),
            x.into(),
            y.into(),
            state.contact_pressure_over_estar[k].into(),
        ]);
    }
    let panels = vec![
        mesh_panel(state, &surface, &last),
        pressure_panel(state, &last),
    ];
    let (nx, ny) = case.options.mesh.counts();
    let remarks = Remarks::with_footer(vec![format!(
        "{}, {:?} kinematics, neo-Hookean κ/G = {}, h/λ = {} (mesh {nx}×{ny}; only y/λ ≤ {:.2} shown). \
         a/λ = {:.4}, p̄/E* = {:.5} (contact forces) / {:.5} (slab reaction).",
        surface_label(&surface),
        case.problem.kinematics,
        s.fe.kappa_over_g.get(),
        s.fe.thickness_over_lambda.get(),
        mesh_y_range(&surface).1,
        last.a_over_lambda,
        last.p_over_estar,
        last.p_over_estar_reaction
    )]);
    let layout = Layout {
        grid: (1, 2),
        panel_px: (700, 1080),
        margin_px: 0,
        font_px: 18,
    };
    Ok(remarks.finish(title, layout, panels, vec![table]))
}

/// The y/λ range of the mesh panel: from below the indenter's deepest point (at most twice the
/// sum of the amplitudes), 0.75 high.
fn mesh_y_range(surface: &Profile) -> (f64, f64) {
    let y_lo = -2.0 * surface.amplitude_sum() - 0.02;
    (y_lo, y_lo + 0.75)
}

/// The mesh (grey), the indenter (black), the nodes in contact (vermilion).
fn mesh_panel(state: &DeformedState, surface: &Profile, last: &CurvePoint) -> Panel {
    let mut series: Vec<Series> = state
        .quads
        .iter()
        .map(|q| {
            let mut pts: Vec<(f64, f64)> = q
                .iter()
                .map(|&i| (state.nodes[i][0], state.nodes[i][1]))
                .collect();
            pts.push(pts[0]);
            Series::line(None, palette::GREY, 1, pts)
        })
        .collect();
    let indenter: Vec<(f64, f64)> = (0..=200)
        .map(|i| 0.5 * i as f64 / 200.0)
        .map(|x| (x, surface.y(x)))
        .collect();
    series.push(Series::line(
        Some("rigid indenter".into()),
        palette::BLACK,
        3,
        indenter,
    ));
    let in_contact: Vec<(f64, f64)> = state
        .bottom
        .iter()
        .zip(&state.in_contact)
        .filter(|(_, &touching)| touching)
        .map(|(&i, _)| (state.nodes[i][0], state.nodes[i][1]))
        .collect();
    series.push(Series::markers(
        Some("nodes in contact".into()),
        palette::VERMILION,
        3,
        in_contact,
    ));
    Panel {
        title: format!("deformed mesh at a/λ = {:.3}", last.a_over_lambda),
        x_label: "x/λ".into(),
        y_label: "y/λ".into(),
        x_range: (0.0, 0.5),
        y_range: mesh_y_range(surface),
        series,
        notes: vec![],
        log_scale: (false, false),
        legend: Some(LegendPosition::UpperRight),
    }
}

/// The contact pressure along the deformed face, with the mean.
fn pressure_panel(state: &DeformedState, last: &CurvePoint) -> Panel {
    let pressure: Vec<(f64, f64)> = state
        .bottom
        .iter()
        .zip(&state.contact_pressure_over_estar)
        .map(|(&i, &p)| (state.nodes[i][0], p))
        .collect();
    let p_max = pressure.iter().map(|p| p.1).fold(0.0_f64, f64::max);
    Panel {
        title: "contact pressure along the deformed face".into(),
        x_label: "current x/λ".into(),
        y_label: "p/E*".into(),
        x_range: (0.0, 0.5),
        y_range: (0.0, 1.1 * p_max.max(last.p_over_estar)),
        series: vec![
            Series::line(
                Some("p/E* (nodal)".into()),
                palette::VERMILION,
                2,
                pressure.clone(),
            ),
            Series::markers(None, palette::VERMILION, 3, pressure),
            Series::dashed(
                Some(format!("mean p̄/E* = {:.4}", last.p_over_estar)),
                palette::BLACK,
                1,
                vec![(0.0, last.p_over_estar), (0.5, last.p_over_estar)],
            ),
        ],
        notes: vec![],
        log_scale: (false, false),
        legend: Some(LegendPosition::UpperRight),
    }
}
