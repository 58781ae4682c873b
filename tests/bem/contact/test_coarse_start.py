"""Nested iteration: the contact solver starts large periodic grids from the solution on the
grid with half the points per axis (bem.contact.solve_contact)."""

import numpy as np
import pytest

import bem
from bem.contact import ContactOptions
from bem.contact.start import coarse_start, prolong
from bem.halfspace.periodic import PeriodicHalfSpace


@pytest.mark.parametrize("shape", [(6,), (8, 6)])
def test_prolong_keeps_the_coarse_values_the_mean_and_the_sign(shape):
    rng = np.random.default_rng(0)
    p = np.maximum(rng.standard_normal(shape), 0.0)
    fine = prolong(p)
    assert fine.shape == tuple(2 * n for n in shape)
    np.testing.assert_array_equal(fine[tuple(slice(0, None, 2) for _ in shape)], p)
    assert fine.mean() == pytest.approx(p.mean(), rel=1e-14)
    assert fine.min() >= 0.0
    # midpoints are the periodic average of their two coarse neighbours
    mid = fine[1::2] if len(shape) == 1 else fine[1::2, ::2]
    np.testing.assert_allclose(mid, 0.5 * (p + np.roll(p, -1, axis=0)))


def test_no_coarse_start_on_odd_or_small_grids():
    material = bem.Material.elastic(1e7)
    min_size = ContactOptions().coarsen_min_size

    def never(*args):
        raise AssertionError("no coarse solve expected")

    odd = PeriodicHalfSpace((2**18 + 1,), 0.01, material, 0.0)
    assert coarse_start(odd, np.zeros(odd.shape), never, min_size) == (None, 0.0, None)
    small = PeriodicHalfSpace((256, 256), 0.01, material, 0.0)
    assert small.size < min_size
    assert coarse_start(small, np.zeros(small.shape), never, min_size) == (None, 0.0, None)


@pytest.mark.parametrize(
    "material", [bem.Material.elastic(1e7), bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)]
)
def test_coarse_start_changes_nothing_but_the_cost(material):
    """512² at ~10-20 % contact, converged to rtol 1e-10 with and without the coarse start:
    the same pressure (to ~1e-8, the tolerance) and fewer products with it (elastic on the
    benchmark surface: 140 -> 99 at 512², 184 -> 108 at 1024²)."""
    assert 512**2 >= ContactOptions().coarsen_min_size
    s = bem.surfaces.self_affine(512, 0.01, hurst=0.8, scales=64, rms_height=2e-5, seed=3)
    out = {}
    for flag in (False, True):
        out[flag] = bem.solve(
            s, material, speed=0.01, load=3.0, rtol=1e-10, contact_options=ContactOptions(coarsen=flag)
        )
    plain, nested = out[False], out[True]
    assert 0.05 < nested.contact_fraction < 0.3
    err = np.linalg.norm(nested.pressure - plain.pressure) / np.linalg.norm(plain.pressure)
    assert err < 1e-7
    assert nested.matvecs < plain.matvecs
    assert "coarser grids" in nested.message and "coarser grids" not in plain.message


def test_coarsened_keeps_the_kind_of_operator():
    material = bem.Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01)
    op = PeriodicHalfSpace((16, 16), 0.01, material, 1.0)
    coarse = op.coarsened()
    assert coarse.shape == (8, 8) and not coarse.is_symmetric
    sym = op.symmetric_part().coarsened()
    assert sym.is_symmetric
    np.testing.assert_array_equal(sym.symbol, np.real(coarse.symbol))


def test_warm_start_goes_through_the_coarse_grid_and_is_kept_only_where_it_is_closer():
    """A warm start on a large grid first warm-starts the coarse solve; the fine solve then
    starts from the warm start itself when its contact set is closer to the new coarse
    solution's than interpolation would bring it, else from the interpolated coarse solution.
    Measured at 512²: the solution as its own warm start takes 1 step; the solution at a tenth
    of the load takes 6 steps (98 products) through the coarse grid, 15 (150) used as it is."""
    from viscobem_bench.periodic.problem import LENGTH, surface_heights

    s = bem.surfaces.from_heights(surface_heights(512), LENGTH)
    m = bem.Material.elastic(1e7)
    assert s.heights.size >= ContactOptions().coarsen_min_size
    cold = bem.solve(s, m, speed=0.0, load=6.0)
    own = bem.solve(s, m, speed=0.0, load=6.0, initial=cold.pressure)
    assert own.iterations == 1  # the fine warm start was kept: it is the answer
    far = bem.solve(s, m, speed=0.0, load=0.6).pressure
    through = bem.solve(s, m, speed=0.0, load=6.0, initial=far)
    fine_only = bem.solve(s, m, speed=0.0, load=6.0, initial=far, contact_options=ContactOptions(coarsen_warm=False))
    assert through.iterations <= cold.iterations + 1 < fine_only.iterations
    assert through.matvecs < 0.8 * fine_only.matvecs
    for r in (own, through, fine_only):
        np.testing.assert_allclose(r.pressure, cold.pressure, rtol=0, atol=1e-6 * cold.pressure.max())
