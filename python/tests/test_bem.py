"""``solve(solver="bem")``: the boundary-element solver from Python, against the command line
it shares its request layer with, and its refusals."""

import subprocess

import numpy as np
import pytest

import wavy

from conftest import WAVY


def test_a_frictional_loop_on_the_half_plane_matches_the_command_line():
    kwargs = dict(ar=0.01, kappa_over_g=2.1667, mu=0.5, tau_max_mpa=1000.0, half_plane=True,
                  until_a_over_lambda=0.2, points=6, unload=True, grid_points=1024)
    r = wavy.solve(solver="bem", **kwargs)
    assert r.mesh is None and r.grid_points == 1024
    assert set(r.branch) == {"loading", "unloading"}
    assert abs(r.a_over_lambda[r.branch == "loading"][-1] - 0.2) < 1e-9
    # friction sticks part of the contact
    assert np.all(r.stick_fraction <= r.contact_fraction + 1e-12)
    assert r.stick_fraction.max() > 0
    assert r.face_dissipation_over_estar_lambda2 > 0
    assert abs(r.cycle_work_over_estar_lambda2) < 1e-5 * r.face_dissipation_over_estar_lambda2
    cli = subprocess.run(
        [str(WAVY), "solve", "--solver", "bem", "--ar", "0.01", "--kappa-over-g", "2.1667",
         "--mu", "0.5", "--tau-max-mpa", "1000", "--half-plane", "--until-a-over-lambda", "0.2",
         "--points", "6", "--unload", "--grid-points", "1024"],
        capture_output=True, text=True, check=True,
    )
    rows = cli.stdout.strip().splitlines()[1:]
    assert len(rows) == len(r)
    p = np.array([float(row.split(",")[1]) for row in rows])
    np.testing.assert_array_equal(p, r.p_over_estar)


def test_the_boundary_element_solver_refuses_what_it_does_not_model():
    with pytest.raises(ValueError, match="small-strain"):
        wavy.solve(solver="bem", ar=0.1, kinematics="finite")
    with pytest.raises(ValueError, match="boundary-element solver's grid"):
        wavy.solve(solver="bem", ar=0.1, mesh=8)
    with pytest.raises(ValueError, match="belongs to the boundary-element solver"):
        wavy.solve(ar=0.1, grid_points=1024)
    with pytest.raises(ValueError, match="frictional one steps node by node"):
        wavy.solve(ar=0.1, tau_max_mpa=0.1, points=5)
    with pytest.raises(ValueError, match="solver"):
        wavy.solve(solver="spectral", ar=0.1)
    with pytest.raises(TypeError, match="grid_points must be an int"):
        wavy.solve(solver="bem", ar=0.1, grid_points=1024.0)
