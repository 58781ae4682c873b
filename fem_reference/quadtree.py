"""Half-space meshes of squares graded in both directions: a balanced quadtree.

The block ``[-L, L] x [-L, 0]`` (``x`` the flow axis, ``y`` up, the free surface at ``y = 0``)
starts as two squares of side ``L``. A square is split into four while its side exceeds the
size requested at its nearest point,

    h(P) = min_i [ s_i + (ratio - 1) dist(P, S_i) ],

with ``S_i`` segments of the surface (the contact, the zones about its edges) and ``s_i`` the
element size on them; then squares are split until the sides of any two that share a face differ
by at most a factor of two (2:1 balance). Every element is a square, so no element is longer than it
is wide, however many decades lie between the contact and the block; the number of elements grows
with ``log(L / s_i) / (ratio - 1)^2`` about each segment.

Where a face of a square meets two squares of half its side, the vertex between those two and the
middle nodes of their faces are *hanging*: the 9-node displacement is kept continuous by setting
them to the large square's quadratic trace on that face (:func:`constraint_matrix`).

Coordinates are integers at the finest level times ``L / 2^level``, offset so that ``x = y = 0``
is exact: near the contact, many decades below ``L``, the vertices keep their full precision.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

__all__ = ["QuadtreeMesh", "quadtree_half_space", "quadtree_strip", "constraint_matrix"]

# deepest level: the integer coordinates at that level must be exact in double precision
MAX_LEVEL = 50


@dataclass(frozen=True)
class _Roots:
    """The squares a quadtree starts from: ``nx`` by ``ny`` of side ``side`` (m), the lower left corner
    at ``(ix0, jy0)`` root sides from the origin (integers, so that every vertex is an exact integer
    multiple of the finest side and ``x = y = 0`` is exact)."""

    side: float
    nx: int
    ny: int
    ix0: int
    jy0: int
    periodic: bool = False

    def inside(self, level, i, j):
        return 0 <= i < self.nx << level and 0 <= j < self.ny << level


def _requested(roots, level, i, j, segments, ratio):
    """The size requested at the point of each square nearest to the segments (m)."""
    side = roots.side / 2.0**level
    x0 = (roots.ix0 * 2.0**level + i) * side
    y1 = (roots.jy0 * 2.0**level + j + 1) * side
    h = np.full(level.shape, np.inf)
    for lo, hi, size in segments:
        dx = np.maximum(0.0, np.maximum(lo - (x0 + side), x0 - hi))
        dy = np.maximum(0.0, -y1)
        h = np.minimum(h, size + (ratio - 1.0) * np.hypot(dx, dy))
    return h


def _refine(roots, segments, ratio):
    """Leaves ``{level: {(i, j), ...}}`` split until each is no larger than the size requested in it."""
    level = 0
    i, j = (a.ravel().astype(np.int64) for a in np.meshgrid(np.arange(roots.nx), np.arange(roots.ny), indexing="ij"))
    tree = {}
    while i.size:
        side = roots.side / 2.0**level
        split = side > _requested(roots, np.full(i.shape, level), i, j, segments, ratio) * (1 + 1e-12)
        if np.any(split) and level >= MAX_LEVEL:
            raise ValueError(f"the mesh would need squares below L / 2^{MAX_LEVEL}: sizes too small for the block")
        tree[level] = set(zip(map(int, i[~split]), map(int, j[~split])))
        a, b = np.array([0, 1, 0, 1]), np.array([0, 0, 1, 1])
        i = (2 * i[split][:, None] + a[None, :]).ravel()
        j = (2 * j[split][:, None] + b[None, :]).ravel()
        level += 1
    return tree


def _covering(tree, level, i, j):
    """The level of the leaf that covers square ``(level, i, j)``, or None if it is split."""
    for m in range(level, -1, -1):
        if (i >> (level - m), j >> (level - m)) in tree.get(m, ()):
            return m
    return None


_FACES = ((1, 0), (-1, 0), (0, 1), (0, -1))


def _split(tree, level, i, j):
    """Replace leaf ``(level, i, j)`` by its four children (in place)."""
    tree[level].discard((i, j))
    tree.setdefault(level + 1, set()).update(
        {(2 * i, 2 * j), (2 * i + 1, 2 * j), (2 * i, 2 * j + 1), (2 * i + 1, 2 * j + 1)}
    )


def _balance(roots, tree):
    """Split leaves until neighbours across every face differ by at most one level (in place)."""
    for lv in sorted(tree, reverse=True):
        if lv < 2:
            break
        for i, j in list(tree.get(lv, ())):
            for di, dj in _FACES:
                ni, nj = i + di, j + dj
                if not roots.inside(lv, ni, nj):
                    continue
                while True:
                    m = _covering(tree, lv - 1, ni >> 1, nj >> 1)
                    if m is None or m >= lv - 1:
                        break
                    # split the coarse leaf covering the neighbour, one level at a time
                    _split(tree, m, ni >> (lv - m), nj >> (lv - m))
    return tree


def _match_sides(roots, tree):
    """Split the squares along the left or the right side where the other side is cut finer at the same
    height (in place); whether any was split."""
    changed = False
    for lv in sorted(tree):
        last = (roots.nx << lv) - 1
        for i, j in list(tree.get(lv, ())):
            if i not in (0, last) or (i, j) not in tree[lv]:
                continue
            other = last if i == 0 else 0
            m = _covering(tree, lv, other, j)
            if m is None:  # finer on the other side: split this one
                _split(tree, lv, i, j)
                changed = True
            elif m < lv:  # coarser on the other side: split that one
                _split(tree, m, other >> (lv - m), j >> (lv - m))
                changed = True
    return changed


def _periodic_balance(roots, tree):
    """Balance, and cut the two sides alike so that a periodic cell's sides carry the same vertices."""
    while True:
        _balance(roots, tree)
        if not _match_sides(roots, tree):
            return tree


@dataclass(frozen=True)
class QuadtreeMesh:
    """A balanced quadtree mesh of the block (lengths in m).

    Attributes
    ----------
    mesh : skfem.MeshQuad
        The squares, with boundaries ``left``, ``right``, ``bottom``, ``top``.
    hanging : (m, 3) int array
        Vertices ``(M, A, B)``: ``M`` hangs at the middle of the face ``A``-``B`` of a larger square.
    element_size : float
        The smallest side.
    width : tuple of float
        ``(x_min, x_max)``: ``(-L, L)`` for the half-space block, ``(0, period)`` for a strip.
    depth : float
        Depth of the block (the bottom is at ``y = -depth``).
    """

    mesh: object
    hanging: np.ndarray
    element_size: float
    width: tuple
    depth: float

    @property
    def n_elements(self):
        return self.mesh.t.shape[1]

    @property
    def smallest_element(self):
        """Side of the smallest square (m)."""
        return self.element_size


def _segments(segments):
    segments = [(float(lo), float(hi), float(s)) for lo, hi, s in segments]
    if not segments or any(s <= 0 or hi < lo for lo, hi, s in segments):
        raise ValueError("need segments (x_lo, x_hi, size) with x_lo <= x_hi and size > 0")
    return segments


def _build(roots, segments, ratio):
    """The :class:`QuadtreeMesh` of ``roots`` refined for ``segments`` and balanced."""
    from skfem import MeshQuad

    if not ratio > 1.0:
        raise ValueError(f"ratio must be > 1, got {ratio!r}")
    tree = _refine(roots, _segments(segments), ratio)
    tree = _periodic_balance(roots, tree) if roots.periodic else _balance(roots, tree)
    top = max(lv for lv, cells in tree.items() if cells)
    lv = np.concatenate([np.full(len(c), v, dtype=np.int64) for v, c in tree.items() if c])
    ij = np.concatenate([np.array(sorted(c), dtype=np.int64).reshape(-1, 2) for v, c in tree.items() if c])
    scale = np.left_shift(1, top - lv)
    i0, j0 = ij[:, 0] * scale, ij[:, 1] * scale
    corners = np.stack(
        [np.stack([i0, i0 + scale, i0 + scale, i0]), np.stack([j0, j0, j0 + scale, j0 + scale])], axis=-1
    )  # (4, nel, 2) integer (X, Y) at the finest level
    keys, t = np.unique(corners.reshape(-1, 2), axis=0, return_inverse=True)
    t = t.reshape(4, -1)
    unit = roots.side / 2.0**top
    x_off, y_off = np.int64(roots.ix0) << top, np.int64(roots.jy0) << top
    p = np.stack([(keys[:, 0] + x_off) * unit, (keys[:, 1] + y_off) * unit])
    # hanging vertices: the middle of each face whose neighbour of the same size is split
    index = {(int(x), int(y)): k for k, (x, y) in enumerate(keys)}
    hanging = []
    for v, cells in tree.items():
        s = 1 << (top - v)
        for i, j in cells:
            for di, dj in _FACES:
                ni, nj = i + di, j + dj
                if not roots.inside(v, ni, nj) or _covering(tree, v, ni, nj) is not None:
                    continue
                if di:
                    x = (i + (di > 0)) * s
                    a, b, m = (x, j * s), (x, (j + 1) * s), (x, j * s + s // 2)
                else:
                    y = (j + (dj > 0)) * s
                    a, b, m = (i * s, y), ((i + 1) * s, y), (i * s + s // 2, y)
                hanging.append((index[m], index[a], index[b]))
    mesh = MeshQuad(p, t)
    x_lo, x_hi = roots.ix0 * roots.side, (roots.ix0 + roots.nx) * roots.side
    y_lo = roots.jy0 * roots.side
    tol = 1e-9 * unit

    def near(a, b):
        return np.abs(a - b) <= tol + 1e-12 * abs(b)

    mesh = mesh.with_boundaries(
        {
            "left": lambda q: near(q[0], x_lo),
            "right": lambda q: near(q[0], x_hi),
            "bottom": lambda q: near(q[1], y_lo),
            "top": lambda q: near(q[1], 0.0),
        }
    )
    hanging = np.array(sorted(set(hanging)), dtype=np.int64).reshape(-1, 3)
    return QuadtreeMesh(mesh, hanging, float(unit), (float(x_lo), float(x_hi)), float(-y_lo))


def quadtree_half_space(segments, *, length, ratio=1.5):
    """Build the mesh of the block ``[-L, L] x [-L, 0]`` for ``segments`` ``[(x_lo, x_hi, size), ...]``
    on the surface (m).

    ``ratio`` > 1 bounds the growth of the requested size, ``(ratio - 1)`` per unit distance;
    the squares' sides themselves double across the faces where they change.
    """
    return _build(_Roots(float(length), 2, 1, -1, -1), segments, ratio)


def quadtree_strip(period, segments, *, depth, ratio=1.5):
    """One period ``[0, period] x [-depth * period, 0]`` of a periodic strip, refined for ``segments``
    ``[(x_lo, x_hi, size), ...]`` on its surface (taken periodically: a segment beyond either end acts
    at its image within the period) and cut alike along its left and right sides, which therefore carry
    the same vertices; ``depth`` is a whole number of periods.
    """
    depth = int(depth)
    if depth < 1:
        raise ValueError(f"depth must be a whole number of periods >= 1, got {depth!r}")
    period = float(period)
    images = [(lo + k * period, hi + k * period, s) for lo, hi, s in _segments(segments) for k in (-1, 0, 1)]
    return _build(_Roots(period, 1, depth, 0, -depth, periodic=True), images, ratio)


def constraint_matrix(basis, hanging):
    """``(T, constrained)``: ``u = T u`` sets the hanging DOFs of a Q2 vector ``basis`` from the
    others (``T`` is the identity on those), with ``constrained`` the hanging DOFs.

    On a face ``A``-``B`` of a large square with middle node ``C``, the two half faces ``A``-``M``
    and ``M``-``B`` of the small squares carry the large square's quadratic trace: ``u_M = u_C``,
    and their middle nodes, at a quarter and three quarters of the face, are
    ``(3/8, 3/4, -1/8)`` and ``(-1/8, 3/4, 3/8)`` of ``(u_A, u_C, u_B)``.
    """
    mesh = basis.mesh
    N = basis.N
    if len(hanging) == 0:
        return None, np.zeros(0, dtype=np.int64)
    nv = mesh.p.shape[1]
    f = np.sort(mesh.facets, axis=0)
    fkey = f[0].astype(np.int64) * nv + f[1]
    order = np.argsort(fkey)

    def facet(a, b):
        k = np.minimum(a, b).astype(np.int64) * nv + np.maximum(a, b)
        pos = np.searchsorted(fkey[order], k)
        if np.any(fkey[order][np.minimum(pos, fkey.size - 1)] != k):
            raise ValueError("a hanging face is not a facet of the mesh")
        return order[pos]

    M, A, B = hanging.T
    fab, fam, fmb = facet(A, B), facet(A, M), facet(M, B)
    rows, cols, vals = [], [], []
    for c in range(2):
        nod, fac = basis.nodal_dofs[c], basis.facet_dofs[c]
        uA, uB, uC = nod[A], nod[B], fac[fab]
        for dof, w in ((nod[M], (0.0, 1.0, 0.0)), (fac[fam], (0.375, 0.75, -0.125)), (fac[fmb], (-0.125, 0.75, 0.375))):
            for src, wk in zip((uA, uC, uB), w):
                if wk:
                    rows.append(dof)
                    cols.append(src)
                    vals.append(np.full(dof.size, wk))
    rows, cols, vals = np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)
    constrained = np.unique(rows)
    keep = np.setdiff1d(np.arange(N), constrained)
    C = sp.csr_matrix((vals, (rows, cols)), shape=(N, N)) + sp.csr_matrix(
        (np.ones(keep.size), (keep, keep)), shape=(N, N)
    )
    # a corner of a large square may itself hang on a larger one: substitute until no constrained DOF
    # refers to another
    T = C
    for _ in range(MAX_LEVEL):
        if not np.any(np.isin(T.tocoo().col, constrained)):
            return T.tocsr(), constrained
        T = (T @ C).tocsr()
    raise ValueError("hanging constraints do not resolve")
