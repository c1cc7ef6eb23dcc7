//! `wavy solve`: one finite-element load curve, one CSV row per converged load step.

use super::input::one_of;
use anyhow::Result;
use std::io::{IsTerminal, Write};
use std::ops::ControlFlow;
use std::process::ExitCode;
use wavy::defaults;
use wavy::fe::{Kinematics, MeshLevel, SolveOptions};
use wavy::profile::Profile;
use wavy::runner::requests::request_error::RequestError;
use wavy::runner::requests::solve_outcome::{SolveOutcome, SolveRow};
use wavy::runner::requests::solve_request::{PreparedSolve, SolveRequest};
use wavy::runner::requests::solver::Solver;

/// Arguments of `wavy solve`.
#[derive(Debug, Clone, clap::Args)]
pub struct SolveArgs {
    /// Aspect ratio Δ/λ (> 0) of a single sinusoid: the shorthand for `--profile 1:AR`.
    #[arg(
        long,
        allow_hyphen_values = true,
        required_unless_present = "profile",
        conflicts_with = "profile"
    )]
    pub ar: Option<f64>,
    /// Instead of --ar: an even periodic profile as cosine harmonics `order:aspect_ratio`,
    /// comma-separated, the first of order 1 (the wavelength λ), e.g. `1:0.1,16:0.05`; each
    /// aspect ratio is the harmonic's amplitude over its own wavelength λ/order
    /// (docs/replication.md R13); at most 16 harmonics. Or a Weierstrass profile
    /// `weierstrass:AR0,gamma,D,K`: the K harmonics `gamma^k : AR0 gamma^((D-1)k)`, integer
    /// gamma ≥ 2, 1 < D < 2 (R14). A profile's rows come a few load steps late, each final once
    /// the later touchdowns have placed its patch edges.
    #[arg(long, value_parser = super::input::profile)]
    pub profile: Option<Profile>,
    /// Interfacial shear strength τ_max in MPa (≥ 0; 0 = frictionless).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub tau_max_mpa: f64,
    /// Friction coefficient μ of the Coulomb–Orowan law (≥ 0; 0 = frictionless).
    #[arg(long, default_value_t = defaults::friction_coefficient(), allow_hyphen_values = true)]
    pub mu: f64,
    /// Elastic slip e_c at which friction is mobilised, over the face element length (≥ 0;
    /// 0 is exact stick: a stuck node is held and its friction force is the reaction).
    #[arg(long, default_value_t = defaults::elastic_slip_over_element(), allow_hyphen_values = true)]
    pub elastic_slip_over_element: f64,
    /// Plane-strain modulus E* in MPa (> 0): τ_max/E* is what the physics sees.
    #[arg(long, default_value_t = defaults::fe_estar_mpa(), allow_hyphen_values = true)]
    pub estar_mpa: f64,
    /// Bulk over shear modulus κ/G (> 0; 1000 is nearly incompressible, ν ≈ 0.4995).
    #[arg(long, default_value_t = defaults::kappa_over_g(), allow_hyphen_values = true)]
    pub kappa_over_g: f64,
    /// Layer thickness over wavelength h/λ (> 0; 1 is practically a half-space).
    #[arg(long, default_value_t = defaults::thickness_over_lambda(), allow_hyphen_values = true)]
    pub thickness_over_lambda: f64,
    /// `finite` (finite strain, neo-Hookean: the paper's physics) or `linear` (small strain).
    /// [default: finite; linear with --solver bem, the only kinematics it models]
    #[arg(long, value_parser = one_of::<Kinematics>(Kinematics::ALL.map(Kinematics::name)))]
    pub kinematics: Option<Kinematics>,
    /// `fe`: the finite-element solver (a layer on a rigid base, finite or linear kinematics);
    /// `bem`: the boundary-element solver (linear kinematics; the layer, or the half-plane with
    /// --half-plane, with Coulomb–Orowan friction; docs/verification.md, "Frictional
    /// boundary elements"). The columns are the same; with bem, slab_displacement_over_lambda
    /// holds the rigid approach δ/λ, newton_iterations the normal–tangential passes, and
    /// active_nodes the contact grid points on [0, λ/2]; with --unload, the loop's work ∮ p̄ dδ
    /// and the work of friction at the face go to stderr.
    #[arg(long, default_value = "fe", value_parser = one_of::<Solver>(Solver::ALL.map(Solver::name)))]
    pub solver: Solver,
    /// With --solver bem: grid points per wavelength, a power of two [default: 4096, or 64 per
    /// wavelength of a profile's finest harmonic].
    #[arg(long)]
    pub grid_points: Option<usize>,
    /// Loading points up to the target. With --solver fe (a frictionless sinusoid; a frictional
    /// curve steps node by node): steps of a/λ of about the target a/λ over this, each to the
    /// first face node that far beyond the contact edge (10000: node by node) [default: 45,
    /// steps of 0.01 to the default target; with --unload, node by node]. With --solver bem:
    /// even steps of the contact half-width on a crest up to the frictionless load of the
    /// target; friction's extra load takes a few more [default: 40].
    #[arg(long)]
    pub points: Option<usize>,
    /// With --solver bem: the half-plane instead of the layer of --thickness-over-lambda.
    #[arg(long)]
    pub half_plane: bool,
    /// Mesh: coarse (32×16 elements), default (48×24), fine (72×36), or N elements along the
    /// contact face (4 to 2048; N/2 across the thickness). A --profile given no mesh gets the
    /// coarsest mesh, at least the default, that resolves its finest harmonic (told on stderr).
    /// [default: default]
    #[arg(long, value_parser = super::input::mesh, conflicts_with = "tolerance")]
    pub mesh: Option<MeshLevel>,
    /// Coarsen the mesh's columns threefold wherever its rows, growing with depth, reach this
    /// many times their width (0 or ≥ 1; a conforming transition row, no hanging nodes): at 4 a
    /// profile's curve on a uniform face takes about half the time and moves by a small part of
    /// its error (docs/replication.md R13, "Columns coarsened with depth"). Not with --tolerance
    /// or --error-estimate, whose errors are measured on meshes that keep every column
    /// [default: every column to the bonded face]
    #[arg(long, allow_hyphen_values = true)]
    pub coarsen_at_aspect: Option<f64>,
    /// Instead of --mesh: the coarsest mesh whose measured largest relative error of p̄/E* at
    /// this (AR, τ_max) is at most this (e.g. 0.005); the choice goes to stderr
    /// (measurements: expected/speed_accuracy.csv, default physics only).
    #[arg(long, allow_hyphen_values = true)]
    pub tolerance: Option<f64>,
    /// Also solve the next coarser mesh (1.5 times fewer elements) and add the column
    /// error_estimate: the Richardson estimate of each point's relative error, with the
    /// convergence order measured by the speed_accuracy scene (docs/results.md);
    /// empty below the coarser curve's first contact point.
    #[arg(long)]
    pub error_estimate: bool,
    /// Load until the contact half-width a/λ reaches this value (in (0, 0.5)).
    #[arg(long, default_value_t = SolveOptions::default().until_a_over_lambda, allow_hyphen_values = true)]
    pub until_a_over_lambda: f64,
    /// Instead of a/λ: load until the mean pressure p̄/E* is this (> 0; the last loading row
    /// is the state at that load); --until-a-over-lambda then caps the contact half-width on
    /// the way (for a profile, full contact is the cap: its outermost patch edge reaches the
    /// valley long before).
    #[arg(long, allow_hyphen_values = true)]
    pub until_p_over_estar: Option<f64>,
    /// Instead of a/λ: load until the contact fraction (total contact length over λ; 2a/λ for
    /// one patch) reaches this (in (0, 1)): a profile's counterpart of --until-a-over-lambda.
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "until_p_over_estar"
    )]
    pub until_contact_fraction: Option<f64>,
    /// Then unload back to zero load, the friction history carried through: the slab
    /// retracts through the loading steps' loads in reverse; a last column `branch`
    /// (loading, unloading) says which branch each row is on, and the loop's work ∮ p̄ dd
    /// and the face's work of friction (the column friction_work_over_estar_lambda2 at the
    /// last row) go to stderr.
    #[arg(long, conflicts_with = "error_estimate")]
    pub unload: bool,
    /// With --unload: unloading steps per loading step (a whole number >= 1), each interval
    /// between the loading steps' loads retraced in this many equal steps: the unloading
    /// branch sampled finer, so that the face's work of friction and the trapezoid sum of the
    /// loop's work converge with it; docs/verification.md ("The energy audit") measures what
    /// each choice does. [default: 1]
    #[arg(long, requires = "unload")]
    pub unloading_substeps: Option<usize>,
    /// Also write the deformed state of every converged point into this folder for ParaView:
    /// one step_NNNN.vtu per point (displacement, reference position, contact and stick
    /// status, pressure, shear and slip on the face, J per element) and series.pvd, the time series
    /// (time: the slab displacement d/λ; on unloading, the slab travel 2 d_max − d). A curve
    /// that stops short writes its converged points, and series.pvd says it is incomplete and
    /// why (status="incomplete", reason="…"); the command still exits 1.
    #[arg(long, value_name = "DIR")]
    pub vtk: Option<std::path::PathBuf>,
    /// Refuse the solve (exit 1, naming the estimate) when its estimated peak memory is above
    /// this many bytes; it is also refused above the memory the machine has available (the
    /// estimate: docs/performance.md, "Large meshes").
    #[arg(long, value_name = "BYTES")]
    pub max_memory: Option<u64>,
}

impl SolveArgs {
    /// The library's request: the same fields (`--ar` is `ar`, …).
    pub fn request(&self) -> SolveRequest {
        let profile = self.profile.unwrap_or_else(|| {
            Profile::sinusoid(self.ar.expect("clap requires --ar or --profile"))
        });
        SolveRequest {
            ar: profile.aspect_ratio,
            finer_harmonics: profile.finer,
            tau_max_mpa: self.tau_max_mpa,
            mu: self.mu,
            elastic_slip_over_element: self.elastic_slip_over_element,
            estar_mpa: self.estar_mpa,
            kappa_over_g: self.kappa_over_g,
            thickness_over_lambda: self.thickness_over_lambda,
            kinematics: self.kinematics.unwrap_or(match self.solver {
                Solver::FiniteElement => Kinematics::Finite,
                Solver::BoundaryElement => Kinematics::Linear,
            }),
            mesh: self.mesh,
            coarsen_at_aspect: self.coarsen_at_aspect,
            tolerance: self.tolerance,
            error_estimate: self.error_estimate,
            until_a_over_lambda: self.until_a_over_lambda,
            until_p_over_estar: self.until_p_over_estar,
            until_contact_fraction: self.until_contact_fraction,
            unload: self.unload,
            unloading_substeps: self.unloading_substeps,
            max_memory: self.max_memory,
            solver: self.solver,
            grid_points: self.grid_points,
            points: self.points,
            half_plane: self.half_plane,
        }
    }

    /// The checked request (the mesh chosen), or an error naming the flag.
    pub fn setup(&self) -> Result<PreparedSolve> {
        Ok(self.request().prepare()?)
    }
}

/// Runs `wavy solve`: the header, then each converged point as soon as it is known; exit 1,
/// after the converged rows, when the solver cannot go on. The solve is the library's
/// (`wavy::runner::requests::solve_request`); this layer prints.
pub fn solve(args: &SolveArgs, out: &mut impl Write) -> Result<ExitCode> {
    if args.solver == Solver::BoundaryElement {
        return solve_bem(args, out);
    }
    if let Some(dir) = &args.vtk {
        wavy::runner::requests::input_checks::vtk_folder(dir)?;
    }
    let prepared = args.setup()?;
    if let (Some(choice), Some(t)) = (&prepared.tolerance_choice, args.tolerance) {
        super::tolerance::announce(choice, t);
    }
    for note in &prepared.notes {
        eprintln!("{note}");
    }
    let bar = std::io::stderr().is_terminal().then(|| {
        let b = indicatif::ProgressBar::new_spinner();
        b.set_style(
            indicatif::ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
                .expect("valid template"),
        );
        b
    });
    // the Richardson estimate needs the next coarser curve first
    if let (Some(b), true) = (&bar, args.error_estimate) {
        b.set_message("the coarser mesh of the error estimate");
    }
    let coarse = prepared.coarse_reference(&mut || ControlFlow::Continue(()))?;
    writeln!(out, "{}", prepared.csv_header())?;
    let extra = prepared.extra_column();
    let mut write_error = None;
    let mut on_row = |row: &SolveRow| {
        let p = &row.point;
        if let Some(b) = &bar {
            b.set_message(format!(
                "{}: a/λ = {:.4}, p̄/E* = {:.5}",
                row.branch.name(),
                p.a_over_lambda,
                p.p_over_estar
            ));
            b.tick();
        }
        if write_error.is_none() {
            if let Err(e) = writeln!(out, "{}", row.csv_line(extra)) {
                write_error = Some(e);
            }
        }
        ControlFlow::Continue(())
    };
    let result = prepared.run(coarse.as_ref(), args.vtk.as_deref(), &mut on_row);
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if let Some(e) = write_error {
        return Err(e.into());
    }
    match result {
        Ok(outcome) => {
            tell_cycle_energy(&outcome, "d");
            Ok(ExitCode::SUCCESS)
        }
        Err(stopped @ RequestError::Stopped { .. }) => {
            eprintln!("error: {stopped}");
            Ok(ExitCode::from(1))
        }
        Err(other) => Err(other.into()),
    }
}

/// `wavy solve --solver bem`: the header, each committed increment as a row, then, with
/// `--unload`, the loop's energy both ways on stderr.
fn solve_bem(args: &SolveArgs, out: &mut impl Write) -> Result<ExitCode> {
    if let Some(dir) = &args.vtk {
        return Err(RequestError::from(
            wavy::runner::requests::input_checks::InputError::Refused {
                flag: "--vtk".into(),
                value: dir.display().to_string(),
                reason: "writes the finite-element solver's deformed mesh; the boundary-element solver has none".into(),
            },
        )
        .into());
    }
    let prepared = args.request().prepare_bem()?;
    let extra = prepared.request.extra_column();
    writeln!(out, "{}", prepared.request.csv_header())?;
    let mut write_error = None;
    let result = prepared.run(&mut |row| {
        if write_error.is_none() {
            if let Err(e) = writeln!(out, "{}", row.csv_line(extra)) {
                write_error = Some(e);
            }
        }
        ControlFlow::Continue(())
    });
    if let Some(e) = write_error {
        return Err(e.into());
    }
    tell_cycle_energy(&result?, "δ");
    Ok(ExitCode::SUCCESS)
}

/// With `--unload`, the loop's energy both ways on stderr: the work of the load over the loop,
/// `∮ p̄ d(travel)` (`travel` the load's displacement: `d` the slab's, `δ` the rigid approach),
/// and the work of friction at the face.
fn tell_cycle_energy(outcome: &SolveOutcome, travel: &str) {
    if let Some(energy) = outcome.cycle_energy {
        eprintln!(
            "loop work ∮ p̄ d{travel} = {:e} E*λ², work of friction at the face = {:e} E*λ² (per unit ridge length and wavelength)",
            energy.cycle_work_over_estar_lambda2, energy.face_dissipation_over_estar_lambda2
        );
    }
}
