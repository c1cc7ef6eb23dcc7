//! The parameter domain the WNL polynomials were fitted on (docs/replication.md R5).

/// A rectangle in (AR, τ_max) on which correction coefficients were fitted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitDomain {
    pub aspect_ratio_min: f64,
    pub aspect_ratio_max: f64,
    pub tau_max_mpa_min: f64,
    pub tau_max_mpa_max: f64,
}

impl FitDomain {
    /// The paper's domain: AR ∈ [0.1, 0.3], τ_max ∈ [0, 0.2] MPa (R5, R6).
    pub const PAPER: FitDomain = FitDomain {
        aspect_ratio_min: 0.1,
        aspect_ratio_max: 0.3,
        tau_max_mpa_min: 0.0,
        tau_max_mpa_max: 0.2,
    };

    /// True when (AR, τ_max) lies inside the closed rectangle (with a relative slack of
    /// 1e-12, so that grid points computed as min + i·step on the boundary count as inside).
    pub fn contains(&self, aspect_ratio: f64, tau_max_mpa: f64) -> bool {
        let slack = 1e-12;
        aspect_ratio >= self.aspect_ratio_min * (1.0 - slack)
            && aspect_ratio <= self.aspect_ratio_max * (1.0 + slack)
            && tau_max_mpa >= self.tau_max_mpa_min - slack * self.tau_max_mpa_max
            && tau_max_mpa <= self.tau_max_mpa_max * (1.0 + slack)
    }
}
