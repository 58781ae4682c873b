"""The exponential streamline/time update of the internal variables (fem_reference.transport).

Reference: the exact solution of ``-ell alpha' + alpha = eps`` on ``[-5, 5]`` with inflow
``alpha(5) = eps(5)``, for ``eps = exp(-x^2)``::

    alpha(x) = (sqrt(pi) / 2 ell) [erfcx(c) e^{-x^2} - erfcx(b) e^{-25 - (5 - x)/ell}]
               + e^{-(5 - x)/ell} eps(5),      c = x + 1/(2 ell), b = 5 + 1/(2 ell).
"""

import numpy as np
import pytest
from scipy.special import erfcx

from fem_reference.transport import exponential_weights, integrate_line, streamline_operators


def exact_gaussian(x, ell):
    c = x + 0.5 / ell
    b = 5.0 + 0.5 / ell
    conv = np.sqrt(np.pi) / (2 * ell) * (erfcx(c) * np.exp(-(x**2)) - erfcx(b) * np.exp(-25.0 - (5.0 - x) / ell))
    return conv + np.exp(-(5.0 - x) / ell) * np.exp(-25.0)


def max_error(n, ell):
    x = np.linspace(5.0, -5.0, n + 1)  # upstream first
    return np.max(np.abs(integrate_line(x, np.exp(-(x**2)), ell) - exact_gaussian(x, ell)))


@pytest.mark.parametrize("ratio", np.logspace(-4, 4, 9))
def test_gaussian_strain_all_advection_lengths(ratio):
    # The update is exact for piecewise-linear strain and alpha is a positive average of
    # the strain (kernel mass <= 1), so the error is bounded by the interpolation error
    # of eps: h^2/8 max|eps''| = 0.05^2/8 * 2 = 6.25e-4, for every ell/h.
    h = 0.05
    assert max_error(200, ratio * h) <= 0.05**2 / 8 * 2


def test_second_order_convergence():
    # Exponential differencing is second order (interpolation of eps); fitted slope of
    # log(error) against log(h) over four halvings.
    ns = np.array([50, 100, 200, 400, 800])
    errs = np.array([max_error(n, 0.3) for n in ns])
    slope = np.polyfit(np.log(10.0 / ns), np.log(errs), 1)[0]
    assert 1.9 <= slope <= 2.1


@pytest.mark.parametrize("ell", [1e-6, 1e-2, 1.0, 1e2, 1e6])
def test_linear_strain_is_exact(ell):
    # eps = x gives alpha = x + ell (1 - exp(-(5 - x)/ell)) exactly; the scheme is exact
    # for piecewise-linear strain, so only round-off remains (on a non-uniform grid too).
    x = np.sort(np.random.default_rng(1).uniform(-5, 5, 60))[::-1]
    x = np.concatenate([[5.0], x])
    alpha = integrate_line(x, x, ell)
    exact = x + ell * -np.expm1(-(5.0 - x) / ell)
    assert np.max(np.abs(alpha - exact)) <= 1e-12 * max(1.0, ell) * 10


def test_limits_and_constant_fixed_point():
    a, wp, wn = exponential_weights(np.array([0.0, 1e-12, 1e-3, 0.099, 0.101, 3.0, 1e3, np.inf]))
    np.testing.assert_allclose(a + wp + wn, 1.0, rtol=0, atol=1e-15)
    assert (a[0], wp[0], wn[0]) == (1.0, 0.0, 0.0)  # glassy: alpha frozen
    assert (a[-1], wp[-1], wn[-1]) == (0.0, 0.0, 1.0)  # relaxed: alpha = eps
    # the series branch (z < 0.1) and the closed form agree at the switch
    z = np.array([0.1 - 1e-9, 0.1 + 1e-9])
    _, wp, wn = exponential_weights(z)
    assert abs(wp[0] - wp[1]) < 1e-9 and abs(wn[0] - wn[1]) < 1e-9


def test_rows_are_independent_and_order_free():
    rng = np.random.default_rng(0)
    x = np.tile(np.linspace(2.0, -2.0, 41), 3)
    keys = np.repeat([7, 3, 5], 41)
    eps = rng.standard_normal(x.size)
    perm = rng.permutation(x.size)
    L, R = streamline_operators(keys[perm], x[perm], 0.4)
    from scipy.sparse.linalg import spsolve

    alpha = np.empty_like(eps)
    alpha[perm] = spsolve(L.tocsc(), R @ eps[perm])
    for k in (3, 5, 7):
        sel = keys == k
        np.testing.assert_allclose(alpha[sel], integrate_line(x[sel], eps[sel], 0.4), rtol=0, atol=1e-13)
