"""Sweeps at scale: results and every wavy exception pickle to equal objects, and a sweep with
one diverging case completes on multiprocessing.Pool, ProcessPoolExecutor and a Dask
LocalCluster (processes, 2 workers: the documented example, python/examples/dask_sweep.py),
each handing back the good results and the failing case's SolveError with reason and partial."""

import concurrent.futures
import multiprocessing
import pickle
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

import wavy
from sweep_cases import CASES, DIVERGING, MESH, UNTIL, job

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "dask_sweep.py"


def expected():
    """Each case solved here: its Result or its SolveError."""
    answers = {}
    for ar in CASES:
        try:
            answers[ar] = job(ar)
        except wavy.SolveError as e:
            answers[ar] = e
    assert isinstance(answers[DIVERGING], wavy.SolveError)
    assert all(isinstance(answers[ar], wavy.Result) for ar in CASES if ar != DIVERGING)
    return answers


def roundtrip(obj):
    return pickle.loads(pickle.dumps(obj))


def test_a_result_pickles_to_an_equal_result():
    r = wavy.solve(ar=0.1, mesh=12, error_estimate=True, until_a_over_lambda=0.3)
    back = roundtrip(r)
    assert back == r and back is not r
    assert back.columns == r.columns and back.notes == r.notes
    assert back != wavy.solve(ar=0.18, mesh=8)


def test_every_wavy_exception_pickles_to_an_equal_one():
    with pytest.raises(wavy.SolveError) as stopped:
        job(DIVERGING)
    e = stopped.value
    back = roundtrip(e)
    assert back == e and type(back) is wavy.SolveError
    assert (str(back), back.reason, back.a_over_lambda) == (str(e), e.reason, e.a_over_lambda)
    assert back.partial == e.partial and back.partial.load_steps > 0
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        wavy.wnl(0.5, 0.05, [0.2])
    w = caught[0].message
    assert isinstance(w, wavy.ExtrapolationWarning) and roundtrip(w) == w
    # the built-in exceptions wavy raises: the same type and message after the trip
    for call in (lambda: wavy.solve(ar=0.0), lambda: wavy.solve(ar="0.1"),
                 lambda: wavy.wnl(0.3, 0.2, [0.001], reading="literal")):
        with pytest.raises(Exception) as raised:
            call()
        back = roundtrip(raised.value)
        assert type(back) is type(raised.value) and back.args == raised.value.args


def assert_sweep(answers, reference):
    for ar in CASES:
        got, want = answers[ar], reference[ar]
        assert type(got) is type(want), (ar, got)
        assert got == want
    failed = answers[DIVERGING]
    assert failed.reason and failed.partial.load_steps > 0


def test_a_sweep_with_a_diverging_case_completes_on_multiprocessing_pool():
    reference = expected()
    with multiprocessing.Pool(2) as pool:
        pending = {ar: pool.apply_async(job, (ar,)) for ar in CASES}
        answers = {}
        for ar, p in pending.items():
            try:
                answers[ar] = p.get(timeout=60)
            except wavy.SolveError as e:
                answers[ar] = e
        # map re-raises the case's own error (it used to hang on an unpicklable one)
        with pytest.raises(wavy.SolveError) as raised:
            pool.map(job, CASES, chunksize=1)
        assert raised.value == reference[DIVERGING]
    assert_sweep(answers, reference)


def test_a_sweep_with_a_diverging_case_completes_on_process_pool_executor():
    reference = expected()
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        futures = {ar: pool.submit(job, ar) for ar in CASES}
        answers = {ar: f.exception(timeout=60) or f.result() for ar, f in futures.items()}
    assert_sweep(answers, reference)


def test_the_dask_example_sweeps_on_a_local_cluster_of_two_worker_processes():
    import dask.distributed  # noqa: F401  a test tool (python/requirements-test.txt): no skip
    reference = expected()
    p = subprocess.run(
        [sys.executable, str(EXAMPLE), "--workers", "2", "--ar", *map(str, CASES),
         "--tau-max-mpa", "0", "--mesh", str(MESH), "--until-a-over-lambda", str(UNTIL)],
        capture_output=True, text=True, timeout=120,
    )
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    sys.path.insert(0, str(EXAMPLE.parent))
    try:
        import dask_sweep
    finally:
        sys.path.pop(0)
    want = [dask_sweep.describe(ar, 0.0, reference[ar]) for ar in CASES]
    assert lines[:-1] == want, p.stdout
    assert lines[-1].startswith(f"{len(CASES)} cases, 1 stopped short")
    assert "stopped after" in want[CASES.index(DIVERGING)]
