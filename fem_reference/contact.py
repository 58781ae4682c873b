"""Unilateral frictionless contact of a rigid profile under load control.

The candidate surface nodes ``i`` have a depression (displacement into the solid, m)
``w = C lam + w0``: ``C[i, j]`` is the depression at ``i`` per unit force at ``j`` and
``w0`` the depression without contact forces. The rigid surface has heights ``h_i``
positive toward the solid (docs/theory.md §4), here ``h = -x^2 / (2R)``; with rigid approach
``d`` the gap is ``g = w - (h + d)``. Conditions: ``lam >= 0``, ``g >= 0``,
``lam g = 0``, ``sum lam = P``.

Algorithm: primal-dual active set (a semismooth Newton method; M. Hintermueller,
K. Ito, K. Kunisch, SIAM J. Optim. 13 (2002) 865-888). On the active set ``A``, solve
``C_AA lam_A - d = h_A - w0_A`` with ``sum lam_A = P``; then ``A <- {lam > 0} u {g < 0}``.
It stops when the set repeats and raises :class:`bem.errors.ConvergenceError` on a cycle or
``maxiter``.

The complementarity residual (:func:`complementarity_residual`) is computed afterwards from the
solution itself, not from the loop's bookkeeping: the gap is evaluated at every node, in the
active set too, from the forces and the flexibility, and the forces' signs are read from the
forces. A wrong active set (a node pulled into contact, a node left penetrating) shows in it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from bem.errors import ConvergenceError

__all__ = [
    "ContactSolution",
    "solve_load_control",
    "solve_corrected",
    "complementarity_residual",
    "complementarity_limit",
    "gap_scale",
    "COMPLEMENTARITY_LIMIT",
]

# Largest accepted complementarity residual of a solution whose gaps come from a linear solve: the
# gap on the active set is then the solve's error relative to the approach. Measured 5e-11 to
# 2.7e-9 (standard solids, resolution 3) and 1.4e-8 (three Prony terms, grading 2) with SuperLU;
# a wrong active set gives O(1e-3) and more (a node penetrating or pulled by a tension).
COMPLEMENTARITY_LIMIT = 1e-7


def complementarity_limit(linear_limit):
    """The largest accepted complementarity residual where the gaps come from a linear solve
    accepted up to the relative residual ``linear_limit``.

    :data:`COMPLEMENTARITY_LIMIT`, or ``linear_limit`` itself where the round-off floor of the
    force balance raised that above it (:func:`fem_reference.linsolve.residual_limit`: broad
    rubbers at high speed, whose balance cancels terms ~1e8 times the load). The gap on the active
    set is then the field solve's error, and it follows the residual: measured 0.07-0.13 times it
    (relative to the approach) on a 20-term rubber, E_inf/E0 = 1000, a decade above its friction
    peak (residuals 3e-7 to 9e-7 accepted under limits of 3e-6 to 8e-6). A wrong active set still
    fails where the limit is raised the most (5e-5 measured): one edge node wrong gives 1e-4 to
    2e-2 (standard solid, resolutions 8 to 2).
    """
    return max(COMPLEMENTARITY_LIMIT, float(linear_limit))


@dataclass(frozen=True)
class ContactSolution:
    """Nodal contact forces ``lam`` (N/m or N), approach ``d`` (m), gap ``g`` (m),
    ``active`` mask, PDAS ``iterations`` and complementarity ``residual`` (dimensionless,
    :func:`complementarity_residual`)."""

    lam: np.ndarray
    d: float
    gap: np.ndarray
    active: np.ndarray
    iterations: int
    residual: float


def solve_load_control(C, h, load, *, w0=None, active=None, maxiter=100):
    """Solve the contact problem described in the module docstring.

    Parameters
    ----------
    C : (n, n) ndarray or callable
        Flexibility of the candidate nodes (m per N, or m per N/m in plane strain), or a callable
        ``C(idx)`` returning its columns ``idx`` (``(n, idx.size)``): only the columns of the nodes
        that enter the active set are asked for.
    h : (n,) ndarray
        Rigid heights at the nodes (m), positive toward the solid, max 0.
    load : float
        Total normal force ``P`` (N, or N/m), > 0.
    w0 : (n,) ndarray, optional
        Depression without contact forces (history of a time-stepped solve).
    active : (n,) bool ndarray, optional
        Initial active set; default: the nodes with the largest heights.
    maxiter : int
        Maximum number of active-set updates.
    """
    n = h.size
    columns = C if callable(C) else (lambda idx: C[:, idx])
    w0 = np.zeros(n) if w0 is None else w0
    if active is None:
        active = h >= np.sort(h)[-max(3, n // 10)]
    active = active.copy()
    seen = set()
    for it in range(1, maxiter + 1):
        idx = np.flatnonzero(active)
        if idx.size == 0:
            raise ConvergenceError("contact active set became empty (load too small for the mesh?)")
        k = idx.size
        Ca = columns(idx)
        S = np.zeros((k + 1, k + 1))
        S[:k, :k] = Ca[idx]
        S[:k, k] = -1.0
        S[k, :k] = 1.0
        rhs = np.concatenate([h[idx] - w0[idx], [load]])
        sol = np.linalg.solve(S, rhs)
        lam = np.zeros(n)
        lam[idx] = sol[:k]
        d = sol[k]
        gap = Ca @ sol[:k] + w0 - h - d
        new = (active & (lam > 0)) | (~active & (gap < 0))
        key = new.tobytes()
        if np.array_equal(new, active):
            res = complementarity_residual(lam, gap, active, load, gap_scale(d, h[idx]))
            return ContactSolution(lam, float(d), gap, active, it, res)
        if key in seen:
            raise ConvergenceError(f"contact active set cycles after {it} iterations")
        seen.add(key)
        active = new
    raise ConvergenceError(f"contact active set did not settle in maxiter={maxiter} iterations")


def gap_scale(d, h_active):
    """The length the gaps are measured against (m): the approach ``|d|`` or the spread of the
    heights over the contact, whichever is larger (the approach alone is arbitrary in 2-D)."""
    spread = float(np.ptp(h_active)) if np.size(h_active) > 1 else 0.0
    return max(abs(float(d)), spread, 1e-300)


def complementarity_residual(lam, gap, active, load, scale):
    """Complementarity residual of a contact solution, from the solution itself (dimensionless).

    The largest of, over the candidate nodes:

    - ``|g_i| / scale`` where node ``i`` is in the active set (it must touch);
    - ``max(-g_i, 0) / scale`` outside it (no penetration);
    - ``max(-lam_i, 0) / mean(lam_A)`` inside it (no tension) and ``|lam_i| / mean(lam_A)`` outside
      it (no force without contact).

    ``gap`` must be computed from the forces (``g = C lam + w0 - h - d``, or from the displaced
    surface), not set to zero on the active set, or the first term cannot fail.

    Parameters
    ----------
    lam, gap : (n,) ndarray
        Nodal forces (N/m or N) and gaps (m) at the candidate nodes.
    active : (n,) bool ndarray
        The active (contact) set the solution claims.
    load : float
        Total normal force (N/m or N); ``load / count(active)`` is the force scale.
    scale : float
        Length scale of the gaps (m), e.g. :func:`gap_scale`.
    """
    lam, gap = np.asarray(lam, float), np.asarray(gap, float)
    active = np.asarray(active, bool)
    f_scale = abs(load) / max(np.count_nonzero(active), 1)
    terms = [0.0]
    if np.any(active):
        terms += [np.max(np.abs(gap[active])) / scale, np.max(np.maximum(-lam[active], 0.0)) / f_scale]
    if np.any(~active):
        terms += [np.max(np.maximum(-gap[~active], 0.0)) / scale, np.max(np.abs(lam[~active])) / f_scale]
    return float(max(terms))


def solve_corrected(C, depression, h, load, *, target, stall, active=None, steps=8, maxiter=100):
    """Contact on an approximate flexibility, corrected with the exact depression.

    ``C`` (columns, as in :func:`solve_load_control`) may be off by a small relative error ``e``
    (a factor's solves without refinement). Writing the exact depression as ``C lam + w0`` with
    ``w0 = w(lam_k) - C lam_k`` from the last iterate, each contact solve on ``C`` is a step of
    iterative refinement of the contact problem: its error contracts by about ``e`` times the
    conditioning of ``C`` on the active set. So one exact field solve per step replaces the
    refinement of every column.

    Parameters
    ----------
    C : callable
        ``C(idx)``: the approximate flexibility's columns ``idx``.
    depression : callable
        ``depression(lam)`` returns ``(w, extra)``: the exact depression (m) at the candidate
        nodes under the nodal forces ``lam``, and whatever the caller keeps of that solve.
    h, load, active, maxiter :
        As in :func:`solve_load_control` (``active`` starts the first contact solve; each later one
        starts from the last).
    target : float
        Complementarity residual (:func:`complementarity_residual`) at which the refinement stops.
    stall : float
        It also stops once a step fails to reduce the residual by this factor: at the floor of the
        exact solves it only fluctuates.
    steps : int
        Most contact solves.

    Returns
    -------
    (ContactSolution, extra) of the step with the lowest residual; the solution's gap, residual
    and the ``extra`` come from the exact depression, its ``iterations`` count every active-set
    update over all steps.
    """
    w0 = np.zeros(h.size)
    best = prev = None
    iterations = 0
    for _ in range(steps):
        sol = solve_load_control(C, h, load, w0=w0, active=active, maxiter=maxiter)
        iterations += sol.iterations
        w, extra = depression(sol.lam)
        gap = w - h - sol.d
        res = complementarity_residual(sol.lam, gap, sol.active, load, gap_scale(sol.d, h[sol.active]))
        sol = ContactSolution(sol.lam, sol.d, gap, sol.active, iterations, res)
        if best is None or res < best[0].residual:
            best = (sol, extra)
        if res <= target or (prev is not None and res > stall * prev):
            break
        prev, active = res, sol.active
        idx = np.flatnonzero(sol.active)
        w0 = w - C(idx) @ sol.lam[idx]
    return best
