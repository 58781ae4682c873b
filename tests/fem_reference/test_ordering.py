"""SuperLU's ordering of the FEM systems (fem_reference.ordering), on a real carried system."""

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from bem import Material
from fem_reference import linsolve, rolling_cylinder
from fem_reference.ordering import PIVOT_THRESHOLD, equilibrate, nested_dissection


def rubber(n, ratio):
    return Material.from_prony(E0=1e6, moduli=np.full(n, (ratio - 1) * 1e6 / n), times=np.logspace(-5, -1, n), nu=0.5)


@pytest.fixture(scope="module")
def carried_system():
    """The first system of a 4-term rubber near its friction peak on the quadtree (every term carried
    by its outflow values: displacements, a zero pressure block at nu = 0.5, transported values)."""
    saved = {}
    original = linsolve._SuperLU.__init__

    def capture(self, A, memory=None):
        saved.setdefault("A", sp.csc_matrix(A))
        original(self, A, memory)

    linsolve._SuperLU.__init__ = capture
    try:
        rolling_cylinder(
            rubber(4, 100),
            radius=0.02,
            load=1500.0,
            speed=3e-3,
            resolution=3,
            mesh="quadtree",
            solver="splu",
            estimate=False,
            passes=1,
        )
    finally:
        linsolve._SuperLU.__init__ = original
    return saved["A"]


def spread(A, axis):
    peaks = abs(A).max(axis=axis).toarray()
    return peaks.max() / peaks.min()


def test_equilibration_brings_rows_and_columns_to_one_scale(carried_system):
    r, c, scaled = equilibrate(carried_system)
    # the raw system's rows and columns peak over many orders (moduli against unit transport
    # couplings); one sweep takes about the square root of that away (measured: the columns' spread
    # from 1.1e11 to 1.2e4, the rows' from 2.0e11 to 4.3e5)
    for axis in (0, 1):
        assert spread(carried_system, axis) > 1e8
        assert spread(scaled, axis) < 1e-5 * spread(carried_system, axis)
    assert abs(sp.diags(r) @ carried_system @ sp.diags(c) - scaled).max() < 1e-15


def test_zero_diagonal_unknowns_follow_a_neighbour(carried_system):
    _, _, scaled = equilibrate(carried_system)
    order = nested_dissection(scaled)
    assert np.array_equal(np.sort(order), np.arange(scaled.shape[0]))
    position = np.empty_like(order)
    position[order] = np.arange(order.size)
    zero = np.flatnonzero(np.abs(scaled.diagonal()) == 0)
    assert zero.size > 100  # the pressures' block at nu = 0.5
    pattern = sp.csr_matrix(abs(scaled) + abs(scaled.T))
    for i in zero:
        nbrs = pattern.indices[pattern.indptr[i] : pattern.indptr[i + 1]]
        nbrs = nbrs[scaled.diagonal()[nbrs] != 0]
        assert position[nbrs].min() < position[i]


def test_nested_dissection_fills_less_than_colamd_and_solves_as_well(carried_system):
    A = carried_system
    b = np.random.default_rng(0).standard_normal(A.shape[0])
    colamd = spla.splu(A, permc_spec="COLAMD", options={"Equil": True})
    ours = linsolve._SuperLU(A)
    # measured on this system: 3.4x fewer entries (the 8-term rubber's 120k system at its peak: 4.3x)
    assert ours.nnz < 0.6 * colamd.nnz
    # measured against the size of each row's own terms (backward error): 2e-16 and 7e-16
    for solve in (colamd.solve, ours.solve):
        assert linsolve.relative_residual(A, solve(b), b, n_equilibrium=0) < 1e-13


def test_without_any_pivoting_the_order_alone_fails(carried_system):
    # the threshold is what keeps the factor stable: with none, the saddle point's small pivots
    # are taken as they come and the solve is garbage (so the check above can fail)
    r, c, scaled = equilibrate(carried_system)
    order = nested_dissection(scaled)
    Ap = sp.csc_matrix(scaled[order][:, order])
    b = np.random.default_rng(1).standard_normal(Ap.shape[0])
    kept = spla.splu(Ap, permc_spec="NATURAL", diag_pivot_thresh=PIVOT_THRESHOLD, options={"SymmetricMode": True})
    assert np.linalg.norm(Ap @ kept.solve(b) - b) < 1e-2 * np.linalg.norm(b)
    try:
        none = spla.splu(Ap, permc_spec="NATURAL", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    except RuntimeError:
        return  # exactly singular pivots: failed, as it should
    assert not np.linalg.norm(Ap @ none.solve(b) - b) < 1e-2 * np.linalg.norm(b)
