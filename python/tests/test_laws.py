"""Westergaard and WNL, forward and inverse, against `wavy eval`: every value to the last digit
(the CLI prints shortest round-trip floats, so equal floats have equal repr) and every
message of bad input."""

import numpy as np
import pytest

import wavy
from conftest import cli_error, cli_rows, python_words

XS = [0.0, 0.01, 0.1, 0.2, 0.25, 0.3, 0.4, 0.45, 0.5]


def same_digits(python_values, cli_strings):
    assert len(python_values) == len(cli_strings)
    for v, s in zip(python_values, cli_strings):
        assert repr(float(v)) == repr(float(s)), (v, s)


@pytest.mark.parametrize("ar", [0.05, 0.1, 0.3])
def test_westergaard_matches_eval(ar):
    rows = cli_rows("eval", "--model", "westergaard", "--ar", ar, "--a-over-lambda", *XS)
    same_digits(wavy.westergaard(ar, XS), [r["p_over_estar"] for r in rows])


@pytest.mark.parametrize("reading", ["bracket-sq", "bracket-2x"])
@pytest.mark.parametrize("coefficients", ["paper-table1", "ours-bracket-sq"])
@pytest.mark.parametrize("ar,tau", [(0.1, 0.0), (0.18, 0.05), (0.3, 0.2)])
def test_wnl_matches_eval(reading, coefficients, ar, tau):
    xs = [0.1, 0.2, 0.3, 0.4, 0.5]
    args = ["eval", "--model", "wnl", "--reading", reading, "--coefficients", coefficients,
            "--ar", ar, "--tau-max-mpa", tau, "--a-over-lambda", *xs]
    rows = cli_rows(*args)
    got = wavy.wnl(ar, tau, xs, reading=reading, coefficients=coefficients)
    same_digits(got, [r["p_over_estar"] for r in rows])


def test_inverses_match_eval():
    ps = [0.0, 0.01, 0.05, 0.1, 0.2]
    rows = cli_rows("eval", "--model", "westergaard", "--ar", 0.1, "--p-over-estar", *ps)
    same_digits(wavy.westergaard_inverse(0.1, ps), [r["a_over_lambda"] for r in rows])
    rows = cli_rows("eval", "--model", "wnl", "--ar", 0.18, "--tau-max-mpa", 0.05,
                    "--p-over-estar", *ps)
    same_digits(wavy.wnl_inverse(0.18, 0.05, ps), [r["a_over_lambda"] for r in rows])


def test_shapes_follow_the_input():
    assert wavy.westergaard(0.1, 0.25).shape == ()
    grid = np.linspace(0, 0.5, 6).reshape(2, 3)
    out = wavy.wnl(0.2, 0.1, grid)
    assert out.shape == (2, 3) and out.dtype == np.float64
    assert np.array_equal(out.ravel(), wavy.wnl(0.2, 0.1, grid.ravel()))
    assert float(wavy.westergaard(0.1, 0.25)) == pytest.approx(np.pi * 0.1 * 0.5)


@pytest.mark.parametrize(
    "call,args",
    [
        (lambda: wavy.westergaard(-1.0, [0.1]), ["--model", "westergaard", "--ar", "-1", "--a-over-lambda", "0.1"]),
        (lambda: wavy.westergaard(0.1, [0.1, 0.6]), ["--model", "westergaard", "--ar", "0.1", "--a-over-lambda", "0.1", "0.6"]),
        (lambda: wavy.wnl(0.1, -0.5, [0.1]), ["--model", "wnl", "--ar", "0.1", "--tau-max-mpa", "-0.5", "--a-over-lambda", "0.1"]),
        (lambda: wavy.wnl(0.1, 0.0, [float("nan")]), ["--model", "wnl", "--ar", "0.1", "--a-over-lambda", "NaN"]),
        (lambda: wavy.westergaard_inverse(0.1, [0.5]), ["--model", "westergaard", "--ar", "0.1", "--p-over-estar", "0.5"]),
        (lambda: wavy.wnl_inverse(0.1, 0.0, [-1.0]), ["--model", "wnl", "--ar", "0.1", "--p-over-estar", "-1"]),
    ],
)
def test_bad_input_is_a_value_error_with_the_cli_message(call, args):
    message, rc = cli_error("eval", *args)
    assert rc == 2
    with pytest.raises(ValueError) as e:
        call()
    assert str(e.value) == python_words(message)


def test_a_law_without_a_physical_value_is_a_runtime_error_with_the_cli_message():
    args = ["--model", "wnl", "--reading", "literal", "--ar", "0.3", "--tau-max-mpa", "0.2",
            "--a-over-lambda", "0.001"]
    message, rc = cli_error("eval", *args)
    assert rc == 1
    with pytest.raises(RuntimeError) as e:
        wavy.wnl(0.3, 0.2, [0.001], reading="literal")
    assert str(e.value) == python_words(message)
    assert not isinstance(e.value, ValueError)


def test_unknown_names_are_value_errors():
    with pytest.raises(ValueError, match=r"^reading = nope is out of range; allowed: bracket-sq"):
        wavy.wnl(0.1, 0.0, [0.1], reading="nope")
