//! How many loading points a request asks for (`--points`): the range both solvers take, and the
//! finite-element solver's default, which only a frictionless sinusoid, loaded only, takes.

use crate::runner::requests::input_checks::{out_of_range, InputError};

/// Finite-element loading points of a frictionless sinusoid, loaded only, when the request names
/// none: steps of 0.01 in a/λ to the default target 0.45, about 40 points at any mesh, each an
/// edge event on the node-by-node curve (docs/performance.md, "frictionless steps over several
/// nodes").
pub const DEFAULT_FE_POINTS: usize = 45;

/// `points` when it is a number of loading points (`--points`) both solvers take, in
/// [2, 10000], else an error naming the flag.
pub fn in_range(points: usize) -> Result<usize, InputError> {
    match (2..=10_000).contains(&points) {
        true => Ok(points),
        false => Err(out_of_range("--points", points, "[2, 10000]")),
    }
}

/// What decides a finite-element curve's loading points besides the number asked for.
#[derive(Debug, Clone, Copy)]
pub struct FeCurve {
    /// With friction (τ_max > 0).
    pub frictional: bool,
    /// A profile with finer harmonics, not a single sinusoid.
    pub profile: bool,
    /// Unloaded after loading (a loop).
    pub unload: bool,
}

/// The finite-element loading points of `curve`: `asked`, checked (in range, and only for a
/// frictionless sinusoid), or for a frictionless sinusoid loaded only, [`DEFAULT_FE_POINTS`];
/// `None`, node by node, otherwise. A frictional curve steps node by node (its friction history
/// is where each node touched, [`crate::fe::StepOptions::da_target_for`]); a profile's steps
/// are its contact events, patches born and merging wherever they come; a loop unloads through
/// its loading steps, and an unloading step across several nodes' releases costs Newton
/// several times the iterations (docs/performance.md, "frictionless steps over several nodes").
pub fn fe_points(asked: Option<usize>, curve: FeCurve) -> Result<Option<usize>, InputError> {
    let Some(n) = asked else {
        let grid = !curve.frictional && !curve.profile && !curve.unload;
        return Ok(grid.then_some(DEFAULT_FE_POINTS));
    };
    let n = in_range(n)?;
    let refused = |reason: &str| InputError::Refused {
        flag: "--points".into(),
        value: n.to_string(),
        reason: reason.into(),
    };
    if curve.frictional {
        return Err(refused(
            "is for a frictionless curve; a frictional one steps node by node, each node's friction anchored where it touches",
        ));
    }
    if curve.profile {
        return Err(refused(
            "is for a single sinusoid; a profile steps from contact event to contact event",
        ));
    }
    Ok(Some(n))
}
