"""docs/theory.md §8: the solver converges for every speed, E_inf/E0 up to 1e4, Prony series of 30
terms and loads from one contact spot to full contact — or raises. Here it must converge.

Grid: 1-D profiles of 128 points and 2-D surfaces of 32² (the 64² version of the same
sweep is marked slow). Each converged result must also be physically sane: p >= 0, gap
>= -rtol * ptp(h), load balance, finite non-negative friction.
"""

import itertools
import re

import numpy as np
import pytest

import bem
from bem.contact.options import MAXITER
from bem.contact.solver import LINES_MAXITER_SHARE

L = 0.01
XI = [1e-8, 1e-4, 1e-2, 1.0, 1e2, 1e8]
LOADS = [1e-4, 1e-2, 1.0, 100.0]  # from a single spot to full contact (see _load)


def _materials():
    taus = np.logspace(-8, 4, 30)
    return {
        "seed": bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01),
        "sls_1e4": bem.Material.standard_linear_solid(E0=1e3, E_inf=1e7, creep_time=0.01),
        "prony30_1e4": bem.Material.from_prony(E0=1e5, moduli=np.full(30, (1e4 - 1) * 1e5 / 30), times=taus),
    }


MATERIALS = _materials()


def _surface(dim, n):
    if dim == 1:
        return bem.surfaces.profile(4 * n, L, hurst=0.8, scales=64, rms_height=2e-5, seed=2)
    return bem.surfaces.self_affine(n, L, hurst=0.8, scales=n // 2, rms_height=2e-5, seed=2)


def _check(surface, material, xi, level):
    area = L**surface.ndim
    load = level * 1e7 * 2e-5 / L * area * 10  # scaled from E_inf * rms height / L
    speed = xi * L / material.creep_times.max()
    res = bem.solve(surface, material, speed=speed, load=load)
    assert res.success and res.residual <= 1e-8
    assert np.all(res.pressure >= 0)
    assert res.pressure.mean() * area == pytest.approx(load, rel=1e-12)
    assert res.gap.min() >= -1e-8 * np.ptp(surface.heights) * 1.0001
    assert np.isfinite(res.friction) and res.friction >= 0
    return res


CASES = list(itertools.product(MATERIALS, [1, 2], XI, LOADS))


@pytest.mark.parametrize("material, dim, xi, level", CASES)
def test_converges_everywhere(material, dim, xi, level):
    _check(_surface(dim, 32), MATERIALS[material], xi, level)


def test_sweep_spans_one_spot_to_full_contact():
    """The load levels really cover the range the contract names."""
    s, m = _surface(2, 32), MATERIALS["seed"]
    low = _check(s, m, 1e-2, LOADS[0])
    high = _check(s, m, 1e-2, LOADS[-1])
    assert low.contact_fraction <= 2 / s.heights.size  # one or two cells
    assert high.contact_fraction == 1.0


@pytest.mark.slow
@pytest.mark.parametrize("material, xi, level", list(itertools.product(MATERIALS, XI, LOADS)))
def test_converges_everywhere_64(material, xi, level):
    _check(_surface(2, 64), MATERIALS[material], xi, level)


@pytest.mark.heavy
def test_crawling_line_attempt_leaves_room_for_the_fallback():
    """The hardest case of the sweep at 128²: E_inf/E0 = 1e4, xi = 1, a few contact spots.

    Its line-preconditioned attempt can creep (steps of 1/16-1/64) without stalling. The
    principle checked: that attempt never takes more than its share of ``maxiter``
    (``bem.contact.solver.LINES_MAXITER_SHARE``), so the unpreconditioned attempt always has
    the rest, and the solve converges. How many steps the first attempt takes depends on the
    machine's round-off (88 and 200 have been measured), so no count is asserted.
    """
    res = _check(_surface(2, 128), MATERIALS["sls_1e4"], 1.0, 1e-2)
    first = re.search(r"after a first attempt of (\d+)", res.message)
    if first is not None:  # the line attempt gave up: it kept within its share
        assert int(first.group(1)) <= LINES_MAXITER_SHARE * MAXITER
        assert res.iterations <= MAXITER
