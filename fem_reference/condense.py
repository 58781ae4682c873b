"""Viscous strains as an explicit, truncated operator on the strain (condensed Prony terms).

Along a streamline (points ``n = 0, 1, ...`` in upstream-first order, positions
``x_0 > x_1 > ...``) the exponential update of :mod:`fem_reference.transport`,

    alpha_n = a_n alpha_{n-1} + p_n eps_{n-1} + q_n eps_n,      alpha_0 = eps_0,

unrolls into ``alpha_n = sum_{m <= n} c_{n,m} eps_m`` with

    c_{n,n} = q_n,     c_{n,m} = G(x_m - x_n) q_m + G(x_{m+1} - x_n) p_{m+1}   (m < n),

where ``G(d) = exp(-d / ell)`` (the products of the ``a`` factors) and ``q_0 = 1``. Every
``c`` is non-negative and each row sums to 1 (a constant strain is a fixed point), so
dropping the entries with ``G(x_{m+1} - x_n) < tol`` changes ``alpha`` by at most
``tol * max|eps|`` (the dropped tail is ``G`` times an average of the strain). The
operator reaches about ``ell * ln(1 / tol)`` upstream: for ``ell`` of a few point
spacings it is a narrow band, and eliminating ``alpha`` removes its 3 (plane strain)
unknowns per quadrature point and term from the linear system. For ``ell`` much longer
than the spacing the band fills the streamline and keeping ``alpha`` as unknowns (a
bidiagonal block) is cheaper; :func:`band_width` measures which.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .transport import exponential_weights

__all__ = ["streamline_order", "band_width", "condensed_operator"]


def streamline_order(keys, x):
    """Points sorted by row, then upstream first; with each point's position in its row."""
    order = np.lexsort((-np.asarray(x, dtype=float), np.asarray(keys)))
    k = np.asarray(keys)[order]
    start = np.concatenate([[True], k[1:] != k[:-1]])
    first = np.maximum.accumulate(np.where(start, np.arange(k.size), 0))
    return order, np.arange(k.size) - first


def band_width(keys, x, ell, tol=1e-13):
    """Mean number of upstream points per point that the truncated operator couples."""
    if ell <= 0:
        return 1.0
    order, pos = streamline_order(keys, x)
    xs = np.asarray(x, dtype=float)[order]
    reach = ell * np.log(1.0 / tol)
    # count points m <= n in the row with x_m - x_n <= reach (rows are sorted decreasing)
    total = 0
    for j in range(1, xs.size):
        ok = pos[j:] >= j
        ok &= (xs[:-j] - xs[j:]) <= reach
        n = int(np.count_nonzero(ok))
        if n == 0:
            break
        total += n
    return 1.0 + total / xs.size


def condensed_operator(keys, x, ells, weights, tol=1e-13):
    """``S = sum_k weights_k A_k`` with ``alpha_k = A_k eps`` (truncated, see module doc).

    Parameters
    ----------
    keys, x : (n,) arrays
        Row label and position along the flow axis (m) of each point.
    ells : sequence of float
        Advection lengths ``V tau_k`` (m), > 0.
    weights : sequence of float
        Weight of each term.
    tol : float
        Truncation of the exponential memory.

    Returns
    -------
    scipy.sparse.csr_matrix, (n, n)
    """
    x = np.asarray(x, dtype=float)
    order, pos = streamline_order(keys, x)
    xs = x[order]
    n = xs.size
    rows, cols, vals = [], [], []
    for ell, wk in zip(ells, weights):
        dx = np.zeros(n)
        dx[1:] = xs[:-1] - xs[1:]
        z = np.where(pos > 0, dx / ell, 0.0)
        _, p, q = exponential_weights(z)
        p = np.where(pos > 0, p, 0.0)
        q = np.where(pos > 0, q, 1.0)
        rows.append(np.arange(n))
        cols.append(np.arange(n))
        vals.append(wk * q)
        for j in range(1, n):
            idx = np.flatnonzero(pos[j:] >= j) + j  # n with m = n - j in its row
            if idx.size == 0:
                break
            m = idx - j
            g_next = np.exp(-(xs[m + 1] - xs[idx]) / ell)
            keep = g_next >= tol
            if not np.any(keep):
                break
            idx, m, g_next = idx[keep], m[keep], g_next[keep]
            c = np.exp(-(xs[m] - xs[idx]) / ell) * q[m] + g_next * p[m + 1]
            rows.append(idx)
            cols.append(m)
            vals.append(wk * c)
    r = order[np.concatenate(rows)]
    c = order[np.concatenate(cols)]
    return sp.coo_matrix((np.concatenate(vals), (r, c)), shape=(n, n)).tocsr()
