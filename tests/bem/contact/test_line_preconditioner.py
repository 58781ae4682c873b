"""The line preconditioner of strongly non-symmetric periodic operators
(bem.contact.line_preconditioner, used by the contact solver's inner solves).

The steady-sliding symbol factors as ``a_q = green(|q|) J(-q_x v)``: ``A = G C`` with ``G``
the elastic operator (unit modulus) and ``C`` the creep compliance, a convolution along x.
The preconditioner of the system on the contact set ``R A R^T`` is
``(R C R^T)^-1 R G^-1 R^T``; these tests rebuild both factors as dense matrices.
"""

import numpy as np
import pytest
from conftest import dense_operator

import bem
import bem.contact.line_preconditioner as line_module
from bem.contact import ContactOptions, solver
from bem.contact.line_preconditioner import line_preconditioner as lines_of
from bem.halfspace.periodic import PeriodicHalfSpace

BUDGET = ContactOptions().line_budget

L = 0.01
RUBBER = bem.Material.from_prony(E0=1e6, moduli=np.full(20, (1e9 - 1e6) / 20), times=np.logspace(-10, 2, 20))
RUBBER_SPEED = 1e-2 * L / RUBBER.creep_times.max()  # xi = 1e-2, the periodic benchmark's rubber
FAST = 10 * RUBBER_SPEED  # symbol phase 1.2-1.35 rad (above 45 degrees) already on grids of 10-32 points


def _dense_creep(op):
    """Dense ``C``: the 1-D convolution along x (axis 0) with ``J(-q_x v)``, built here from
    the material (real at the x-Nyquist mode, like the operator's symbol)."""
    n0 = op.shape[0]
    J = op.material.complex_compliance(-2 * np.pi * np.fft.fftfreq(n0, L / n0) * op.speed)
    if n0 % 2 == 0:
        J[n0 // 2] = J[n0 // 2].real
    eye = np.eye(op.size).reshape((op.size,) + op.shape)
    cols = np.fft.ifft(np.fft.fft(eye, axis=1) * J[None, :, None], axis=1).real
    return cols.reshape(op.size, op.size).T


def test_symbol_is_elastic_times_creep_along_x():
    op = PeriodicHalfSpace((12, 10), L, RUBBER, FAST)
    assert op.max_phase() > np.pi / 4  # strongly non-symmetric: the case it serves
    # the unit-modulus operator, as 1e7 times a solid's of 1e7 Pa (a unit modulus is no solid's)
    G = 1e7 * dense_operator(PeriodicHalfSpace(op.shape, L, bem.Material.elastic(1e7, nu=RUBBER.nu), 0.0))
    A = dense_operator(op)
    np.testing.assert_allclose(A, G @ _dense_creep(op), rtol=0, atol=1e-12 * np.abs(A).max())


@pytest.mark.parametrize("shape", [(12, 10), (9, 8)])
def test_line_preconditioner_is_restricted_creep_inverse_after_elastic_inverse(shape, monkeypatch):
    op = PeriodicHalfSpace(shape, L, RUBBER, FAST)
    rng = np.random.default_rng(4)
    contact_set = rng.random(shape) < 0.4
    contact_set[:, 3] = False  # a line without contact
    contact_set[:, 5] = True  # and one in full contact
    idx = np.flatnonzero(contact_set)
    C = _dense_creep(op)
    elastic = PeriodicHalfSpace(shape, L, bem.Material.elastic(1e7, nu=RUBBER.nu), 0.0)
    r = rng.standard_normal(idx.size)
    full = np.zeros(op.size)
    full[idx] = r
    w = elastic.pressure_from_displacement(full.reshape(shape)).ravel()[idx] / 1e7  # R G^-1 R^T r, unit modulus
    expected = np.linalg.solve(C[np.ix_(idx, idx)], w)
    # the line inverses are stored in float32: exact up to its rounding times the
    # condition number of the line systems
    tol = (
        10
        * np.finfo(np.float32).eps
        * max(
            np.linalg.cond(C[np.ix_(line, line)])
            for line in (idx[idx % shape[1] == y] for y in range(shape[1]))
            if line.size
        )
    )
    built = []  # lines whose dense matrix is formed and inverted, per call
    line_matrices = line_module._line_matrices
    monkeypatch.setattr(
        line_module, "_line_matrices", lambda kernel, x, valid: built.append(len(x)) or line_matrices(kernel, x, valid)
    )
    cache = {}
    got = lines_of(op, contact_set, cache=cache, budget=BUDGET)(r)
    np.testing.assert_allclose(got, expected, rtol=tol, atol=tol * np.abs(expected).max())
    assert sum(built) == shape[1] - 1  # every line with contact
    # a second call with one line changed reuses the other lines' inverses and stays exact
    kept = {y: inv.copy() for y, (_, inv) in cache.items()}
    built.clear()
    contact_set[0, 0] = not contact_set[0, 0]
    idx = np.flatnonzero(contact_set)
    r = rng.standard_normal(idx.size)
    full[:] = 0.0
    full[idx] = r
    w = elastic.pressure_from_displacement(full.reshape(shape)).ravel()[idx] / 1e7
    got = lines_of(op, contact_set, cache=cache, budget=BUDGET)(r)
    expected = np.linalg.solve(C[np.ix_(idx, idx)], w)
    np.testing.assert_allclose(got, expected, rtol=tol, atol=tol * np.abs(expected).max())
    assert sum(built) == 1  # line y = 0 only
    assert all(np.array_equal(cache[y][1], kept[y]) for y in kept if y != 0)
    # no line preconditioner where it does not apply, or where it would exceed its memory budget
    assert lines_of(op.symmetric_part(), contact_set, budget=BUDGET) is None
    assert lines_of(PeriodicHalfSpace((16,), L, RUBBER, FAST), np.ones(16, bool), budget=BUDGET) is None
    assert lines_of(op, contact_set, budget=0) is None


def test_line_preconditioner_threads_change_nothing(monkeypatch):
    """Its batches (``chunk`` lines each) run on the FFT's cores; one core or two give
    the same numbers to the last bit."""
    shape = (24, 3 * 32 + 5)  # four batches of 32 lines (the default chunk)
    op = PeriodicHalfSpace(shape, L, RUBBER, FAST)
    rng = np.random.default_rng(5)
    contact_set = rng.random(shape) < 0.5
    r = rng.standard_normal(np.count_nonzero(contact_set))
    results = []
    for workers in (1, 2):
        with bem.use_threads(workers):
            results.append(lines_of(op, contact_set, budget=BUDGET)(r))
    np.testing.assert_array_equal(results[0], results[1])
    assert np.all(np.isfinite(results[0])) and np.any(results[0] != 0)


def _rubber_problem(n=128, speed=RUBBER_SPEED):
    s = bem.surfaces.self_affine(n, L, hurst=0.8, scales=n // 4, rms_slope=0.1, seed=1)
    return s, dict(speed=speed, load=0.9)


def test_line_preconditioner_same_answer_fewer_products():
    """The benchmark's 20-term rubber (E_inf/E0 = 1000, xi = 1e-2) on a 128² rough surface at
    ~10 % contact, to rtol 1e-10 with and without the line preconditioner: the same pressure
    (to ~1e-8, the tolerance) and fewer products with it (here 464 -> 279; on the benchmark
    surface at 512²: 1615 -> 961, 1024²: 3836 -> 1604)."""
    s, kw = _rubber_problem()
    out = {}
    for flag in (False, True):
        out[flag] = bem.solve(
            s, RUBBER, contact_options=ContactOptions(line_budget=2**30 if flag else 0), rtol=1e-10, maxiter=1000, **kw
        )
    plain, lines = out[False], out[True]
    assert 0.05 < lines.contact_fraction < 0.2
    err = np.linalg.norm(lines.pressure - plain.pressure) / np.linalg.norm(plain.pressure)
    assert err < 1e-7
    assert lines.friction == pytest.approx(plain.friction, rel=1e-7)
    assert lines.matvecs < 0.8 * plain.matvecs


def test_line_attempt_that_stalls_falls_back(monkeypatch):
    """A line-preconditioned attempt that spends its share of ``maxiter`` (here after one step:
    ``bem.contact.solver.LINES_MAXITER_SHARE = 0``) hands over to the unpreconditioned solve,
    which converges; the message and the counts include both attempts."""
    s, kw = _rubber_problem(32, FAST)
    reference = bem.solve(s, RUBBER, **kw)
    monkeypatch.setattr(solver, "LINES_MAXITER_SHARE", 0.0)
    r = bem.solve(s, RUBBER, **kw)
    assert r.success and "after a first attempt of 1 " in r.message
    np.testing.assert_allclose(r.pressure, reference.pressure, rtol=0, atol=1e-6 * reference.pressure.max())
