"""Inputs judged as the command line judges them, in Python's words: a number is a Python or
numpy number (a str or bool is a TypeError naming the argument), every message names the
Python argument (tau_max_mpa), never a flag (--tau-max-mpa). One row per bad input."""

import pathlib

import numpy as np
import pytest

import wavy

SOLVE = dict(ar=0.3, mesh=8, until_a_over_lambda=0.2)


def solve(**changes):
    return lambda: wavy.solve(**{**SOLVE, **changes})


# (call, exception, the message's start: the argument it names)
BAD = [
    # numbers given as str, bool, None or other objects
    (solve(ar="0.3"), TypeError, "ar must be a real number"),
    (solve(ar="abc"), TypeError, "ar must be a real number"),
    (solve(ar=True), TypeError, "ar must be a real number"),
    (solve(ar=np.bool_(True)), TypeError, "ar must be a real number"),
    (solve(ar=1 + 2j), TypeError, "ar must be a real number"),
    (solve(ar=[0.3]), TypeError, "ar must be a real number"),
    (solve(tau_max_mpa="0.1"), TypeError, "tau_max_mpa must be a real number"),
    (solve(tau_max_mpa=None), TypeError, "tau_max_mpa must be a real number"),
    (solve(mu="1"), TypeError, "mu must be a real number"),
    (solve(estar_mpa=False), TypeError, "estar_mpa must be a real number"),
    (solve(kappa_over_g="1000"), TypeError, "kappa_over_g must be a real number"),
    (solve(thickness_over_lambda="1"), TypeError, "thickness_over_lambda must be a real number"),
    (solve(tolerance="0.01", mesh=None), TypeError, "tolerance must be a real number"),
    (solve(until_a_over_lambda="0.2"), TypeError, "until_a_over_lambda must be a real number"),
    (solve(until_p_over_estar=True), TypeError, "until_p_over_estar must be a real number"),
    (solve(ar=None, profile="1:0.1,4:0.05", until_contact_fraction="0.3"), TypeError,
     "until_contact_fraction must be a real number"),
    # flags, names, meshes and paths of the wrong type
    (solve(unload="yes"), TypeError, "unload must be True or False"),
    (solve(unload=1), TypeError, "unload must be True or False"),
    (solve(error_estimate=None), TypeError, "error_estimate must be True or False"),
    (solve(kinematics=1), TypeError, "kinematics must be a str"),
    (solve(mesh=48.0), TypeError, "mesh must be"),
    (solve(mesh=True), TypeError, "mesh must be"),
    (solve(vtk=3), TypeError, "vtk must be a path"),
    (solve(ar=None, profile=1.0), TypeError, "profile must be a str"),
    (lambda: wavy.wnl(0.2, 0.1, [0.1], reading=None), TypeError, "reading must be a str"),
    (lambda: wavy.wnl(0.2, 0.1, [0.1], coefficients=1), TypeError, "coefficients must be a str"),
    (lambda: wavy.wnl("0.2", 0.1, [0.1]), TypeError, "ar must be a real number"),
    (lambda: wavy.wnl(0.2, "0.1", [0.1]), TypeError, "tau_max_mpa must be a real number"),
    (lambda: wavy.westergaard(0.2, ["0.1"]), TypeError, "a_over_lambda must be numbers"),
    (lambda: wavy.westergaard(0.2, [True, False]), TypeError, "a_over_lambda must be numbers"),
    (lambda: wavy.westergaard_inverse(0.2, "0.1"), TypeError, "p_over_estar must be numbers"),
    (lambda: wavy.wnl_inverse(0.2, 0.1, [0.1, None]), TypeError, "p_over_estar must be numbers"),
    (lambda: wavy.wnl(0.2, 0.1, [0.1], return_flags="yes"), TypeError,
     "return_flags must be True or False"),
    (lambda: wavy.run(None), TypeError, "spec_path must be a path"),
    (lambda: wavy.run("x.toml", out=1), TypeError, "out must be a path"),
    # values out of range or options that do not combine: the library's check, Python's names
    (solve(ar=0.0), ValueError, "ar = 0 is out of range; allowed: > 0"),
    (solve(ar=float("inf")), ValueError, "ar = inf is out of range"),
    (solve(tau_max_mpa=-0.1), ValueError, "tau_max_mpa = -0.1 is out of range"),
    (solve(mu=float("nan")), ValueError, "mu = NaN is out of range"),
    (solve(elastic_slip_over_element=-1), ValueError,
     "elastic_slip_over_element = -1 is out of range; allowed: >= 0"),
    (solve(estar_mpa=0), ValueError, "estar_mpa = 0 is out of range"),
    (solve(kappa_over_g=-1), ValueError, "kappa_over_g = -1 is out of range"),
    (solve(thickness_over_lambda=0), ValueError, "thickness_over_lambda = 0 is out of range"),
    (solve(until_a_over_lambda=0.5), ValueError, "until_a_over_lambda = 0.5 is out of range"),
    (solve(until_p_over_estar=-1), ValueError, "until_p_over_estar = -1 is out of range"),
    (solve(until_contact_fraction=1.5), ValueError, "until_contact_fraction = 1.5 is out of range"),
    (solve(until_contact_fraction=0.5, until_p_over_estar=0.1), ValueError,
     "until_contact_fraction = 0.5: cannot be used with until_p_over_estar"),
    (solve(tolerance=0.01), ValueError, "mesh = 8: cannot be used with tolerance"),
    (solve(mesh=None, tolerance=2.0), ValueError, "tolerance = 2 is out of range"),
    (solve(mesh=3), ValueError, "mesh = 3 is out of range"),
    (solve(mesh="huge"), ValueError, "mesh = huge is out of range"),
    (solve(kinematics="elastic"), ValueError, "kinematics = elastic is out of range"),
    (solve(unload=True, error_estimate=True), ValueError,
     "unload = true: cannot be used with error_estimate"),
    (solve(unload=True, unloading_substeps=0), ValueError,
     "unloading_substeps = 0 is out of range; allowed: an int >= 1"),
    (solve(unload=True, unloading_substeps=2.0), TypeError, "unloading_substeps must be an int"),
    (solve(unloading_substeps=2), ValueError, "unloading_substeps = 2: needs unload"),
    (solve(ar=None, profile="2:0.1"), ValueError, "profile = 2:0.1: "),
    (solve(ar=None, profile="1:0.1,4:0.1", tolerance=0.01, mesh=None), ValueError,
     "tolerance = 0.01: is measured for a single sinusoid; with profile choose mesh"),
    (solve(profile="1:0.1"), ValueError, "give exactly one of ar"),
    (solve(ar=None), ValueError, "give exactly one of ar"),
    (lambda: wavy.wnl(0.2, 0.1, [0.1], reading="square"), ValueError, "reading = square is out of range"),
    (lambda: wavy.wnl(0.2, 0.1, [0.1], coefficients="mine"), ValueError,
     "coefficients = mine is out of range"),
    (lambda: wavy.wnl(-0.2, 0.1, [0.1]), ValueError, "ar = -0.2 is out of range"),
    (lambda: wavy.westergaard(0.2, [0.6]), ValueError, "a_over_lambda = 0.6 is out of range"),
    (lambda: wavy.westergaard_inverse(0.2, [-1]), ValueError, "p_over_estar = -1 is out of range"),
]


@pytest.mark.parametrize("call,error,start", BAD, ids=[b[2][:40] for b in BAD])
def test_a_bad_input_raises_its_named_error(call, error, start):
    with pytest.raises(error) as raised:
        call()
    message = str(raised.value)
    assert message.startswith(start), message
    assert "--" not in message, message
    # a TypeError is raised before anything is computed, a ValueError is not a TypeError
    assert type(raised.value) is error


def test_numpy_and_python_numbers_are_numbers():
    plain = wavy.solve(**SOLVE)
    for ar in (np.float64(0.3), np.array(0.3), np.float64(0.3).item()):
        assert wavy.solve(**{**SOLVE, "ar": ar}) == plain
    assert wavy.solve(**{**SOLVE, "mesh": np.int64(8)}) == plain
    assert np.array_equal(wavy.westergaard(1, np.arange(3) / 10), wavy.westergaard(1.0, [0, 0.1, 0.2]))


def test_a_path_may_be_a_pathlib_path(tmp_path):
    r = wavy.solve(**SOLVE, vtk=pathlib.Path(tmp_path))
    assert (tmp_path / "series.pvd").is_file() and r.load_steps > 0
