"""The cases of the sweep tests: three cheap curves (mesh 8) of which AR 0.3 diverges (Newton,
load step 8), and the job every pool runs (module level, so that pools pickle it by name)."""

import wavy

MESH = 8
UNTIL = 0.45
CASES = [0.1, 0.18, 0.3]
DIVERGING = 0.3


def job(ar):
    """One case as a sweep runs it: the Result, or the SolveError raised."""
    return wavy.solve(ar=ar, mesh=MESH, until_a_over_lambda=UNTIL)
