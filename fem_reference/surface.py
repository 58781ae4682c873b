"""The top surface (``y = 0``) of a 9-node quadrilateral mesh: nodes, weights, edges.

Pressure is recovered from consistent nodal forces: ``p_i = lam_i / w_i`` with
``w_i = int phi_i ds`` (``int phi_i 2 pi r dr`` for axisymmetry). For the quadratic
edge of length ``D`` the weights are ``D/6, 2D/3, D/6`` (end, middle, end); a uniform
pressure is recovered exactly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["TopSurface", "top_surface", "band", "contact_edges"]


@dataclass(frozen=True)
class TopSurface:
    """Top nodes sorted by ``x`` (m), their vertical DOFs and weights ``w_i`` (m or m^2)."""

    x: np.ndarray
    ydofs: np.ndarray
    weights: np.ndarray


def top_surface(basis, axisymmetric=False):
    """Collect the top-surface nodes of a Q2 vector ``basis`` (boundary named ``top``)."""
    ydofs = basis.get_dofs("top").all("u^2")
    x = basis.doflocs[0, ydofs]
    order = np.argsort(x)
    x, ydofs = x[order], ydofs[order]
    # vertices at even positions, mid-edge nodes at odd positions
    x0, xm, x1 = x[:-1:2], x[1::2], x[2::2]
    w = np.zeros(x.size)
    if axisymmetric:
        # exact 3-point Gauss integration of phi_i * 2 pi r on each edge (degree 3)
        gx, gw = np.polynomial.legendre.leggauss(3)
        for s, wt in zip(0.5 * (gx + 1), 0.5 * gw):
            r = x0 + s * (x1 - x0)
            phis = [(1 - s) * (1 - 2 * s), 4 * s * (1 - s), s * (2 * s - 1)]
            for off, ph in enumerate(phis):
                np.add.at(w, np.arange(off, x.size - 2 + off, 2), wt * ph * 2 * np.pi * r * (x1 - x0))
    else:
        d = x1 - x0
        np.add.at(w, np.arange(0, x.size - 2, 2), d / 6)
        np.add.at(w, np.arange(2, x.size, 2), d / 6)
        w[1::2] += 2 * d / 3
    assert np.allclose(xm, 0.5 * (x0 + x1), rtol=0, atol=1e-9 * np.max(np.abs(x)))
    return TopSurface(x, ydofs, w)


def band(top, x_band):
    """Mask of ``top``'s nodes from ``min(x_band)`` to ``max(x_band)`` (a candidate contact band,
    which on a graded mesh need not be symmetric about ``x = 0``)."""
    x_band = np.asarray(x_band, float)
    slack = 1e-12 * np.max(np.abs(x_band))
    mask = (top.x >= x_band.min() - slack) & (top.x <= x_band.max() + slack)
    if np.count_nonzero(mask) != x_band.size:
        raise ValueError(f"the band holds {np.count_nonzero(mask)} top nodes, expected {x_band.size}")
    return mask


def contact_edges(x, p, active):
    """Leading (``+x``) and trailing contact edges (m) from nodal pressures.

    The pressure at a smooth contact edge falls as ``sqrt(distance)``, so ``p^2`` is
    extrapolated linearly from the two outermost active nodes to zero, and the edge
    is kept between the outermost active node and the first inactive one. (A fit over
    more nodes is worse where the pressure is not elliptic near a moving edge, as in
    creep indentation.)
    """
    idx = np.flatnonzero(active)

    def edge(i_out, i_in, i_free):
        p2o, p2i = p[i_out] ** 2, p[i_in] ** 2
        if p2i > p2o:
            xe = x[i_out] + p2o * (x[i_out] - x[i_in]) / (p2i - p2o)
        else:
            xe = 0.5 * (x[i_out] + x[i_free])
        lo, hi = sorted((x[i_out], x[i_free]))
        return float(np.clip(xe, lo, hi))

    if idx.size < 2:
        return float(x[idx[-1]]), float(x[idx[0]])
    lead = edge(idx[-1], idx[-2], min(idx[-1] + 1, x.size - 1))
    trail = edge(idx[0], idx[1], max(idx[0] - 1, 0))
    return lead, trail
