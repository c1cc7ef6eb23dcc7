//! The mesh of a profile: without an explicit mesh, the coarsest one at least as fine as the
//! default that resolves the profile's finest harmonic (said in a note); an explicit mesh that
//! cannot is refused, naming the smallest that can. The rule a mesh must meet is the solver's
//! own ([`fe::validate`]), so the choice and the check cannot disagree.

use crate::fe::{self, LayerProblem, MeshLevel, SolveOptions};
use crate::runner::requests::input_checks::InputError;

/// The mesh to solve `problem` on, and the note that says it was chosen (for a profile given no
/// mesh, when the default is too coarse). `explicit`: the caller named `options.mesh`.
pub fn choose(
    problem: &LayerProblem,
    options: &SolveOptions,
    explicit: bool,
) -> Result<(MeshLevel, Option<String>), InputError> {
    let profile = problem.profile();
    let refused = |flag: &str, value: String, reason: String| InputError::Refused {
        flag: flag.into(),
        value,
        reason,
    };
    let unresolved = match fe::validate(problem, options) {
        Err(e @ fe::SolveError::ProfileUnresolved { .. }) => e,
        Err(e @ fe::SolveError::ProfileTooSteep { .. }) => {
            return Err(refused("--profile", profile.to_string(), e.to_string()))
        }
        // resolved, or an error the solve itself reports
        _ => return Ok((options.mesh, None)),
    };
    let given = options.mesh;
    let (nx, ny) = given.counts();
    let Some(smallest) = coarsest_resolving(problem, options, nx + 1) else {
        return Err(refused(
            "--profile",
            profile.to_string(),
            format!(
                "{unresolved}; no allowed mesh (up to {} elements along the face) resolves it: drop the harmonic or lower its order",
                MeshLevel::ELEMENTS_ALONG_FACE.end()
            ),
        ));
    };
    let n = smallest.counts().0;
    if explicit {
        return Err(refused(
            "--mesh",
            given.to_string(),
            format!("{unresolved}; the coarsest mesh that resolves it is {n} (--mesh {n})"),
        ));
    }
    let (sx, sy) = smallest.counts();
    let note = format!(
        "the profile {profile} needs a finer mesh than the default {nx}×{ny}: solving on {sx}×{sy}, the coarsest that resolves its finest harmonic (at least {} face elements per harmonic wavelength)",
        fe::MIN_ELEMENTS_PER_HARMONIC_WAVELENGTH
    );
    Ok((smallest, Some(note)))
}

/// The coarsest mesh of at least `from` elements along the face on which `problem` is
/// resolved, if an allowed one is.
fn coarsest_resolving(
    problem: &LayerProblem,
    options: &SolveOptions,
    from: usize,
) -> Option<MeshLevel> {
    (from..=*MeshLevel::ELEMENTS_ALONG_FACE.end())
        .map(MeshLevel::along_face)
        .find(|&mesh| {
            !matches!(
                fe::validate(problem, &SolveOptions { mesh, ..*options }),
                Err(fe::SolveError::ProfileUnresolved { .. })
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::runner::requests::solve_request::SolveRequest;

    fn prepared(profile: &str, mesh: Option<MeshLevel>) -> Result<MeshLevel, String> {
        let p: crate::profile::Profile = profile.parse().unwrap();
        let request = SolveRequest {
            mesh,
            ..SolveRequest::with_profile(&p)
        };
        request
            .prepare()
            .map(|s| s.mesh())
            .map_err(|e| e.to_string())
    }

    /// A profile steeper than the verified finite-strain limit (Σ 2π AR_k = 2.199 > 1.885) is
    /// refused by the solver's check under finite kinematics, on the mesh that resolves it, and
    /// taken under linear kinematics, which has no slope limit.
    #[test]
    fn the_slope_limit_is_finite_strains_alone() {
        let p: crate::profile::Profile = "1:0.05,4:0.1,16:0.2".parse().unwrap();
        let linear = SolveRequest {
            kinematics: crate::fe::Kinematics::Linear,
            ..SolveRequest::with_profile(&p)
        }
        .prepare()
        .unwrap();
        assert!(fe::validate(&linear.problem, &linear.options).is_ok());
        let finite = LayerProblem {
            kinematics: crate::fe::Kinematics::Finite,
            ..linear.problem
        };
        assert!(matches!(
            fe::validate(&finite, &linear.options),
            Err(fe::SolveError::ProfileTooSteep { .. })
        ));
    }

    #[test]
    fn a_profile_without_mesh_gets_the_coarsest_resolving_mesh_and_one_coarser_is_refused() {
        let chosen = prepared("1:0.1,8:0.05", None).unwrap();
        let n = chosen.counts().0;
        assert!(n > 48, "{chosen:?}");
        // the one coarser does not resolve it, and naming it is refused with the chosen one
        let e = prepared("1:0.1,8:0.05", Some(MeshLevel::along_face(n - 1))).unwrap_err();
        assert!(e.starts_with(&format!("--mesh = {}", n - 1)), "{e}");
        assert!(e.ends_with(&format!("(--mesh {n})")), "{e}");
        assert_eq!(
            prepared("1:0.1,8:0.05", Some(MeshLevel::along_face(n))).unwrap(),
            chosen
        );
        // resolved by the default: the default, no note
        assert_eq!(prepared("1:0.1,2:0.05", None).unwrap(), MeshLevel::Default);
    }
}
