"""Influence coefficients of square elements (2-D surfaces on a 3-D half-space), elastic and
steady sliding, on the half-cell lattice of the fine grid.

``G = (1 - nu**2) / (pi r)``. Elastic part: Love's closed form (1929) for a uniformly
loaded rectangle, the corner sum of ``F(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|)`` (the
signed form, docs/theory.md §12). Creep part of term ``k`` (shift ``L = v lambda_k``): the integral is
computed for one fine cell on all half-cell offsets, exactly at the shifted points (no
interpolation, docs/theory.md §12) by composite Gauss-Legendre quadrature, as the backward recursion
``k(X) = int_0^dX exp(-r/L) g(X + r) dr/L + exp(-dX/L) k(X + dX)`` (``dX = dx/2``, ``g`` the
cell's elastic influence) started from a graded tail quadrature; an element's coefficient
is the sum over its cells (superposition, exact), taken from summed-area tables.
"""

import numpy as np

from ..halfspace.cache import table_for
from ..halfspace.influence import love_corner

__all__ = ["cell_creep_table", "matrices_2d"]

_GL8 = np.polynomial.legendre.leggauss(8)
_CUT = 45.0  # exp(-45) ~ 3e-20: the creep weight is dropped beyond z = 45


def _love_slope_corner(X, Y):
    """``d/dX`` of :func:`love_corner`: ``asinh(Y/|X|)`` (X = 0 only occurs in pairs that
    cancel, see :func:`_rect`)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(X != 0, np.arcsinh(Y / np.where(X != 0, np.abs(X), 1.0)), 0.0)


def _rect(x, y, x1, x2, y1, y2, corner):
    """Corner sum of ``corner`` for the rectangle ``[x1,x2] x [y1,y2]`` seen from ``(x, y)``."""
    return corner(x2 - x, y2 - y) - corner(x1 - x, y2 - y) - corner(x2 - x, y1 - y) + corner(x1 - x, y1 - y)


def _cell_influence(X, Y, h):
    """``int int 1/r`` (m) over the cell ``[-h/2, h/2]**2`` seen from ``(X, Y)``."""
    return _rect(X, Y, -h / 2, h / 2, -h / 2, h / 2, love_corner)


def _panel_rule(edges):
    """Composite 8-point Gauss-Legendre nodes and weights on consecutive ``edges``."""
    x, w = _GL8
    a, b = edges[:-1, None], edges[1:, None]
    return (0.5 * (b - a) * (x + 1) + a).ravel(), (0.5 * (b - a) * w).ravel()


def _weight_rule(lo, hi, shift, scale=None, extra=()):
    """Nodes ``r`` in ``[lo, hi]`` and weights of ``exp(-r/shift)/shift dr``, panels graded
    geometrically toward ``lo`` at the rate of the weight (``shift``) and of the integrand
    (``scale``, the distance to the nearest singularity), plus ``extra`` panel edges."""
    pts = [lo, hi, *extra]
    for base in (shift,) if scale is None else (shift, scale):
        g = lo + base * 2.0 ** np.arange(-4, 60)
        pts.extend(g[g < hi])
    edges = np.unique(np.clip(pts, lo, min(hi, lo + _CUT * shift)))
    r, w = _panel_rule(edges)
    return r, w * np.exp(-r / shift) / shift


def cell_creep_table(n, h, shift):
    """Creep integral ``int_0^inf exp(-z) g(X + shift z, Y) dz`` of one fine cell (``g`` =
    :func:`_cell_influence`, m) at the half-cell offsets ``X = i h/2``, ``i = -2n..2n`` (axis
    0) and ``Y = j h/2``, ``j = 0..2n`` (axis 1; even in ``Y``)."""
    dX = 0.5 * h
    X = dX * np.arange(-2 * n, 2 * n + 1)
    Y = dX * np.arange(0, 2 * n + 1)
    table = np.empty((X.size, Y.size))
    # tail beyond the last offset: far from the cell, graded from the cell's size
    r, w = _weight_rule(0.0, _CUT * shift, shift, h)
    table[-1] = np.sum(w[:, None] * _cell_influence(X[-1] + r[:, None], Y[None, :], h), axis=0)
    # one interval of width dX: plain panels, and panels graded toward both ends for the
    # intervals that touch a cell edge on rows |Y| <= h/2 (log-singular slope there)
    r, w = _weight_rule(0.0, dX, shift, None)  # the cell is >= dX away: smooth on scale dX
    ends = np.array([2**-12, 2**-9, 2**-6, 2**-4, 2**-2])
    rs, ws = _weight_rule(0.0, dX, shift, dX, extra=dX * np.concatenate([ends, 1 - ends]))
    decay = np.exp(-dX / shift)
    near = Y <= dX * (1 + 1e-12)
    parts = np.empty((X.size - 1, Y.size))
    # The cell's corners sit on the lattice (h/2 = dX), and F is odd in each argument, so
    # g(X_i + r, Y_b) = F(X_{i-1}+r, Y_{b-1}) - F(X_{i+1}+r, Y_{b-1}) - F(X_{i-1}+r, Y_{b+1})
    # + F(X_{i+1}+r, Y_{b+1}): one evaluation of F per lattice point and node, not four.
    Yx = dX * np.arange(-1, 2 * n + 2)  # Y_{b-1} .. Y_{b+1}
    for i0 in range(0, X.size - 1, 128):
        i1 = min(i0 + 128, X.size - 1)
        Xj = dX * (np.arange(i0 - 1, i1 + 1) - 2 * n)  # X_{i-1} .. X_{i+1}
        phi = love_corner(Xj[:, None, None] + r[None, :, None], Yx[None, None, :])
        g = phi[:-2, :, :-2] - phi[2:, :, :-2] - phi[:-2, :, 2:] + phi[2:, :, 2:]
        parts[i0:i1] = np.einsum("k,ikb->ib", w, g)
    for i in range(X.size - 1):
        if abs(abs(X[i]) - dX) < 1e-9 * h or abs(abs(X[i + 1]) - dX) < 1e-9 * h:
            parts[i, near] = np.sum(ws[:, None] * _cell_influence(X[i] + rs[:, None], Y[None, near], h), axis=0)
    for i in range(X.size - 2, -1, -1):
        table[i] = parts[i] + decay * table[i + 1]
    return table


def _half_offsets(mesh, rows):
    """Per axis: the collocation points of ``rows`` in half-cell units from the domain start
    (``2 start + size``), and every element's first and one-past-last edge (``2 start``,
    ``2 (start + size)``)."""
    out = []
    for d in range(mesh.ndim):
        centre = (2 * mesh.start[rows, d] + mesh.size[rows])[:, None]
        lo = (2 * mesh.start[:, d])[None, :]
        out.append((centre, lo, lo + 2 * mesh.size[None, :]))
    return out


def _corner_sums(table, n, mesh, rows):
    """Love's corner sum for every (row, element) pair, ``table`` holding the corner function
    on the half-cell lattice ``[-2n, 2n]**2`` (edges minus collocation points)."""
    (cx, x1, x2), (cy, y1, y2) = _half_offsets(mesh, rows)
    m = table.shape[1]
    flat = table.ravel()
    ix1, ix2 = (x1 - cx + 2 * n) * m, (x2 - cx + 2 * n) * m
    iy1, iy2 = y1 - cy + 2 * n, y2 - cy + 2 * n
    return np.take(flat, ix2 + iy2) - np.take(flat, ix1 + iy2) - np.take(flat, ix2 + iy1) + np.take(flat, ix1 + iy1)


def _block_sums(table, n, mesh, rows):
    """Sum of the cell ``table`` (half-cell offsets, see :func:`cell_creep_table`) over the
    cells of every element, seen from the centres of elements ``rows``: shape (rows, N_e)."""
    full = np.concatenate([table[:, :0:-1], table], axis=1)  # Y from -2n to 2n
    out = np.empty((rows.size, len(mesh)))
    s_i = mesh.size[rows]
    for parity in (0, 1):
        sel = np.flatnonzero((s_i > 1) == bool(parity))
        if not sel.size:
            continue
        sub = full[parity::2, parity::2]
        P = np.zeros((sub.shape[0] + 1, sub.shape[1] + 1))
        P[1:, 1:] = sub.cumsum(0).cumsum(1)
        m = P.shape[1]
        flat = P.ravel()
        (cx, x1, x2), (cy, y1, y2) = _half_offsets(mesh, rows[sel])
        # cells c of an element: offsets centre - (2c + 1) from x2 - 1 - centre ... ; in the
        # parity sub-table, index (offset + 2n - parity) / 2
        a0 = (cx - x2 + 1 + 2 * n - parity) // 2 * m
        a1 = ((cx - x1 - 1 + 2 * n - parity) // 2 + 1) * m
        b0 = (cy - y2 + 1 + 2 * n - parity) // 2
        b1 = (cy - y1 - 1 + 2 * n - parity) // 2 + 1
        out[sel] = np.take(flat, a1 + b1) - np.take(flat, a0 + b1) - np.take(flat, a1 + b0) + np.take(flat, a0 + b0)
    return out


def matrices_2d(mesh, material, speed, with_slope=True, chunk=512):
    """Influence and x-slope matrices (m/Pa and 1/Pa; slope None unless ``with_slope``) of a
    square-element mesh."""
    n, h = mesh.n, mesh.spacing
    lattice = 0.5 * h * np.arange(-2 * n, 2 * n + 1)
    love = table_for(("adaptive", "love", n, h), lambda: love_corner(lattice[:, None], lattice[None, :]))
    love_dx = table_for(("adaptive", "love_dx", n, h), lambda: _love_slope_corner(lattice[:, None], lattice[None, :]))
    factor = material.plane_strain_factor / np.pi
    shifts = speed * material.creep_times
    tables = {
        k: table_for(("adaptive", "creep", n, h, L), lambda L=L: cell_creep_table(n, h, L))
        for k, L in enumerate(shifts)
        if L >= 1e-4 * h
    }
    ne = len(mesh)
    K = np.empty((ne, ne))
    S = np.empty((ne, ne)) if with_slope else None
    small = any(k not in tables for k in range(shifts.size))
    for r0 in range(0, ne, chunk):
        rows = np.arange(r0, min(ne, r0 + chunk))
        g = _corner_sums(love, n, mesh, rows)  # int int 1/r over the element (m)
        # x-derivative of g at the point
        slope = -_corner_sums(love_dx, n, mesh, rows) if with_slope or small else None
        Kr = g / material.E_inf
        Sr = slope / material.E_inf if with_slope else None
        for k, (Ck, L) in enumerate(zip(material.compliances, shifts)):
            if k in tables:
                creep = _block_sums(tables[k], n, mesh, rows)
                Kr += Ck * creep
                if with_slope:
                    Sr += Ck * (creep - g) / L
            else:  # shift below 1e-4 cells: first order in L (error ~ (L/h)**2)
                Kr += Ck * (g + L * slope)
                if with_slope:
                    Sr += Ck * slope
        K[rows] = factor * Kr
        if with_slope:
            S[rows] = factor * Sr
    return K, S
