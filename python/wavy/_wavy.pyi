# Type stubs of the extension module (python/src/lib.rs); the public API wraps it (__init__.pyi).
from typing import Any, Dict, List, Optional, Tuple

import numpy as np
import numpy.typing as npt

__version__: str
BRANCHES: List[str]
COLUMNS: List[str]
SOLVE_DEFAULTS: Dict[str, float]

def law(model: str, ar: float, tau_max_mpa: float, reading: str, coefficients: str,
        values: npt.NDArray[np.float64], inverse: bool
        ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.bool_]]: ...
def fit_domain(coefficients: str) -> Tuple[float, float, float, float]: ...
def solve(*, ar: float, tau_max_mpa: float, mu: float, elastic_slip_over_element: float,
          estar_mpa: float, kappa_over_g: float,
          thickness_over_lambda: float, kinematics: Optional[str], mesh: Optional[str],
          tolerance: Optional[float], error_estimate: bool, until_a_over_lambda: float,
          until_p_over_estar: Optional[float], unload: bool,
          unloading_substeps: Optional[int], vtk: Optional[str],
          profile: Optional[str], until_contact_fraction: Optional[float],
          max_memory: Optional[int], solver: str, grid_points: Optional[int],
          points: Optional[int], half_plane: bool,
          coarsen_at_aspect: Optional[float]) -> Dict[str, Any]: ...
def run(spec: str, out: str, cache: Optional[str] = None) -> List[str]: ...
