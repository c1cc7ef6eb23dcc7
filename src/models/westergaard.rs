//! Westergaard's solution for a rigid sinusoid on a linear elastic half-plane, frictionless
//! (Westergaard 1939; docs/replication.md R4):
//!
//! p̄(a) = π E* (Δ/λ) sin²(π a/λ),  full contact at p* = π E* Δ/λ.

use super::PressureLaw;
use std::f64::consts::PI;

/// Westergaard's law for one aspect ratio AR = Δ/λ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Westergaard {
    /// Δ/λ, amplitude over wavelength (dimensionless, > 0).
    pub aspect_ratio: f64,
}

impl Westergaard {
    pub fn new(aspect_ratio: f64) -> Self {
        Self { aspect_ratio }
    }
}

impl PressureLaw for Westergaard {
    fn p_over_estar(&self, a_over_lambda: f64) -> f64 {
        let s = (PI * a_over_lambda).sin();
        PI * self.aspect_ratio * s * s
    }

    fn full_contact_p_over_estar(&self) -> f64 {
        PI * self.aspect_ratio
    }
}
