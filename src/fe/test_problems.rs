//! The problem of the solver's unit tests: a sinusoid on a layer one wavelength thick (finite
//! kinematics, κ/G 1000), meshed coarse.

use crate::fe::{Interface, Kinematics, LayerProblem, MeshLevel, SolveOptions};

/// The sinusoid of aspect ratio `aspect_ratio` with `interface`, and the default options on
/// the coarse mesh (32 × 16 elements).
pub(crate) fn coarse_sinusoid(
    aspect_ratio: f64,
    interface: Interface,
) -> (LayerProblem, SolveOptions) {
    let problem = LayerProblem {
        aspect_ratio,
        finer_harmonics: crate::profile::FinerHarmonics::NONE,
        thickness_over_lambda: 1.0,
        kappa_over_g: 1000.0,
        kinematics: Kinematics::Finite,
        interface,
    };
    let opts = SolveOptions {
        mesh: MeshLevel::Coarse,
        ..SolveOptions::default()
    };
    (problem, opts)
}
