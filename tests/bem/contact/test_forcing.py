"""The inexact Newton's forcing term and the set-change detector (bem.contact.forcing): pure
functions, checked on synthetic sequences; then their effect on a broad-band contact."""

import numpy as np
import pytest

import bem
from bem.contact import forcing as fc
from bem.contact import newton
from bem.contact.newton import SetTrack

CONVERGING = dict(decrease=fc.OSCILLATION_DECREASE, settling=fc.SETTLING_CHANGES)


def _steps(flips, size=10_000):
    """Run the tracker over sets that flip the given index ranges in turn; the verdicts."""
    track, contact, out = SetTrack(), np.zeros(size, bool), []
    for flip in flips:
        new = contact.copy()
        new[flip] = ~new[flip]
        track, changed, converging = track.after(contact, new)
        out.append((changed, converging))
        contact = new
    return out


def test_converging_sets_pass():
    # the first step has nothing to compare with; then most undo the last, but 0.4 as many
    assert _steps([np.arange(2000), np.arange(1500, 2300)]) == [(2000, True), (800, True)]
    # nearly as many, none undone: a front moving on
    assert _steps([np.arange(2000), np.arange(3000, 4500)])[-1] == (1500, True)
    # growing, but below SETTLING_CHANGES: a settling set
    assert _steps([np.arange(50), np.arange(60)])[-1] == (60, True)


def test_diverging_and_oscillating_sets_are_caught():
    assert _steps([np.arange(1000), np.arange(2000, 3200)])[-1] == (1200, False)  # more than the last step
    assert _steps([np.arange(1000), np.arange(200, 1000)])[-1] == (800, False)  # 0.8 as many, all undoing


@pytest.mark.parametrize(
    "changed, before, undone, expected",
    [
        (10, 0, 0, True),  # first step
        (500, 1000, 500, True),  # halved
        (800, 1000, 0, True),  # 0.8 as many, none undone: a moving front
        (800, 1000, 500, False),  # 0.8 as many, mostly undoing the last step
        (1200, 1000, 0, False),  # growing
        (90, 50, 90, True),  # growing but settling
    ],
)
def test_set_converging_on_single_steps(changed, before, undone, expected):
    assert fc.set_converging(changed, before, undone, **CONVERGING) is expected


def test_the_detector_follows_its_threshold():
    assert not fc.set_converging(800, 1000, 800, decrease=0.7, settling=100)
    assert fc.set_converging(800, 1000, 800, decrease=0.9, settling=100)
    assert fc.set_converging(800, 1000, 800, decrease=0.7, settling=1000)


def test_settled_by_count_or_share():
    assert fc.settled(100, 10**6, changes=100, share=0.01)
    assert not fc.settled(101, 1000, changes=100, share=0.01)
    assert fc.settled(5000, 10**6, changes=100, share=0.01)


def test_forcing_rules_on_a_synthetic_sequence():
    """The ceiling drops a decade once (never twice), a damped settled step tightens eta, the
    fast attempt relaxes it back up to the ceiling, and an attempt with its own forcing keeps it."""
    f = fc.Forcing.at(0.1)
    step = dict(damped=False, settled=False, converging=True, relax=True)
    f = fc.next_forcing(f, **dict(step, converging=False))
    assert (f.eta, f.top) == pytest.approx((0.01, 0.01))
    f = fc.next_forcing(f, **dict(step, converging=False))  # a second oscillation: the ceiling stays
    assert f.top == pytest.approx(0.01) and f.eta == pytest.approx(0.01)
    f = fc.next_forcing(f, **dict(step, damped=True, settled=True))
    assert f.eta == pytest.approx(0.001)
    for _ in range(5):
        f = fc.next_forcing(f, **step)
    assert f.eta == pytest.approx(0.01)  # relaxed back to the ceiling, not beyond
    g = fc.Forcing.at(0.1)
    for _ in range(10):
        g = fc.next_forcing(g, **dict(step, damped=True, settled=True))
    assert g.eta == pytest.approx(fc.ETA_MIN)  # never below the floor
    own = fc.Forcing.at(0.01)
    kept = fc.next_forcing(
        own, **dict(step, converging=False, damped=True, settled=True, relax=False), oscillation=False, damping=False
    )
    assert kept == own
    careful = fc.next_forcing(fc.Forcing.at(0.1), **dict(step, relax=False))
    assert careful == fc.Forcing.at(0.1)


def test_broad_band_contact_costs_less_with_both_rules(monkeypatch):
    """1024² with 512 scales (2 points per shortest wavelength), about 63 % contact: measured
    216 operator products with the rules, 257 without (the set oscillates for 14 steps); the
    same pressure either way."""
    s = bem.surfaces.self_affine(1024, 0.01, hurst=0.8, scales=512, rms_slope=0.1, seed=1)
    m = bem.Material.elastic(1e7)
    with_rules = bem.solve(s, m, speed=0.0, load=50.0)
    monkeypatch.setattr(newton, "NESTED_ETA", 0.1)
    monkeypatch.setattr(fc, "OSCILLATION_DECREASE", 1e9)
    without = bem.solve(s, m, speed=0.0, load=50.0)
    assert with_rules.matvecs < 0.9 * without.matvecs
    assert with_rules.iterations < without.iterations
    err = np.linalg.norm(with_rules.pressure - without.pressure) / np.linalg.norm(without.pressure)
    assert err < 1e-7 and with_rules.contact_fraction == pytest.approx(without.contact_fraction, abs=1e-4)
