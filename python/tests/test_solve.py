"""wavy.solve against `wavy solve`: every column to the last digit, the unloading branch, the
error estimate, the mesh choice, bad input and the solver stopping short."""

import csv
import io
import math

import numpy as np
import pytest

import wavy
from conftest import cli, cli_error, cli_rows, python_words

NUMERIC = ["a_over_lambda", "p_over_estar", "p_over_estar_reaction",
           "slab_displacement_over_lambda", "newton_iterations", "active_nodes",
           "contact_fraction", "patches", "friction_work_over_estar_lambda2"]


def assert_same_rows(result, rows, extra=()):
    assert result.load_steps == len(rows) == len(result.a_over_lambda)
    for column in NUMERIC:
        got = getattr(result, column)
        for v, s in zip(got, (r[column] for r in rows)):
            assert repr(float(v)) == repr(float(s)), (column, v, s)
    for column in extra:
        if column == "branch":
            assert list(result.branch) == [r["branch"] for r in rows]
        if column == "error_estimate":
            for v, s in zip(result.error_estimate, (r["error_estimate"] for r in rows)):
                assert (s == "" and math.isnan(v)) or repr(float(v)) == repr(float(s))


def test_the_default_solve_matches_the_cli():
    rows = cli_rows("solve", "--ar", 0.1)
    r = wavy.solve(ar=0.1)
    assert_same_rows(r, rows)
    assert r.mesh == (48, 24) and r.unknowns == 2 * 49 * 25
    assert r.newton_iterations_total == sum(int(x["newton_iterations"]) for x in rows)
    assert r.tangent_assemblies > 0 and r.factorisations > 0
    assert list(r.branch) == ["loading"] * len(rows)
    assert repr(r).startswith("<wavy.Result: ")


def test_an_unloading_loop_matches_the_cli():
    args = ["--ar", 0.3, "--tau-max-mpa", 0.05, "--until-a-over-lambda", 0.4, "--unload",
            "--mesh", 16]
    rows = cli_rows("solve", *args)
    r = wavy.solve(ar=0.3, tau_max_mpa=0.05, until_a_over_lambda=0.4, unload=True, mesh=16)
    assert_same_rows(r, rows, extra=["branch"])
    assert r.branch[0] == "loading" and r.branch[-1] == "unloading"
    # the loop closes at zero load
    assert r.p_over_estar[-1] == pytest.approx(0.0, abs=1e-6)
    # its energy both ways: the face's work of friction at the last point is the loop's work to
    # the load steps' error (measured 0.42 % at 16 elements)
    assert r.face_dissipation_over_estar_lambda2 == r.friction_work_over_estar_lambda2[-1]
    assert r.face_dissipation_over_estar_lambda2 == pytest.approx(
        r.cycle_work_over_estar_lambda2, rel=0.01)


def test_unloading_substeps_match_the_cli():
    args = ["--ar", 0.3, "--tau-max-mpa", 0.05, "--until-a-over-lambda", 0.4, "--unload",
            "--mesh", 16, "--unloading-substeps", 2]
    rows = cli_rows("solve", *args)
    r = wavy.solve(ar=0.3, tau_max_mpa=0.05, until_a_over_lambda=0.4, unload=True, mesh=16,
                   unloading_substeps=2)
    assert_same_rows(r, rows, extra=["branch"])
    one = wavy.solve(ar=0.3, tau_max_mpa=0.05, until_a_over_lambda=0.4, unload=True, mesh=16)
    loading = list(r.branch).count("loading")
    assert list(one.branch).count("loading") == loading
    assert list(r.branch).count("unloading") > list(one.branch).count("unloading")


def test_loading_points_match_the_cli():
    args = ["--ar", 0.1, "--until-a-over-lambda", 0.3, "--points", 10]
    rows = cli_rows("solve", *args)
    r = wavy.solve(ar=0.1, until_a_over_lambda=0.3, points=10)
    assert_same_rows(r, rows)
    assert r.load_steps < len(wavy.solve(ar=0.1, until_a_over_lambda=0.3).a_over_lambda) / 2


def test_exact_stick_matches_the_cli():
    args = ["--ar", 0.3, "--tau-max-mpa", 0.1, "--until-a-over-lambda", 0.3, "--mesh", 16,
            "--elastic-slip-over-element", 0]
    rows = cli_rows("solve", *args)
    r = wavy.solve(ar=0.3, tau_max_mpa=0.1, until_a_over_lambda=0.3, mesh=16,
                   elastic_slip_over_element=0)
    assert_same_rows(r, rows)
    penalty = wavy.solve(ar=0.3, tau_max_mpa=0.1, until_a_over_lambda=0.3, mesh=16)
    assert list(penalty.p_over_estar) != list(r.p_over_estar)


def test_the_error_estimate_matches_the_cli():
    rows = cli_rows("solve", "--ar", 0.1, "--mesh", 24, "--error-estimate")
    r = wavy.solve(ar=0.1, mesh=24, error_estimate=True)
    assert "error_estimate" in r.columns
    assert_same_rows(r, rows, extra=["error_estimate"])


def test_a_tolerance_chooses_the_cli_mesh():
    rows = cli_rows("solve", "--ar", 0.2, "--tolerance", 0.02)
    r = wavy.solve(ar=0.2, tolerance=0.02)
    assert_same_rows(r, rows)


def test_a_pressure_target_matches_the_cli():
    rows = cli_rows("solve", "--ar", 0.1, "--mesh", 16, "--until-p-over-estar", 0.1)
    r = wavy.solve(ar=0.1, mesh=16, until_p_over_estar=0.1)
    assert_same_rows(r, rows)


@pytest.mark.parametrize(
    "kwargs,args",
    [
        (dict(ar=0.0), ["--ar", "0"]),
        (dict(ar=0.1, tau_max_mpa=-1.0), ["--ar", "0.1", "--tau-max-mpa", "-1"]),
        (dict(ar=0.1, until_a_over_lambda=0.5), ["--ar", "0.1", "--until-a-over-lambda", "0.5"]),
        (dict(ar=0.1, until_p_over_estar=-1.0), ["--ar", "0.1", "--until-p-over-estar", "-1"]),
        (dict(ar=0.1, mu=float("nan")), ["--ar", "0.1", "--mu", "NaN"]),
        (dict(ar=0.1, tolerance=2.0), ["--ar", "0.1", "--tolerance", "2"]),
        (dict(ar=0.1, tolerance=1e-4), ["--ar", "0.1", "--tolerance", "0.0001"]),
        (dict(ar=0.1, kinematics="linear", tolerance=0.01),
         ["--ar", "0.1", "--kinematics", "linear", "--tolerance", "0.01"]),
    ],
)
def test_bad_input_is_a_value_error_with_the_cli_message(kwargs, args):
    message, rc = cli_error("solve", *args)
    assert rc == 2
    with pytest.raises(ValueError) as e:
        wavy.solve(**kwargs)
    assert str(e.value) == python_words(message)


def test_a_bad_mesh_names_the_argument_as_the_cli_names_the_flag():
    _, _, err = cli("solve", "--ar", 0.1, "--mesh", 3)
    with pytest.raises(ValueError) as e:
        wavy.solve(ar=0.1, mesh=3)
    assert str(e.value) in python_words(err) and str(e.value).startswith("mesh = 3 is out of range")
    with pytest.raises(ValueError, match="^mesh = 48: cannot be used with tolerance"):
        wavy.solve(ar=0.1, mesh=48, tolerance=0.01)


def test_a_solve_that_stops_raises_solve_error_with_the_converged_part():
    # mesh 4 resolves no contact edge beyond a/λ ≈ 0.44 (tests/solver/fe_extremes.rs: a target beyond the mesh)
    rc, out, err = cli("solve", "--ar", 0.1, "--mesh", 4)
    assert rc == 1
    rows = list(csv.DictReader(io.StringIO(out)))
    with pytest.raises(wavy.SolveError) as e:
        wavy.solve(ar=0.1, mesh=4)
    assert isinstance(e.value, RuntimeError)
    assert "error: " + str(e.value) + "\n" == python_words(err)
    assert e.value.reason in str(e.value) and "contact is complete" in e.value.reason
    assert_same_rows(e.value.partial, rows)
    assert e.value.a_over_lambda == float(rows[-1]["a_over_lambda"])


def test_to_pandas_has_the_cli_columns():
    # pandas is one of the test tools (python/requirements-test.txt): no skip when it is missing
    import pandas as pd
    r = wavy.solve(ar=0.3, mesh=8, until_a_over_lambda=0.3)
    df = r.to_pandas()
    assert isinstance(df, pd.DataFrame)
    assert list(df.columns) == list(wavy.COLUMNS)
    assert len(df) == r.load_steps
    for column in wavy.COLUMNS:
        np.testing.assert_array_equal(df[column].to_numpy(), np.asarray(getattr(r, column)))


def test_to_pandas_without_pandas_says_so(monkeypatch):
    import sys
    monkeypatch.setitem(sys.modules, "pandas", None)
    r = wavy.solve(ar=0.3, mesh=8, until_a_over_lambda=0.3)
    with pytest.raises(ImportError, match="pip install pandas"):
        r.to_pandas()


def _vtu_arrays(path):
    """The DataArrays of a VTK XML UnstructuredGrid written as binary base64 with a UInt64
    header (what wavy writes), read with the standard library and numpy alone."""
    import base64
    import xml.etree.ElementTree as ET

    kinds = {"Float64": np.float64, "Float32": np.float32, "UInt8": np.uint8,
             "Int64": np.int64, "UInt64": np.uint64, "Int32": np.int32}
    root = ET.parse(path).getroot()
    assert root.get("type") == "UnstructuredGrid" and root.get("header_type") == "UInt64"
    piece = root.find("UnstructuredGrid/Piece")
    arrays = {}
    for da in piece.iter("DataArray"):
        raw = base64.b64decode(da.text.strip())
        size = int(np.frombuffer(raw[:8], dtype="<u8")[0])
        values = np.frombuffer(raw[8:8 + size], dtype=np.dtype(kinds[da.get("type")]).newbyteorder("<"))
        arrays[da.get("Name") or "Points"] = values.reshape(-1, int(da.get("NumberOfComponents", "1")))
    return int(piece.get("NumberOfPoints")), int(piece.get("NumberOfCells")), arrays


def test_vtk_writes_a_time_series_that_reads_back(tmp_path):
    import xml.etree.ElementTree as ET

    r = wavy.solve(ar=0.3, mesh=16, until_a_over_lambda=0.3, vtk=tmp_path)
    datasets = ET.parse(tmp_path / "series.pvd").getroot().findall("Collection/DataSet")
    assert len(datasets) == len(r.a_over_lambda)
    times = np.array([float(d.get("timestep")) for d in datasets])
    assert np.array_equal(times, r.slab_displacement_over_lambda)
    for d in datasets:
        points, cells, arrays = _vtu_arrays(tmp_path / d.get("file"))
        assert cells == 16 * 8 and points == 17 * 9
        assert np.array_equal(
            arrays["displacement_over_lambda"],
            arrays["Points"] - arrays["reference_position_over_lambda"],
        )
        assert (arrays["J"] > 0).all()
        assert set(np.unique(arrays["in_contact"])) <= {0, 1}
    # the last step: as many nodes in contact as the solver reports
    assert int(arrays["in_contact"].sum()) == r.active_nodes[-1]


def test_vtk_of_a_curve_that_stops_holds_its_converged_states_and_says_why(tmp_path):
    import xml.etree.ElementTree as ET

    with pytest.raises(wavy.SolveError) as e:
        wavy.solve(ar=0.3, mesh=8, until_a_over_lambda=0.45, vtk=tmp_path / "out")
    partial = e.value.partial
    collection = ET.parse(tmp_path / "out" / "series.pvd").getroot().find("Collection")
    assert collection.get("status") == "incomplete"
    assert e.value.reason in collection.get("reason")
    datasets = collection.findall("DataSet")
    assert partial.load_steps > 0 and len(datasets) == partial.load_steps
    times = np.array([float(d.get("timestep")) for d in datasets])
    assert np.array_equal(times, partial.slab_displacement_over_lambda)
    for d in datasets:
        _, cells, _ = _vtu_arrays(tmp_path / "out" / d.get("file"))
        assert cells == 8 * 4
    # the command line writes the same series and still fails
    rc, _, _ = cli("solve", "--ar", 0.3, "--mesh", 8, "--until-a-over-lambda", 0.45,
                   "--vtk", tmp_path / "cli")
    assert rc == 1
    for name in ["series.pvd"] + [d.get("file") for d in datasets]:
        assert (tmp_path / "cli" / name).read_bytes() == (tmp_path / "out" / name).read_bytes()


def test_a_vtk_path_that_is_a_file_is_a_value_error(tmp_path):
    target = tmp_path / "taken"
    target.write_text("")
    with pytest.raises(ValueError, match=r"^vtk = .*taken: is a file; give a folder"):
        wavy.solve(ar=0.3, mesh=8, until_a_over_lambda=0.3, vtk=target)
    message, rc = cli_error("solve", "--ar", 0.3, "--mesh", 8, "--vtk", target)
    assert rc == 2 and message.startswith("--vtk = ")


def test_a_profile_without_mesh_gets_the_coarsest_mesh_that_resolves_it(capfd):
    args = ("--profile", "1:0.1,8:0.05", "--until-contact-fraction", 0.3)
    rc, out, err = cli("solve", *args)
    assert rc == 0
    r = wavy.solve(profile="1:0.1,8:0.05", until_contact_fraction=0.3)
    assert r.mesh == (52, 26) and len(r.notes) == 1 and "52×26" in r.notes[0]
    assert r.notes[0] in err and r.notes[0] in capfd.readouterr().err
    assert_same_rows(r, list(csv.DictReader(io.StringIO(out))))
    # one element coarser is refused, naming the mesh that works
    with pytest.raises(ValueError) as e:
        wavy.solve(profile="1:0.1,8:0.05", mesh=51)
    assert str(e.value).startswith("mesh = 51: profile harmonic 8")
    assert str(e.value).endswith("the coarsest mesh that resolves it is 52 (mesh 52)")
    message, rc = cli_error("solve", "--profile", "1:0.1,8:0.05", "--mesh", 51)
    assert rc == 2 and python_words(message) == str(e.value)
    # a sinusoid keeps the default, without a note
    assert wavy.solve(ar=0.3, until_a_over_lambda=0.1).notes == []


def test_a_two_scale_profile_matches_the_cli():
    args = ("--profile", "1:0.1,8:0.1", "--mesh", 64, "--until-contact-fraction", 0.5)
    rows = cli_rows("solve", *args)
    r = wavy.solve(profile="1:0.1,8:0.1", mesh=64, until_contact_fraction=0.5)
    assert_same_rows(r, rows)
    assert r.contact_fraction[-1] >= 0.5 and max(r.patches) >= 2


def test_coarsened_columns_match_the_cli_with_fewer_unknowns():
    args = ("--profile", "1:0.1,8:0.1", "--mesh", 64, "--until-contact-fraction", 0.5,
            "--coarsen-at-aspect", 4)
    rows = cli_rows("solve", *args)
    r = wavy.solve(profile="1:0.1,8:0.1", mesh=64, until_contact_fraction=0.5,
                   coarsen_at_aspect=4)
    assert_same_rows(r, rows)
    assert r.mesh == (64, 32) and r.unknowns < 2 * 65 * 33


@pytest.mark.parametrize(
    "kwargs,args",
    [
        (dict(coarsen_at_aspect=0.5), ["--coarsen-at-aspect", "0.5"]),
        (dict(coarsen_at_aspect=4, tolerance=0.01),
         ["--coarsen-at-aspect", "4", "--tolerance", "0.01"]),
    ],
)
def test_coarsening_out_of_range_or_with_a_tolerance_is_the_cli_error(kwargs, args):
    message, rc = cli_error("solve", "--ar", "0.1", *args)
    assert rc == 2
    with pytest.raises(ValueError) as e:
        wavy.solve(ar=0.1, **kwargs)
    assert str(e.value) == python_words(message)


def test_a_profile_the_mesh_cannot_resolve_is_a_value_error():
    with pytest.raises(ValueError, match="harmonic 16"):
        wavy.solve(profile="1:0.1,16:0.1", mesh=32)
    with pytest.raises(ValueError, match="exactly one of ar"):
        wavy.solve(ar=0.1, profile="1:0.1")
