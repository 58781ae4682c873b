"""The rolling FEM's fallback from a PARDISO solve that misses its residual (``solver="auto"``), in
the default test run whether or not pypardiso is installed: a stand-in factor named ``pardiso``
whose solves refinement cannot bring under the limit takes its place, so that every branch of
:func:`fem_reference.rolling._superlu_operator` runs here.

- the missed solve is refactored with SuperLU, and the answer is SuperLU's own;
- where SuperLU's factor of the same system would outgrow its budget, every term is carried by its
  outflow values, and the answer is that form's own;
- where that fails too, a ConvergenceError names both failures; no number is returned.
"""

import logging

import numpy as np
import pytest

from bem import Material
from bem.errors import ConvergenceError
from fem_reference import rolling, rolling_cylinder, steady
from fem_reference.linsolve import factorize

R, P = 0.02, 500.0
SOLID = Material.standard_linear_solid(E0=2e6, E_inf=2e7, relaxation_time=0.01, nu=0.5)
V = 0.03  # Hunter's friction peak of this solid is 0.0295 m/s
# the fallbacks of the result's own solves (the error estimate's twin is tested elsewhere)
KW = dict(radius=R, load=P, speed=V, resolution=2, estimate=False)


class _Missing:
    """A factor named like PARDISO whose solve is a tenth of the exact one: each refinement step
    removes a tenth of the residual, which stalls refinement (a step must halve it) far above its
    limit, as PARDISO's perturbed pivots do on the stiffest systems."""

    name = "pardiso"

    def __init__(self, A):
        self._exact = factorize(A, "splu")
        self.nnz = self._exact.nnz

    def solve(self, b):
        return 0.1 * self._exact.solve(b)


@pytest.fixture
def missing_pardiso(monkeypatch):
    """``solver="auto"`` factors with :class:`_Missing`; an explicit solver is left alone."""

    def fake(A, solver="auto", memory=None):
        return _Missing(A) if solver == "auto" else factorize(A, solver, memory=memory)

    monkeypatch.setattr(steady, "factorize", fake)


def _close(a, b):
    # both solves meet the linear limit 1e-8 on the same discretisation, so they agree to about that
    # (measured: to the last digit, the same SuperLU factor of the same system)
    assert a.friction == pytest.approx(b.friction, rel=1e-7)
    assert a.friction_dissipation == pytest.approx(b.friction_dissipation, rel=1e-7)
    np.testing.assert_allclose(a.pressure, b.pressure, rtol=0, atol=1e-7 * b.peak_pressure)


def test_a_missed_solve_is_refactored_with_superlu(missing_pardiso, caplog):
    reference = rolling_cylinder(SOLID, solver="splu", **KW)
    with caplog.at_level(logging.WARNING, logger="fem_reference.rolling"):
        r = rolling_cylinder(SOLID, **KW)
    assert "factoring with SuperLU" in caplog.text
    assert r.success and r.solver == "splu"
    assert r.linear_residual <= r.linear_residual_limit
    _close(r, reference)


def test_superlu_over_budget_carries_every_term(missing_pardiso, monkeypatch, caplog):
    def over_budget(A, solver="auto", memory=None):
        if memory is not None:  # the budgeted refactorisation of the condensed system
            raise MemoryError("SuperLU's factor needs more than its budget")
        return factorize(A, solver)

    monkeypatch.setattr(rolling, "factorize", over_budget)
    reference = rolling_cylinder(SOLID, solver="splu", condense=False, **KW)
    with caplog.at_level(logging.WARNING, logger="fem_reference.rolling"):
        r = rolling_cylinder(SOLID, **KW)
    assert "carrying every term by its outflow values" in caplog.text
    assert r.success and r.solver == "splu" and r.condensed == (False,)
    _close(r, reference)


def test_every_fallback_failing_raises(missing_pardiso, monkeypatch):
    def no_memory(A, solver="auto", memory=None):
        raise MemoryError("no memory left")

    real = steady.steady_operator

    def carried_fails(ops, material, speed, *, solver="auto", condense=False):
        if condense is False and solver == "splu":
            raise MemoryError("the carried form needs more than the memory available")
        return real(ops, material, speed, solver=solver, condense=condense)

    monkeypatch.setattr(rolling, "factorize", no_memory)
    monkeypatch.setattr(rolling, "steady_operator", carried_fails)
    with pytest.raises(ConvergenceError, match="pardiso solve residual .* fallback to SuperLU failed"):
        rolling_cylinder(SOLID, **KW)
