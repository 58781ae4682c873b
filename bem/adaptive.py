"""Adaptive non-uniform mesh BEM for isolated contacts (the seed's method).

Putignano, Afferrante, Carbone & Demelio, IJSS 49 (2012) 338-343,
doi:10.1016/j.ijsolstr.2011.10.009, and IJSS 49 (2012) 2300 (viscoelastic sliding). The
half-space is loaded by piecewise-constant pressure on elements of several sizes: squares
(2-D surfaces, 3-D half-space) or strips (1-D profiles, plane strain). The solve starts on a
coarse uniform mesh; elements in contact, near the contact edge (``buffer``) or across a
steep pressure jump (``gradient``) are split in 2 (strips) or 4 (squares), and the problem is
solved again, ``levels`` times, until the refined elements are the cells of the fine grid.

Geometry (SPEC §2.3, :mod:`bem.surfaces`). The fine grid is the surface's grid: ``n`` cells of
side ``dx = length / n`` per side on a domain ``[-length/2, length/2]`` centred on the
indenter (cell ``j`` centred at ``(j + 1/2) dx - length/2``). Elements are aligned blocks of
``s = 2**m`` fine cells. Heights are taken at element centres: the callable ``height`` is
evaluated there exactly; otherwise a block of one cell takes that cell's height and a larger
block the mean of its 2 (or 2 x 2) central cells, i.e. the linear interpolation at its centre.
Pressure outside the domain is zero.

Response (SPEC §2.2), indenter moving in ``+x``, displacement positive into the solid::

    u(x) = (1/E_inf) (G * p)(x) + sum_k C_k integral_0^inf exp(-z) (G * p)(x + v lambda_k z) dz.

Influence coefficients (collocation at element centres, per unit pressure, m/Pa):

- 2-D, ``G = (1 - nu**2) / (pi r)``. Elastic part: Love's closed form (1929) for a uniformly
  loaded rectangle, the corner sum of ``F(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|)`` (the
  signed form, SPEC §7). Creep part of term ``k`` (shift ``L = v lambda_k``): the integral is
  computed for one fine cell on all half-cell offsets, exactly at the shifted points (no
  interpolation, SPEC §7) by composite Gauss-Legendre quadrature, as the backward recursion
  ``k(X) = int_0^dX exp(-r/L) g(X + r) dr/L + exp(-dX/L) k(X + dX)`` (``dX = dx/2``, ``g`` the
  cell's elastic influence) started from a graded tail quadrature; an element's coefficient
  is the sum over its cells (superposition, exact), taken from summed-area tables.
- 1-D, ``G = (2 (1 - nu**2) / pi) ln(l_ref / |x|)`` with ``l_ref`` the domain length (the
  displacement of a line load is defined up to a constant times the load; ``l_ref`` fixes
  it, so the approach of a profile is relative to it; creep term ``k`` uses
  ``l_ref + v lambda_k`` so that its kernel stays positive when ``v lambda_k >> l_ref``).
  Closed forms: with
  ``G0(a) = a ln(|a|/l_ref) - a`` the strip ``[x1, x2]`` gives ``-(G0(x2 - x) - G0(x1 - x))``;
  the creep term replaces ``G0(a)`` by ``G0(a) + L D(a/L)``,
  ``D(t) = exp(-t) Ei(t) - ln|t| - gamma`` (an ``a``-independent constant dropped), evaluated
  by its power series for ``|t| <= 1`` so that large ``L`` does not cancel (SPEC §7).

Contact: :func:`bem.contact.solve_contact` (semismooth Newton, GMRES inner solves) on the dense
system written for the element *forces* ``f_i = A_i p_i`` (N; N/m for profiles), so that its
load constraint ``mean(f) = load / N_e`` is exactly the total force. Its complementarity
residual is therefore stated in forces: ``max |min(f_i / f_mean, g_i / h_ref)|``.

Cost and when to use it: the dense system makes assembly and products ``O(N_e**2)``; with
elements refined wherever there is contact, ``N_e`` is at least the number of fine cells in
contact. ``benchmarks/isolated.py`` (results in ``benchmarks/results/``) finds the uniform
DC-FFT grid (:mod:`bem.isolated`) faster at equal error on cylinders and spheres, and about
as fast only when the contact covers ~1% of a wide domain; ``method="auto"`` therefore picks
the uniform grid. The adaptive solver remains an independent check of it (same collocation
inside the contact, independent kernels) and the seed's method.

Friction: ``friction`` is the dissipation form ``-(1/F) sum_i f_i u'(x_i)`` with the slope of
the displacement at the element centres (closed form; the creep slope is
``(k - g) / L``), ``friction_eq6 = -(1/F) sum_i f_i h'(x_i)`` with the indenter's slope there.
Both converge to ``F_x / F_N`` with refinement. Output fields are mapped back to the fine
grid piecewise constant per element (``gap >= 0`` and ``p gap = 0`` hold exactly there).
"""
import logging
import time
from dataclasses import dataclass

import numpy as np
from scipy import special

from .checks import check_int, check_positive
from .contact import solve_contact
from .errors import ConvergenceError, InputError
from .material import Material

__all__ = ["AdaptiveMesh", "solve_adaptive", "adaptive_mesh", "influence_matrix"]

log = logging.getLogger(__name__)

_GL8 = np.polynomial.legendre.leggauss(8)
_CUT = 45.0  # exp(-45) ~ 3e-20: the creep weight is dropped beyond z = 45


# ------------------------------------------------------------------------------ mesh
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


# ------------------------------------------------------------------------------ 2-D kernels
def _love_corner(X, Y):
    """``X asinh(Y/|X|) + Y asinh(X/|Y|)`` (0 where a factor vanishes): the antiderivative of
    ``1/r`` over the rectangle from the origin to ``(X, Y)``, valid in every quadrant."""
    ax, ay = np.abs(X), np.abs(Y)
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = np.where(ax > 0, X * np.arcsinh(Y / np.where(ax > 0, ax, 1.0)), 0.0)
        t2 = np.where(ay > 0, Y * np.arcsinh(X / np.where(ay > 0, ay, 1.0)), 0.0)
    return t1 + t2


def _love_slope_corner(X, Y):
    """``d/dX`` of :func:`_love_corner`: ``asinh(Y/|X|)`` (X = 0 only occurs in pairs that
    cancel, see :func:`_rect`)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(X != 0, np.arcsinh(Y / np.where(X != 0, np.abs(X), 1.0)), 0.0)


def _rect(x, y, x1, x2, y1, y2, corner):
    """Corner sum of ``corner`` for the rectangle ``[x1,x2] x [y1,y2]`` seen from ``(x, y)``."""
    return (corner(x2 - x, y2 - y) - corner(x1 - x, y2 - y)
            - corner(x2 - x, y1 - y) + corner(x1 - x, y1 - y))


def _cell_influence(X, Y, h):
    """``int int 1/r`` (m) over the cell ``[-h/2, h/2]**2`` seen from ``(X, Y)``."""
    return _rect(X, Y, -h / 2, h / 2, -h / 2, h / 2, _love_corner)


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
        phi = _love_corner(Xj[:, None, None] + r[None, :, None], Yx[None, None, :])
        g = phi[:-2, :, :-2] - phi[2:, :, :-2] - phi[:-2, :, 2:] + phi[2:, :, 2:]
        parts[i0:i1] = np.einsum("k,ikb->ib", w, g)
    for i in range(X.size - 1):
        if abs(abs(X[i]) - dX) < 1e-9 * h or abs(abs(X[i + 1]) - dX) < 1e-9 * h:
            parts[i, near] = np.sum(ws[:, None] * _cell_influence(X[i] + rs[:, None], Y[None, near], h),
                                    axis=0)
    for i in range(X.size - 2, -1, -1):
        table[i] = parts[i] + decay * table[i + 1]
    return table


_TABLES = {}


def _cached(key, build):
    """Small cache of lattice tables, reused across refinement levels and calls."""
    if key not in _TABLES:
        if len(_TABLES) >= 8:
            _TABLES.pop(next(iter(_TABLES)))
        _TABLES[key] = build()
    return _TABLES[key]


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
    return (np.take(flat, ix2 + iy2) - np.take(flat, ix1 + iy2)
            - np.take(flat, ix2 + iy1) + np.take(flat, ix1 + iy1))


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
        out[sel] = (np.take(flat, a1 + b1) - np.take(flat, a0 + b1)
                    - np.take(flat, a1 + b0) + np.take(flat, a0 + b0))
    return out


def _matrices_2d(mesh, material, speed, with_slope=True, chunk=512):
    """Influence and x-slope matrices (m/Pa and 1/Pa; slope None unless ``with_slope``) of a
    square-element mesh."""
    n, h = mesh.n, mesh.spacing
    lattice = 0.5 * h * np.arange(-2 * n, 2 * n + 1)
    love = _cached(("love", n, h), lambda: _love_corner(lattice[:, None], lattice[None, :]))
    love_dx = _cached(("love_dx", n, h), lambda: _love_slope_corner(lattice[:, None], lattice[None, :]))
    factor = material.plane_strain_factor / np.pi
    shifts = speed * material.creep_times
    tables = {k: _cached(("creep", n, h, L), lambda L=L: cell_creep_table(n, h, L))
              for k, L in enumerate(shifts) if L >= 1e-4 * h}
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


# ------------------------------------------------------------------------------ 1-D kernels
def _exp_ei(t):
    """``exp(-t) Ei(t)`` for real ``t != 0`` (asymptotic series beyond ``|t| = 40``)."""
    t = np.asarray(t, dtype=float)
    out = np.empty_like(t)
    mid = np.abs(t) <= 40
    out[mid] = np.exp(-t[mid]) * special.expi(t[mid])
    tb = t[~mid]
    acc, term = np.zeros_like(tb), 1.0 / tb
    for k in range(40):  # sum_k k! / t**(k+1): terms shrink while k < |t|; 40 terms at |t| > 40
        acc += term
        term = term * (k + 1) / tb
    out[~mid] = acc
    return out


def _d_creep(t):
    """``D(t) = exp(-t) Ei(t) - ln|t| - gamma`` (``D(0) = 0``), accurate to round-off
    relative to itself near 0 (series ``gamma expm1(-t) + exp(-t) S(t) + expm1(-t) ln|t|``,
    ``S(t) = sum_k t**k / (k k!)``)."""
    t = np.asarray(t, dtype=float)
    out = np.zeros_like(t)
    small = (np.abs(t) <= 1) & (t != 0)
    ts = t[small]
    s, term = np.zeros_like(ts), np.ones_like(ts)
    for k in range(1, 25):  # |t| <= 1: 24 terms reach 1e-26 (in place: no (N, 24) temporaries)
        term *= ts / k
        s += term / k
    em = np.expm1(-ts)
    out[small] = np.euler_gamma * em + np.exp(-ts) * s + em * np.log(np.abs(ts))
    big = np.abs(t) > 1
    out[big] = _exp_ei(t[big]) - np.log(np.abs(t[big])) - np.euler_gamma
    return out


def _g0(a, ell):
    """``a ln(|a|/ell) - a`` (0 at ``a = 0``)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(a != 0, a * np.log(np.abs(a) / ell), 0.0) - a


def _matrices_1d(mesh, material, speed, chunk=512):
    """Influence and x-slope matrices (m/Pa, 1/Pa) of a strip mesh (plane strain), built in
    blocks of ``chunk`` rows (bounded temporaries)."""
    c = mesh.centres()[:, 0]
    half = 0.5 * mesh.size * mesh.spacing
    ell = mesh.length
    ne = c.size
    K, S = np.empty((ne, ne)), np.empty((ne, ne))
    factor = 2.0 * material.plane_strain_factor / np.pi
    for r0 in range(0, ne, chunk):
        rows = slice(r0, min(ne, r0 + chunk))
        a2 = (c + half)[None, :] - c[rows, None]  # far edge minus collocation point
        a1 = (c - half)[None, :] - c[rows, None]
        elastic = -(_g0(a2, ell) - _g0(a1, ell))
        with np.errstate(divide="ignore"):
            slope = np.log(np.abs(a2)) - np.log(np.abs(a1))
        Kr = elastic / material.E_inf
        Sr = slope / material.E_inf
        for Ck, lam in zip(material.compliances, material.creep_times):
            L = speed * lam
            if L == 0:
                Kr += Ck * elastic
                Sr += Ck * slope
                continue
            dd = _d_creep(a2 / L) - _d_creep(a1 / L)
            # reference length l_ref + L for this term (adds width * ln(1 + L/l_ref), a constant
            # times the load): keeps the kernel ~ ln((l_ref + L)/L) + gamma > 0 when L >> l_ref
            Kr += Ck * (elastic - L * dd + (a2 - a1) * np.log1p(L / ell))
            Sr -= Ck * dd  # exact: G0'(a) + D'(a/L) = ln(L/l_ref) - gamma - D(a/L)
        K[rows], S[rows] = factor * Kr, factor * Sr
    return K, S


def influence_matrix(mesh, material, speed, with_slope=True):
    """Dense influence matrix ``K`` (m/Pa) and slope matrix ``S`` (1/Pa) of ``mesh``:
    ``u_i = sum_j K_ij p_j`` and ``du/dx (x_i) = sum_j S_ij p_j`` at the element centres
    (see the module docstring), for the material sliding at ``speed`` (m/s). ``S`` is
    ``None`` unless ``with_slope`` (2-D; it is cheap in 1-D and always returned)."""
    if mesh.ndim == 1:
        return _matrices_1d(mesh, material, speed)
    return _matrices_2d(mesh, material, speed, with_slope)


# ------------------------------------------------------------------------------ contact
class _ForceOperator:
    """Dense response to element forces (m/N): ``u = K (f / area)``, for :mod:`bem.contact`."""

    def __init__(self, K, areas, phase_symbol):
        self.matrix = K / areas[None, :]
        self.shape = (K.shape[0],)
        self.symbol = phase_symbol
        self.is_symmetric = False

    def displacement(self, f):
        return self.matrix @ f

    def self_influence(self):
        return float(np.mean(np.diag(self.matrix)))

    def symmetric_part(self):
        twin = object.__new__(_ForceOperator)
        twin.__dict__.update(self.__dict__)
        twin.matrix = 0.5 * (self.matrix + self.matrix.T)
        twin.symbol = np.real(self.symbol)
        twin.is_symmetric = True
        return twin

    def initial_pressure(self, ht, *, mean_pressure, approach=None):
        """First iterate for :mod:`bem.contact` (load control): Winkler forces."""
        return _winkler_start(ht, 1.0 / np.diag(self.matrix), mean_pressure * self.shape[0])

    def pressure_from_displacement(self, u):
        """Zero-sum forces whose displacement is ``u`` up to a constant (full contact)."""
        n = self.shape[0]
        a = np.zeros((n + 1, n + 1))
        a[:n, :n], a[:n, n], a[n, :n] = self.matrix, -1.0, 1.0
        return np.linalg.solve(a, np.concatenate([u, [0.0]]))[:n]


def _phase_symbol(material, speed, mesh):
    """``J(-q v)`` sampled over the mesh's wavenumbers: its phase tells the contact solver how
    far from symmetric the operator is (as the periodic symbol does)."""
    if material.is_elastic or speed == 0:
        return np.zeros(1)
    q = np.geomspace(np.pi / mesh.length, np.pi / mesh.spacing, 64)
    return material.complex_compliance(np.concatenate([-q, q]) * speed)


def _winkler_start(heights, stiffness, load):
    """Initial forces of a Winkler foundation (each element a spring of ``stiffness``, N/m)
    pressed to carry ``load``: ``f = k max(h - max h + d, 0)`` with ``d`` by bisection."""
    ht = heights - heights.max()

    def total(d):
        return float(np.sum(stiffness * np.maximum(ht + d, 0.0)))

    stiffness = np.abs(stiffness)
    lo, hi = 0.0, max(float(np.ptp(ht)), 1e-300)
    for _ in range(2000):
        if total(hi) >= load:
            break
        hi *= 2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if total(mid) < load else (lo, mid)
    return stiffness * np.maximum(ht + hi, 0.0)


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


def _element_values(mesh, field, sampling):
    """Per-element values of a fine-grid ``field``: ``"centre"`` (the cell itself, or the mean
    of the 2 or 2 x 2 central cells, i.e. the linear interpolation at the centre) or
    ``"mean"`` (the block average)."""
    if sampling == "mean":
        return _block_mean(field, mesh.start, mesh.size)
    s = mesh.size
    two = np.where(s > 1, 2, 1)
    return _block_mean(field, mesh.start + (s // 2 - (s > 1))[:, None], two)


def _indenter(surface, height, sampling):
    """Functions ``mesh -> (heights, x-slopes)`` at the element centres."""
    dx = surface.spacing
    if height is not None:
        def values(c):
            return np.broadcast_to(np.asarray(height(*c.T), dtype=float), (len(c),))

        def at(mesh):
            c = mesh.centres()
            e = np.zeros(c.shape[1])
            e[0] = 0.25 * dx  # central difference: exact for quadratic indenters
            return values(c), (values(c + e) - values(c - e)) / (0.5 * dx)
        return at
    h = np.asarray(surface.heights, dtype=float)
    dh = np.gradient(h, dx, axis=0)  # second order inside; the contact must stay off the border
    return lambda mesh: (_element_values(mesh, h, sampling), _element_values(mesh, dh, sampling))


def _solve_level(mesh, material, speed, load, heights, initial, rtol, maxiter, with_slope):
    """One contact solve on ``mesh``; returns (solution in forces, K, S)."""
    K, S = influence_matrix(mesh, material, speed, with_slope)
    areas = mesh.areas()
    op = _ForceOperator(K, areas, _phase_symbol(material, speed, mesh))
    # initial None on the coarsest level: the contact solver starts strongly non-symmetric
    # problems from its symmetric part's contact, others from op.initial_pressure
    sol = solve_contact(op, heights, mean_pressure=load / len(mesh), rtol=rtol, maxiter=maxiter,
                        initial=initial, raise_on_failure=False)
    return sol, K, S


def _check(surface, material, speed, load, rtol, levels, buffer, gradient, sampling, height):
    from .surfaces import Surface

    if not isinstance(surface, Surface):
        raise InputError(f"surface must be a bem.surfaces.Surface, got {type(surface).__name__}")
    if not isinstance(material, Material):
        raise InputError(f"material must be a bem.Material, got {type(material).__name__}")
    speed = check_positive("speed", speed, allow_zero=True)
    load = check_positive("load", load)
    rtol = check_positive("rtol", rtol)
    if rtol >= 1:
        raise InputError(f"rtol must be in (0, 1), got {rtol!r}")
    levels = check_int("levels", levels, 0, 12)
    if surface.n % 2**levels:
        raise InputError(f"levels must leave whole coarse elements: surface.n = {surface.n} must be divisible "
                         f"by 2**levels = {2**levels}; got levels = {levels}")
    buffer = check_positive("buffer", buffer, allow_zero=True)
    gradient = check_positive("gradient", gradient)
    if sampling not in ("centre", "mean"):
        raise InputError(f"sampling must be 'centre' or 'mean', got {sampling!r}")
    if height is not None and not callable(height):
        raise InputError(f"height must be a callable h(x[, y]) (m), got {type(height).__name__}")
    return speed, load, rtol, levels, buffer, gradient


def _run(surface, material, speed, load, rtol, levels, buffer, gradient, refine_contact, sampling,
         height, maxiter, max_elements):
    """The refinement loop; returns ``(meshes, last solution, K, S, heights, slopes, totals)``."""
    speed, load, rtol, levels, buffer, gradient = _check(surface, material, speed, load, rtol, levels,
                                                         buffer, gradient, sampling, height)
    indenter = _indenter(surface, height, sampling)
    mesh = uniform_mesh(surface.n, surface.length, surface.ndim, 2**levels)
    meshes, initial, iterations, matvecs = [], None, 0, 0
    for level in range(levels + 1):
        if len(mesh) > max_elements:
            raise InputError(f"max_elements: level {level} needs {len(mesh)} elements > max_elements = "
                             f"{max_elements}; use fewer levels, a coarser surface or a larger limit")
        hts, slopes = indenter(mesh)
        sol, K, S = _solve_level(mesh, material, speed, load, hts, initial, rtol, maxiter,
                                 with_slope=level == levels)
        iterations, matvecs = iterations + sol.iterations, matvecs + sol.matvecs
        meshes.append(mesh)
        log.info("adaptive level %d: %d elements, %s", level, len(mesh), sol.message)
        if level == levels or not sol.success:
            break
        p = sol.pressure / mesh.areas()
        mark = marked_elements(mesh, p, buffer=buffer, gradient=gradient, refine_contact=refine_contact)
        fine = refine(mesh, mark)
        # warm start: the parent's pressure on its children
        owner = _owner(mesh, fine)
        initial = p[owner] * fine.areas()
        mesh = fine
    return meshes, sol, K, S, hts, slopes, iterations, matvecs


def _owner(coarse, fine):
    """Index of the ``coarse`` element that contains each ``fine`` element."""
    return coarse.labels()[tuple(fine.start.T)]


def adaptive_mesh(surface, material, *, speed, load, rtol=1e-8, levels=3, buffer=1.0, gradient=0.05,
                  refine_contact=True, sampling="centre", height=None, maxiter=400, max_elements=20000):
    """The sequence of meshes :func:`solve_adaptive` builds (coarsest first), same arguments.

    It repeats the solves (the refinement depends on each level's pressure), so it costs as
    much as :func:`solve_adaptive`.

    Returns
    -------
    list of AdaptiveMesh
    """
    return _run(surface, material, speed, load, rtol, levels, buffer, gradient, refine_contact, sampling,
                height, maxiter, max_elements)[0]


def solve_adaptive(surface, material, *, speed, load, rtol=1e-8, levels=3, buffer=1.0, gradient=0.05,
                   refine_contact=True, sampling="centre", height=None, maxiter=400, max_elements=20000,
                   raise_on_failure=True):
    """Steady sliding of an isolated indenter on the adaptive non-uniform mesh.

    Parameters
    ----------
    surface : bem.surfaces.Surface
        Indenter on the fine grid (the finest level): 1-D profile (plane strain, strips) or
        square 2-D map (squares), heights (m) positive toward the half-space, coordinates
        centred on the domain (``surface.centered``; see the module docstring).
    material : bem.Material
    speed : float
        Sliding speed (m/s) in ``+x``, >= 0.
    load : float
        Normal force (N), or per unit length (N/m) for a profile, > 0.
    rtol : float
        Complementarity residual in forces (module docstring), in (0, 1).
    levels : int
        Refinement levels, 0..12: the coarse mesh has blocks of ``2**levels`` fine cells
        (``surface.n`` must be divisible by it); ``0`` is the dense uniform fine mesh.
    buffer : float
        Elements within ``buffer`` times their own size of the contact edge are refined (>= 0).
    gradient : float
        Elements across a pressure jump larger than ``gradient * max(p)`` are refined (> 0).
    refine_contact : bool
        Refine every element in contact (the seed's rule, default) or only those flagged by
        ``buffer`` and ``gradient``.
    sampling : {"centre", "mean"}
        Element heights from the fine grid (module docstring); ignored with ``height``.
    height : callable, optional
        ``height(x)`` or ``height(x, y)`` (m, arrays of centre coordinates in m): exact heights
        at the element centres instead of sampling ``surface.heights``.
    maxiter : int
        Active-set iterations per level.
    max_elements : int
        Refuse meshes with more elements (the dense matrix has ``N_e**2`` entries).
    raise_on_failure : bool
        Raise :class:`bem.errors.ConvergenceError` if a level does not converge.

    Returns
    -------
    bem.sliding.SlidingResult
        Fields on the fine grid (piecewise constant per element; ``displacement`` absolute,
        see the module docstring for profiles); ``iterations`` and ``matvecs`` summed over
        the levels; ``residual`` and ``message`` those of the finest level. The mesh is
        returned by :func:`adaptive_mesh`.
    """
    from .sliding import SlidingResult

    t0 = time.perf_counter()
    maxiter = check_int("maxiter", maxiter, 1)
    max_elements = check_int("max_elements", max_elements, 1)
    meshes, sol, K, S, hts, slopes, iterations, matvecs = _run(
        surface, material, speed, load, rtol, levels, buffer, gradient, refine_contact, sampling, height,
        maxiter, max_elements)
    mesh = meshes[-1]
    f = sol.pressure
    areas = mesh.areas()
    p = f / areas
    total = float(f.sum())
    if S is None:  # a coarser level failed: its slope matrix was not built
        S = influence_matrix(mesh, material, speed)[1]
    slope_u = S @ p
    friction = float(-np.dot(f, slope_u) / total)
    friction_eq6 = float(-np.dot(f, slopes) / total)
    speed = float(speed)
    message = f"{len(meshes) - 1} refinement levels, {len(mesh)} elements; {sol.message}"
    result = SlidingResult(
        pressure=mesh.to_fine(p), displacement=mesh.to_fine(sol.displacement), gap=mesh.to_fine(sol.gap),
        approach=float(sol.approach), contact_fraction=float(np.sum(areas[p > 0]) / mesh.length**mesh.ndim),
        friction=friction, friction_eq6=friction_eq6, dissipated_power=friction * total * speed,
        load=total, speed=speed, iterations=iterations, matvecs=matvecs, residual=sol.residual,
        success=sol.success, message=message, wall_time=time.perf_counter() - t0)
    if not sol.success and raise_on_failure:
        raise ConvergenceError(f"speed {speed!r} m/s: {message}", result)
    return result
