"""Meshes of the adaptive BEM: elements as aligned blocks of fine cells, refinement rules,
and the indenter's heights sampled at the element centres.

Geometry (docs/theory.md §4, :mod:`bem.surfaces`). The fine grid is the surface's grid: ``n`` cells of
side ``dx = length / n`` per side on a domain ``[-length/2, length/2]`` centred on the
indenter (cell ``j`` centred at ``(j + 1/2) dx - length/2``). Elements are aligned blocks of
``s = 2**m`` fine cells. Heights are taken at element centres: the callable ``height`` is
evaluated there exactly; otherwise a block of one cell takes that cell's height and a larger
block the mean of its 2 (or 2 x 2) central cells, i.e. the linear interpolation at its centre.
Pressure outside the domain is zero.
"""

from dataclasses import dataclass

import numpy as np

__all__ = ["AdaptiveMesh", "uniform_mesh", "marked_elements", "refine", "owner", "element_values"]


@dataclass(frozen=True, eq=False)
class AdaptiveMesh:
    """Elements as aligned blocks of fine cells.

    Attributes
    ----------
    start : ndarray of int, shape (N_e, ndim)
        Index of each element's first fine cell along each axis.
    size : ndarray of int, shape (N_e,)
        Side of each element in fine cells (a power of 2).
    n : int
        Fine cells per side.
    length : float
        Domain side (m); the domain is ``[-length/2, length/2]**ndim``.
    """

    start: np.ndarray
    size: np.ndarray
    n: int
    length: float

    @property
    def ndim(self):
        return self.start.shape[1]

    @property
    def spacing(self):
        return self.length / self.n

    def __len__(self):
        return self.size.size

    def centres(self):
        """Element centres (m), shape (N_e, ndim)."""
        return (self.start + 0.5 * self.size[:, None]) * self.spacing - 0.5 * self.length

    def areas(self):
        """Element areas (m²), or lengths (m) for strips."""
        return (self.size * self.spacing) ** self.ndim

    def labels(self):
        """Fine-grid array (shape ``(n,) * ndim``) holding each cell's element index."""
        out = np.empty((self.n,) * self.ndim, dtype=np.intp)
        for e, (st, s) in enumerate(zip(self.start, self.size)):
            out[tuple(slice(a, a + s) for a in st)] = e
        return out

    def to_fine(self, values):
        """Per-element ``values`` spread over the fine grid (piecewise constant)."""
        return np.asarray(values)[self.labels()]


def uniform_mesh(n, length, ndim, size):
    """Uniform mesh of blocks of ``size`` fine cells (``size`` divides ``n``)."""
    k = np.arange(0, n, size)
    grids = np.meshgrid(*([k] * ndim), indexing="ij")
    start = np.stack([g.ravel() for g in grids], axis=1)
    return AdaptiveMesh(start, np.full(len(start), size), n, float(length))


def _box_gap(mesh, rows, cols):
    """Chebyshev gap (in fine cells) between the boxes of elements ``rows`` and ``cols``."""
    lo, s = mesh.start, mesh.size
    gap = np.zeros((rows.size, cols.size))
    for d in range(mesh.ndim):
        a0, a1 = lo[rows, d][:, None], (lo[rows, d] + s[rows])[:, None]
        b0, b1 = lo[cols, d][None, :], (lo[cols, d] + s[cols])[None, :]
        gap = np.maximum(gap, np.maximum(b0 - a1, a0 - b1))
    return gap


def marked_elements(mesh, pressure, *, buffer=1.0, gradient=0.05, refine_contact=True):
    """Elements to split: in contact (``refine_contact``), within ``buffer`` of their own
    size from the contact edge, or across a pressure jump larger than ``gradient * max(p)``
    to a touching element. Only elements larger than one fine cell are returned."""
    contact = pressure > 0
    big = mesh.size > 1
    mark = contact & big if refine_contact else np.zeros_like(big)
    if not contact.any():
        return mark
    c = np.flatnonzero(contact)
    outside = np.flatnonzero(~contact)
    # elements in contact on the edge: touching a non-contact element
    edge = np.zeros_like(contact)
    if outside.size:
        touch = _box_gap(mesh, c, outside) <= 0
        edge[c[touch.any(axis=1)]] = True
    e = np.flatnonzero(edge) if edge.any() else c
    near = _box_gap(mesh, np.arange(len(mesh)), e).min(axis=1) <= buffer * mesh.size
    mark |= near & big
    # steep pressure jumps between touching elements
    pmax = pressure.max()
    idx = np.flatnonzero(contact)
    touch = _box_gap(mesh, idx, np.arange(len(mesh))) <= 0
    jump = np.abs(pressure[idx][:, None] - pressure[None, :]) > gradient * pmax
    steep = touch & jump
    mark[idx[steep.any(axis=1)]] |= big[idx[steep.any(axis=1)]]
    mark |= steep.any(axis=0) & big
    return mark


def refine(mesh, mark):
    """Split the ``mark``-ed elements into 2**ndim children of half their size."""
    keep = ~mark
    starts, sizes = [mesh.start[keep]], [mesh.size[keep]]
    half = mesh.size[mark] // 2
    for corner in np.ndindex(*([2] * mesh.ndim)):
        starts.append(mesh.start[mark] + np.asarray(corner)[None, :] * half[:, None])
        sizes.append(half)
    start, size = np.concatenate(starts), np.concatenate(sizes)
    order = np.lexsort(start.T[::-1])
    return AdaptiveMesh(start[order], size[order], mesh.n, mesh.length)


def owner(coarse, fine):
    """Index of the ``coarse`` element that contains each ``fine`` element."""
    return coarse.labels()[tuple(fine.start.T)]


def _block_mean(field, start, size):
    """Mean of ``field`` (fine grid) over the blocks ``start`` (N, ndim), side ``size``."""
    csum = field.cumsum(0)
    if field.ndim == 2:
        csum = csum.cumsum(1)
    P = np.pad(csum, [(1, 0)] * field.ndim)
    if field.ndim == 1:
        a = start[:, 0]
        return (P[a + size] - P[a]) / size
    a, b = start[:, 0], start[:, 1]
    return (P[a + size, b + size] - P[a, b + size] - P[a + size, b] + P[a, b]) / size.astype(float) ** 2


def element_values(mesh, field, sampling):
    """Per-element values of a fine-grid ``field``: ``"centre"`` (the cell itself, or the mean
    of the 2 or 2 x 2 central cells, i.e. the linear interpolation at the centre) or
    ``"mean"`` (the block average)."""
    if sampling == "mean":
        return _block_mean(field, mesh.start, mesh.size)
    s = mesh.size
    two = np.where(s > 1, 2, 1)
    return _block_mean(field, mesh.start + (s // 2 - (s > 1))[:, None], two)
