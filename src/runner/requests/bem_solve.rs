//! `wavy solve --solver bem`: the request checked for what the boundary-element solver models
//! (small strain, on the half-plane or the layer), the frictional
//! curve solved ([`crate::bem::frictional_curve`]) and its increments as the rows of a solve,
//! with the loop's energy both ways.

use crate::bem::frictional_contact::{FrictionalProblem, Increment, InterfaceLaw, NormalCoupling};
use crate::bem::frictional_curve::{self, CurveRequest, LoadTarget};
use crate::bem::{self, ElasticBody};
use crate::fe::{self, CurvePoint, Kinematics, LoadDirection, SolveWork};
use crate::profile::Profile;
use crate::runner::requests::input_checks::InputError;
use crate::runner::requests::loading_points;
use crate::runner::requests::request_error::RequestError;
use crate::runner::requests::solve_outcome::{CycleEnergy, SolveOutcome, SolveRow};
use crate::runner::requests::solve_request::{refused, SolveRequest};
use std::ops::ControlFlow;

/// Loading points when the request names none (`--points`).
pub const DEFAULT_POINTS: usize = 40;

/// Grid points per wavelength when the request names none: 4096, or 64 on the shortest
/// wavelength of a finer profile (Westergaard's p̄ within 3e-4 at 4096, 7e-5 at 8192:
/// docs/verification.md, "Frictional boundary elements").
pub fn default_grid_points(profile: &Profile) -> usize {
    (64 * profile.max_order() as usize)
        .next_power_of_two()
        .max(4096)
}

/// The relative tolerance of the solver's gaps and slips (over `Σ Δ_k`) for a request and for
/// a scene's boundary-element curves.
pub const TOLERANCE: f64 = 1e-10;

/// A checked boundary-element request, ready to solve.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedBemSolve {
    pub request: SolveRequest,
    pub profile: Profile,
    pub body: ElasticBody,
    /// ν of the body, from κ/G.
    pub poisson: f64,
    pub law: InterfaceLaw,
    pub grid_points: usize,
    pub curve: CurveRequest,
}

impl SolveRequest {
    /// The request checked for the boundary-element solver (the ranges shared with the
    /// finite-element solver first, [`SolveRequest::check_ranges`]).
    pub fn prepare_bem(&self) -> Result<PreparedBemSolve, RequestError> {
        self.check_ranges()?;
        self.check_bem_flags()?;
        let profile = Profile {
            aspect_ratio: self.ar,
            finer: self.finer_harmonics,
        };
        let law = InterfaceLaw {
            friction_coefficient: self.mu,
            tau_max_over_estar: self.tau_max_mpa / self.estar_mpa,
        };
        let poisson = fe::poisson_ratio(self.kappa_over_g);
        let body = if self.half_plane {
            ElasticBody::HalfPlane
        } else {
            ElasticBody::Layer {
                thickness: self.thickness_over_lambda,
                poisson,
            }
        };
        let grid_points = self.bem_grid_points(&profile)?;
        let points = loading_points::in_range(self.points.unwrap_or(DEFAULT_POINTS))?;
        let target = match (self.until_p_over_estar, self.until_contact_fraction) {
            (Some(p), _) => LoadTarget::MeanPressure(p),
            (None, Some(c)) => LoadTarget::ContactFraction(c),
            (None, None) => LoadTarget::ContactHalfWidth(self.until_a_over_lambda),
        };
        Ok(PreparedBemSolve {
            request: *self,
            profile,
            body,
            poisson,
            law,
            grid_points,
            curve: CurveRequest {
                target,
                points,
                unload: self.unload,
            },
        })
    }

    /// Refuses what the boundary-element solver does not model (finite kinematics) and the
    /// flags of the finite-element solver.
    fn check_bem_flags(&self) -> Result<(), RequestError> {
        if self.kinematics != Kinematics::Linear {
            return Err(refused(
                "--kinematics",
                self.kinematics.name(),
                "the boundary-element solver is small-strain: pass --kinematics linear",
            ));
        }
        let fe_only = [
            ("--mesh", self.mesh.is_some()),
            ("--coarsen-at-aspect", self.coarsen_at_aspect.is_some()),
            ("--tolerance", self.tolerance.is_some()),
            ("--error-estimate", self.error_estimate),
            ("--max-memory", self.max_memory.is_some()),
        ];
        if let Some((flag, _)) = fe_only.iter().find(|(_, given)| *given) {
            return Err(refused(
                flag,
                "given",
                "belongs to the finite-element solver; the boundary-element solver's grid is --grid-points",
            ));
        }
        if let Some(n) = self.unloading_substeps {
            return Err(refused(
                "--unloading-substeps",
                n,
                "belongs to the finite-element solver; the boundary-element solver unloads back through its loading pressures",
            ));
        }
        Ok(())
    }

    /// The grid points per wavelength, given or the profile's default: a power of two from the
    /// profile's minimum to [`bem::MAX_POINTS_PER_WAVELENGTH`].
    fn bem_grid_points(&self, profile: &Profile) -> Result<usize, RequestError> {
        let grid_points = self
            .grid_points
            .unwrap_or_else(|| default_grid_points(profile));
        let minimum = bem::min_points_per_wavelength(profile);
        if !grid_points.is_power_of_two()
            || grid_points < minimum
            || grid_points > bem::MAX_POINTS_PER_WAVELENGTH
        {
            return Err(InputError::OutOfRange {
                flag: "--grid-points".into(),
                value: grid_points.to_string(),
                allowed: format!("a power of two in [{minimum}, 2^24] for this profile"),
            }
            .into());
        }
        Ok(grid_points)
    }
}

impl PreparedBemSolve {
    /// Solves the curve, handing each converged row to `on_row` as soon as it is committed;
    /// `Break` stops the solve ([`RequestError::Interrupted`]).
    pub fn run(
        &self,
        on_row: &mut dyn FnMut(&SolveRow) -> ControlFlow<()>,
    ) -> Result<SolveOutcome, RequestError> {
        let problem = FrictionalProblem {
            profile: &self.profile,
            body: self.body,
            poisson: self.poisson,
            law: self.law,
            coupling: NormalCoupling::Full,
            points_per_wavelength: self.grid_points,
            tol: TOLERANCE,
        };
        let mut rows: Vec<SolveRow> = vec![];
        let mut friction_work = 0.0;
        let solved = frictional_curve::solve_curve(&problem, &self.curve, &mut |unloading, inc| {
            let branch = if unloading {
                LoadDirection::Unloading
            } else {
                LoadDirection::Loading
            };
            friction_work += inc.dissipation_over_estar_lambda2;
            let row = SolveRow {
                point: curve_point(inc, self.grid_points, friction_work),
                branch,
                error_estimate: None,
            };
            rows.push(row);
            on_row(&row)
        });
        let outcome = |rows: Vec<SolveRow>, energy| SolveOutcome {
            mesh: None,
            grid_points: Some(self.grid_points),
            unknowns: self.grid_points,
            extra: self.request.extra_column(),
            rows,
            work: SolveWork::default(),
            cycle_energy: energy,
        };
        match solved {
            Ok(curve) => {
                let energy = self.curve.unload.then(|| CycleEnergy {
                    cycle_work_over_estar_lambda2: curve.cycle_work_over_estar_lambda2(),
                    face_dissipation_over_estar_lambda2: curve
                        .face_dissipation_over_estar_lambda2(),
                });
                Ok(outcome(rows, energy))
            }
            Err(bem::BemError::Stopped { .. }) => Err(RequestError::Interrupted {
                partial: Box::new(outcome(rows, None)),
            }),
            Err(error) => Err(RequestError::Failed(format!(
                "the boundary-element solver stopped after {} converged points: {error}",
                rows.len()
            ))),
        }
    }
}

/// An increment as a curve point: the rigid approach δ in the slab displacement's column, the
/// alternation's passes in the Newton iterations' column, the contact grid points of the half
/// period `[0, ½]` in the active nodes' column; `friction_work` is the face's work of friction
/// up to and with this increment (over E* λ²).
fn curve_point(inc: &Increment, grid_points: usize, friction_work: f64) -> CurvePoint {
    let half = grid_points / 2;
    CurvePoint {
        a_over_lambda: frictional_curve::outermost_edge(inc),
        p_over_estar: inc.p_over_estar,
        p_over_estar_reaction: inc.p_over_estar,
        slab_displacement_over_lambda: inc.approach_over_lambda,
        newton_iterations: inc.passes,
        active_nodes: inc.state.pressure_over_estar[..=half]
            .iter()
            .filter(|&&p| p > 0.0)
            .count(),
        contact_fraction: inc.contact_fraction,
        patches: inc.patches.len(),
        stick_fraction: inc.stick_fraction,
        stick_half_width_over_lambda: inc.stick_half_width_over_lambda,
        friction_work_over_estar_lambda2: friction_work,
    }
}
