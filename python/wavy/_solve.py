"""One finite-element load curve (``wavy solve``) and a spec run (``wavy run``), with Python's
argument checks; the solve runs on its own thread, the GIL released, and Ctrl-C stops it."""

from __future__ import annotations

import os
import sys
from typing import List, Optional, Union

from . import _checks, _wavy
from ._result import Result, SolveError

PathLike = Union[str, "os.PathLike[str]"]


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
    elastic_slip_over_element: Optional[float] = None,
    estar_mpa: Optional[float] = None,
    kappa_over_g: Optional[float] = None,
    thickness_over_lambda: Optional[float] = None,
    kinematics: Optional[str] = None,
    vtk: Optional[PathLike] = None,
    profile: Optional[str] = None,
    until_contact_fraction: Optional[float] = None,
    max_memory: Optional[float] = None,
    solver: str = "fe",
    grid_points: Optional[int] = None,
    points: Optional[int] = None,
    half_plane: bool = False,
    unloading_substeps: Optional[int] = None,
    coarsen_at_aspect: Optional[float] = None,
) -> Result:
    """One finite-element load curve, as ``wavy solve`` computes it with the same options.

    A neo-Hookean layer (plane strain, finite strain by default) on a rigid base is pressed
    onto a rigid wavy surface with Coulomb–Orowan friction; the curve follows the contact from
    first touch, one row per contact event, up to the target. Exactly one of ``ar`` and
    ``profile`` gives the surface.

    Parameters
    ----------
    ar : float, optional
        Aspect ratio Δ/λ of a single sinusoid (amplitude over wavelength), dimensionless,
        > 0; the paper's range is [0.1, 0.3]. Default None (then ``profile`` is required).
    tau_max_mpa : float, optional
        Interfacial shear strength τ_max in MPa, >= 0 (0 = frictionless). Default 0.0.
    mesh : int or str, optional
        "coarse" (32×16 elements), "default" (48×24), "fine" (72×36), or an int N in
        [4, 2048]: N elements along the contact face and N/2 across the thickness. Default
        None: "default", or for a ``profile`` the coarsest mesh at least as fine that
        resolves its finest harmonic (said in ``Result.notes`` and on stderr).
    tolerance : float, optional
        Instead of ``mesh``: the coarsest mesh whose measured largest relative error of
        p̄/E* at this (ar, tau_max_mpa) is at most this, in (0, 1), e.g. 0.005 (default
        physics only; the choice is in ``Result.notes``). Default None.
    until_a_over_lambda : float, optional
        Load until the contact half-width a/λ reaches this, in (0, 0.5); with
        ``until_p_over_estar`` the cap on the way. Default None: 0.45.
    until_p_over_estar : float, optional
        Instead: load until the mean pressure p̄/E* is this, > 0 (the last row is the state
        at that load). A sinusoid is capped on the way by ``until_a_over_lambda``, a profile
        by full contact. Default None.
    unload : bool, optional
        Then unload back to zero load, the friction history carried through (``branch``
        says which rows are unloading). Not with ``error_estimate``. Default False.
    error_estimate : bool, optional
        Also solve the next coarser mesh (1.5 times fewer elements) and give the column
        ``error_estimate``, the Richardson estimate of each point's relative error. Default
        False.
    mu : float, optional
        Friction coefficient μ of the Coulomb–Orowan law, >= 0 (0 = frictionless). Default
        None: 1.0.
    elastic_slip_over_element : float, optional
        Elastic slip at which friction is fully mobilised, over the face element length,
        >= 0 (0 = exact stick: a stuck node is held and its friction force is the reaction;
        > 0 = penalty-regularised stick). Default None: 0.005.
    estar_mpa : float, optional
        Plane-strain modulus E* of the layer in MPa, > 0 (τ_max/E* is what the physics
        sees). Default None: 1.0.
    kappa_over_g : float, optional
        Bulk over shear modulus κ/G, > 0 (1000 is nearly incompressible, ν ≈ 0.4995).
        Default None: 1000.0.
    thickness_over_lambda : float, optional
        Layer thickness over wavelength h/λ, > 0 (1 is practically a half-space). Default
        None: 1.0.
    kinematics : str, optional
        "finite" (finite strain, neo-Hookean: the paper's physics) or "linear" (small
        strain). Default None: "finite", and "linear" with ``solver="bem"`` (the only
        kinematics it models).
    vtk : str or os.PathLike, optional
        A folder (created if missing; not a file) that receives the deformed state of every
        converged point as a ParaView time series: ``series.pvd`` and one ``step_NNNN.vtu``
        per point. A curve that stops short still writes its converged points, and
        ``series.pvd`` says it is incomplete and why. Default None (nothing written).
    profile : str, optional
        Instead of ``ar``: an even periodic profile as ``order:aspect_ratio`` pairs,
        comma-separated, the first of order 1, e.g. "1:0.1,16:0.05" (each aspect ratio is the
        harmonic's amplitude over its own wavelength λ/order), or a Weierstrass profile
        "weierstrass:AR0,gamma,D,K" (docs/replication.md R14). Default None.
    until_contact_fraction : float, optional
        Instead of ``until_a_over_lambda``: load until the contact fraction (total contact
        length over λ) reaches this, in (0, 1); a profile's counterpart of
        ``until_a_over_lambda``. Not with ``until_p_over_estar``. Default None.
    max_memory : int or float, optional
        Refuse the solve (``MemoryError``) when its estimated peak memory is above this many
        bytes, e.g. ``4e9``. The estimate (docs/performance.md, "Large meshes") grows with the
        mesh: about 0.6 GB at mesh 512, 2.5 GB at 1024, 10 GB at 2048. A solve is refused
        above the memory the machine has available in any case. Default None (no cap).
    solver : str, optional
        "fe" (the finite-element solver) or "bem" (the boundary-element solver: linear
        kinematics; the layer, or the half-plane with ``half_plane=True``, with
        Coulomb–Orowan friction and its history). The columns are the same; with "bem",
        ``slab_displacement_over_lambda`` holds the rigid approach δ/λ,
        ``newton_iterations`` the normal–tangential passes and ``active_nodes`` the contact
        grid points on [0, λ/2]. Default "fe".
    grid_points : int, optional
        With ``solver="bem"``: grid points per wavelength, a power of two. Default None:
        4096, or 64 per wavelength of a profile's finest harmonic.
    points : int, optional
        Loading points up to the target, in [2, 10000]. With ``solver="fe"`` (a frictionless
        sinusoid; a frictional curve steps node by node): steps of a/λ of about
        ``until_a_over_lambda / points``, each to the first face node that far beyond the
        contact edge (None: 45, steps of 0.01 to the default target, or with ``unload`` node by
        node; 10000: node by node). With ``solver="bem"``: up to the frictionless load of the
        target (None: 40). Default None.
    half_plane : bool, optional
        With ``solver="bem"``: the half-plane instead of the layer.
        Default False.
    unloading_substeps : int, optional
        With ``unload``: unloading steps per loading step, an int >= 1, each interval
        between the loading steps' loads retraced in this many equal steps: the unloading
        branch sampled finer, so that the face's work of friction and the trapezoid sum of the
        loop's work converge with it (docs/verification.md, "The energy audit", measures what
        each choice does). Default None: 1.
    coarsen_at_aspect : float, optional
        Coarsen the mesh's columns threefold wherever its rows, growing with depth, reach
        this many times their width, 0 or >= 1 (a conforming transition row): at 4 a
        profile's curve on a uniform face takes about half the time and moves by a small
        part of its error (docs/replication.md R13, "Columns coarsened with depth"). Not with
        ``tolerance`` or ``error_estimate``, whose errors are measured on meshes that keep
        every column; finite-element solver only. Default None: every column to the bonded
        face.

    Returns
    -------
    Result
        The columns (numpy arrays, one entry per converged load step) and metadata; see
        :class:`Result`.

    Raises
    ------
    TypeError
        A number given as ``str`` or ``bool``, a flag not a bool, a name not a ``str``, a
        path not a ``str`` or ``os.PathLike`` (the message names the argument).
    ValueError
        An input out of range or options that cannot be combined (the message names the
        argument, its value and what is allowed), a ``vtk`` path that is a file.
    SolveError
        The solver stopped before the target; ``e.partial`` holds the converged steps,
        ``e.reason`` why.
    MemoryError
        The estimated memory is above ``max_memory`` or what the machine has available (the
        message names the estimate); nothing was solved.
    KeyboardInterrupt
        Ctrl-C during the solve (raised within a fraction of a second at any mesh).
    RuntimeError
        Another failed computation (e.g. the error estimate's coarser curve stopped).

    Notes
    -----
    The solve runs on a thread of its own with the GIL released, so other Python threads run
    meanwhile; results pickle, so a sweep can run on ``multiprocessing``,
    ``concurrent.futures`` or Dask (docs/python.md).

    Examples
    --------
    >>> import wavy
    >>> r = wavy.solve(ar=0.3, mesh=8, until_a_over_lambda=0.3)
    >>> r.mesh
    (8, 4)
    >>> bool(r.p_over_estar[-1] > 0)
    True
    """
    if (ar is None) == (profile is None):
        raise ValueError("give exactly one of ar (a sinusoid) and profile (e.g. \"1:0.1,16:0.05\")")
    defaults = _wavy.SOLVE_DEFAULTS

    def or_default(argument: str, value: object) -> float:
        return _checks.number(argument, defaults[argument] if value is None else value)

    fields = _wavy.solve(
        ar=float("nan") if ar is None else _checks.number("ar", ar),
        tau_max_mpa=_checks.number("tau_max_mpa", tau_max_mpa),
        mu=or_default("mu", mu),
        elastic_slip_over_element=or_default("elastic_slip_over_element", elastic_slip_over_element),
        estar_mpa=or_default("estar_mpa", estar_mpa),
        kappa_over_g=or_default("kappa_over_g", kappa_over_g),
        thickness_over_lambda=or_default("thickness_over_lambda", thickness_over_lambda),
        kinematics=None if kinematics is None else _checks.name("kinematics", kinematics),
        mesh=_checks.mesh(mesh),
        tolerance=_checks.optional_number("tolerance", tolerance),
        error_estimate=_checks.flag("error_estimate", error_estimate),
        until_a_over_lambda=or_default("until_a_over_lambda", until_a_over_lambda),
        until_p_over_estar=_checks.optional_number("until_p_over_estar", until_p_over_estar),
        unload=_checks.flag("unload", unload),
        vtk=_checks.optional_path("vtk", vtk),
        profile=None if profile is None else _checks.name("profile", profile),
        until_contact_fraction=_checks.optional_number(
            "until_contact_fraction", until_contact_fraction
        ),
        max_memory=_checks.max_memory(max_memory),
        solver=_checks.name("solver", solver),
        grid_points=_checks.optional_count("grid_points", grid_points),
        points=_checks.optional_count("points", points),
        half_plane=_checks.flag("half_plane", half_plane),
        unloading_substeps=_checks.optional_count("unloading_substeps", unloading_substeps),
        coarsen_at_aspect=_checks.optional_number("coarsen_at_aspect", coarsen_at_aspect),
    )
    stopped = fields.pop("stopped")
    result = Result(fields)
    for note in result.notes:
        print(f"wavy: {note}", file=sys.stderr)
    if stopped is not None:
        message, reason = stopped
        raise SolveError(message, reason, result)
    return result


def run(spec_path: PathLike, out: Optional[PathLike] = None,
        cache: Optional[PathLike] = None) -> List[str]:
    """Runs a spec as ``wavy run SPEC --out OUT --cache CACHE`` does.

    Parameters
    ----------
    spec_path : str or os.PathLike
        A TOML spec, e.g. "experiments/fig2_correction_surfaces.toml". No default.
    out : str or os.PathLike, optional
        The folder the figure (SVG) and its tables (CSV) are written to. Default None:
        "figures", relative to the working directory.
    cache : str or os.PathLike, optional
        The folder of the FE curve cache (reused by later runs). Default None:
        ".wavy-cache", relative to the working directory.

    Returns
    -------
    list of str
        The paths written.

    Raises
    ------
    TypeError
        A path that is not a ``str`` or ``os.PathLike``.
    ValueError
        A bad spec (the message names the field, its line and column).
    RuntimeError
        The run failed, or its figures rest on curves that stopped short (then written and
        marked INCOMPLETE).

    Examples
    --------
    >>> import wavy
    >>> wavy.run("experiments/fig2_correction_surfaces.toml", out="/tmp/figs")  # doctest: +SKIP
    ['/tmp/figs/fig2_correction_surfaces.svg', ...]
    """
    spec = _checks.optional_path("spec_path", spec_path)
    if spec is None:
        raise TypeError("spec_path must be a path (str or os.PathLike), not NoneType (None)")
    return _wavy.run(
        spec,
        _checks.optional_path("out", out) or "figures",
        _checks.optional_path("cache", cache),
    )
