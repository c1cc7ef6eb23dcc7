//! Rigid sinusoidal indenter and the interface law.
//!
//! Indenter surface (units of λ, amplitude `Δ/λ = AR`):
//!
//! ```text
//! y_s(x)   = −Δ (1 − cos 2πx)
//! y_s'(x)  = −2πΔ sin 2πx
//! y_s''(x) = −4π²Δ cos 2πx
//! ```
//!
//! Its peak `x = 0` touches the undeformed layer at zero load.
//!
//! # Contact enforcement (exact, by nonlinear elimination)
//! A contact-face node is *active* when it lies on the surface. For finite kinematics
//! its current `y` is eliminated, `y = y_s(x)`, and it keeps one unknown, its current
//! `x`: the node slides along the indenter without friction. By the chain rule the
//! reduced residual and tangent of that unknown are
//!
//! ```text
//! r_x = ∂Π/∂x + y_s' ∂Π/∂y
//! K_xx = [1, y_s'] H_node [1, y_s']ᵀ + y_s'' ∂Π/∂y
//! ```
//!
//! so frictionless contact stays an energy minimisation with a symmetric tangent. The
//! contact force exerted by the indenter on the node is `λ (−y_s', 1)` with the
//! multiplier `λ = ∂Π/∂y ≥ 0`. For linear kinematics the gap is evaluated at the
//! reference `X`: an active node has `u_y = y_s(X)` and a free `u_x`.
//!
//! Active-set update after each converged Newton solve: release every active node with
//! `λ < 0`, activate every free node that penetrates (`y < y_s(x)`, projecting it onto
//! the surface), and repeat until the set is stable.
//!
//! # Friction (regularised Coulomb–Orowan, REPLICATION.md R3)
//! With [`Interface::CoulombOrowan`] the indenter also exerts a tangential force `T` on
//! each active node, along the surface tangent `t = (1, y_s')/w`, `w = √(1 + y_s'²)`. The
//! normal force is `N = n·g = (g_y − y_s' g_x)/w` (`g = ∂Π/∂x` the node's internal force,
//! `n = (−y_s', 1)/w`), and the nodal slip threshold is the traction bound
//! `τ_sl = min(μ p, τ_max)` integrated over the node's tributary length `ℓ` on the deformed
//! face (half of each adjacent face segment, chords):
//!
//! ```text
//! L = min(μ N, τ_max ℓ)
//! ```
//!
//! Stick is regularised as in penalty friction: the tangential force grows with the
//! *elastic slip* `e` and reaches the threshold at `e_c` (a small fraction of the element
//! size, [`CoulombOrowan::elastic_slip_over_element`]). Return mapping, per load step,
//! from the committed history `(e_n, S_n)` (elastic slip and arc-length position on the
//! indenter at the last converged step):
//!
//! ```text
//! e* = e_n + S(x) − S_n            (trial elastic slip; S the arc length along y_s)
//! φ  = e*/e_c  if |e*| ≤ e_c (stick),   sign(e*) otherwise (slip)
//! T  = −L φ                        (opposes the slip)
//! ```
//!
//! and on convergence `e_{n+1} = e_c φ`, `S_{n+1} = S(x)`. The reduced residual of the
//! node's sliding unknown becomes `r_x = (1, y_s')·g + w L φ` (zero: the tangential
//! internal force balances the friction force). In the Coulomb regime
//! `w L φ = μ φ (−y_s', 1)·g`, so the friction row is a modified left vector on the
//! element Hessian rows; in the Orowan regime it depends on the neighbours' positions
//! through `ℓ`. The tangent is not symmetric (LU instead of Cholesky). With
//! [`Interface::Frictionless`] none of this is built. For linear kinematics the same law
//! acts on `u_x` at the reference position (`y_s' = 0`, `S = x`).

/// Interface law between the layer and the indenter.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Interface {
    /// Adhesionless, frictionless.
    #[default]
    Frictionless,
    /// Adhesionless, regularised Coulomb–Orowan friction.
    CoulombOrowan(CoulombOrowan),
}

impl Interface {
    /// The interface for friction coefficient `μ` and shear strength `τ_max/E*`:
    /// frictionless when either is zero (`τ_sl = min(μ p, τ_max) ≡ 0`), so that no
    /// friction machinery is built for a frictionless scene.
    pub fn coulomb_orowan(
        friction_coefficient: f64,
        tau_max_over_estar: f64,
        elastic_slip_over_element: f64,
    ) -> Self {
        if friction_coefficient == 0.0 || tau_max_over_estar == 0.0 {
            Interface::Frictionless
        } else {
            Interface::CoulombOrowan(CoulombOrowan {
                friction_coefficient,
                tau_max_over_estar,
                elastic_slip_over_element,
            })
        }
    }
}

/// Regularised Coulomb–Orowan friction, `τ_sl = min(μ p, τ_max)` (REPLICATION.md R3).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CoulombOrowan {
    /// Friction coefficient `μ` (> 0).
    pub friction_coefficient: f64,
    /// Interfacial shear strength over the plane-strain modulus, `τ_max/E*` (> 0).
    pub tau_max_over_estar: f64,
    /// Elastic slip at which the full threshold is mobilised, over the mean element length
    /// along the contact face (> 0). Abaqus's penalty friction uses 0.005 by default.
    pub elastic_slip_over_element: f64,
}

/// Rigid sinusoidal indenter `y_s(x) = −Δ (1 − cos 2πx)`.
#[derive(Clone, Copy, Debug)]
pub struct Indenter {
    /// Amplitude `Δ/λ` (the aspect ratio).
    pub amplitude: f64,
}

impl Indenter {
    /// `y_s(x)`.
    pub fn y(&self, x: f64) -> f64 {
        -self.amplitude * (1.0 - (std::f64::consts::TAU * x).cos())
    }
    /// `y_s'(x)`.
    pub fn slope(&self, x: f64) -> f64 {
        -self.amplitude * std::f64::consts::TAU * (std::f64::consts::TAU * x).sin()
    }
    /// `y_s''(x)`.
    pub fn curvature(&self, x: f64) -> f64 {
        let t = std::f64::consts::TAU;
        -self.amplitude * t * t * (t * x).cos()
    }
    /// Arc length along the surface from `x0` to `x1` (signed), `∫ √(1 + y_s'²) dx`, by
    /// 8-point Gauss–Legendre quadrature: the integrand is analytic, so for the short
    /// intervals of one load step (≪ λ) the rule is exact to round-off.
    pub fn arc_length(&self, x0: f64, x1: f64) -> f64 {
        const NODES: [f64; 4] = [
            0.183_434_642_495_649_8,
            0.525_532_409_916_329,
            0.796_666_477_413_626_7,
            0.960_289_856_497_536_3,
        ];
        const WEIGHTS: [f64; 4] = [
            0.362_683_783_378_362,
            0.313_706_645_877_887_3,
            0.222_381_034_453_374_5,
            0.101_228_536_290_376_3,
        ];
        if self.amplitude == 0.0 {
            return x1 - x0;
        }
        let (mid, half) = (0.5 * (x0 + x1), 0.5 * (x1 - x0));
        let w = |x: f64| (1.0 + self.slope(x).powi(2)).sqrt();
        half * NODES
            .iter()
            .zip(WEIGHTS)
            .map(|(&t, c)| c * (w(mid - half * t) + w(mid + half * t)))
            .sum::<f64>()
    }
}
