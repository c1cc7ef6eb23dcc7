//! `wavy solve` without its arguments: a request with the command line's names and units →
//! the checked problem and mesh (the `--tolerance` choice included) → the error estimate's
//! coarser curve → one finite-element curve, row by row, → a [`SolveOutcome`] with the rows and
//! what the solve cost. The command line streams the rows as CSV; the Python bindings collect
//! them into arrays; both call these functions, so values and messages are the same.

use crate::accuracy::measured::{self, Choice};
use crate::defaults;
use crate::fe::input_ranges;
use crate::fe::{
    self, CurvePoint, Kinematics, LayerProblem, LoadDirection, MeshLevel, SolveOptions, SolveWork,
};
use crate::profile::{FinerHarmonics, Profile};
use crate::runner::requests::cost_estimate::{self, CostEstimate};
use crate::runner::requests::input_checks::{
    non_negative, positive, vtk_folder, within, InputError,
};
use crate::runner::requests::loading_points;
use crate::runner::requests::profile_mesh;
use crate::runner::requests::request_error::RequestError;
use crate::runner::requests::solve_outcome::{CycleEnergy, ExtraColumn, SolveOutcome, SolveRow};
use crate::runner::requests::solver::Solver;
use crate::runner::sweep::fe_cases::{FeCase, FePhysics};
use crate::vtk::{write_incomplete_series, write_series, VtkStep};
use std::ops::ControlFlow;
use std::path::Path;

/// What `wavy solve` is asked, field by field its flags (`ar` is `--ar`, …), in its units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveRequest {
    /// Aspect ratio Δ/λ (> 0): of the sinusoid, or of the profile's big wave (order 1).
    pub ar: f64,
    /// The profile's finer harmonics (`--profile 1:AR,n:AR_n,…` beyond its first pair; none
    /// for a sinusoid).
    pub finer_harmonics: FinerHarmonics,
    /// Interfacial shear strength τ_max in MPa (≥ 0; 0 = frictionless).
    pub tau_max_mpa: f64,
    /// Friction coefficient μ (≥ 0).
    pub mu: f64,
    /// Elastic slip `e_c` over the face element length (≥ 0; 0 = exact stick).
    pub elastic_slip_over_element: f64,
    /// Plane-strain modulus E* in MPa (> 0).
    pub estar_mpa: f64,
    /// Bulk over shear modulus κ/G (> 0).
    pub kappa_over_g: f64,
    /// Layer thickness over wavelength h/λ (> 0).
    pub thickness_over_lambda: f64,
    pub kinematics: Kinematics,
    /// The mesh (`None`: the default mesh, or the one `tolerance` chooses; both is refused).
    pub mesh: Option<MeshLevel>,
    /// Coarsen the mesh's columns threefold where its rows reach this many times their width
    /// (0 or ≥ 1; `None`: every column to the bonded face; [`crate::fe::Grading::coarsen_at_aspect`]).
    pub coarsen_at_aspect: Option<f64>,
    /// The coarsest mesh whose measured relative error is at most this (in (0, 1)).
    pub tolerance: Option<f64>,
    /// Also solve the next coarser mesh and estimate each point's relative error.
    pub error_estimate: bool,
    /// Load until a/λ reaches this (in (0, 0.5)); with `until_p_over_estar`, the cap on the way.
    pub until_a_over_lambda: f64,
    /// Instead: load until p̄/E* is this (> 0).
    pub until_p_over_estar: Option<f64>,
    /// Instead: load until the contact fraction (contact length over λ) is this (in (0, 1)).
    pub until_contact_fraction: Option<f64>,
    /// Then unload back to zero load.
    pub unload: bool,
    /// With `unload`: unloading steps per loading step (a whole number ≥ 1; `None`: the
    /// solver's default, [`crate::fe::StepOptions::unloading_substeps`]).
    pub unloading_substeps: Option<usize>,
    /// Refuse the solve when its estimated peak memory is above this many bytes
    /// ([`CostEstimate::check`]; it is also refused above the memory available).
    pub max_memory: Option<u64>,
    /// The finite-element solver (default) or the boundary-element one ([`bem_solve`]).
    pub solver: Solver,
    /// The boundary-element grid, points per wavelength (`None`: its default).
    pub grid_points: Option<usize>,
    /// Loading points up to the target (`None`: the solver's default). The boundary-element
    /// solver steps the contact half-width evenly; the finite-element one steps `a/λ` by about
    /// `until_a_over_lambda / points` from edge event to edge event
    /// ([`crate::fe::StepOptions::da_target`]; a frictionless sinusoid only).
    pub points: Option<usize>,
    /// The boundary-element solver on the half-plane instead of the layer.
    pub half_plane: bool,
}

impl SolveRequest {
    /// A request at aspect ratio `ar` with every other field at the command line's default.
    pub fn new(ar: f64) -> Self {
        SolveRequest {
            ar,
            finer_harmonics: FinerHarmonics::NONE,
            tau_max_mpa: 0.0,
            mu: defaults::friction_coefficient(),
            elastic_slip_over_element: defaults::elastic_slip_over_element(),
            estar_mpa: defaults::fe_estar_mpa(),
            kappa_over_g: defaults::kappa_over_g(),
            thickness_over_lambda: defaults::thickness_over_lambda(),
            kinematics: Kinematics::Finite,
            mesh: None,
            coarsen_at_aspect: None,
            tolerance: None,
            error_estimate: false,
            until_a_over_lambda: SolveOptions::default().until_a_over_lambda,
            until_p_over_estar: None,
            until_contact_fraction: None,
            unload: false,
            unloading_substeps: None,
            max_memory: None,
            solver: Solver::FiniteElement,
            grid_points: None,
            points: None,
            half_plane: false,
        }
    }

    /// A request for the profile `profile` with every other field at the command line's
    /// default.
    pub fn with_profile(profile: &Profile) -> Self {
        SolveRequest {
            finer_harmonics: profile.finer,
            ..Self::new(profile.aspect_ratio)
        }
    }

    /// The column after the curve point's columns.
    pub fn extra_column(&self) -> ExtraColumn {
        match (self.error_estimate, self.unload) {
            (true, _) => ExtraColumn::ErrorEstimate,
            (false, true) => ExtraColumn::Branch,
            (false, false) => ExtraColumn::None,
        }
    }

    /// The CSV header of `wavy solve` (either solver).
    pub fn csv_header(&self) -> String {
        let extra = match self.extra_column() {
            ExtraColumn::None => "",
            ExtraColumn::ErrorEstimate => ",error_estimate",
            ExtraColumn::Branch => ",branch",
        };
        format!("{}{extra}", CurvePoint::CSV_HEADER)
    }

    /// Every input checked (in the command line's order), the mesh chosen: the
    /// finite-element solve to run (a boundary-element request: [`Self::prepare_bem`]).
    pub fn prepare(&self) -> Result<PreparedSolve, RequestError> {
        self.check_ranges()?;
        let bem_only = [
            ("--grid-points", self.grid_points.is_some()),
            ("--half-plane", self.half_plane),
        ];
        if self.solver != Solver::FiniteElement {
            return Err(refused(
                "--solver",
                self.solver.name(),
                "is prepared by prepare_bem",
            ));
        }
        if let Some((flag, _)) = bem_only.iter().find(|(_, given)| *given) {
            return Err(refused(
                flag,
                "given",
                "belongs to the boundary-element solver (--solver bem)",
            ));
        }
        self.prepare_fe()
    }

    /// The ranges both solvers share, in the command line's order, and the combinations no
    /// solver takes.
    pub(crate) fn check_ranges(&self) -> Result<(), RequestError> {
        within("--ar", &input_ranges::ASPECT_RATIO, self.ar)?;
        positive("--estar-mpa", self.estar_mpa)?;
        within(
            "--kappa-over-g",
            &input_ranges::KAPPA_OVER_G,
            self.kappa_over_g,
        )?;
        let thickness = self.thickness_over_lambda;
        within(
            "--thickness-over-lambda",
            &input_ranges::THICKNESS_OVER_LAMBDA,
            thickness,
        )?;
        // zero is the frictionless interface here; a frictional one's μ and τ_max are > 0
        non_negative("--tau-max-mpa", self.tau_max_mpa)?;
        non_negative("--mu", self.mu)?;
        within(
            "--elastic-slip-over-element",
            &input_ranges::ELASTIC_SLIP_OVER_ELEMENT,
            self.elastic_slip_over_element,
        )?;
        if let Some(c) = self.coarsen_at_aspect {
            within("--coarsen-at-aspect", &input_ranges::COARSEN_AT_ASPECT, c)?;
        }
        let x = self.until_a_over_lambda;
        within(
            "--until-a-over-lambda",
            &input_ranges::UNTIL_A_OVER_LAMBDA,
            x,
        )?;
        if let Some(p) = self.until_p_over_estar {
            within("--until-p-over-estar", &input_ranges::UNTIL_P_OVER_ESTAR, p)?;
        }
        if let Some(c) = self.until_contact_fraction {
            within(
                "--until-contact-fraction",
                &input_ranges::UNTIL_CONTACT_FRACTION,
                c,
            )?;
            if self.until_p_over_estar.is_some() {
                return Err(refused(
                    "--until-contact-fraction",
                    c,
                    "cannot be used with --until-p-over-estar",
                ));
            }
        }
        if self.unload && self.error_estimate {
            return Err(refused(
                "--unload",
                true,
                "cannot be used with --error-estimate",
            ));
        }
        if let Some(n) = self.unloading_substeps {
            within(
                "--unloading-substeps",
                &input_ranges::UNLOADING_SUBSTEPS,
                n as f64,
            )?;
            if !self.unload {
                return Err(refused("--unloading-substeps", n, "needs --unload"));
            }
        }
        Ok(())
    }

    /// The finite-element options that cannot be combined: a measured-error option (`--tolerance`,
    /// `--error-estimate`) with a profile or a coarsened mesh, and `--mesh` with `--tolerance`.
    fn check_fe_combinations(&self) -> Result<(), RequestError> {
        if !self.finer_harmonics.is_empty() {
            // the measured tiers and their convergence orders are a sinusoid's
            if let Some(t) = self.tolerance {
                return Err(refused(
                    "--tolerance",
                    t,
                    "is measured for a single sinusoid; with --profile choose --mesh",
                ));
            }
            if self.error_estimate {
                return Err(refused(
                    "--error-estimate",
                    true,
                    "is measured for a single sinusoid; not with --profile",
                ));
            }
        }
        if let Some(c) = self.coarsen_at_aspect.filter(|&c| c > 0.0) {
            let measured = [
                ("--tolerance", self.tolerance.is_some()),
                ("--error-estimate", self.error_estimate),
            ];
            if let Some((flag, _)) = measured.iter().find(|(_, given)| *given) {
                return Err(refused(
                    "--coarsen-at-aspect",
                    c,
                    &format!("cannot be used with {flag}, whose errors are measured on meshes that keep every column"),
                ));
            }
        }
        if let (Some(mesh), Some(_)) = (self.mesh, self.tolerance) {
            return Err(refused(
                "--mesh",
                mesh,
                "cannot be used with --tolerance (which chooses the mesh)",
            ));
        }
        Ok(())
    }

    /// [`Self::prepare`] once the ranges hold.
    fn prepare_fe(&self) -> Result<PreparedSolve, RequestError> {
        self.check_fe_combinations()?;
        let x = self.until_a_over_lambda;
        let physics = FePhysics {
            estar_mpa: self.estar_mpa,
            thickness_over_lambda: self.thickness_over_lambda,
            kappa_over_g: self.kappa_over_g,
            friction_coefficient: self.mu,
            elastic_slip_over_element: self.elastic_slip_over_element,
            kinematics: self.kinematics,
        };
        let (mesh, tolerance_choice) = match self.tolerance {
            Some(t) => {
                let (mesh, choice) = crate::runner::requests::tolerance_choice::solve_mesh(
                    t,
                    self.ar,
                    self.tau_max_mpa,
                    &physics,
                    x,
                )?;
                (mesh, Some(choice))
            }
            None => (self.mesh.unwrap_or_default(), None),
        };
        let mut options = SolveOptions {
            until_a_over_lambda: x,
            until_p_over_estar: self.until_p_over_estar,
            until_contact_fraction: self.until_contact_fraction,
            mesh,
            ..SolveOptions::default()
        };
        if let Some(n) = self.unloading_substeps {
            options.steps.unloading_substeps = n;
        }
        let curve = loading_points::FeCurve {
            frictional: self.tau_max_mpa > 0.0,
            profile: !self.finer_harmonics.is_empty(),
            unload: self.unload,
        };
        if let Some(n) = loading_points::fe_points(self.points, curve)? {
            options.steps.da_target = x / n as f64;
        }
        if let Some(c) = self.coarsen_at_aspect {
            options.grading.coarsen_at_aspect = c;
        }
        let case = FeCase::new(&physics, self.ar, self.tau_max_mpa, options);
        let problem = LayerProblem {
            finer_harmonics: self.finer_harmonics,
            ..case.problem
        };
        // a profile gets a mesh that resolves it, or is refused here, before any solve
        let (mesh, mesh_note) = profile_mesh::choose(&problem, &case.options, self.mesh.is_some())?;
        // the memory it needs, refused above the caller's cap or what is available
        let unknowns = mesh.unknowns_graded(case.options.grading, problem.thickness_over_lambda);
        let cost = CostEstimate::with_unknowns(mesh, unknowns);
        cost.check(self.max_memory)?;
        let told = (mesh.counts().0 >= cost_estimate::TOLD_FROM_ELEMENTS).then(|| cost.describe());
        Ok(PreparedSolve {
            request: *self,
            problem,
            options: SolveOptions {
                mesh,
                ..case.options
            },
            tolerance_choice,
            notes: mesh_note.into_iter().chain(told).collect(),
        })
    }
}

/// The flag `flag` refused at `value` for `reason`.
pub(crate) fn refused(flag: &str, value: impl std::fmt::Display, reason: &str) -> RequestError {
    InputError::Refused {
        flag: flag.into(),
        value: value.to_string(),
        reason: reason.into(),
    }
    .into()
}

/// The coarser curve of the error estimate, its element-count ratio and the convergence order.
#[derive(Debug, Clone)]
pub struct CoarseReference {
    points: Vec<CurvePoint>,
    ratio: f64,
    order: f64,
}

impl CoarseReference {
    fn estimate(&self, p: &CurvePoint) -> Option<f64> {
        fe::convergence::p_at(&self.points, p.a_over_lambda).map(|pc| {
            crate::accuracy::richardson_relative_error(pc, p.p_over_estar, self.ratio, self.order)
        })
    }
}

/// A checked request, ready to solve.
#[derive(Debug, Clone)]
pub struct PreparedSolve {
    pub request: SolveRequest,
    pub problem: LayerProblem,
    pub options: SolveOptions,
    /// With `tolerance`: the measured choice behind the mesh (the command line tells it).
    pub tolerance_choice: Option<Choice>,
    /// What the command line tells on stderr and Python keeps in the result's notes: for a
    /// profile given no mesh the finer mesh chosen to resolve it; from mesh 256 on the
    /// estimated memory and time ([`CostEstimate`]).
    pub notes: Vec<String>,
}

/// A solve that ended because its caller asked: a step callback's `Break`
/// ([`fe::SolveError::Stopped`]) or the flag of [`fe::interrupt`], whatever error the
/// interrupted iteration left.
fn stopped_by_caller(error: &fe::SolveError) -> bool {
    matches!(error, fe::SolveError::Stopped { .. }) || fe::interrupt::requested()
}

impl PreparedSolve {
    /// The mesh solved.
    pub fn mesh(&self) -> MeshLevel {
        self.options.mesh
    }

    /// The column after the curve point's columns.
    pub fn extra_column(&self) -> ExtraColumn {
        self.request.extra_column()
    }

    /// The CSV header of `wavy solve`.
    pub fn csv_header(&self) -> String {
        self.request.csv_header()
    }

    fn outcome(&self, rows: Vec<SolveRow>, work: SolveWork) -> SolveOutcome {
        SolveOutcome {
            mesh: Some(self.mesh()),
            grid_points: None,
            unknowns: (self.mesh())
                .unknowns_graded(self.options.grading, self.problem.thickness_over_lambda),
            extra: self.extra_column(),
            rows,
            work,
            cycle_energy: None,
        }
    }

    /// With `error_estimate`: the curve on the next coarser mesh (solved now; `keep_going` is
    /// asked after each of its steps), else `None`.
    pub fn coarse_reference(
        &self,
        keep_going: &mut dyn FnMut() -> ControlFlow<()>,
    ) -> Result<Option<CoarseReference>, RequestError> {
        if !self.request.error_estimate {
            return Ok(None);
        }
        let mesh = self.mesh();
        let (level, ratio) =
            crate::accuracy::coarser_level(mesh).ok_or_else(|| InputError::Refused {
                flag: "--error-estimate".into(),
                value: format!("{mesh:?}"),
                reason: "no coarser mesh of at least 4 elements along the face".into(),
            })?;
        let order = measured::committed()?.fe_order()?;
        let coarse_options = SolveOptions {
            mesh: level,
            ..self.options
        };
        let solved = fe::solve_curve(&self.problem, &coarse_options, &mut |_| keep_going());
        if let Err(f) = &solved {
            if stopped_by_caller(&f.error) {
                return Err(RequestError::Interrupted {
                    partial: Box::new(self.outcome(vec![], SolveWork::default())),
                });
            }
        }
        let curve = solved.map_err(|f| {
            let reached = f.points.last().map_or(0.0, |p| p.a_over_lambda);
            RequestError::Failed(format!(
                "the error estimate needs the curve on the coarser mesh {}×{}, which stops at a/λ = {reached:.4}: {}; choose a finer --mesh",
                level.counts().0,
                level.counts().1,
                f.error
            ))
        })?;
        Ok(Some(CoarseReference {
            points: curve.points,
            ratio,
            order,
        }))
    }

    /// Solves, handing each converged row to `on_row` as soon as it is known; `Break` from
    /// `on_row` stops the solve ([`RequestError::Interrupted`]). `coarse` is what
    /// [`Self::coarse_reference`] returned. With `vtk`, a complete curve also writes the
    /// deformed state of every converged point into that folder as a ParaView time series
    /// ([`crate::vtk::write_series`]); a curve that stops short writes its converged states
    /// and a collection that says it is incomplete and why
    /// ([`crate::vtk::write_incomplete_series`]), and still fails. A solve stopped by
    /// [`fe::interrupt`] (the caller's flag) is [`RequestError::Interrupted`].
    pub fn run(
        &self,
        coarse: Option<&CoarseReference>,
        vtk: Option<&Path>,
        on_row: &mut dyn FnMut(&SolveRow) -> ControlFlow<()>,
    ) -> Result<SolveOutcome, RequestError> {
        let mut rows = vec![];
        let mut vtk_steps: Vec<VtkStep> = vec![];
        let mut on_step = |branch: LoadDirection, p: &CurvePoint| {
            let row = SolveRow {
                point: *p,
                branch,
                error_estimate: coarse.and_then(|c| c.estimate(p)),
            };
            rows.push(row);
            on_row(&row)
        };
        let solved = match (vtk, self.request.unload) {
            (Some(_), unload) => fe::solve_with_states(
                &self.problem,
                &self.options,
                unload,
                &mut |branch, p, state| {
                    vtk_steps.push(VtkStep {
                        direction: branch,
                        point: *p,
                        state: state.clone(),
                    });
                    on_step(branch, p)
                },
            ),
            (None, true) => fe::solve_cycle(&self.problem, &self.options, &mut on_step),
            (None, false) => fe::solve_curve(&self.problem, &self.options, &mut |p| {
                on_step(LoadDirection::Loading, p)
            }),
        };
        match solved {
            Ok(curve) => {
                if let Some(dir) = vtk {
                    write_series(dir, &vtk_steps)
                        .map_err(|e| RequestError::Failed(e.to_string()))?;
                }
                let unload = self.request.unload;
                let energy = unload.then(|| CycleEnergy::of_finite_element_loop(&rows));
                Ok(SolveOutcome {
                    cycle_energy: energy,
                    ..self.outcome(rows, curve.work)
                })
            }
            Err(failure) if stopped_by_caller(&failure.error) => Err(RequestError::Interrupted {
                partial: Box::new(self.outcome(rows, SolveWork::default())),
            }),
            Err(failure) => {
                let stopped = RequestError::Stopped {
                    error: failure.error,
                    partial: Box::new(self.outcome(rows, SolveWork::default())),
                };
                if let Some(dir) = vtk {
                    let reason = stopped.to_string();
                    if let Err(e) = write_incomplete_series(dir, &vtk_steps, &reason) {
                        return Err(RequestError::Failed(format!(
                            "{reason}; the VTK series of its converged points could not be written either: {e}"
                        )));
                    }
                }
                Err(stopped)
            }
        }
    }
}

/// The whole request: prepare, the coarser curve if asked, the solve; `on_row` as in
/// [`PreparedSolve::run`] (also asked, with no row, after each step of the coarser curve), and
/// `vtk` as there (the finite-element solver's alone).
pub fn solve(
    request: &SolveRequest,
    vtk: Option<&Path>,
    on_row: &mut dyn FnMut(Option<&SolveRow>) -> ControlFlow<()>,
) -> Result<SolveOutcome, RequestError> {
    if request.solver == Solver::BoundaryElement {
        if vtk.is_some() {
            return Err(refused(
                "--vtk",
                "given",
                "writes the finite-element solver's deformed mesh; the boundary-element solver has none",
            ));
        }
        return request.prepare_bem()?.run(&mut |row| on_row(Some(row)));
    }
    if let Some(dir) = vtk {
        vtk_folder(dir)?;
    }
    let prepared = request.prepare()?;
    let coarse = prepared.coarse_reference(&mut || on_row(None))?;
    prepared.run(coarse.as_ref(), vtk, &mut |row| on_row(Some(row)))
}
