"""Observed orders of the FEM (viscobem_bench.fem_convergence): the order estimate itself, and the
time-step order of creep indentation on a coarse mesh."""

import numpy as np
import pytest

from viscobem_bench.fem_convergence import observed_orders, time_step_study


def test_observed_orders_recover_known_rates():
    h = np.array([0.4, 0.2, 0.1, 0.05])
    np.testing.assert_allclose(observed_orders(h, 3.0 * h**2), 2.0)
    np.testing.assert_allclose(observed_orders(h, 0.5 * h), 1.0)
    np.testing.assert_allclose(observed_orders(h, -(h**1.5)), 1.5)  # the sign of an error is not its size
    assert np.isnan(observed_orders([1.0, 0.5], [0.0, 0.0])).all()


@pytest.mark.slow
def test_indentation_time_step_order():
    # self-convergence of the approach in the steps per decade (the spatial error is common to all
    # rows): measured 1.78 between 4 and 8 steps per decade against 32 on this mesh (2.2 between 8
    # and 16), i.e. second order with a pre-asymptotic lag; a first-order update would give ~1
    rows = time_step_study(2, [4, 8, 32])
    assert rows[1]["order"] == pytest.approx(1.78, abs=0.3)
