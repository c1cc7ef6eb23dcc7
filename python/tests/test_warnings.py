"""Every warning the command line gives, Python gives: an extrapolated law value warns
(wavy.ExtrapolationWarning) and return_flags=True gives each value's flag, the CLI's
`extrapolated` column; a solve's metadata says whether it lies outside the fit domain."""

import warnings

import numpy as np
import pytest

import wavy
from conftest import cli_rows

INSIDE = (0.18, 0.05)
OUTSIDE = [(0.5, 0.05), (0.05, 0.0), (0.2, 0.3)]


def quietly(call):
    """The call's answer, with any warning an error."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return call()


@pytest.mark.parametrize("ar,tau", OUTSIDE)
@pytest.mark.parametrize("inverse", [False, True])
def test_wnl_outside_its_fit_domain_warns_and_flags_each_value_as_the_cli_does(ar, tau, inverse):
    values = [0.01, 0.02] if inverse else [0.1, 0.2, 0.3]
    law = wavy.wnl_inverse if inverse else wavy.wnl
    flag = "--p-over-estar" if inverse else "--a-over-lambda"
    rows = cli_rows("eval", "--model", "wnl", "--ar", ar, "--tau-max-mpa", tau, flag, *values)
    assert [r["extrapolated"] for r in rows] == ["true"] * len(values)
    with pytest.warns(wavy.ExtrapolationWarning, match=rf"ar={ar}, tau_max_mpa={tau}\) is outside"):
        got, flags = law(ar, tau, values, return_flags=True)
    assert flags.dtype == bool and flags.shape == got.shape and flags.all()
    # the warning points at the caller's line, not at wavy's
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        law(ar, tau, values)
    assert caught[0].filename == __file__


@pytest.mark.parametrize("inverse", [False, True])
def test_wnl_inside_its_fit_domain_is_silent_and_unflagged(inverse):
    law = wavy.wnl_inverse if inverse else wavy.wnl
    values = np.array([[0.01, 0.02], [0.03, 0.04]])
    got, flags = quietly(lambda: law(*INSIDE, values, return_flags=True))
    assert flags.shape == (2, 2) and not flags.any()
    assert np.array_equal(got, quietly(lambda: law(*INSIDE, values)))


@pytest.mark.parametrize("law,values", [(wavy.westergaard, [0.1, 0.4]),
                                        (wavy.westergaard_inverse, [0.01, 0.1])])
def test_westergaard_never_extrapolates(law, values):
    # no fitted part: silent at any aspect ratio, every flag False
    got, flags = quietly(lambda: law(5.0, values, return_flags=True))
    assert not flags.any() and got.shape == flags.shape == (2,)


def test_an_extrapolation_warning_can_be_an_error_or_silenced():
    with warnings.catch_warnings():
        warnings.simplefilter("error", wavy.ExtrapolationWarning)
        with pytest.raises(wavy.ExtrapolationWarning):
            wavy.wnl(0.5, 0.05, [0.2])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.simplefilter("ignore", wavy.ExtrapolationWarning)
        assert wavy.wnl(0.5, 0.05, [0.2]).shape == (1,)


@pytest.mark.parametrize("ar,tau,outside", [(0.1, 0.0, False), (0.3, 0.2, False),
                                            (0.05, 0.0, True), (0.1, 0.3, True)])
def test_a_solve_says_whether_it_lies_outside_the_fit_domain(ar, tau, outside):
    r = quietly(lambda: wavy.solve(ar=ar, tau_max_mpa=tau, mesh=8, until_a_over_lambda=0.2))
    assert r.extrapolated is outside
