//! `wavy solve`: one finite-element load curve, one CSV row per converged load step.

use super::input::{non_negative, one_of, out_of_range, positive, InputError};
use anyhow::Result;
use std::io::{IsTerminal, Write};
use std::process::ExitCode;
use wavy::defaults;
use wavy::fe::{
    self, CurvePoint, Kinematics, LayerProblem, LoadDirection, MeshLevel, SolveOptions,
};
use wavy::runner::fe_cases::{FeCase, FePhysics};

/// Arguments of `wavy solve`.
#[derive(Debug, Clone, clap::Args)]
pub struct SolveArgs {
    /// Aspect ratio Δ/λ (> 0).
    #[arg(long, allow_hyphen_values = true)]
    pub ar: f64,
    /// Interfacial shear strength τ_max in MPa (≥ 0; 0 = frictionless).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub tau_max_mpa: f64,
    /// Friction coefficient μ of the Coulomb–Orowan law (≥ 0; 0 = frictionless).
    #[arg(long, default_value_t = defaults::friction_coefficient(), allow_hyphen_values = true)]
    pub mu: f64,
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
    #[arg(long, default_value = "finite", value_parser = one_of::<Kinematics>(Kinematics::ALL.map(Kinematics::name)))]
    pub kinematics: Kinematics,
    /// Mesh: coarse (32×16 elements), default (48×24), fine (72×36), or N elements along the
    /// contact face (4 to 2048; N/2 across the thickness).
    #[arg(long, default_value = "default", value_parser = super::input::mesh, conflicts_with = "tolerance")]
    pub mesh: MeshLevel,
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
    #[arg(long, default_value_t = 0.45, allow_hyphen_values = true)]
    pub until_a_over_lambda: f64,
    /// Instead of a/λ: load until the mean pressure p̄/E* is this (> 0; the last loading row
    /// is the state at that load); --until-a-over-lambda then caps the contact half-width on
    /// the way.
    #[arg(long, allow_hyphen_values = true)]
    pub until_p_over_estar: Option<f64>,
    /// Then unload back to zero load, the friction history carried through: the slab
    /// retracts through the loading steps' loads in reverse; a last column `branch`
    /// (loading, unloading) says which branch each row is on.
    #[arg(long, conflicts_with = "error_estimate")]
    pub unload: bool,
}

impl SolveArgs {
    /// The solver's problem and options, or an error naming the flag ([`InputError`]).
    pub fn setup(&self) -> Result<(LayerProblem, SolveOptions)> {
        positive("--ar", self.ar)?;
        positive("--estar-mpa", self.estar_mpa)?;
        positive("--kappa-over-g", self.kappa_over_g)?;
        positive("--thickness-over-lambda", self.thickness_over_lambda)?;
        non_negative("--tau-max-mpa", self.tau_max_mpa)?;
        non_negative("--mu", self.mu)?;
        let x = self.until_a_over_lambda;
        if !(x.is_finite() && x > 0.0 && x < 0.5) {
            return Err(out_of_range("--until-a-over-lambda", x, "(0, 0.5)").into());
        }
        if let Some(p) = self.until_p_over_estar {
            positive("--until-p-over-estar", p)?;
        }
        let physics = FePhysics {
            estar_mpa: self.estar_mpa,
            thickness_over_lambda: self.thickness_over_lambda,
            kappa_over_g: self.kappa_over_g,
            friction_coefficient: self.mu,
            elastic_slip_over_element: defaults::elastic_slip_over_element(),
            kinematics: self.kinematics,
        };
        let mesh = match self.tolerance {
            Some(t) => super::tolerance::solve_mesh(t, self.ar, self.tau_max_mpa, &physics, x)?,
            None => self.mesh,
        };
        let options = SolveOptions {
            until_a_over_lambda: x,
            until_p_over_estar: self.until_p_over_estar,
            mesh,
            ..SolveOptions::default()
        };
        let case = FeCase::new(&physics, self.ar, self.tau_max_mpa, options);
        Ok((case.problem, case.options))
    }
}

/// Runs `wavy solve`: the header, then each converged point as soon as it is known; exit 1,
/// after the converged rows, when the solver cannot go on.
pub fn solve(args: &SolveArgs, out: &mut impl Write) -> Result<ExitCode> {
    let (problem, opts) = args.setup()?;
    let bar = std::io::stderr().is_terminal().then(|| {
        let b = indicatif::ProgressBar::new_spinner();
        b.set_style(
            indicatif::ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
                .expect("valid template"),
        );
        b
    });
    // the Richardson estimate needs the next coarser curve first
    let coarse = match args.error_estimate {
        false => None,
        true => {
            let (level, ratio) =
                wavy::accuracy::coarser_level(opts.mesh).ok_or_else(|| InputError::Refused {
                    flag: "--error-estimate".into(),
                    value: format!("{:?}", opts.mesh),
                    reason: "no coarser mesh of at least 4 elements along the face".into(),
                })?;
            let order = wavy::accuracy::measured::committed()?.fe_order()?;
            if let Some(b) = &bar {
                b.set_message("the coarser mesh of the error estimate");
            }
            let coarse_opts = SolveOptions {
                mesh: level,
                ..opts
            };
            let curve = fe::solve_curve(&problem, &coarse_opts, &mut |_| {}).map_err(|f| {
                let reached = f.points.last().map_or(0.0, |p| p.a_over_lambda);
                anyhow::anyhow!(
                    "the error estimate needs the curve on the coarser mesh {}×{}, which stops at a/λ = {reached:.4}: {}; choose a finer --mesh",
                    level.counts().0,
                    level.counts().1,
                    f.error
                )
            })?;
            Some((curve.points, ratio, order))
        }
    };
    let estimate = |p: &CurvePoint| -> String {
        coarse.as_ref().map_or(String::new(), |(c, ratio, order)| {
            let e = wavy::fe::convergence::p_at(c, p.a_over_lambda).map(|pc| {
                wavy::accuracy::richardson_relative_error(pc, p.p_over_estar, *ratio, *order)
            });
            format!(",{}", e.map_or(String::new(), |e| e.to_string()))
        })
    };
    let header_extra = match (coarse.is_some(), args.unload) {
        (true, _) => ",error_estimate",
        (false, true) => ",branch",
        (false, false) => "",
    };
    writeln!(out, "{}{header_extra}", CurvePoint::CSV_HEADER)?;
    let mut write_error = None;
    let mut on_step = |branch: LoadDirection, p: &CurvePoint| {
        if let Some(b) = &bar {
            b.set_message(format!(
                "{}: a/λ = {:.4}, p̄/E* = {:.5}",
                branch.name(),
                p.a_over_lambda,
                p.p_over_estar
            ));
            b.tick();
        }
        if write_error.is_none() {
            let extra = match args.unload {
                true => format!(",{}", branch.name()),
                false => estimate(p),
            };
            if let Err(e) = writeln!(out, "{}{extra}", p.csv_row()) {
                write_error = Some(e);
            }
        }
    };
    let result = match args.unload {
        true => fe::solve_cycle(&problem, &opts, &mut on_step),
        false => fe::solve_curve(&problem, &opts, &mut |p| on_step(LoadDirection::Loading, p)),
    };
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    if let Some(e) = write_error {
        return Err(e.into());
    }
    match result {
        Ok(_) => Ok(ExitCode::SUCCESS),
        Err(failure) => {
            eprintln!("error: the solver stopped: {}", failure.error);
            Ok(ExitCode::from(1))
        }
    }
}
