"""The inexact Newton's forcing term (bem.contact.forcing): pure functions, checked on synthetic
sequences."""

import pytest

from bem.contact import forcing as fc


def test_settled_by_count():
    assert fc.settled(100, changes=100) and not fc.settled(101, changes=100)
    assert fc.settled(fc.SETTLING_CHANGES) and not fc.settled(fc.SETTLING_CHANGES + 1)


def test_a_damped_step_on_a_settled_set_tightens_eta_down_to_its_floor():
    assert fc.next_eta(0.1, damped=True, settled=True) == pytest.approx(0.01)
    assert fc.next_eta(0.1, damped=True, settled=False) == 0.1  # the set still moves: loose is fine
    assert fc.next_eta(0.1, damped=False, settled=True) == 0.1  # a full step: the point was good
    eta = 0.1
    for _ in range(10):
        eta = fc.next_eta(eta, damped=True, settled=True)
    assert eta == pytest.approx(fc.ETA_MIN)  # never below the floor
