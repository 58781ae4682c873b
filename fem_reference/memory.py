"""Viscous strains along streamlines, element by element (upwind discontinuous Galerkin).

Each Prony arm's viscous strain obeys, along a row of quadrature points (a streamline;
material flows toward ``-x``, ``s = -x`` the distance travelled, ``ell = V tau``),

    ell d(alpha)/ds + alpha = eps,        alpha = eps where material enters (x = +L).

Why not the point-to-point update of :mod:`fem_reference.transport`: that one treats the
strain as linear between neighbouring points. Where ``ell`` is far below the point spacing
``dx`` the arm's stress is ``E_k (eps - alpha) ~ -E_k ell eps'`` and the two-point update gives
``-E_k ell`` times the chord slope between two points, the derivative half a step upstream: a
first-order error ``E_k ell dx eps'' / 2``. ``E_k ell`` is the arm's modulus times its creep
length (``E0 V lambda`` for a standard solid), so at a large modulus ratio this error is of the
order of the relaxed stress times ``dx`` over the contact size; near a contact edge, where a
graded mesh has ``dx ~ (ratio - 1) d`` at a distance ``d``, it does not fall with the resolution,
only with the grading, and it moves the whole contact downstream. (Integrating each element's
own quadratic exactly instead cures the bias but drops the strain's jumps between elements,
which the solve then no longer damps: at ``E_inf/E0 = 1000`` the flexibility lost its positive
diagonal.)

Here ``alpha`` lives in the same space as the strain of a 9-node element along a row: a
quadratic in ``x`` on each element, nodal at its 3 Gauss points. The equation is imposed in
the upwind DG form: on each element ``e`` (length ``h``, local ``t`` in ``[-1, 1]`` downstream)

    (D + zeta W + e_in e_in^T) alpha_e = zeta W eps_e + e_in (r^T alpha_{e-1}),   zeta = h / (2 ell),

with ``D_ij = int phi_j' phi_i dt``, ``W`` the Gauss weights, ``e_in = phi(-1)`` and
``r = phi(+1)`` the basis at the inflow and outflow faces. Material enters at the upstream end
of the block (``x = +L``) relaxed: the first element of a row has ``alpha = eps`` and passes its
strain at its outflow face to the next. (An unstrained inflow, ``alpha = 0`` there, makes the
viscous term dissipative in the quadrature's inner product on every row, but the mismatch with the
small strain at the truncated boundary dissipates energy there: +0.28 % on the dissipation form of
the friction at E_inf/E0 = 10, at every resolution.) Properties:

- exact for constant strain (beyond the inflow's reach), in the relaxed (``zeta -> inf``:
  ``alpha = eps``) and glassy (``zeta -> 0``: ``alpha`` carried unchanged) limits;
- where ``ell << h``: ``eps - alpha -> -ell`` times the DG upwind derivative of the strain,
  the element's own derivative plus its inflow jump lifted onto its points: second order at
  the points and dissipative (the jumps are damped, as the two-point update damps them);
- the decay from one element to the next, ``gamma = r^T (D + zeta W + e e^T)^-1 e_in``, lies
  in (0, 1) for every ``zeta`` (no growth, no sign changes): ``exp(-2 zeta)`` to second order
  where the memory is long, ``O(1 / zeta)`` where it is short (there it carries only the
  lifted inflow jump of the strain);
- unrolled, ``alpha_e = S_e eps_e + c_e sum_{f < e} Gamma_{e,f} q_f^T eps_f`` with scalar
  products ``Gamma`` of the ``gamma`` between, truncated where they fall below ``tol``
  (:func:`condensed_memory`), or kept as unknowns with a block-bidiagonal
  ``L alpha = R eps`` (:func:`memory_operators`);
- the only thing an element passes downstream is one number per row and strain component, its
  outflow value ``beta_e = r^T alpha_e``. Keeping those as the unknowns,
  ``alpha_e = S_e eps_e + c_e beta_{e-1}`` and ``beta_e - gamma_e beta_{e-1} = q_e^T eps_e``
  (:func:`state_operators`), is exact, has a third of the unknowns of ``alpha`` and couples each
  point only to its own element and the outflow of the one upstream, however long the memory.
  The truncated memory instead couples a point to every element within its reach
  (:func:`memory_reach`): cheaper only where that reach is an element or two.

Which outflow values a row of an element receives is a :class:`Flow`: on rows of points
(:func:`row_flow`) the element upstream on the same row; on a mesh of rectangles (:func:`mesh_flow`)
the elements whose outflow faces meet its inflow face, whose traces (quadratics in height, nodal at
their rows) are projected onto its own, so that elements may halve or double across a face.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

__all__ = [
    "Flow",
    "row_flow",
    "mesh_flow",
    "reference_element",
    "element_blocks",
    "memory_operators",
    "state_operators",
    "memory_reach",
    "condensed_memory",
]


def reference_element():
    """``(nodes, weights, D, e_in, r)`` of the 3-point Gauss element on ``t in [-1, 1]``."""
    g = math.sqrt(0.6)
    nodes = np.array([-g, 0.0, g])
    w = np.array([5.0, 8.0, 5.0]) / 9.0

    def basis(t):
        return np.array(
            [np.prod([(t - nodes[m]) / (nodes[j] - nodes[m]) for m in range(3) if m != j]) for j in range(3)]
        )

    def dbasis(t):
        out = np.zeros(3)
        for j in range(3):
            others = [m for m in range(3) if m != j]
            den = np.prod([nodes[j] - nodes[m] for m in others])
            out[j] = sum(t - nodes[m] for m in others) / den
        return out

    D = np.array([w[i] * dbasis(nodes[i]) for i in range(3)])  # Gauss is exact for phi_j' phi_i
    return nodes, w, D, basis(-1.0), basis(1.0)


def element_blocks(zeta):
    """``(K, S, c)`` per element for ``zeta = h / (2 ell)`` (n,), ``0`` and ``inf`` allowed.

    ``K = (D + zeta W + e e^T) / (1 + zeta)`` (scaled to stay finite), ``S = K^-1 zeta W /
    (1 + zeta)`` and ``c = K^-1 e_in / (1 + zeta)``: ``alpha_e = S eps_e + c alpha_in``.
    """
    _, w, D, e_in, _ = reference_element()
    zeta = np.asarray(zeta, dtype=float)
    finite = np.isfinite(zeta)
    inv = np.where(finite, 1.0 / (1.0 + np.where(finite, zeta, 0.0)), 0.0)
    frac = np.where(finite, np.where(finite, zeta, 0.0) * inv, 1.0)
    K = inv[:, None, None] * (D + np.outer(e_in, e_in))[None] + frac[:, None, None] * np.diag(w)[None]
    rhs = np.concatenate(
        [frac[:, None, None] * np.diag(w)[None], (inv[:, None] * e_in[None])[:, :, None]], axis=2
    )  # (n, 3, 4)
    sol = np.linalg.solve(K, rhs)
    return K, sol[:, :, :3], sol[:, :, 3]


@dataclass(frozen=True)
class Flow:
    """Where each row segment of an element takes its inflow from.

    A *segment* is one row of an element's 3x3 Gauss points: its 3 points along the flow, at one
    height. The viscous strain of a term is a quadratic in ``x`` on each segment, nodal at its points,
    and the segment passes downstream only its outflow value ``beta`` (:func:`state_operators`).

    Attributes
    ----------
    points : (ns, 3) int array
        Quadrature-point index of each segment's points, upstream (largest ``x``) first.
    length : (ns,) array
        Length of each segment's element along the flow (m).
    inflow : scipy.sparse.csr_matrix, (ns, ns)
        ``alpha_in = inflow @ beta``: the value each segment receives at its inflow face from the
        outflow values of the segments upstream of that face. Its rows sum to 1 (a constant passes
        unchanged); a segment whose inflow face is the block's upstream end has an empty row (the
        material arrives relaxed there, ``alpha = eps``).
    n_points : int
        Number of quadrature points.
    """

    points: np.ndarray
    length: np.ndarray
    inflow: sp.csr_matrix
    n_points: int

    @property
    def opens(self):
        """Segments whose inflow face is the block's upstream end."""
        return np.diff(self.inflow.indptr) == 0


def row_flow(keys, x, cells):
    """:class:`Flow` of points on rows: ``keys`` the row of each point, ``x`` its position (m) and
    ``cells`` its element (3 points of each row per element); each element takes its inflow from
    the one upstream on its row."""
    keys = np.asarray(keys)
    x = np.asarray(x, dtype=float)
    cells = np.asarray(cells)
    order = np.lexsort((-x, keys))  # by row, then upstream (large x) first
    ks, xs, cs = keys[order], x[order], cells[order]
    n = xs.size
    row_start = np.concatenate([[True], ks[1:] != ks[:-1]])
    el_start = row_start | np.concatenate([[True], cs[1:] != cs[:-1]])
    first = np.flatnonzero(el_start)
    if not np.all(np.diff(np.concatenate([first, [n]])) == 3):
        raise ValueError("every element must hold exactly 3 points of each row it crosses")
    length = (xs[first] - xs[first + 2]) / math.sqrt(0.6)
    ns = first.size
    up = np.flatnonzero(~row_start[first])
    inflow = sp.csr_matrix((np.ones(up.size), (up, up - 1)), shape=(ns, ns))
    return Flow(order[first[:, None] + np.arange(3)[None, :]], length, inflow, n)


def _face_weights(e_lo, e_hi, f_lo, f_hi):
    """``(m, 3, 3)`` weights of the L2 projection of a quadratic on ``[f_lo, f_hi]`` (nodal at its
    Gauss points) onto the quadratics on ``[e_lo, e_hi]``, over their overlap only. Summed over the
    intervals that tile the face, a row of weights sums to 1; where ``[f_lo, f_hi]`` covers the face
    they are the upstream quadratic's values at the face's Gauss points (exact restriction)."""
    nodes, w, _, _, _ = reference_element()
    lo, hi = np.maximum(e_lo, f_lo), np.minimum(e_hi, f_hi)
    yq = 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * nodes[None, :]  # (m, 3) overlap Gauss points
    wq = 0.5 * (hi - lo)[:, None] * w[None, :]

    def lagrange(lo_, hi_):
        t = (2.0 * yq - (lo_ + hi_)[:, None]) / (hi_ - lo_)[:, None]  # (m, q)
        out = np.ones(t.shape + (3,))
        for j in range(3):
            for m in range(3):
                if m != j:
                    out[..., j] *= (t - nodes[m]) / (nodes[j] - nodes[m])
        return out  # (m, q, 3)

    pe, pf = lagrange(e_lo, e_hi), lagrange(f_lo, f_hi)
    mass = 0.5 * (e_hi - e_lo)[:, None] * w[None, :]  # the Lagrange mass at Gauss nodes is diagonal
    out = np.einsum("mq,mqj,mqi->mji", wq, pe, pf) / mass[:, :, None]
    out[(e_lo == f_lo) & (e_hi == f_hi)] = np.eye(3)  # a matching face: row to row, without round-off
    return out


def mesh_flow(p, t, points, periodic=False):
    """:class:`Flow` of the 3x3 Gauss points of axis-aligned rectangles.

    ``p`` (2, nv) and ``t`` (4, nel) are the mesh's vertices and elements, ``points`` (2, nel, 9)
    the quadrature points. An element takes its inflow through its ``x = x_max`` face from every
    element whose ``x = x_min`` face overlaps it, projected onto its own face (:func:`_face_weights`):
    one neighbour of the same height on a tensor mesh, or up to two of half or twice its height
    where the mesh coarsens. ``periodic``: the elements at the upstream end (``x_max`` of the mesh)
    take their inflow from those at the downstream end (its ``x_min``), so that every row is a closed
    streamline of a periodic cell and no segment opens relaxed.
    """
    pv = p[:, t]  # (2, 4, nel)
    lo, hi = pv.min(axis=1), pv.max(axis=1)
    nel = t.shape[1]
    # the faces where material enters each element: on a periodic cell the right end is the left end
    face = np.where(hi[0] == hi[0].max(), lo[0].min(), hi[0]) if periodic else hi[0]
    rel = (points - lo[:, :, None]) / (hi - lo)[:, :, None]  # (2, nel, 9) in (0, 1)
    pos = 2 - np.searchsorted([0.3, 0.7], rel[0].ravel()).reshape(rel[0].shape)  # upstream first
    lev = np.searchsorted([0.3, 0.7], rel[1].ravel()).reshape(rel[1].shape)
    idx = np.empty((nel, 3, 3), dtype=int)
    q = np.arange(points.shape[2])
    idx[np.arange(nel)[:, None], lev, pos] = np.arange(nel)[:, None] * points.shape[2] + q[None, :]
    pairs_e, pairs_f = [], []
    for xv in np.intersect1d(face, lo[0]):
        es = np.flatnonzero(face == xv)
        fs = np.flatnonzero(lo[0] == xv)
        es = es[np.argsort(lo[1, es])]
        fs = fs[np.argsort(lo[1, fs])]
        start = np.searchsorted(hi[1, fs], lo[1, es], side="right")
        stop = np.searchsorted(lo[1, fs], hi[1, es], side="left")
        count = np.maximum(stop - start, 0)
        pe = np.repeat(es, count)
        pf = fs[np.repeat(start - np.cumsum(count) + count, count) + np.arange(count.sum())]
        pairs_e.append(pe)
        pairs_f.append(pf)
    pe = np.concatenate(pairs_e) if pairs_e else np.zeros(0, dtype=int)
    pf = np.concatenate(pairs_f) if pairs_f else np.zeros(0, dtype=int)
    wts = _face_weights(lo[1, pe], hi[1, pe], lo[1, pf], hi[1, pf])  # (m, 3 rows of e, 3 rows of f)
    rows = np.broadcast_to(3 * pe[:, None, None] + np.arange(3)[None, :, None], wts.shape)
    cols = np.broadcast_to(3 * pf[:, None, None] + np.arange(3)[None, None, :], wts.shape)
    inflow = sp.csr_matrix((wts.ravel(), (rows.ravel(), cols.ravel())), shape=(3 * nel, 3 * nel))
    inflow.eliminate_zeros()
    length = np.repeat(hi[0] - lo[0], 3)
    return Flow(idx.reshape(3 * nel, 3), length, inflow, nel * points.shape[2])


def _zeta(length, ell):
    if ell <= 0:
        return np.full(length.shape, np.inf)
    if not np.isfinite(ell):
        return np.zeros(length.shape)
    return length / (2.0 * ell)


def _segment_blocks(flow, ell):
    """``(S, c, gamma, q)`` of every segment; one with nothing upstream is relaxed (``alpha = eps``)."""
    _, S, c = element_blocks(_zeta(flow.length, ell))
    opens = flow.opens
    S = np.where(opens[:, None, None], np.eye(3)[None], S)
    c = np.where(opens[:, None], 0.0, c)
    _, _, _, _, r = reference_element()
    return S, c, c @ r, np.einsum("sij,i->sj", S, r)


def _on_points(flow, vals):
    """``(n, ns)`` matrix putting ``vals`` (ns, 3) on each segment's points."""
    ns = flow.length.size
    return sp.csr_matrix((vals.ravel(), (flow.points.ravel(), np.repeat(np.arange(ns), 3))), shape=(flow.n_points, ns))


def _own_blocks(flow, S):
    pts = flow.points
    return sp.csr_matrix(
        (S.ravel(), (np.repeat(pts, 3, axis=1).ravel(), np.tile(pts, (1, 3)).ravel())),
        shape=(flow.n_points, flow.n_points),
    )


def memory_operators(flow, ell):
    """Sparse ``L``, ``R`` with ``L alpha = R eps`` (``alpha`` at the points, in their order).

    Each segment's rows are the update solved for its own points, ``alpha_s - c_s alpha_in =
    S_s eps_s`` (:func:`element_blocks`) with ``alpha_in`` the inflow (:class:`Flow`) of the
    upstream segments' outflow values ``r^T alpha``: ``L`` has a unit diagonal, ``R`` holds the
    ``S_s``. ``ell`` is the advection length ``V tau`` (m), ``>= 0``; ``inf`` allowed (glassy).
    """
    S, c, _, _ = _segment_blocks(flow, ell)
    _, _, _, _, r = reference_element()
    out = _on_points(flow, np.broadcast_to(r, (flow.length.size, 3))).T  # r^T alpha of each segment
    L = sp.identity(flow.n_points, format="csr") - _on_points(flow, c) @ flow.inflow @ out
    return L.tocsr(), _own_blocks(flow, S)


def state_operators(flow, ell):
    """Exact memory through the outflow values ``beta`` of the segments (see the module docstring).

    Returns sparse ``(D, E, L, R)`` with ``alpha = D eps + E beta`` and ``L beta = R eps``: ``D``
    (n, n) holds each segment's own ``S_s``, ``E`` (n, ns) its ``c_s`` on its inflow from the outflow
    values upstream, ``L = I - diag(gamma) inflow`` (ns, ns) and ``R`` (ns, n) holds ``q_s^T =
    r^T S_s``; ``ns`` segments (:class:`Flow`), points in their order.
    """
    S, c, gamma, q = _segment_blocks(flow, ell)
    ns = gamma.size
    E = _on_points(flow, c) @ flow.inflow
    L = sp.identity(ns, format="csr") - sp.diags(gamma) @ flow.inflow
    R = _on_points(flow, q).T
    return _own_blocks(flow, S), E.tocsr(), L.tocsr(), R.tocsr()


def _truncated_series(flow, gamma, tol, limit=np.inf):
    """Yield ``A_j = inflow (diag(gamma) inflow)^j`` for ``j = 0, 1, ...``, entries below ``tol`` in
    magnitude dropped, until none is left or the mean count of entries so far exceeds ``limit``."""
    step = (sp.diags(gamma) @ flow.inflow).tocsr()
    A = flow.inflow.copy()
    ns = max(gamma.size, 1)
    total = 0
    while A.nnz:
        A.data[np.abs(A.data) < tol] = 0.0
        A.eliminate_zeros()
        if not A.nnz:
            return
        yield A
        total += A.nnz
        if total / ns > limit:
            return
        A = (A @ step).tocsr()


def memory_reach(flow, ell, tol=1e-13, limit=np.inf):
    """Mean number of upstream segments the truncated memory (:func:`condensed_memory`) couples to
    each segment (on rows: elements ``f < e`` with ``prod_{g=f+1}^{e-1} gamma_g >= tol``); counting
    stops once the mean exceeds ``limit`` (the value returned is then above it)."""
    ns = flow.length.size
    if ns == 0:
        return 0.0
    _, _, gamma, _ = _segment_blocks(flow, ell)
    return float(sum(A.nnz for A in _truncated_series(flow, gamma, tol, limit)) / ns)


def condensed_memory(flow, ells, weights, tol=1e-13):
    """``S = sum_k weights_k A_k`` with ``alpha_k = A_k eps`` (points in their order).

    The memory is truncated where the product of the decays ``gamma`` from the source segment falls
    below ``tol`` (each decay is in (0, 1) and the weights of a segment are bounded, so the dropped
    tail is ``O(tol max|eps|)``).
    """
    total = sp.csr_matrix((flow.n_points, flow.n_points))
    for ell, wk in zip(ells, weights):
        S, c, gamma, q = _segment_blocks(flow, ell)
        series = sp.csr_matrix((gamma.size, gamma.size))
        for A in _truncated_series(flow, gamma, tol):
            series = series + A
        A = _own_blocks(flow, S) + _on_points(flow, c) @ series @ _on_points(flow, q).T
        total = total + wk * A.tocsr()
    return total.tocsr()
