//! Frictional contact on the periodic half-plane or a layer bonded to a rigid base: a rigid even
//! profile pressed by a mean pressure onto a compressible linear elastic body with Coulomb–Orowan
//! friction, the slip history carried from increment to increment (loading and unloading).
//!
//! Units: lengths over λ, tractions over E*.
//!
//! # Coupling
//!
//! With `p` the contact pressure and `q` the shear traction on the solid (along `+x`), the
//! half-plane's surface displacements (`u_z` into the solid, `u_x` along `+x`) follow from
//! Johnson's eqs. 2.25 (*Contact Mechanics*, 1985), harmonic by harmonic:
//!
//! ```text
//! u_z = K p + β K H q,     u_x = K q − β K H p
//! ```
//!
//! `K` the frictionless compliance (`2/(E*|q_k|)`), `H` the periodic Hilbert transform
//! (`H cos = sin`), `β = (1 − 2ν)/(2(1 − ν))` Dundurs' parameter for a rigid indenter. The
//! operator is symmetric and positive definite for `|β| < 1`. With `β = 0` (incompressible)
//! the normal and tangential problems decouple and normal loading makes no shear. A layer
//! scales each harmonic of the three operators by its own ratios,
//! `u_z = K_n p + K_c H q`, `u_x = K_t q − K_c H p` ([`super::HarmonicCompliance`]); below the
//! half-plane's `β K` stands for `K_c`, `K` for `K_n` in the normal and `K_t` in the tangential
//! problem. A bonded layer is coupled even when incompressible.
//!
//! # One increment (from the committed state to the mean pressure `p̄`)
//!
//! The slip of the increment is `Δu_x` (the rigid surface does not move sideways); the law: stick
//! (`Δu_x = 0`) where `|q| < f`, else `q = −f sign(Δu_x)`, `f = min(μ p, τ_max)`, `q = 0` off
//! the contact. The increment alternates two solves until `q` stops changing:
//! 1. the normal problem for `p` at `q` fixed: frictionless contact of the shifted surface
//!    `s + β K H q` ([`super::polonsky_keer`], from the last pressure);
//! 2. the tangential problem for `q` at `p` fixed: the bound-constrained minimum of
//!    `½ qᵀKq + qᵀ(−β K H p − u_x⁰)` with `|q| ≤ f(p)` ([`super::shear_active_set`]), whose gradient is the
//!    slip and whose optimality conditions are the law.
//!
//! [`NormalCoupling::Goodman`] drops `β K H q` from step 1 (Goodman's approximation: the
//! pressure is the frictionless one), which makes the increment a single pass.
//!
//! The slip is backward Euler: the law holds for the increment's slip at its end state, so the
//! dissipation of the increment is `Σ_i |q_i| |Δu_x,i| / N` per wavelength (E* λ²), which
//! [`Increment`] reports for the energy audit.

use super::grid::GridCompliance;
use super::polonsky_keer::{self, Stalled};
use super::{edges, shear_active_set, BemError};
use super::{ElasticBody, HarmonicCompliance};
use crate::profile::Profile;

/// Whether the shear traction acts back on the normal problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalCoupling {
    /// Both ways (the elastic solution).
    Full,
    /// Goodman's approximation: the pressure as without friction, the shear from it.
    Goodman,
}

/// The interface law: Coulomb–Orowan, `|q| ≤ min(μ p, τ_max)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InterfaceLaw {
    /// Friction coefficient μ (≥ 0).
    pub friction_coefficient: f64,
    /// Shear strength τ_max/E* (≥ 0; `f64::INFINITY` for pure Coulomb).
    pub tau_max_over_estar: f64,
}

impl InterfaceLaw {
    /// Whether any shear can be carried (`μ > 0` and `τ_max > 0`).
    pub fn admits_friction(&self) -> bool {
        self.friction_coefficient > 0.0 && self.tau_max_over_estar > 0.0
    }

    /// The slip threshold `min(μ p, τ_max)` at the pressure `p` (0 off the contact).
    pub fn threshold(&self, p: f64) -> f64 {
        if p > 0.0 {
            (self.friction_coefficient * p).min(self.tau_max_over_estar)
        } else {
            0.0
        }
    }
}

/// A frictional problem on the half-plane or a layer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrictionalProblem<'a> {
    pub profile: &'a Profile,
    /// The half-plane, or a layer bonded to a rigid base.
    pub body: ElasticBody,
    /// Poisson ratio ν of the body (`−1 < ν ≤ ½`; a layer's own, which it must equal).
    pub poisson: f64,
    pub law: InterfaceLaw,
    pub coupling: NormalCoupling,
    /// Grid points per wavelength (a power of two, at least
    /// [`super::min_points_per_wavelength`]).
    pub points_per_wavelength: usize,
    /// Relative tolerance (`0 < tol < 1`): gaps and slips within `tol · Σ Δ_k`.
    pub tol: f64,
}

/// The state an increment starts from.
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionalState {
    /// `p/E*` on the grid.
    pub pressure_over_estar: Vec<f64>,
    /// `q/E*` on the grid (odd).
    pub shear_over_estar: Vec<f64>,
    /// `u_x/λ` on the grid, the tangential displacement the next slip is measured from.
    pub tangential_displacement_over_lambda: Vec<f64>,
}

/// One converged increment: the end state and what it measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Increment {
    pub state: FrictionalState,
    /// `g/λ` on the grid.
    pub gap_over_lambda: Vec<f64>,
    /// The mean pressure `p̄/E*`.
    pub p_over_estar: f64,
    /// `δ/λ`: the rigid peak past the mean plane of the deformed surface.
    pub approach_over_lambda: f64,
    /// Contact intervals in `[0, ½]` ([`edges::patches`]).
    pub patches: Vec<[f64; 2]>,
    /// Total contact length over λ.
    pub contact_fraction: f64,
    /// Stick length over λ: the runs of contact points below their slip threshold, each half a
    /// grid step beyond its end points and cut at its patch's edges ([`stick_intervals`]).
    pub stick_fraction: f64,
    /// Half-width over λ of the stick zone through the peak (`x = 0`): halfway between its last
    /// stick point and the first slip point, or the patch edge when the whole patch sticks.
    pub stick_half_width_over_lambda: f64,
    /// `Σ |q| |Δu_x| / N`: the work of friction at the face in this increment, over E* λ²
    /// (per unit length of ridge and per wavelength).
    pub dissipation_over_estar_lambda2: f64,
    /// Normal and tangential passes of the alternation.
    pub passes: usize,
    /// Conjugate-gradient iterations of all passes, normal and tangential.
    pub iterations: usize,
}

/// The converged grid fields of an increment (units of the module doc).
struct Fields {
    pressure: Vec<f64>,
    shear: Vec<f64>,
    gap: Vec<f64>,
    /// `Δu_x` of the increment.
    slip: Vec<f64>,
    /// `δ`.
    approach: f64,
}

/// The alternation's cap (each pass contracts the change of `q` by about `β²` on the half-plane,
/// by up to `S_c²/(S_n S_t)` on a layer: ¾ for a thin incompressible one).
const MAX_PASSES: usize = 200;

/// The frictional solver of one problem: its grid, operator and committed state.
pub struct FrictionalContact {
    law: InterfaceLaw,
    coupling: NormalCoupling,
    depth: Vec<f64>,
    /// `K_n`, `K_t` and `K_c` of the module doc.
    normal_op: GridCompliance,
    tangential_op: GridCompliance,
    coupling_op: GridCompliance,
    /// The relative tolerance and the absolute one it gives gaps and slips (`tol · Σ Δ_k`, λ).
    tol: f64,
    tol_abs: f64,
    full_contact: f64,
    committed: FrictionalState,
}

impl FrictionalContact {
    /// The problem checked and its operator built, in the unloaded state.
    pub fn new(problem: &FrictionalProblem) -> Result<Self, BemError> {
        let profile = Profile::new(&problem.profile.harmonics().collect::<Vec<_>>())?;
        let n = problem.points_per_wavelength;
        check_inputs(problem, &profile)?;
        let depth: Vec<f64> = (0..n).map(|i| -profile.y(i as f64 / n as f64)).collect();
        let matrix = |q| HarmonicCompliance::of(problem.body, q, problem.poisson);
        let coupling_op = GridCompliance::scaled(n, |q| Ok(matrix(q)?.coupling))?;
        Ok(Self {
            law: problem.law,
            coupling: problem.coupling,
            depth,
            normal_op: GridCompliance::scaled(n, |q| Ok(matrix(q)?.normal))?,
            tangential_op: GridCompliance::scaled(n, |q| Ok(matrix(q)?.tangential))?,
            coupling_op,
            tol: problem.tol,
            tol_abs: problem.tol * profile.amplitude_sum(),
            full_contact: super::full_contact_pressure_on(&profile, problem.body)?,
            committed: FrictionalState {
                pressure_over_estar: vec![0.0; n],
                shear_over_estar: vec![0.0; n],
                tangential_displacement_over_lambda: vec![0.0; n],
            },
        })
    }

    /// The committed state.
    pub fn state(&self) -> &FrictionalState {
        &self.committed
    }

    /// Makes `increment`'s end state the one the next increment starts from.
    pub fn commit(&mut self, increment: &Increment) {
        self.committed = increment.state.clone();
    }

    /// The increment from the committed state to the mean pressure `p_over_estar` (not
    /// committed).
    pub fn increment(&mut self, p_over_estar: f64) -> Result<Increment, BemError> {
        self.check_mean_pressure(p_over_estar)?;
        let (n, tol) = (self.depth.len(), self.tol);
        let stalled = |s: Stalled| BemError::NoConvergence {
            p_over_estar,
            points: n,
            iterations: s.iterations,
            residual: s.residual,
            tol,
            reason: s.reason,
        };
        let mut q = self.committed.shear_over_estar.clone();
        let mut p = self.committed.pressure_over_estar.clone();
        let mut iterations = 0;
        let max_iterations = super::max_iterations(n);
        let mut change = f64::INFINITY;
        for pass in 1..=MAX_PASSES {
            let shifted = self.shifted_surface(&q);
            let normal = polonsky_keer::solve(
                Some(p),
                &shifted,
                p_over_estar,
                &mut self.normal_op,
                self.tol_abs,
                max_iterations,
            )
            .map_err(stalled)?;
            iterations += normal.iterations;
            let shear = self
                .tangential(&normal.pressure, q.clone(), max_iterations)
                .map_err(stalled)?;
            iterations += shear.iterations;
            change = q
                .iter()
                .zip(&shear.shear)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            q = shear.shear;
            p = normal.pressure;
            let settled = self.coupling == NormalCoupling::Goodman
                || self.coupling_op.is_zero()
                || change * self.tangential_op.diagonal() <= self.tol_abs;
            if settled {
                let fields = Fields {
                    pressure: p,
                    shear: q,
                    gap: normal.gap,
                    slip: shear.slip,
                    approach: normal.approach,
                };
                return Ok(self.measure(fields, pass, iterations));
            }
        }
        Err(stalled(Stalled {
            iterations: MAX_PASSES,
            residual: change * self.tangential_op.diagonal() / self.tol_abs,
            reason: "the normal–tangential alternation did not settle",
        }))
    }

    /// A mean pressure an increment can reach: finite, positive and below full contact.
    fn check_mean_pressure(&self, p_over_estar: f64) -> Result<(), BemError> {
        if !(p_over_estar.is_finite() && p_over_estar > 0.0) {
            return Err(BemError::InvalidInput {
                field: "mean pressure p̄/E*",
                value: p_over_estar,
                allowed: "finite, > 0",
            });
        }
        if p_over_estar >= self.full_contact {
            return Err(BemError::FullContact {
                p_over_estar,
                full_contact: self.full_contact,
            });
        }
        Ok(())
    }

    /// The surface the normal problem sees at the shear `q`: the profile's depth shifted by the
    /// normal displacement the shear makes, `β K H q` (the depth itself under Goodman's
    /// approximation or without coupling).
    fn shifted_surface(&mut self, q: &[f64]) -> Vec<f64> {
        let mut shifted = self.depth.clone();
        if self.coupling == NormalCoupling::Full && !self.coupling_op.is_zero() {
            let mut scratch = vec![0.0; q.len()];
            self.coupling_op.apply_hilbert(q, &mut scratch);
            for (si, &hi) in shifted.iter_mut().zip(&scratch) {
                *si += hi;
            }
        }
        shifted
    }

    /// The tangential problem at the pressure `pressure`, from the shear `start`: the shear
    /// bounded by the law's threshold whose slip from the committed tangential displacement
    /// obeys the law.
    fn tangential(
        &mut self,
        pressure: &[f64],
        start: Vec<f64>,
        max_iterations: usize,
    ) -> Result<shear_active_set::ShearSolution, Stalled> {
        let bound: Vec<f64> = pressure.iter().map(|&pi| self.law.threshold(pi)).collect();
        let mut scratch = vec![0.0; pressure.len()];
        self.coupling_op.apply_hilbert(pressure, &mut scratch);
        let b: Vec<f64> = scratch
            .iter()
            .zip(&self.committed.tangential_displacement_over_lambda)
            .map(|(&hp, &u0)| -hp - u0)
            .collect();
        shear_active_set::solve(
            start,
            &b,
            &bound,
            &mut self.tangential_op,
            self.tol_abs,
            max_iterations,
        )
    }

    /// The increment's measures from its converged fields.
    fn measure(&self, fields: Fields, passes: usize, iterations: usize) -> Increment {
        let Fields {
            pressure: p,
            shear: q,
            gap,
            slip,
            approach,
        } = fields;
        let n = p.len();
        let patches = edges::patches(&p, &gap);
        let contact_fraction = 2.0 * patches.iter().map(|[a, b]| b - a).sum::<f64>();
        let sticks: Vec<bool> = (0..=n / 2)
            .map(|i| p[i] > 0.0 && q[i].abs() < self.law.threshold(p[i]))
            .collect();
        let stick_runs = stick_intervals(&sticks, &patches, n);
        let stick_half_width = match stick_runs.first() {
            Some(&[0.0, end]) => end,
            _ => 0.0,
        };
        let dissipation = q
            .iter()
            .zip(&slip)
            .map(|(qi, si)| (qi * si).abs())
            .sum::<f64>()
            / n as f64;
        let u_x: Vec<f64> = self
            .committed
            .tangential_displacement_over_lambda
            .iter()
            .zip(&slip)
            .map(|(u0, s)| u0 + s)
            .collect();
        Increment {
            p_over_estar: p.iter().sum::<f64>() / n as f64,
            state: FrictionalState {
                pressure_over_estar: p,
                shear_over_estar: q,
                tangential_displacement_over_lambda: u_x,
            },
            gap_over_lambda: gap,
            approach_over_lambda: approach,
            contact_fraction,
            patches,
            stick_fraction: 2.0 * stick_runs.iter().map(|[a, b]| b - a).sum::<f64>(),
            stick_half_width_over_lambda: stick_half_width,
            dissipation_over_estar_lambda2: dissipation,
            passes,
            iterations,
        }
    }
}

/// The stick intervals in `[0, ½]` of the grid's stick flags on `0 ..= N/2` (`n` = N): each run
/// of stick points spans half a grid step beyond its end points, cut to the contact patch that
/// holds it (whose edges lie between grid points), so that a patch that sticks whole sticks
/// over its contact length exactly.
fn stick_intervals(sticks: &[bool], patches: &[[f64; 2]], n: usize) -> Vec<[f64; 2]> {
    let h = 1.0 / n as f64;
    let last = sticks.len() - 1;
    let mut out = vec![];
    let mut i = 0;
    while i <= last {
        if !sticks[i] {
            i += 1;
            continue;
        }
        let first = i;
        while i < last && sticks[i + 1] {
            i += 1;
        }
        let x = first as f64 * h;
        let patch = patches
            .iter()
            .find(|[a, b]| *a <= x + 0.5 * h && x - 0.5 * h <= *b)
            .copied()
            .unwrap_or([0.0, 0.5]);
        let start = if first == 0 {
            0.0
        } else {
            ((first as f64 - 0.5) * h).max(patch[0])
        };
        let end = if i == last {
            0.5
        } else {
            ((i as f64 + 0.5) * h).min(patch[1])
        };
        out.push([start, end]);
        i += 1;
    }
    out
}

/// The ranges of a frictional problem.
fn check_inputs(problem: &FrictionalProblem, profile: &Profile) -> Result<(), BemError> {
    let invalid = |field, value, allowed| {
        Err(BemError::InvalidInput {
            field,
            value,
            allowed,
        })
    };
    let nu = problem.poisson;
    if !(nu.is_finite() && nu > -1.0 && nu <= 0.5) {
        return invalid("Poisson ratio ν", nu, "−1 < ν ≤ ½");
    }
    let mu = problem.law.friction_coefficient;
    if !(mu.is_finite() && mu >= 0.0) {
        return invalid("friction coefficient μ", mu, "finite, ≥ 0");
    }
    let tau = problem.law.tau_max_over_estar;
    if tau.is_nan() || tau < 0.0 {
        return invalid("shear strength τ_max/E*", tau, "≥ 0 (∞ allowed)");
    }
    let tol = problem.tol;
    if !(tol.is_finite() && tol > 0.0 && tol < 1.0) {
        return invalid("relative tolerance", tol, "0 < tol < 1");
    }
    if let ElasticBody::Layer { poisson, .. } = problem.body {
        if poisson != nu {
            return invalid("Poisson ratio ν of the layer", poisson, "the problem's ν");
        }
    }
    super::check_grid(profile, problem.points_per_wavelength)
}
