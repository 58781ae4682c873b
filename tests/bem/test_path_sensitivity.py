"""The answer does not depend on the path that round-off sends a solve along (docs/theory.md §4.2).

The case: a 32² rough cell on a standard linear solid with E_inf/E0 = 1e4 at xi = 100, about 30 %
contact, whose operator products change several-fold when its heights change in the last bits
(another processor's round-off). Its friction, contact set and pressure must not: they are fixed by
the contact problem, to the accuracy ``rtol`` bounds. The perturbation is the one that makes a test
run stand for another machine (``tests/conftest.py``).
"""

import numpy as np
import pytest

import bem
from tests.conftest import perturbed
from validation.references import periodic_exact as ref

L = 0.01


@pytest.fixture(scope="module")
def sensitive():
    surface = bem.surfaces.self_affine(32, L, hurst=0.8, scales=16, rms_height=2e-5, seed=2)
    material = bem.Material.standard_linear_solid(E0=1e3, E_inf=1e7, creep_time=0.01)
    speed = 100 * L / material.creep_times.max()
    a = ref.symbol(surface.shape, L, material, speed)
    full_contact = float(-ref.full_contact_pressure(surface.heights - surface.heights.max(), a).min()) * L**2
    return surface, material, speed, 0.05 * full_contact  # N: the stress suite's load level


def test_perturbed_copies_are_seeded_last_bit_changes(sensitive):
    surface = sensitive[0]
    h = surface.heights.copy()
    a, b, c = perturbed(surface, 1e-12, 0), perturbed(surface, 1e-12, 0), perturbed(surface, 1e-12, 1)
    np.testing.assert_array_equal(surface.heights, h)  # the original is untouched
    np.testing.assert_array_equal(a.heights, b.heights)  # seeded
    assert not np.array_equal(a.heights, c.heights) and not np.array_equal(a.heights, h)
    rel = np.abs(a.heights - h) / np.abs(h).max()
    assert 0 < rel.max() < 1e-11  # the size asked for (a few standard deviations of 1e-12)
    assert a.length == surface.length and a.shape == surface.shape


@pytest.mark.slow
def test_same_answer_on_every_path(sensitive):
    """Nominal and three perturbed copies: the products may differ several-fold (they are not
    asserted); friction, contact fraction and pressure agree to what rtol = 1e-8 bounds (the
    pressure's relative L2 error is at most 10 rtol against the exact solution, so two solves
    differ by at most 20 rtol; friction, a quadratic form of it, likewise)."""
    surface, material, speed, load = sensitive
    h = surface.heights
    runs = [
        bem.solve(s, material, speed=speed, load=load, rtol=1e-8)
        for s in [surface] + [perturbed(surface, 1e-12, k) for k in range(3)]
    ]
    base = runs[0]
    assert 0.05 < base.contact_fraction < 0.6, base.contact_fraction
    for res in runs[1:]:
        assert res.success
        assert res.friction == pytest.approx(base.friction, rel=2e-7)
        assert res.contact_fraction == pytest.approx(base.contact_fraction, abs=2 / h.size)
        err = np.linalg.norm(res.pressure - base.pressure) / np.linalg.norm(base.pressure)
        assert err <= 20 * 1e-8
