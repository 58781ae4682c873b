"""Nested iteration: the contact solver starts large grids (and strongly non-symmetric problems
on any grid) from the solution on the grid with half the points per axis
(bem.contact.solve_contact, bem.contact.start); the operators' grid transfers."""

import numpy as np
import pytest

import bem
from bem.contact import ContactOptions, start
from bem.contact.start import coarse_start
from bem.halfspace.isolated import IsolatedHalfSpace
from bem.halfspace.periodic import PeriodicHalfSpace

prolong = PeriodicHalfSpace.prolong


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


def test_no_coarse_start_on_odd_or_small_grids_or_near_full_contact():
    material = bem.Material.elastic(1e7)

    def never(*args):
        raise AssertionError("no coarse solve expected")

    odd = PeriodicHalfSpace((2**18 + 1,), 0.01, material, 0.0)
    assert coarse_start(odd, np.zeros(odd.shape), never) == (None, 0.0, None)
    h = np.zeros((8, 8))
    small = PeriodicHalfSpace(h.shape, 0.01, material, 0.0)
    assert small.size < start.COARSEN_MIN_SIZE
    assert not start.wants_coarse_start(small, h, 1e3, ContactOptions())
    big = PeriodicHalfSpace((16, 16), 0.01, material, 0.0)
    rough = 1e-5 * np.random.default_rng(1).standard_normal(big.shape)
    assert start.wants_coarse_start(big, rough, 1e3, ContactOptions())
    assert not start.wants_coarse_start(big, rough, 1e3, ContactOptions(coarsen=False))
    assert not start.wants_coarse_start(big, np.zeros(big.shape), 1e3, ContactOptions())  # full contact


def test_strongly_nonsymmetric_problems_coarsen_on_small_grids_unless_nearly_in_full_contact():
    rubber = bem.Material.standard_linear_solid(E0=1e3, E_inf=1e7, creep_time=0.01)
    s = bem.surfaces.self_affine(256, 0.01, hurst=0.8, scales=16, rms_height=2e-5, seed=2, dim=1)
    op = PeriodicHalfSpace(s.shape, s.length, rubber, 1.0)
    assert op.max_phase() > np.pi / 4
    assert start.wants_coarse_start(op, s.heights, 10.0, ContactOptions())
    assert not start.wants_coarse_start(op, s.heights, 1e9, ContactOptions())  # nearly full contact
    tiny = PeriodicHalfSpace((64,), s.length, rubber, 1.0)
    assert tiny.size < start.COARSEN_MIN_SIZE
    assert not start.wants_coarse_start(tiny, s.heights[::4], 10.0, ContactOptions())


@pytest.mark.parametrize("shape", [(6,), (8, 6)])
def test_isolated_grid_transfers_keep_the_mean_the_sign_and_linear_fields(shape):
    """Isolated grids are cell-centred: a coarse element is the mean of the two (four) fine
    elements it covers, and interpolation is linear between coarse centres, zero beyond the
    domain; a linear field is carried exactly away from the ends."""
    op = IsolatedHalfSpace(tuple(2 * n for n in shape), 0.01, bem.Material.elastic(1e7), 0.0)
    rng = np.random.default_rng(1)
    fine = np.maximum(rng.standard_normal(op.shape), 0.0)
    coarse = op.restrict(fine)
    assert coarse.shape == shape and coarse.mean() == pytest.approx(fine.mean(), rel=1e-14)
    back = op.prolong(np.maximum(rng.standard_normal(shape), 0.0))
    assert back.shape == op.shape and back.min() >= 0.0
    x = (np.arange(op.shape[0]) + 0.5) / op.shape[0]
    line = np.broadcast_to(x.reshape((-1,) + (1,) * (len(shape) - 1)), op.shape)
    inner = tuple(slice(2, -2) for _ in shape)
    np.testing.assert_allclose(op.prolong(op.restrict(line))[inner], line[inner], rtol=0, atol=1e-14)
    assert op.coarsened().shape == shape
    assert IsolatedHalfSpace((7,), 0.01, bem.Material.elastic(1e7), 0.0).coarsened() is None


@pytest.mark.parametrize(
    "material", [bem.Material.elastic(1e7), bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)]
)
def test_coarse_start_changes_nothing_but_the_cost(material):
    """512² at ~10-20 % contact, converged to rtol 1e-10 with and without the coarse start:
    the same pressure (to ~1e-8, the tolerance) and fewer products with it (elastic on the
    benchmark surface: 140 -> 99 at 512², 184 -> 108 at 1024²)."""
    assert 512**2 >= start.COARSEN_MIN_SIZE
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
    assert s.heights.size >= start.COARSEN_MIN_SIZE
    cold = bem.solve(s, m, speed=0.0, load=6.0)
    own = bem.solve(s, m, speed=0.0, load=6.0, initial=cold.pressure)
    assert own.iterations == 1  # the fine warm start was kept: it is the answer
    far = bem.solve(s, m, speed=0.0, load=0.6).pressure
    through = bem.solve(s, m, speed=0.0, load=6.0, initial=far)
    fine_only = bem.solve(s, m, speed=0.0, load=6.0, initial=far, contact_options=ContactOptions(coarsen=False))
    assert through.iterations <= cold.iterations + 1 < fine_only.iterations
    assert through.matvecs < 0.8 * fine_only.matvecs
    for r in (own, through, fine_only):
        np.testing.assert_allclose(r.pressure, cold.pressure, rtol=0, atol=1e-6 * cold.pressure.max())
