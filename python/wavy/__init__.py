"""wavy from Python: the contact of a soft solid on a rigid wavy surface.

Westergaard's law, the WNL model and the finite-element solver of the ``wavy`` command line,
with its names and units, numpy in and out. Every value, check and message comes from the
Rust library the command line uses (``wavy eval``, ``wavy solve``, ``wavy run``); this package
checks Python types, shapes arguments and results, and names arguments as Python does
(``tau_max_mpa``, not ``--tau-max-mpa``). ``help(wavy.solve)``, ``help(wavy.wnl)``,
``help(wavy.Result)`` describe every argument; docs/python.md the rest.

Examples
--------
>>> import wavy
>>> r = wavy.solve(ar=0.3, mesh=8, until_a_over_lambda=0.3)
>>> float(wavy.westergaard(0.1, 0.25))
0.15707963267948963
"""

from __future__ import annotations

from . import _wavy
from ._laws import westergaard, westergaard_inverse, wnl, wnl_inverse
from ._result import COLUMNS, ExtrapolationWarning, Result, SolveError
from ._solve import run, solve

#: The package's version (that of the wheel and of its Rust crate).
__version__: str = _wavy.__version__

__all__ = [
    "COLUMNS",
    "ExtrapolationWarning",
    "Result",
    "SolveError",
    "__version__",
    "run",
    "solve",
    "westergaard",
    "westergaard_inverse",
    "wnl",
    "wnl_inverse",
]

# the public objects say they are wavy's (reprs, pickles and help name `wavy.Result`, …)
for _name in ("ExtrapolationWarning", "Result", "SolveError", "run", "solve", "westergaard",
              "westergaard_inverse", "wnl", "wnl_inverse"):
    globals()[_name].__module__ = __name__
del _name
