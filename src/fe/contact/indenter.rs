//! Rigid indenter and normal contact.
//!
//! Indenter surface (units of λ): an even periodic profile ([`crate::profile`]), for a single
//! sinusoid of amplitude `Δ/λ = AR`:
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
//! `x`: the node slides along the indenter. Without friction, by the chain rule the
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
//! # Friction
//! With [`crate::fe::Interface::CoulombOrowan`] an active node also carries a tangential
//! friction force; its law, return mapping and tangent rows are in [`crate::fe::contact::friction`].

use crate::profile::Profile;

/// Rigid indenter of an even periodic profile ([`Profile`]; the single sinusoid
/// `y_s(x) = −Δ (1 − cos 2πx)` is `1:AR`).
#[derive(Clone, Copy, Debug)]
pub struct Indenter {
    /// The surface profile.
    pub profile: Profile,
}

impl Indenter {
    /// The single sinusoid of amplitude `Δ/λ = AR`.
    pub fn sinusoid(aspect_ratio: f64) -> Self {
        Self {
            profile: Profile::sinusoid(aspect_ratio),
        }
    }
    /// The scale of gaps and of the first load step: `Σ Δ_k/λ` (`Δ/λ` of a sinusoid).
    pub fn amplitude(&self) -> f64 {
        self.profile.amplitude_sum()
    }
    /// `y_s(x)`.
    pub fn y(&self, x: f64) -> f64 {
        self.profile.y(x)
    }
    /// `y_s'(x)`.
    pub fn slope(&self, x: f64) -> f64 {
        self.profile.slope(x)
    }
    /// `y_s''(x)`.
    pub fn curvature(&self, x: f64) -> f64 {
        self.profile.curvature(x)
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
        if self.amplitude() == 0.0 {
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
