"""A solve asked for more than round-off allows stops at its floor and says which residual it
attained (bem.contact.newton): in the message, and as ``attainable`` on the result.

The case: a 4096-point periodic rough profile (16 scales) under 300 N/m on a standard linear
solid with E_inf/E0 = 100 at xi = 1, strongly non-symmetric. Its residual settles near 2.3e-12:
quantised in steps of 4.6e-13, the spacing of floating-point numbers at the size of the gap's
terms over the gap scale. rtol 1e-11 converges; a tighter rtol must stop within 3x its products,
fail, and name the residual it attained.
"""

import re

import numpy as np
import pytest

import bem
from bem.contact import newton
from bem.contact.inner import Problem
from tests.conftest import perturbed

SLS = bem.Material.standard_linear_solid(E0=1e5, E_inf=1e7, creep_time=0.01)
KW = dict(speed=1.0, load=300.0, raise_on_failure=False)


@pytest.fixture(scope="module")
def profile():
    return bem.surfaces.self_affine(4096, 0.01, hurst=0.8, scales=16, rms_slope=0.1, seed=1, dim=1)


@pytest.fixture(scope="module")
def attainable(profile):
    res = bem.solve(profile, SLS, rtol=1e-11, **KW)
    assert res.success and res.attainable is None
    return res


@pytest.mark.parametrize("rtol", [1e-12, 1e-15])
def test_a_tolerance_below_the_floor_fails_fast_and_names_the_floor(profile, attainable, rtol):
    res = bem.solve(profile, SLS, rtol=rtol, **KW)
    assert not res.success
    assert res.matvecs <= 3 * attainable.matvecs  # within 3x of the solve at the last attainable tolerance
    assert "round-off floor" in res.message and "ask for rtol >=" in res.message
    assert res.attainable is not None and rtol < res.attainable < 1e-11
    assert f"{res.attainable:.2e}" in res.message
    with pytest.raises(bem.ConvergenceError, match="round-off floor"):
        bem.solve(profile, SLS, rtol=rtol, speed=1.0, load=300.0)


@pytest.mark.parametrize("seed", [None, *range(8)])
def test_what_it_says_is_attainable_is(profile, seed):
    """Asked for the tolerance the message quotes, a solve converges, whatever path round-off
    sends it along: the profile as it is and with its heights perturbed by 1e-12 relative, as
    another processor would round them (at the floor the residual settles a quantum of 4.6e-13
    higher or lower from one path to the next; quoted alone, the lowest residual was not reached
    again on 5 of these 8 perturbed copies)."""
    surface = profile if seed is None else perturbed(profile, 1e-12, seed)
    stopped = bem.solve(surface, SLS, rtol=1e-13, **KW)
    quoted = float(re.search(r"ask for rtol >= (\S+)", stopped.message).group(1))
    assert quoted >= stopped.attainable
    asked = bem.solve(surface, SLS, rtol=quoted, **KW)
    assert asked.success and asked.residual <= quoted


def test_without_the_stop_the_solve_crawls(profile, attainable, monkeypatch):
    """The check can fail: with the floor never recognised the same solve spends every step it is
    allowed (here 60) on the settled set."""
    monkeypatch.setattr(newton, "FLOOR_MARGIN", 0.0)
    res = bem.solve(profile, SLS, rtol=1e-12, maxiter=60, **KW)
    assert not res.success and res.iterations == 60 and res.attainable is None
    assert res.matvecs > 3 * attainable.matvecs


def test_the_floor_is_the_spacing_of_floats_at_the_gap_and_pressure_scales():
    ht = np.array([0.0, -1.0, -0.5])
    pb = Problem(ht=ht, load_control=True, approach=None, p_ref=2.0, h_ref=1e-3, c=1.0, final_atol=0.0)
    it = newton.Iterate(
        p=np.array([4.0, 0.0, 0.0]), u=np.zeros(3), g=np.zeros(3), delta=0.5, contact=ht == 0, residual=0.0
    )
    eps = np.finfo(float).eps
    assert newton.roundoff_floor(pb, it) == pytest.approx(eps * (1.0 / 1e-3 + 4.0 / 2.0))
