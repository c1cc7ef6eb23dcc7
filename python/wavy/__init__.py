"""wavy from Python: the contact of a soft solid on a rigid wavy surface.

Westergaard's law, the WNL model and the finite-element solver of the ``wavy`` command line,
with its names and units, numpy in and out. Every value, check and message comes from the
Rust library the command line uses (``wavy eval``, ``wavy solve``, ``wavy run``); this module
only shapes arguments and results. Details: docs/python.md.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _wavy

__all__ = [
    "Result",
    "SolveError",
    "run",
    "solve",
    "westergaard",
    "westergaard_inverse",
    "wnl",
    "wnl_inverse",
]

ArrayLike = Union[float, Sequence[float], np.ndarray]

#: The columns of ``wavy solve`` in its order, then ``branch`` (loading / unloading).
COLUMNS = (
    "a_over_lambda",
    "p_over_estar",
    "p_over_estar_reaction",
    "slab_displacement_over_lambda",
    "newton_iterations",
    "active_nodes",
    "contact_fraction",
    "patches",
    "branch",
)


def _flat(values: ArrayLike) -> Tuple[np.ndarray, Tuple[int, ...]]:
    """The values as a contiguous 1-D float64 array, and the shape to give the results."""
    array = np.asarray(values, dtype=np.float64)
    return np.ascontiguousarray(array.ravel()), array.shape


def _law(model, ar, tau_max_mpa, values, reading, coefficients, inverse):
    """The law's answer at each value, shaped like ``values``: p̄/E* at each a/λ, or with
    ``inverse`` a/λ at each p̄/E* (``wavy eval``)."""
    flat, shape = _flat(values)
    x, p, _ = _wavy.law(model, float(ar), float(tau_max_mpa), reading, coefficients, flat, inverse)
    return (x if inverse else p).reshape(shape)


def westergaard(ar: float, a_over_lambda: ArrayLike) -> np.ndarray:
    """p̄/E* of Westergaard's law at each a/λ in [0, 0.5] (``wavy eval --model westergaard``)."""
    return _law("westergaard", ar, 0.0, a_over_lambda, "bracket-sq", "paper-table1", False)


def westergaard_inverse(ar: float, p_over_estar: ArrayLike) -> np.ndarray:
    """a/λ of Westergaard's law at each p̄/E* (``wavy eval --model westergaard --p-over-estar``)."""
    return _law("westergaard", ar, 0.0, p_over_estar, "bracket-sq", "paper-table1", True)


def wnl(
    ar: float,
    tau_max_mpa: float,
    a_over_lambda: ArrayLike,
    reading: str = "bracket-sq",
    coefficients: str = "paper-table1",
) -> np.ndarray:
    """p̄/E* of the WNL model at each a/λ (``wavy eval --model wnl``); τ_max in MPa."""
    return _law("wnl", ar, tau_max_mpa, a_over_lambda, reading, coefficients, False)


def wnl_inverse(
    ar: float,
    tau_max_mpa: float,
    p_over_estar: ArrayLike,
    reading: str = "bracket-sq",
    coefficients: str = "paper-table1",
) -> np.ndarray:
    """a/λ of the WNL model at each p̄/E* (``wavy eval --model wnl --p-over-estar``)."""
    return _law("wnl", ar, tau_max_mpa, p_over_estar, reading, coefficients, True)


class Result:
    """A solved load curve: one entry per converged load step in every column.

    Columns (numpy arrays, the CSV columns of ``wavy solve``): ``a_over_lambda``,
    ``p_over_estar``, ``p_over_estar_reaction``, ``slab_displacement_over_lambda``,
    ``newton_iterations``, ``active_nodes``, ``branch`` ("loading" / "unloading"), and with
    ``error_estimate=True`` ``error_estimate`` (NaN where the CLI leaves the cell empty).

    Metadata: ``mesh`` (elements along the face, across the thickness), ``unknowns`` (nodal
    displacement unknowns, two per node), ``load_steps``, ``newton_iterations_total``,
    ``tangent_assemblies`` and ``factorisations`` (0 for the converged part of a stopped solve).
    """

    def __init__(self, fields: Dict[str, Any]):
        self._fields = dict(fields)
        self._fields["branch"] = np.asarray(self._fields["branch"], dtype=str)
        self.columns: Tuple[str, ...] = COLUMNS + (
            ("error_estimate",) if "error_estimate" in self._fields else ()
        )
        self.mesh: Tuple[int, int] = tuple(self._fields["mesh"])  # type: ignore[assignment]
        self.unknowns: int = self._fields["unknowns"]
        self.load_steps: int = self._fields["load_steps"]
        self.newton_iterations_total: int = self._fields["newton_iterations_total"]
        self.tangent_assemblies: int = self._fields["tangent_assemblies"]
        self.factorisations: int = self._fields["factorisations"]

    def __getattr__(self, name: str) -> np.ndarray:
        fields = self.__dict__.get("_fields", {})
        if name in fields and name in COLUMNS + ("error_estimate",):
            return fields[name]
        raise AttributeError(f"wavy.Result has no column or attribute {name!r}")

    def __len__(self) -> int:
        return self.load_steps

    def __repr__(self) -> str:
        last = (
            f", last a/λ = {self.a_over_lambda[-1]!r}, p̄/E* = {self.p_over_estar[-1]!r}"
            if self.load_steps
            else ""
        )
        return (
            f"<wavy.Result: {self.load_steps} load steps on mesh {self.mesh[0]}×{self.mesh[1]}"
            f"{last}>"
        )

    def to_pandas(self):
        """The columns as a pandas DataFrame (needs pandas: ``pip install pandas``)."""
        try:
            import pandas as pd
        except ImportError as e:
            raise ImportError(
                "wavy.Result.to_pandas needs pandas, which is not installed: pip install pandas"
            ) from e
        return pd.DataFrame({c: getattr(self, c) for c in self.columns})


class SolveError(RuntimeError):
    """The solver stopped before the target (``wavy solve`` exits 1 there).

    ``str(e)`` is the command line's message; ``reason`` why the solver stopped;
    ``a_over_lambda`` the contact half-width of the last converged step (None before the first);
    ``partial`` the converged part of the curve, a :class:`Result`.
    """

    def __init__(self, message: str, reason: str, partial: Result):
        super().__init__(message)
        self.reason = reason
        self.partial = partial
        self.a_over_lambda: Optional[float] = (
            float(partial.a_over_lambda[-1]) if partial.load_steps else None
        )


def solve(
    ar: Optional[float] = None,
    tau_max_mpa: float = 0.0,
    mesh: Union[None, int, str] = None,
    tolerance: Optional[float] = None,
    until_a_over_lambda: Optional[float] = None,
    until_p_over_estar: Optional[float] = None,
    unload: bool = False,
    error_estimate: bool = False,
    mu: Optional[float] = None,
    estar_mpa: Optional[float] = None,
    kappa_over_g: Optional[float] = None,
    thickness_over_lambda: Optional[float] = None,
    kinematics: str = "finite",
    vtk: Optional[str] = None,
    profile: Optional[str] = None,
    until_contact_fraction: Optional[float] = None,
) -> Result:
    """One finite-element load curve, as ``wavy solve`` with the same options computes it.

    ``mesh``: "coarse", "default", "fine" or N elements along the contact face (default
    "default"); ``tolerance`` instead chooses the coarsest mesh whose measured error meets it.
    ``mu``, ``estar_mpa``, ``kappa_over_g``, ``thickness_over_lambda``, ``until_a_over_lambda``:
    None takes the command line's default (``wavy._wavy.SOLVE_DEFAULTS``). The GIL is released while solving; Ctrl-C stops the solve after the
    current load step (``KeyboardInterrupt``). ``vtk``: a folder that receives the deformed
    state of every converged point as a ParaView time series (``series.pvd`` and one
    ``step_NNNN.vtu`` per point), as ``wavy solve --vtk``; written only for a complete curve.

    ``profile`` instead of ``ar``: an even periodic profile as ``wavy solve --profile`` takes
    it, e.g. "1:0.1,16:0.05" (order:aspect_ratio pairs, the first of order 1);
    ``until_contact_fraction`` loads until the contact fraction (``contact_fraction``, total
    contact length over λ) reaches it, a profile's counterpart of ``until_a_over_lambda``.

    Raises ``ValueError`` for bad input (the command line's message, naming the flag) and
    :class:`SolveError` when the solver stops short, with the converged part attached.
    """
    if (ar is None) == (profile is None):
        raise ValueError("give exactly one of ar (a sinusoid) and profile (e.g. \"1:0.1,16:0.05\")")
    defaults = _wavy.SOLVE_DEFAULTS
    fields = _wavy.solve(
        ar=float("nan") if ar is None else float(ar),
        tau_max_mpa=float(tau_max_mpa),
        mu=float(defaults["mu"] if mu is None else mu),
        estar_mpa=float(defaults["estar_mpa"] if estar_mpa is None else estar_mpa),
        kappa_over_g=float(defaults["kappa_over_g"] if kappa_over_g is None else kappa_over_g),
        thickness_over_lambda=float(
            defaults["thickness_over_lambda"]
            if thickness_over_lambda is None
            else thickness_over_lambda
        ),
        kinematics=kinematics,
        mesh=None if mesh is None else str(mesh),
        tolerance=None if tolerance is None else float(tolerance),
        error_estimate=bool(error_estimate),
        until_a_over_lambda=float(
            defaults["until_a_over_lambda"] if until_a_over_lambda is None else until_a_over_lambda
        ),
        until_p_over_estar=None if until_p_over_estar is None else float(until_p_over_estar),
        unload=bool(unload),
        vtk=None if vtk is None else str(vtk),
        profile=None if profile is None else str(profile),
        until_contact_fraction=None
        if until_contact_fraction is None
        else float(until_contact_fraction),
    )
    stopped = fields.pop("stopped")
    result = Result(fields)
    if stopped is not None:
        message, reason = stopped
        raise SolveError(message, reason, result)
    return result


def run(spec_path, out=None, cache=None) -> List[str]:
    """Runs a spec as ``wavy run SPEC [--out OUT] [--cache CACHE]`` does; the written paths.

    ``out`` defaults to "figures", ``cache`` to ".wavy-cache" (relative to the working
    directory, as on the command line). ``ValueError`` for a bad spec; ``RuntimeError`` when
    the run fails or its figures rest on curves that stopped short (written, marked INCOMPLETE).
    """
    return _wavy.run(
        str(spec_path), "figures" if out is None else str(out), None if cache is None else str(cache)
    )
