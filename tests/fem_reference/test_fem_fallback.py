"""The FEM's one solver policy (:func:`fem_reference.linsolve.solver_path`) and its fallbacks, in the
default test run whether or not pypardiso is installed: PARDISO is declared available and a stand-in
factor named ``pardiso``, whose solves refinement cannot bring under the limit, takes its place, so
that every step of the ``"auto"`` path runs here.

- the path each request gets, with and without PARDISO, for the condensed and the carried forms;
- a missed solve is refactored with SuperLU, and the answer is SuperLU's own, in the rolling model
  and in the indentation;
- where SuperLU's factor of the same system would outgrow its budget, every term is carried by its
  outflow values, and the answer is that form's own;
- where that fails too, a ConvergenceError names both failures; no number is returned;
- every result reports the steps it took.
"""

import logging
import weakref

import numpy as np
import pytest

from bem import Material
from bem.errors import ConvergenceError, InputError
from fem_reference import axisymmetric as axi
from fem_reference import indentation, linsolve, rolling_cylinder, steady
from fem_reference.linsolve import CONDENSED_FILL, Step, factorize, solver_path

R, P = 0.02, 500.0
SOLID = Material.standard_linear_solid(E0=2e6, E_inf=2e7, relaxation_time=0.01, nu=0.5)
V = 0.03  # Hunter's friction peak of this solid is 0.0295 m/s
# the fallbacks of the result's own solves (the error estimate's twin is tested elsewhere)
KW = dict(radius=R, load=P, speed=V, resolution=1, estimate=False)


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

    def diagnostics(self):
        return {"solver": self.name, "factor_nonzeros": self.nnz}


def _stand_in(budgeted=None, carried=None):
    """A ``factorize`` whose PARDISO is :class:`_Missing`; SuperLU with a memory budget (the
    refactorisation of the same system) and without (the carried form, after a miss) may raise.
    Every factorisation after a miss checks that the missed factor is gone: a factor kept alive
    by the path would hold its memory while the next one fills in."""
    seen = {"missed": None}

    def fake(A, solver="auto", memory=None):
        if solver == "pardiso":
            factor = _Missing(A)
            seen["missed"] = weakref.ref(factor)
            return factor
        if seen["missed"] is not None:
            assert seen["missed"]() is None, "the missed factor is still alive"
        if memory is not None and budgeted is not None:
            raise budgeted
        if memory is None and seen["missed"] is not None and carried is not None:
            raise carried
        return factorize(A, solver, memory=memory)

    return fake


@pytest.fixture
def pardiso_present(monkeypatch):
    monkeypatch.setattr(linsolve, "pardiso_available", lambda: True)


@pytest.fixture
def missing_pardiso(pardiso_present, monkeypatch):
    monkeypatch.setattr(steady, "factorize", _stand_in())


def test_the_path_each_request_gets(monkeypatch):
    monkeypatch.setattr(linsolve, "pardiso_available", lambda: True)
    full = (Step("pardiso"), Step("splu", fill=CONDENSED_FILL), Step("splu", carried=True))
    assert solver_path("auto", condenses=True) == full
    assert solver_path("auto") == full[:2]  # nothing to carry: no carried form to fall back on
    assert solver_path("auto", carries=True, condenses=True) == (Step("splu"),)
    assert solver_path("splu", condenses=True) == (Step("splu"),)
    assert solver_path("pardiso", carries=True) == (Step("pardiso"),)
    monkeypatch.setattr(linsolve, "pardiso_available", lambda: False)
    assert solver_path("auto", condenses=True) == (Step("splu"),)
    with pytest.raises(InputError, match="solver must be one of"):
        solver_path("mumps")


def _close(a, b):
    # both solves meet the linear limit 1e-8 on the same discretisation, so they agree to about that
    # (measured: to the last digit, the same SuperLU factor of the same system)
    assert a.friction == pytest.approx(b.friction, rel=1e-7)
    assert a.friction_dissipation == pytest.approx(b.friction_dissipation, rel=1e-7)
    np.testing.assert_allclose(a.pressure, b.pressure, rtol=0, atol=1e-7 * b.peak_pressure)


def test_a_missed_solve_is_refactored_with_superlu(missing_pardiso, caplog):
    reference = rolling_cylinder(SOLID, solver="splu", **KW)
    with caplog.at_level(logging.WARNING, logger="fem_reference.linsolve"):
        r = rolling_cylinder(SOLID, **KW)
    assert "factoring with SuperLU" in caplog.text
    assert r.success and r.solver == "splu"
    assert r.linear_residual <= r.linear_residual_limit
    missed, met = r.solver_path
    assert missed["solver"] == "pardiso" and missed["outcome"] == "missed" and missed["residual"] > missed["limit"]
    assert met["solver"] == "splu" and met["form"] == "as asked" and met["outcome"] == "met"
    assert met["factor_nonzeros"] > 0 and met["residual"] <= met["limit"]
    assert reference.solver_path == ({**met, "residual": reference.linear_residual},)
    _close(r, reference)


def test_superlu_over_budget_carries_every_term(pardiso_present, monkeypatch, caplog):
    monkeypatch.setattr(steady, "factorize", _stand_in(budgeted=MemoryError("SuperLU's factor needs more")))
    # the tensor mesh's path: on squares every term is carried from the start
    reference = rolling_cylinder(SOLID, solver="splu", condense=False, mesh="graded", **KW)
    with caplog.at_level(logging.WARNING, logger="fem_reference.linsolve"):
        r = rolling_cylinder(SOLID, mesh="graded", **KW)
    assert "carrying every term by its outflow values" in caplog.text
    assert r.success and r.solver == "splu" and r.condensed == (False,)
    assert [s["outcome"][:6] for s in r.solver_path] == ["missed", "memory", "met"]
    assert r.solver_path[-1]["form"] == "carried"
    _close(r, reference)


def test_every_fallback_failing_raises(pardiso_present, monkeypatch):
    fake = _stand_in(budgeted=MemoryError("no memory left"), carried=MemoryError("the carried form needs more"))
    monkeypatch.setattr(steady, "factorize", fake)
    with pytest.raises(ConvergenceError, match="pardiso solve residual .* fallback to SuperLU failed: the carried"):
        rolling_cylinder(SOLID, **KW)


def test_an_explicit_solver_that_misses_is_reported_not_replaced(missing_pardiso):
    r = rolling_cylinder(SOLID, solver="pardiso", **KW)
    assert not r.success and "linear solve residual" in r.message
    assert [s["outcome"] for s in r.solver_path] == ["missed"]


def test_the_indentation_takes_the_same_path(pardiso_present, monkeypatch):
    monkeypatch.setattr(axi, "factorize", _stand_in())
    kw = dict(radius=R, load=P, times=[0.0, 0.01], resolution=2, steps_per_decade=2)
    reference = indentation(SOLID, solver="splu", **kw)
    r = indentation(SOLID, **kw)
    assert r.success and r.solver == "splu"
    assert [(s["solver"], s["outcome"]) for s in r.solver_path] == [("pardiso", "missed"), ("splu", "met")]
    np.testing.assert_allclose(r.contact_radius, reference.contact_radius, rtol=1e-7)


def test_one_factor_alive_at_a_time(monkeypatch):
    # Each mesh's factor (of a remesh pass, and of the error estimate's twin) is freed once its fields
    # are solved, before the next mesh is factored: two alive at once double a run's peak memory
    made = []

    def tracked(A, solver="auto", memory=None):
        assert all(ref() is None for ref in made), "an earlier mesh's factor is still alive"
        factor = factorize(A, solver, memory=memory)
        made.append(weakref.ref(factor))
        return factor

    monkeypatch.setattr(steady, "factorize", tracked)
    r = rolling_cylinder(SOLID, **{**KW, "estimate": True})
    assert r.success and r.passes >= 2 and len(made) == r.passes + 1  # the passes and the twin
