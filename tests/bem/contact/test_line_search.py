"""The active-set line search (``bem.contact.newton.line_search``): the full step when it lowers
the merit ``||min(p, c g)||**2``, else the first minimum of the merit over 1/2, 1/4, ... below its
value at the start, however short; a direction along which nothing lowers it gives a step that
changes nothing. One contact point whose gap stays open, so the merit is ``p(t)**2``."""

import numpy as np
import pytest

from bem.contact.newton import line_search


def _search(p0, p1, *, full):
    """The step along ``p0 -> p1`` of one point with a wide-open gap (the merit is ``p**2``)."""
    p, p_new = np.array([p0]), np.array([p1])
    g = np.array([1e6])
    return line_search(p, g, p_new, g, 1.0, full=full)


def test_the_full_step_when_it_lowers_the_merit():
    assert _search(1.0, 0.5, full=True) == 1.0


def test_a_damped_step_stops_at_the_first_minimum_of_the_halvings():
    # p(t) = 1 - 5 t: merit 2.25 at 1/2, 0.0625 at 1/4, 0.14 at 1/8 -> 1/4
    assert _search(1.0, -4.0, full=False) == 0.25
    assert _search(1.0, -4.0, full=True) == 0.25  # the full step raises the merit (16 > 1)


@pytest.mark.parametrize("zero", [1e-3, 1e-6, 1e-10])
def test_the_search_has_no_length_of_its_own(zero):
    """The merit's zero at ``t = zero``, far below any fixed count of halvings: the step found is
    within a factor two of it."""
    t = _search(1.0, 1.0 - 1.0 / zero, full=True)
    assert zero / 2 <= t <= 2 * zero


def test_a_direction_that_only_raises_the_merit_changes_nothing():
    p0, p1 = 1.0, 3.0
    t = _search(p0, p1, full=True)
    assert 0 < t and p0 + t * (p1 - p0) == p0
