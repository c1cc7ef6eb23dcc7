"""The closed-form laws (``wavy eval``): Westergaard's and the WNL model, forward (a/λ → p̄/E*)
and inverse (p̄/E* → a/λ), any shape in and the same shape out; an extrapolated WNL value warns
(``ExtrapolationWarning``) and ``return_flags=True`` gives every value's flag."""

from __future__ import annotations

import warnings
from typing import Tuple, Union

import numpy as np

from . import _checks, _wavy
from ._result import ExtrapolationWarning

ArrayLike = _checks.ArrayLike
Flagged = Union[np.ndarray, Tuple[np.ndarray, np.ndarray]]


def _law(function, model, ar, tau_max_mpa, argument, values, reading, coefficients, inverse,
         return_flags) -> Flagged:
    """The law's answer at each value, shaped like ``values``, with the flags if asked; warns
    when a value is extrapolated."""
    ar = _checks.number("ar", ar)
    tau_max_mpa = _checks.number("tau_max_mpa", tau_max_mpa)
    reading = _checks.name("reading", reading)
    coefficients = _checks.name("coefficients", coefficients)
    return_flags = _checks.flag("return_flags", return_flags)
    flat, shape = _checks.values(argument, values)
    x, p, flags = _wavy.law(model, ar, tau_max_mpa, reading, coefficients, flat, inverse)
    out = (x if inverse else p).reshape(shape)
    flags = np.asarray(flags, dtype=bool).reshape(shape)
    if flags.any():
        a0, a1, t0, t1 = _wavy.fit_domain(coefficients)
        warnings.warn(
            ExtrapolationWarning(
                f"wavy.{function}(ar={ar!r}, tau_max_mpa={tau_max_mpa!r}) is outside the fit"
                f" domain of the coefficients {coefficients} (ar in [{a0}, {a1}], tau_max_mpa"
                f" in [{t0}, {t1}]): its values are extrapolated"
            ),
            stacklevel=3,
        )
    return (out, flags) if return_flags else out


def westergaard(ar: float, a_over_lambda: ArrayLike, *, return_flags: bool = False) -> Flagged:
    """Westergaard's mean pressure at each contact half-width (``wavy eval --model westergaard``).

    A rigid sinusoid on a linear elastic half-plane, frictionless:
    p̄/E* = π·AR·sin²(π a/λ).

    Parameters
    ----------
    ar : float
        Aspect ratio Δ/λ of the sinusoid (amplitude over wavelength), dimensionless, > 0.
        No default.
    a_over_lambda : float or array_like of float
        Contact half-widths a/λ, dimensionless, each in [0, 0.5] (0.5 = full contact); any
        shape. No default.
    return_flags : bool, optional
        Also return the per-value ``extrapolated`` flags (always False: the law has no fitted
        part). Default False.

    Returns
    -------
    numpy.ndarray of float
        p̄/E* at each a/λ, the shape of ``a_over_lambda`` (0-d for a scalar); with
        ``return_flags`` a tuple (values, flags).

    Raises
    ------
    TypeError
        A number given as ``str`` or ``bool``, or values that are not numbers.
    ValueError
        ``ar`` <= 0 or an a/λ outside [0, 0.5] (the message names the argument and the
        allowed range).

    Examples
    --------
    >>> import wavy
    >>> float(wavy.westergaard(0.1, 0.25))
    0.15707963267948963
    """
    return _law("westergaard", "westergaard", ar, 0.0, "a_over_lambda", a_over_lambda,
                "bracket-sq", "paper-table1", False, return_flags)


def westergaard_inverse(ar: float, p_over_estar: ArrayLike, *,
                        return_flags: bool = False) -> Flagged:
    """Westergaard's contact half-width at each mean pressure
    (``wavy eval --model westergaard --p-over-estar``).

    Parameters
    ----------
    ar : float
        Aspect ratio Δ/λ, dimensionless, > 0. No default.
    p_over_estar : float or array_like of float
        Mean pressures p̄/E*, dimensionless, each in [0, π·AR] (π·AR is full contact); any
        shape. No default.
    return_flags : bool, optional
        Also return the per-value ``extrapolated`` flags (always False). Default False.

    Returns
    -------
    numpy.ndarray of float
        a/λ at each p̄/E*, the shape of ``p_over_estar``; with ``return_flags`` a tuple
        (values, flags).

    Raises
    ------
    TypeError
        A number given as ``str`` or ``bool``, or values that are not numbers.
    ValueError
        ``ar`` <= 0, or a pressure below 0 or above full contact.

    Examples
    --------
    >>> import wavy
    >>> round(float(wavy.westergaard_inverse(0.1, 0.1)), 6)
    0.190811
    """
    return _law("westergaard_inverse", "westergaard", ar, 0.0, "p_over_estar", p_over_estar,
                "bracket-sq", "paper-table1", True, return_flags)


_WNL_COMMON = """
    Parameters
    ----------
    ar : float
        Aspect ratio Δ/λ, dimensionless, > 0; fitted on [0.1, 0.3]. No default.
    tau_max_mpa : float
        Interfacial shear strength τ_max in MPa, >= 0 (0 = frictionless); fitted on
        [0, 0.2]. No default.
    {argument} : float or array_like of float
        {meaning}; any shape. No default.
    reading : str, optional
        Reading of the paper's Eq. 4: "bracket-sq" (p̄_W·[B + x·A·cos²(πx)]), "bracket-2x"
        (p̄_W·[B + x·A·cos(2πx)]) or "literal" (p̄_W·B + x·A·cos²(πx)). Default "bracket-sq".
    coefficients : str, optional
        Coefficient set of A and B: "paper-table1" (the paper's Table 1) or one of our refits
        ("ours-bracket-sq", "ours-bracket-2x", "ours-literal"). Default "paper-table1".
    return_flags : bool, optional
        Also return the per-value ``extrapolated`` flags, True where (ar, tau_max_mpa) lies
        outside the coefficient set's fit domain. Default False.

    Returns
    -------
    numpy.ndarray of float
        {returns}, the shape of ``{argument}``; with ``return_flags`` a tuple (values, flags),
        the flags a bool array of the same shape.

    Warns
    -----
    ExtrapolationWarning
        When (ar, tau_max_mpa) lies outside the fit domain (every value is then extrapolated).

    Raises
    ------
    TypeError
        A number given as ``str`` or ``bool``, a name not a ``str``, or values that are not
        numbers.
    ValueError
        An input out of range or an unknown ``reading`` / ``coefficients`` (the message names
        the argument and what is allowed){inverse_note}.
    RuntimeError
        The law gives no physical value at a point (the message names the inputs).
"""


def wnl(ar: float, tau_max_mpa: float, a_over_lambda: ArrayLike,
        reading: str = "bracket-sq", coefficients: str = "paper-table1", *,
        return_flags: bool = False) -> Flagged:
    return _law("wnl", "wnl", ar, tau_max_mpa, "a_over_lambda", a_over_lambda, reading,
                coefficients, False, return_flags)


def wnl_inverse(ar: float, tau_max_mpa: float, p_over_estar: ArrayLike,
                reading: str = "bracket-sq", coefficients: str = "paper-table1", *,
                return_flags: bool = False) -> Flagged:
    return _law("wnl_inverse", "wnl", ar, tau_max_mpa, "p_over_estar", p_over_estar, reading,
                coefficients, True, return_flags)


wnl.__doc__ = (
    "The WNL model's mean pressure at each contact half-width (``wavy eval --model wnl``).\n\n"
    "    Westergaard's law corrected by the fitted polynomials A(AR, τ_max) and B(AR, τ_max)\n"
    "    of the paper (Table 1).\n"
    + _WNL_COMMON.format(
        argument="a_over_lambda",
        meaning="Contact half-widths a/λ, dimensionless, each in [0, 0.5]",
        returns="p̄/E* at each a/λ",
        inverse_note="",
    )
    + """
    Examples
    --------
    >>> import wavy
    >>> wavy.wnl(0.18, 0.05, [0.1, 0.2]).shape
    (2,)
    >>> values, flags = wavy.wnl(0.18, 0.05, [0.1, 0.2], return_flags=True)
    >>> bool(flags.any())
    False
    """
)

wnl_inverse.__doc__ = (
    "The WNL model's contact half-width at each mean pressure\n"
    "    (``wavy eval --model wnl --p-over-estar``), by bracketed root finding.\n"
    + _WNL_COMMON.format(
        argument="p_over_estar",
        meaning="Mean pressures p̄/E*, dimensionless, each in [0, the model's full-contact"
        " pressure]",
        returns="a/λ at each p̄/E*",
        inverse_note="; a pressure above full contact, or one the model cannot invert",
    )
    + """
    Examples
    --------
    >>> import wavy
    >>> 0 < float(wavy.wnl_inverse(0.18, 0.05, 0.1)) < 0.5
    True
    """
)
