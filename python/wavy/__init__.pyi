# Type stubs of the public API (docstrings: help(wavy.solve) and friends; docs/python.md).
# python/tests/test_docs.py keeps every signature here equal to the runtime one.
import os
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str
COLUMNS: Tuple[str, ...]

ArrayLike = Union[float, Sequence[float], npt.NDArray[Any]]
PathLike = Union[str, os.PathLike[str]]
Reading = Literal["bracket-sq", "bracket-2x", "literal"]
Coefficients = Literal["paper-table1", "ours-bracket-sq", "ours-bracket-2x", "ours-literal"]
Mesh = Union[None, int, Literal["coarse", "default", "fine"]]
Values = npt.NDArray[np.float64]
Flags = npt.NDArray[np.bool_]

class ExtrapolationWarning(UserWarning): ...

class Result:
    a_over_lambda: npt.NDArray[np.float64]
    p_over_estar: npt.NDArray[np.float64]
    p_over_estar_reaction: npt.NDArray[np.float64]
    slab_displacement_over_lambda: npt.NDArray[np.float64]
    newton_iterations: npt.NDArray[np.int64]
    active_nodes: npt.NDArray[np.int64]
    contact_fraction: npt.NDArray[np.float64]
    patches: npt.NDArray[np.int64]
    stick_fraction: npt.NDArray[np.float64]
    stick_half_width_over_lambda: npt.NDArray[np.float64]
    friction_work_over_estar_lambda2: npt.NDArray[np.float64]
    branch: npt.NDArray[np.str_]
    error_estimate: npt.NDArray[np.float64]
    columns: Tuple[str, ...]
    mesh: Optional[Tuple[int, int]]
    grid_points: Optional[int]
    unknowns: int
    load_steps: int
    newton_iterations_total: int
    tangent_assemblies: int
    factorisations: int
    notes: List[str]
    extrapolated: bool
    cycle_work_over_estar_lambda2: Optional[float]
    face_dissipation_over_estar_lambda2: Optional[float]
    def __init__(self, fields: Dict[str, Any]) -> None: ...
    def __eq__(self, other: object) -> bool: ...
    def __len__(self) -> int: ...
    def to_pandas(self) -> Any: ...

class SolveError(RuntimeError):
    reason: str
    partial: Result
    a_over_lambda: Optional[float]
    def __init__(self, message: str, reason: str, partial: Result) -> None: ...

@overload
def westergaard(ar: float, a_over_lambda: ArrayLike, *,
                return_flags: Literal[False] = ...) -> Values: ...
@overload
def westergaard(ar: float, a_over_lambda: ArrayLike, *,
                return_flags: Literal[True]) -> Tuple[Values, Flags]: ...
@overload
def westergaard_inverse(ar: float, p_over_estar: ArrayLike, *,
                        return_flags: Literal[False] = ...) -> Values: ...
@overload
def westergaard_inverse(ar: float, p_over_estar: ArrayLike, *,
                        return_flags: Literal[True]) -> Tuple[Values, Flags]: ...
@overload
def wnl(ar: float, tau_max_mpa: float, a_over_lambda: ArrayLike,
        reading: Reading = ..., coefficients: Coefficients = ..., *,
        return_flags: Literal[False] = ...) -> Values: ...
@overload
def wnl(ar: float, tau_max_mpa: float, a_over_lambda: ArrayLike,
        reading: Reading = ..., coefficients: Coefficients = ..., *,
        return_flags: Literal[True]) -> Tuple[Values, Flags]: ...
@overload
def wnl_inverse(ar: float, tau_max_mpa: float, p_over_estar: ArrayLike,
                reading: Reading = ..., coefficients: Coefficients = ..., *,
                return_flags: Literal[False] = ...) -> Values: ...
@overload
def wnl_inverse(ar: float, tau_max_mpa: float, p_over_estar: ArrayLike,
                reading: Reading = ..., coefficients: Coefficients = ..., *,
                return_flags: Literal[True]) -> Tuple[Values, Flags]: ...
def solve(
    ar: Optional[float] = None,
    tau_max_mpa: float = 0.0,
    mesh: Mesh = None,
    tolerance: Optional[float] = None,
    until_a_over_lambda: Optional[float] = None,
    until_p_over_estar: Optional[float] = None,
    unload: bool = False,
    error_estimate: bool = False,
    mu: Optional[float] = None,
    elastic_slip_over_element: Optional[float] = None,
    estar_mpa: Optional[float] = None,
    kappa_over_g: Optional[float] = None,
    thickness_over_lambda: Optional[float] = None,
    kinematics: Optional[Literal["finite", "linear"]] = None,
    vtk: Optional[PathLike] = None,
    profile: Optional[str] = None,
    until_contact_fraction: Optional[float] = None,
    max_memory: Optional[float] = None,
    solver: Literal["fe", "bem"] = "fe",
    grid_points: Optional[int] = None,
    points: Optional[int] = None,
    half_plane: bool = False,
    unloading_substeps: Optional[int] = None,
    coarsen_at_aspect: Optional[float] = None,
) -> Result: ...
def run(spec_path: PathLike, out: Optional[PathLike] = None,
        cache: Optional[PathLike] = None) -> List[str]: ...
