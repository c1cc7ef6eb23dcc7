//! Which solver `wavy solve` runs: the finite elements or the boundary elements.

/// Which solver a `wavy solve` request runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Solver {
    /// The finite-element solver (`fe`): finite or linear kinematics on the layer.
    #[default]
    FiniteElement,
    /// The boundary-element solver (`bem`): linear kinematics, the half-plane or the layer.
    BoundaryElement,
}

impl Solver {
    pub const ALL: [Solver; 2] = [Solver::FiniteElement, Solver::BoundaryElement];

    /// The name on the command line and in Python.
    pub fn name(self) -> &'static str {
        match self {
            Solver::FiniteElement => "fe",
            Solver::BoundaryElement => "bem",
        }
    }
}

/// A solver name that is neither `fe` nor `bem`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown solver `{0}`; allowed: fe, bem")]
pub struct SolverParseError(pub String);

impl std::str::FromStr for Solver {
    type Err = SolverParseError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Solver::ALL
            .into_iter()
            .find(|v| v.name() == s)
            .ok_or_else(|| SolverParseError(s.into()))
    }
}
