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
//! # Extension to friction
//! The interface law is selected by [`Interface`]. A frictional law (regularised
//! Coulomb–Orowan, return mapping on the tangential traction) will add a variant that
//! carries the slip history per contact node and contributes a tangential nodal force
//! and a (non-symmetric) tangent to the active node's sliding unknown; with
//! [`Interface::Frictionless`] nothing of that is built.

/// Interface law between the layer and the indenter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Interface {
    /// Adhesionless, frictionless.
    #[default]
    Frictionless,
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
}
