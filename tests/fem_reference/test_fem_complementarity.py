"""The FEM's complementarity residual is computed from the solution (gaps of the displaced surface
in and out of the active set, signs of the forces), so a wrong active set fails it and turns the
results' ``success`` off. Before, the loop zeroed the active gaps and returned only when the set
repeated, so the residual was 0 by construction and ``success`` could not fail on it."""

import importlib

import numpy as np
import pytest

from bem import Material
from fem_reference import contact, indentation, rolling, rolling_cylinder
from fem_reference.contact import COMPLEMENTARITY_LIMIT, ContactSolution, complementarity_residual, gap_scale

R, P = 0.01, 100.0


def _hertz_flexibility(n=41):
    """A small symmetric flexibility (log kernel of a line load) and a parabolic profile."""
    x = np.linspace(-2.0, 2.0, n)
    d = np.abs(x[:, None] - x[None, :])
    C = -np.log(d + 0.05) / np.pi + 2.0  # positive, decreasing with the distance
    return x, C, -(x**2) / 2


def test_residual_of_a_solution_is_round_off():
    x, C, h = _hertz_flexibility()
    sol = contact.solve_load_control(C, h, 1.0)
    assert sol.residual < 1e-12
    assert np.all(sol.lam[sol.active] > 0) and np.all(sol.gap[~sol.active] >= 0)


@pytest.mark.parametrize("change", ["drop_edge", "add_outside"])
def test_wrong_active_set_fails(change):
    x, C, h = _hertz_flexibility()
    good = contact.solve_load_control(C, h, 1.0)
    act = good.active.copy()
    idx = np.flatnonzero(act)
    if change == "drop_edge":
        act[idx[-1]] = False  # an edge node left out: it penetrates
    else:
        act[idx[-1] + 2] = True  # a node beyond the edge pulled into contact: tension or a gap
        act[idx[-1] + 1] = True
    k = np.flatnonzero(act)
    S = np.block([[C[np.ix_(k, k)], -np.ones((k.size, 1))], [np.ones((1, k.size)), np.zeros((1, 1))]])
    sol = np.linalg.solve(S, np.concatenate([h[k], [1.0]]))
    lam = np.zeros(x.size)
    lam[k] = sol[:-1]
    gap = C @ lam - h - sol[-1]
    res = complementarity_residual(lam, gap, act, 1.0, gap_scale(sol[-1], h[k]))
    assert res > 1e3 * COMPLEMENTARITY_LIMIT


def _wrong_set_solver(real):
    """``solve_load_control`` that returns the converged solution with its leading edge node
    dropped from the active set and the forces re-solved on that set (a stopped-too-early loop)."""

    def solve(C, h, load, *, w0=None, active=None, maxiter=100):
        good = real(C, h, load, w0=w0, active=active, maxiter=maxiter)
        act = good.active.copy()
        act[np.flatnonzero(act)[-1]] = False
        k = np.flatnonzero(act)
        w0v = np.zeros(h.size) if w0 is None else w0
        S = np.block([[C[np.ix_(k, k)], -np.ones((k.size, 1))], [np.ones((1, k.size)), np.zeros((1, 1))]])
        sol = np.linalg.solve(S, np.concatenate([h[k] - w0v[k], [load]]))
        lam = np.zeros(h.size)
        lam[k] = sol[:-1]
        gap = C @ lam + w0v - h - sol[-1]
        gap[k] = 0.0
        return ContactSolution(lam, float(sol[-1]), gap, act, good.iterations, 0.0)

    return solve


def test_rolling_success_fails_on_a_wrong_active_set(monkeypatch):
    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, relaxation_time=0.01, nu=0.5)
    ok = rolling_cylinder(m, radius=R, load=P, speed=0.01, resolution=2, grading=2.0, mesh="uniform")
    assert ok.success and ok.residual < COMPLEMENTARITY_LIMIT  # measured 1e-11
    monkeypatch.setattr(rolling, "solve_load_control", _wrong_set_solver(contact.solve_load_control))
    bad = rolling_cylinder(m, radius=R, load=P, speed=0.01, resolution=2, grading=2.0, mesh="uniform")
    assert not bad.success and "complementarity" in bad.message
    assert bad.residual > 1e3 * COMPLEMENTARITY_LIMIT


def test_indentation_success_fails_on_a_wrong_active_set(monkeypatch):
    ind_module = importlib.import_module("fem_reference.indentation")

    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, creep_time=1.0, nu=0.5)
    kw = dict(radius=R, load=1.0, times=[0.0, 1e4], resolution=2, steps_per_decade=1)
    ok = indentation(m, **kw)
    assert ok.success and ok.residual < COMPLEMENTARITY_LIMIT
    assert np.allclose(ok.contact_force, 1.0, rtol=1e-12)
    monkeypatch.setattr(ind_module, "solve_load_control", _wrong_set_solver(contact.solve_load_control))
    bad = indentation(m, **kw)
    assert not bad.success and bad.residual > 1e3 * COMPLEMENTARITY_LIMIT


def test_complementarity_limit_follows_a_raised_linear_limit(monkeypatch):
    # The active gaps come from the field solve and err as it does. Where the round-off floor raises
    # the linear solve's limit (broad rubbers at high speed: measured active gaps of 1.2e-7 and
    # 2.7e-7 under a limit of 7.8e-6, on results within 0.05 % of the BEM), the complementarity
    # limit follows; at the default linear limit it stays COMPLEMENTARITY_LIMIT.
    from fem_reference import linsolve
    from fem_reference.contact import complementarity_limit

    assert complementarity_limit(linsolve.RESIDUAL_LIMIT) == COMPLEMENTARITY_LIMIT
    assert complementarity_limit(7.8e-6) == 7.8e-6
    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, relaxation_time=0.01, nu=0.5)
    kw = dict(radius=R, load=P, speed=0.01, resolution=2, grading=2.0, mesh="uniform")
    real = rolling.complementarity_residual
    monkeypatch.setattr(rolling, "complementarity_residual", lambda *a: max(real(*a), 5e-7))
    strict = rolling_cylinder(m, **kw)
    assert not strict.success and "complementarity residual 5.00e-07 > 1.0e-07" in strict.message
    monkeypatch.setattr(linsolve, "RESIDUAL_LIMIT", 1e-6)  # as the round-off floor raises it
    raised = rolling_cylinder(m, **kw)
    assert raised.linear_residual_limit == 1e-6 and raised.success, raised.message


def test_contact_on_an_approximate_flexibility_is_refined_to_the_exact_one():
    # columns off by 1e-6 (a factor's unrefined solves, SuperLU's residual ~1e-7 on the periodic
    # cells) put the forces of the approximate contact 9.3e-5 (max, of the largest) off the exact
    # ones and their gaps 4.7e-7; each correction against the exact depression contracts that by
    # about the columns' error times the conditioning: measured 4.9e-9, then 1.8e-13 (held to 1e-12)
    x, C, h = _hertz_flexibility(81)
    rng = np.random.default_rng(7)
    approx = C * (1.0 + 1e-6 * rng.standard_normal(C.shape))  # not symmetric, as the steady operator
    exact = contact.solve_load_control(C, h, 1.0)
    target = 1e-12

    def depression(lam):
        return C @ lam, None

    def columns(idx):
        return approx[:, idx]

    once, _ = contact.solve_corrected(columns, depression, h, 1.0, target=target, stall=0.5, steps=1)
    assert once.residual > 1e-7  # uncorrected, the approximate columns show in the exact gaps
    assert np.max(np.abs(once.lam - exact.lam)) > 1e-5 * np.max(exact.lam)
    sol, _ = contact.solve_corrected(columns, depression, h, 1.0, target=target, stall=0.5)
    assert sol.residual <= target
    np.testing.assert_array_equal(sol.active, exact.active)
    np.testing.assert_allclose(sol.lam, exact.lam, rtol=0, atol=1e-12 * np.max(exact.lam))
    assert sol.d == pytest.approx(exact.d, rel=1e-12)


def test_refinement_of_the_contact_that_stalls_reports_its_exact_residual():
    # columns 1 % off (random, far from a factor's error) do not contract: the refinement stops on
    # the stall (measured: residual 3.4e-3 after 11 active-set updates) and what comes back is a
    # step's solution with its gaps from the exact depression and its residual above the target,
    # for the caller to report
    x, C, h = _hertz_flexibility(81)
    rng = np.random.default_rng(8)
    approx = C * (1.0 + 0.01 * rng.standard_normal(C.shape))
    target = COMPLEMENTARITY_LIMIT

    def depression(lam):
        return C @ lam, None

    sol, _ = contact.solve_corrected(lambda idx: approx[:, idx], depression, h, 1.0, target=target, stall=0.5)
    assert sol.residual > target
    np.testing.assert_allclose(sol.gap, C @ sol.lam - h - sol.d, rtol=0, atol=1e-15)
    res = complementarity_residual(sol.lam, sol.gap, sol.active, 1.0, gap_scale(sol.d, h[sol.active]))
    assert sol.residual == res
