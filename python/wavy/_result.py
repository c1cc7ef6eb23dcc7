"""What a solve gives (``Result``), and what wavy raises or warns (``SolveError``,
``ExtrapolationWarning``): each pickles to an equal object, so results and failures cross process
pools and distributed schedulers (multiprocessing, concurrent.futures, Dask) intact."""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from . import _wavy

#: The columns of a ``Result`` in the order of ``wavy solve``'s CSV, then ``branch`` (loading /
#: unloading); ``error_estimate`` follows when asked for.
COLUMNS: Tuple[str, ...] = tuple(_wavy.COLUMNS)

#: The metadata of a ``Result``, after its columns.
METADATA: Tuple[str, ...] = (
    "mesh",
    "grid_points",
    "unknowns",
    "load_steps",
    "newton_iterations_total",
    "tangent_assemblies",
    "factorisations",
    "notes",
    "extrapolated",
    "cycle_work_over_estar_lambda2",
    "face_dissipation_over_estar_lambda2",
)


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.dtype.kind == "f" and b.dtype.kind == "f":
            return a.shape == b.shape and bool(np.array_equal(a, b, equal_nan=True))
        return a.shape == b.shape and bool(np.array_equal(a, b))
    return bool(a == b)


class Result:
    """A solved load curve: one entry per converged load step in every column.

    Made by :func:`wavy.solve`; not meant to be built by hand. Equal results compare equal
    (``==``, NaN equal to NaN), and a result pickles to an equal one.

    Parameters
    ----------
    fields : dict
        The columns and metadata as the extension returns them (internal).

    Attributes
    ----------
    a_over_lambda : numpy.ndarray of float
        Contact half-width a over wavelength λ, dimensionless, in [0, 0.5] (0.5 = full
        contact); for a profile the outermost patch edge.
    p_over_estar : numpy.ndarray of float
        Mean contact pressure p̄ over the plane-strain modulus E*, dimensionless, >= 0, from
        the contact forces.
    p_over_estar_reaction : numpy.ndarray of float
        The same pressure from the reaction at the slab (a check of equilibrium).
    slab_displacement_over_lambda : numpy.ndarray of float
        The imposed displacement d of the layer's base over λ (the load parameter).
    newton_iterations : numpy.ndarray of int
        Newton iterations of each load step.
    active_nodes : numpy.ndarray of int
        Contact-face nodes in contact at each step.
    contact_fraction : numpy.ndarray of float
        Total contact length over λ, in [0, 1] (2a/λ for one patch).
    patches : numpy.ndarray of int
        Contact patches in the half period [0, λ/2].
    stick_fraction : numpy.ndarray of float
        Total stick length over λ: the part of ``contact_fraction`` where the face sticks to
        the indenter, in [0, 1] (0 without friction).
    stick_half_width_over_lambda : numpy.ndarray of float
        Half-width over λ of the stick zone at the peak, in [0, 0.5] (0 when the peak
        slips, and without friction).
    friction_work_over_estar_lambda2 : numpy.ndarray of float
        The work of friction at the contact face along the path up to each point, over E* λ²
        (per unit ridge length and wavelength; 0 without friction): on a closed loop, the
        energy the loop dissipates.
    branch : numpy.ndarray of str
        "loading" or "unloading" (only "loading" without ``unload=True``).
    error_estimate : numpy.ndarray of float
        Only with ``error_estimate=True``: the Richardson estimate of the relative error of
        ``p_over_estar`` (NaN below the coarser curve's first contact point).
    columns : tuple of str
        The column names above that this result has, in the order of ``wavy solve``'s CSV.
    mesh : tuple of (int, int) or None
        Elements along the contact face and across the thickness (None for
        ``solver="bem"``).
    grid_points : int or None
        Grid points per wavelength of ``solver="bem"`` (None for the finite-element solver).
    unknowns : int
        Nodal displacement unknowns (two per node), or the grid's pressures.
    load_steps : int
        Converged load steps (the length of every column).
    newton_iterations_total : int
        Newton iterations of the whole solve.
    tangent_assemblies, factorisations : int
        Work of the solve (0 for the converged part of a solve that stopped).
    notes : list of str
        What the command line says on stderr: the mesh a ``tolerance`` chose, the finer mesh a
        profile needed, and from mesh 256 on the estimated memory and time of the solve.
    extrapolated : bool
        True when (ar, tau_max_mpa) lies outside the paper's fit domain of the WNL model
        (AR in [0.1, 0.3], τ_max in [0, 0.2] MPa): comparing this curve with :func:`wavy.wnl`
        compares it with an extrapolation.
    cycle_work_over_estar_lambda2, face_dissipation_over_estar_lambda2 : float or None
        Only with ``unload=True`` (else None): the loop's work ∮ p̄ dd (for ``solver="bem"``,
        ∮ p̄ dδ) by the trapezoid rule on the converged points, and the work of friction at the
        face at the last point, over E* λ² (per unit ridge length and wavelength).

    Examples
    --------
    >>> import wavy
    >>> r = wavy.solve(ar=0.3, mesh=8, until_a_over_lambda=0.3)
    >>> r.columns[:2]
    ('a_over_lambda', 'p_over_estar')
    >>> len(r) == len(r.p_over_estar) == r.load_steps
    True
    """

    def __init__(self, fields: Dict[str, Any]):
        fields = dict(fields)
        fields["branch"] = np.asarray(fields["branch"], dtype=str)
        self.columns: Tuple[str, ...] = COLUMNS + (
            ("error_estimate",) if "error_estimate" in fields else ()
        )
        for column in self.columns:
            setattr(self, column, fields[column])
        mesh = fields.get("mesh")
        self.mesh: Optional[Tuple[int, int]] = None if mesh is None else tuple(mesh)  # type: ignore[assignment]
        grid = fields.get("grid_points")
        self.grid_points: Optional[int] = None if grid is None else int(grid)
        self.unknowns: int = int(fields["unknowns"])
        self.load_steps: int = int(fields["load_steps"])
        self.newton_iterations_total: int = int(fields["newton_iterations_total"])
        self.tangent_assemblies: int = int(fields["tangent_assemblies"])
        self.factorisations: int = int(fields["factorisations"])
        self.notes: List[str] = list(fields.get("notes", ()))
        self.extrapolated: bool = bool(fields.get("extrapolated", False))
        work, face = (fields.get(k) for k in METADATA[-2:])
        self.cycle_work_over_estar_lambda2: Optional[float] = None if work is None else float(work)
        self.face_dissipation_over_estar_lambda2: Optional[float] = (
            None if face is None else float(face)
        )

    def _fields(self) -> Dict[str, Any]:
        return {k: getattr(self, k) for k in self.columns + METADATA}

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Result):
            return NotImplemented
        mine, theirs = self._fields(), other._fields()
        return mine.keys() == theirs.keys() and all(_same(mine[k], theirs[k]) for k in mine)

    __hash__ = None  # type: ignore[assignment]  # mutable arrays: not hashable

    def __reduce__(self):
        return (Result, (self._fields(),))

    def __len__(self) -> int:
        return self.load_steps

    def __repr__(self) -> str:
        on = (
            f"mesh {self.mesh[0]}×{self.mesh[1]}"
            if self.mesh is not None
            else f"a grid of {self.grid_points} points"
        )
        last = (
            f", last a/λ = {float(self.a_over_lambda[-1]):.6g},"
            f" p̄/E* = {float(self.p_over_estar[-1]):.6g}"
            if self.load_steps
            else ""
        )
        return f"<wavy.Result: {self.load_steps} load steps on {on}{last}>"

    def to_pandas(self):
        """The columns as a pandas DataFrame.

        Returns
        -------
        pandas.DataFrame
            One column per name of ``columns``, one row per load step.

        Raises
        ------
        ImportError
            When pandas is not installed (``pip install pandas``).

        Examples
        --------
        >>> import wavy
        >>> df = wavy.solve(ar=0.3, mesh=8, until_a_over_lambda=0.3).to_pandas()  # doctest: +SKIP
        """
        try:
            import pandas as pd
        except ImportError as e:
            raise ImportError(
                "wavy.Result.to_pandas needs pandas, which is not installed: pip install pandas"
            ) from e
        return pd.DataFrame({c: getattr(self, c) for c in self.columns})


class SolveError(RuntimeError):
    """The solver stopped before the target (``wavy solve`` exits 1 there).

    Raised by :func:`wavy.solve`; it pickles to an equal error (``==`` compares the message,
    reason and partial curve), so a process pool or a Dask cluster hands it back intact.

    Parameters
    ----------
    message : str
        The whole message, ``str(e)``: the command line's, in Python's argument names.
    reason : str
        Why the solver stopped (the solver's part of the message).
    partial : Result
        The converged part of the curve (possibly no steps).

    Attributes
    ----------
    reason : str
        Why the solver stopped.
    partial : Result
        The converged load steps before the stop.
    a_over_lambda : float or None
        The contact half-width a/λ of the last converged step (None before the first).

    Examples
    --------
    >>> import wavy
    >>> try:
    ...     wavy.solve(ar=0.1, mesh=4)
    ... except wavy.SolveError as e:
    ...     print(e.partial.load_steps > 0, "contact is complete" in e.reason)
    True True
    """

    def __init__(self, message: str, reason: str, partial: Result):
        super().__init__(message)
        self.reason = reason
        self.partial = partial
        self.a_over_lambda: Optional[float] = (
            float(partial.a_over_lambda[-1]) if partial.load_steps else None
        )

    def __reduce__(self):
        return (SolveError, (str(self), self.reason, self.partial))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, SolveError):
            return NotImplemented
        return (str(self), self.reason, self.partial) == (str(other), other.reason, other.partial)

    def __hash__(self) -> int:
        return hash((SolveError, str(self), self.reason))


class ExtrapolationWarning(UserWarning):
    """A law was evaluated outside the domain its coefficients were fitted on.

    Warned (``warnings.warn``) by :func:`wavy.wnl` and :func:`wavy.wnl_inverse` when (ar,
    tau_max_mpa) lies outside the coefficient set's fit domain (the paper's: AR in [0.1, 0.3],
    τ_max in [0, 0.2] MPa), as the command line flags the rows ``extrapolated``. Turn it into
    an error with ``warnings.simplefilter("error", wavy.ExtrapolationWarning)``, or silence it
    with ``"ignore"``; ``return_flags=True`` gives the flag of every value. Equal warnings
    compare equal and pickle to equal ones.

    Parameters
    ----------
    message : str
        What was extrapolated, and the fit domain.
    """

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ExtrapolationWarning):
            return NotImplemented
        return self.args == other.args

    def __hash__(self) -> int:
        return hash((ExtrapolationWarning, self.args))
