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
It stops when the set repeats, which makes the complementarity residual zero to
round-off; it raises :class:`bem.errors.ConvergenceError` on a cycle or ``maxiter``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from bem.errors import ConvergenceError

__all__ = ["ContactSolution", "solve_load_control"]


@dataclass(frozen=True)
class ContactSolution:
    """Nodal contact forces ``lam`` (N/m or N), approach ``d`` (m), gap ``g`` (m),
    ``active`` mask, PDAS ``iterations`` and complementarity ``residual``
    ``max_i |min(lam_i / mean(lam_A), g_i / |d|)|`` (dimensionless)."""

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
    C : (n, n) ndarray
        Flexibility of the candidate nodes (m per N, or m per N/m in plane strain).
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
        S = np.zeros((k + 1, k + 1))
        S[:k, :k] = C[np.ix_(idx, idx)]
        S[:k, k] = -1.0
        S[k, :k] = 1.0
        rhs = np.concatenate([h[idx] - w0[idx], [load]])
        sol = np.linalg.solve(S, rhs)
        lam = np.zeros(n)
        lam[idx] = sol[:k]
        d = sol[k]
        gap = C @ lam + w0 - h - d
        gap[idx] = 0.0
        new = (active & (lam > 0)) | (~active & (gap < 0))
        key = new.tobytes()
        if np.array_equal(new, active):
            scale_l = load / k
            scale_g = max(abs(d), np.ptp(h[idx]) if k > 1 else 0.0, 1e-300)
            res = float(np.max(np.abs(np.minimum(lam / scale_l, gap / scale_g))))
            return ContactSolution(lam, float(d), gap, active, it, res)
        if key in seen:
            raise ConvergenceError(f"contact active set cycles after {it} iterations")
        seen.add(key)
        active = new
    raise ConvergenceError(f"contact active set did not settle in maxiter={maxiter} iterations")
