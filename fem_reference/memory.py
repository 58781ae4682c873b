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
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp

__all__ = [
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


def _elements(keys, x, cells):
    """Elements along each row in flow order: first sorted point of each, its length and
    whether it opens its row; with the sort order of the points."""
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
    return order, first, length, row_start[first]


def _zeta(length, ell):
    if ell <= 0:
        return np.full(length.shape, np.inf)
    if not np.isfinite(ell):
        return np.zeros(length.shape)
    return length / (2.0 * ell)


def _unsort(M, order):
    inv = np.empty(order.size, dtype=int)
    inv[order] = np.arange(order.size)
    return M[inv][:, inv].tocsr()


def _row_blocks(length, opens, ell):
    """``(S, c)`` of every element, a row's first element relaxed (``alpha = eps``, nothing in)."""
    _, S, c = element_blocks(_zeta(length, ell))
    S = np.where(opens[:, None, None], np.eye(3)[None], S)
    c = np.where(opens[:, None], 0.0, c)
    return S, c


def memory_operators(keys, x, ell, cells):
    """Sparse ``L``, ``R`` with ``L alpha = R eps`` (points in the given order).

    Each element's rows are the update solved for its own points, ``alpha_e - c_e r^T
    alpha_{e-1} = S_e eps_e`` (:func:`element_blocks`), so ``L`` is unit block-lower-bidiagonal in
    flow order (its diagonal is the identity, as pivots need), and ``R`` block-diagonal.

    Parameters
    ----------
    keys : (n,) int array
        Streamline (row) label of each point.
    x : (n,) array
        Position along the flow axis (m); material flows toward ``-x``.
    ell : float
        Advection length ``V tau`` (m), ``>= 0``; ``inf`` allowed (glassy).
    cells : (n,) int array
        Element of each point (3 points of each row per element).
    """
    order, first, length, opens = _elements(keys, x, cells)
    n = order.size
    S, c = _row_blocks(length, opens, ell)
    _, _, _, _, r = reference_element()
    loc = np.arange(3)
    blk_r = np.broadcast_to(first[:, None, None] + loc[None, :, None], (first.size, 3, 3))
    blk_c = np.broadcast_to(first[:, None, None] + loc[None, None, :], (first.size, 3, 3))
    up = np.flatnonzero(~opens)
    cpl = -c[up][:, :, None] * r[None, None, :]  # -c_e r^T on the upstream element's points
    L = sp.coo_matrix(
        (
            np.concatenate([np.ones(n), cpl.ravel()]),
            (
                np.concatenate([np.arange(n), blk_r[up].ravel()]),
                np.concatenate([np.arange(n), (blk_c[up] - 3).ravel()]),
            ),
        ),
        shape=(n, n),
    ).tocsr()
    R = sp.coo_matrix((S.ravel(), (blk_r.ravel(), blk_c.ravel())), shape=(n, n)).tocsr()
    return _unsort(L, order), _unsort(R, order)


def state_operators(keys, x, ell, cells):
    """Exact memory through the outflow values ``beta`` of the elements (see the module docstring).

    Returns sparse ``(D, E, L, R)`` with ``alpha = D eps + E beta`` and ``L beta = R eps``: ``D``
    (n, n) holds each element's own ``S_e``, ``E`` (n, m) its ``c_e`` on the outflow of the element
    upstream, ``L`` (m, m) is unit lower bidiagonal with ``-gamma_e`` below the diagonal and ``R``
    (m, n) holds ``q_e^T = r^T S_e``; ``m`` is the number of elements crossed by all rows (in flow
    order along each row). Points in the given order; parameters as :func:`memory_operators`.
    """
    order, first, length, opens = _elements(keys, x, cells)
    n = order.size
    ne = first.size
    S, c = _row_blocks(length, opens, ell)
    _, _, _, _, r = reference_element()
    loc = np.arange(3)
    pts = first[:, None] + loc[None, :]  # (ne, 3) sorted point indices of each element
    inv = np.empty(n, dtype=int)
    inv[order] = np.arange(n)
    pts = order[pts]  # back to the given order
    D = sp.coo_matrix((S.ravel(), (np.repeat(pts, 3, axis=1).ravel(), np.tile(pts, (1, 3)).ravel())), shape=(n, n))
    up = np.flatnonzero(~opens)
    E = sp.coo_matrix((c[up].ravel(), (pts[up].ravel(), np.repeat(up - 1, 3))), shape=(n, ne))
    gamma = c[up] @ r
    L = sp.coo_matrix(
        (
            np.concatenate([np.ones(ne), -gamma]),
            (np.concatenate([np.arange(ne), up]), np.concatenate([np.arange(ne), up - 1])),
        ),
        shape=(ne, ne),
    )
    q = np.einsum("eij,i->ej", S, r)
    R = sp.coo_matrix((q.ravel(), (np.repeat(np.arange(ne), 3), pts.ravel())), shape=(ne, n))
    return D.tocsr(), E.tocsr(), L.tocsr(), R.tocsr()


def memory_reach(keys, x, ell, cells, tol=1e-13):
    """Mean number of upstream elements the truncated memory (:func:`condensed_memory`) couples
    to each element: the ``f < e`` of its row with ``prod_{g=f+1}^{e-1} gamma_g >= tol``."""
    _, first, length, opens = _elements(keys, x, cells)
    ne = first.size
    if ne == 0:
        return 0.0
    _, _, c = element_blocks(_zeta(length, ell))
    _, _, _, _, r = reference_element()
    gamma = np.clip(c @ r, 1e-300, 1.0)
    gamma[opens] = 1.0  # never multiplied in: a row's first element has nothing upstream
    # log Gamma_{e,f} = C[e-1] - C[f] with C the running sum of log gamma (non-increasing)
    C = np.cumsum(np.log(gamma))
    row_first = np.maximum.accumulate(np.where(opens, np.arange(ne), 0))
    e = np.arange(1, ne)
    fmin = np.searchsorted(-C, -C[e - 1] + math.log(tol), side="left")
    reach = np.where(opens[e], 0, e - np.maximum(fmin, row_first[e]))
    return float(np.sum(np.maximum(reach, 0)) / ne)


def condensed_memory(keys, x, ells, weights, cells, tol=1e-13):
    """``S = sum_k weights_k A_k`` with ``alpha_k = A_k eps`` (points in the given order).

    The memory of each element is truncated where the product of the decays ``gamma`` from
    the source element falls below ``tol`` (each decay is in (0, 1) and the weights of an
    element are bounded, so the dropped tail is ``O(tol max|eps|)``).
    """
    order, first, length, opens = _elements(keys, x, cells)
    n = order.size
    ne = first.size
    _, _, _, e_in, r = reference_element()
    # the row each element belongs to, as the index of the row's first element
    row_first = np.maximum.accumulate(np.where(opens, np.arange(ne), 0))
    loc = np.arange(3)
    pts = first[:, None] + loc[None, :]  # (ne, 3)
    total = sp.csr_matrix((n, n))
    for ell, wk in zip(ells, weights):
        S, c = _row_blocks(length, opens, ell)
        gamma = c @ r  # (ne,)
        q = np.einsum("eij,i->ej", S, r)  # r^T S_e
        rows = [np.repeat(pts, 3, axis=1).ravel()]
        cols = [np.tile(pts, (1, 3)).ravel()]
        vals = [S.ravel()]
        G = np.ones(ne)
        for j in range(1, ne):
            e = np.arange(j, ne)
            f = e - j
            ok = row_first[e] <= f
            if j > 1:
                G = G[1:] * gamma[f + 1]  # Gamma_{e,f} = prod_{g=f+1}^{e-1} gamma_g
            else:
                G = np.ones(e.size)
            keep = ok & (G >= tol)
            if not np.any(keep):
                break
            ek, fk, Gk = e[keep], f[keep], G[keep]
            block = c[ek][:, :, None] * (Gk[:, None] * q[fk])[:, None, :]  # (m, 3, 3)
            rows.append(np.repeat(pts[ek], 3, axis=1).ravel())
            cols.append(np.tile(pts[fk], (1, 3)).ravel())
            vals.append(block.ravel())
        A = sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
        total = total + wk * A.tocsr()
    return _unsort(total.tocsr(), order)
