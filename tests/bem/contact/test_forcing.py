"""The inexact Newton's forcing term (bem.contact.forcing): pure functions, checked on synthetic
sequences."""

import pytest

from bem.contact import forcing as fc


def test_a_damped_step_tightens_eta_down_to_its_floor():
    assert fc.next_eta(0.1, damped=True) == pytest.approx(0.01)
    assert fc.next_eta(0.1, damped=False) == 0.1  # a full step: the point was good
    eta = 0.1
    for _ in range(10):
        eta = fc.next_eta(eta, damped=True)
    assert eta == pytest.approx(fc.ETA_MIN)  # never below the floor
