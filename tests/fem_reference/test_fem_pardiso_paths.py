"""The PARDISO paths of the FEM (:class:`fem_reference.linsolve._Pardiso`: its own refinement, the
probe before a many-column solve, deflation) in the default test run, on a stand-in for pypardiso
whose factor is the exact factor of a matrix with perturbed pivots, as PARDISO's static pivoting
leaves it (``stand_in_pardiso``). The real solver runs the same paths under ``-m pardiso``.

Measured on the saddle-point system of a standard solid (E_inf/E0 = 10, nu = 0.5, 7040 unknowns):
with 4 to 200 pivots perturbed by 1e-4 to 1e-2 of the largest entry, the factor's own refinement
takes all its 20 steps, and on the perturbed directions M^-1 A is nearly zero (singular values
3e-6 .. 4e-5): a deflated solve corrected through the factor carries only its round-off there (the
rolling result missed its residual at up to 8e-4, its friction 2 % off), one corrected through
products with A reaches 1e-11.
"""

import sys

import numpy as np
import pytest
import stand_in_pardiso

from bem import Material
from fem_reference import linsolve, rolling_cylinder
from fem_reference.graded import graded_half_space, initial_edges
from fem_reference.kinematics import quadrature_operators
from fem_reference.rolling_inputs import domain_size
from fem_reference.steady import steady_operator

SOLID = Material.standard_linear_solid(E0=2e6, E_inf=2e7, relaxation_time=0.01, nu=0.5)
R, P, V = 0.02, 500.0, 0.03  # V: Hunter's friction peak of this solid, 0.0295 m/s


@pytest.fixture
def stand_in(monkeypatch):
    """Install a stand-in pypardiso with ``perturbed`` pivots of ``size`` times the largest entry."""

    def install(perturbed, size):
        monkeypatch.setitem(sys.modules, "pypardiso", stand_in_pardiso.module(perturbed, size))

    return install


@pytest.fixture(scope="module")
def system():
    """``(A, n_equilibrium, b)``: the steady operator of SOLID on its first graded mesh, and unit
    downward forces at 40 surface dofs (the flexibility's right-hand sides)."""
    trail, lead = initial_edges(SOLID, R, P, V)
    hs = graded_half_space(
        (trail, lead), SOLID, V, resolution=2, length=domain_size(SOLID, R, P, V), ratio=1.5, layer_floor=0.01
    )
    op = steady_operator(quadrature_operators(hs.mesh, "plane"), SOLID, V, solver="splu")
    A, nf = op.matrix, op.free.size
    cols = np.random.default_rng(0).choice(nf, 40, replace=False)
    b = np.zeros((A.shape[0], cols.size))
    b[cols, np.arange(cols.size)] = -1.0 / SOLID.E_inf
    return A, nf, b


def test_auto_takes_pardiso_where_it_is_installed(stand_in, system):
    stand_in(4, 1e-8)
    assert linsolve.pardiso_available()
    assert linsolve.factorize(system[0]).name == "pardiso"


@pytest.mark.parametrize("perturbed, size", [(4, 1e-4), (40, 1e-3)])
def test_deflated_solve_meets_the_limit_where_perturbed_pivots_dominate(stand_in, system, perturbed, size):
    # the factor's own refinement runs out of its 20 steps on the probe column, so the factor is
    # deflated before the 40 columns are solved (its refinement would cost a solve of all of them a step)
    stand_in(perturbed, size)
    A, nf, b = system
    fac = linsolve.factorize(A, "pardiso")
    assert fac.slow_to_refine(b[:, 0])
    fac = linsolve.factorize(A, "pardiso")
    x, res, limit = linsolve.solve_refined(A, fac, b, n_equilibrium=nf)
    assert fac.deflated >= perturbed  # deflation finds the perturbed directions
    assert res <= limit  # measured 3e-12 against 1e-8


def test_rolling_on_pardiso_agrees_with_superlu(stand_in):
    stand_in(4, 1e-4)
    # one mesh: a second is meshed on the edges the first solve found, which the two solvers place
    # only within their residuals, and a segment of the graded mesh may gain an element with them
    kw = dict(radius=R, load=P, speed=V, resolution=2, passes=1, estimate=False)
    reference = rolling_cylinder(SOLID, solver="splu", **kw)
    r = rolling_cylinder(SOLID, solver="pardiso", **kw)
    assert r.success and r.solver == "pardiso"
    assert r.linear_residual <= r.linear_residual_limit
    # both meet the linear limit 1e-8 on the same discretisation
    assert r.friction == pytest.approx(reference.friction, rel=1e-7)
    assert r.friction_dissipation == pytest.approx(reference.friction_dissipation, rel=1e-7)
