"""Exact exponential update of the internal (viscous-strain) variables.

Each Maxwell arm ``k`` of the Prony series carries a viscous strain ``alpha_k`` that obeys

    tau_k d(alpha_k)/dt + alpha_k = eps.

In steady rolling, in the indenter's frame, material flows in ``-x`` at speed ``V``, so
``d/dt = -V d/dx`` and, with the advection length ``ell_k = V tau_k``,

    -ell_k d(alpha_k)/dx + alpha_k = eps          (inflow at the upstream end, x = +L).

In time (indentation) the same equation is integrated over steps ``dt`` instead of ``dx``.
Along a line, with ``z = dx / ell`` (or ``dt / tau``), ``a = exp(-z)`` and
``phi = (1 - a) / z``, the update

    alpha_{n+1} = a alpha_n + (phi - a) eps_n + (1 - phi) eps_{n+1}

is the exact convolution for a strain that is piecewise linear between the points. It is
exact in both limits (``z -> inf``: ``alpha = eps``, relaxed; ``z -> 0``: ``alpha`` frozen,
glassy), unconditionally stable and second order in the point spacing (exponential time
differencing; R.L. Taylor, K.S. Pister, G.L. Goudreau, IJNME 2 (1970) 45-59); measured in the time
step of creep indentation, docs/theory.md §9.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

__all__ = ["exponential_weights", "streamline_operators", "integrate_line"]

_SERIES_Z = 0.1  # below this, the weights are summed as Taylor series (no cancellation)


def exponential_weights(z):
    """Weights ``(a, phi - a, 1 - phi)`` of the exponential update for steps ``z >= 0``.

    ``z`` may be 0 (glassy: ``(1, 0, 0)``) or ``inf`` (relaxed: ``(0, 0, 1)``). The three
    weights sum to 1 exactly in exact arithmetic, so a constant strain is a fixed point.
    """
    z = np.asarray(z, dtype=float)
    a = np.exp(-z)
    with np.errstate(divide="ignore", invalid="ignore"):
        phi = np.where(z > 0, -np.expm1(-z) / np.where(z > 0, z, 1.0), 1.0)
    w_prev = phi - a
    w_next = 1.0 - phi
    small = z < _SERIES_Z
    if np.any(small):
        zs = z[small]
        s_prev = np.zeros_like(zs)
        s_next = np.zeros_like(zs)
        term = np.ones_like(zs)  # (-z)^n / (n+1)!
        for n in range(1, 10):
            term = term * (-zs) / (n + 1)
            s_prev += -n * term
            s_next -= term
        w_prev = np.array(w_prev, copy=True)
        w_next = np.array(w_next, copy=True)
        w_prev[small] = s_prev
        w_next[small] = s_next
    return a, w_prev, w_next


def streamline_operators(keys, x, ell):
    """Sparse operators ``L`` and ``R`` with ``L alpha = R eps`` along streamlines.

    Parameters
    ----------
    keys : (n,) int array
        Streamline (row) label of each point.
    x : (n,) array
        Position of each point along the flow axis (m). Material flows toward ``-x``, so
        the first point of each row is its largest ``x`` (inflow, where ``alpha = eps``:
        the material arrives fully relaxed).
    ell : float
        Advection length ``V tau`` (m), ``>= 0``; ``inf`` is allowed (glassy).

    Returns
    -------
    L, R : scipy.sparse.csr_matrix, shape (n, n)
        ``L`` is unit lower bidiagonal in upstream order (a permutation of it in the
        given order), ``R`` holds the strain weights.
    """
    keys = np.asarray(keys)
    x = np.asarray(x, dtype=float)
    n = x.size
    order = np.lexsort((-x, keys))  # by row, then upstream (large x) first
    k_sorted = keys[order]
    same = k_sorted[1:] == k_sorted[:-1]
    prev = order[:-1][same]
    nxt = order[1:][same]
    dx = x[prev] - x[nxt]
    with np.errstate(divide="ignore"):
        z = dx / ell if ell > 0 else np.full(dx.shape, np.inf)
    a, w_prev, w_next = exponential_weights(z)
    diag_r = np.ones(n)
    diag_r[nxt] = w_next
    L = sp.coo_matrix(
        (np.concatenate([np.ones(n), -a]), (np.concatenate([np.arange(n), nxt]), np.concatenate([np.arange(n), prev]))),
        shape=(n, n),
    ).tocsr()
    R = sp.coo_matrix(
        (np.concatenate([diag_r, w_prev]), (np.concatenate([np.arange(n), nxt]), np.concatenate([np.arange(n), prev]))),
        shape=(n, n),
    ).tocsr()
    return L, R


def integrate_line(x, eps, ell):
    """``alpha(x)`` on one streamline for samples ``eps(x)``; ``x`` strictly decreasing.

    Convenience wrapper of :func:`streamline_operators` for a single line (used by the
    tests and for 1-D checks). The inflow point ``x[0]`` has ``alpha = eps``.
    """
    x = np.asarray(x, dtype=float)
    L, R = streamline_operators(np.zeros(x.size, dtype=int), x, ell)
    return spla.spsolve(L.tocsc(), R @ np.asarray(eps, dtype=float))
