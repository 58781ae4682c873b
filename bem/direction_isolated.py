"""Isolated contacts sliding along an oblique direction ``d = (cos theta, sin theta)`` (2-D).

The operator of :mod:`bem.isolated` with each creep term's shift along ``d``:

    K(r) = (1 - nu**2) [G(r) / E_inf + sum_k C_k I_k(r)],   I_k(r) = ∫_0^inf exp(-z) G(r + L_k z d) dz,

with ``L_k = v lambda_k`` and ``G`` Love's uniformly loaded square (:func:`bem.influence.square_elastic`)
evaluated at the shifted, off-grid points, and the slope along ``d`` of the creep part,
``S = (1 - nu**2) sum_k C_k (I_k - G) / L_k`` (integration by parts, as for x). Terms are folded
as in :mod:`bem.isolated` (``L < 1e-6 d``: relaxed; ``L > 1e6 length``: a constant, dropped).

Quadrature. ``I_k(r) = ∫_0^inf exp(-t/L)/L G(r + t d) dt`` along the ray from each element-centre
offset ``r``. ``G`` is smooth except on the element's edge lines ``x = ±w/2``, ``y = ±w/2``, where
it has ``u ln|u|`` kinks. Rays passing within two element widths of the element are split where
they cross those lines, with pieces growing geometrically (ratio 4) on both sides of each
crossing from ``w/2 / 4**6`` to the ray's end; every ray also gets such pieces about its
closest approach (scaled by that distance), pieces doubling from ``w/2`` to ``40 max L``, and
``L_k (1, 2, 4, 8, 16, 40)`` for the weights of terms with ``L_k < w/2``; 8-point
Gauss–Legendre on every piece (see :func:`_breakpoints`). All terms
share the nodes (only the weights differ). The accuracy is measured in the tests against the
exact-shift x-quadrature of :func:`bem.influence.square_creep_sum` run along ``+x`` and ``+y``.
"""

import numpy as np
import scipy.fft as sfft

from . import influence
from .angles import unit_vector
from .isolated import IsolatedHalfSpace

__all__ = ["DirectedIsolatedHalfSpace", "oblique_kernels"]

_FOLD = 1e-6
_CHUNK = 2**21  # node evaluations per block (bounded memory)


def _ladder(points, scale, top):
    """Breakpoints ``points ± scale * 4**j`` (``j`` from ``lowest`` up to the ray's end ``top``),
    rows of ``points`` (``(M, k)``) and ``scale`` (``(M, 1)`` or a number)."""
    j = np.arange(-6, int(np.ceil(np.log(top / np.min(scale)) / np.log(4))) + 1)
    steps = np.asarray(scale, dtype=float)[..., None] * 4.0**j
    out = (points[:, :, None] + np.concatenate([-steps, steps], axis=-1)).reshape(len(points), -1)
    return np.concatenate([points, out], axis=1)


def _breakpoints(x, y, c, s, h, shifts, near):
    """Per-offset sorted breakpoints along the rays from ``(x, y)`` (rows), 0 first.

    Every ray: 0, the ray's end ``top = 40 max(L, h)``, ``h 2**k`` and, for ``L < h``, ``L (1, 2,
    4, 8, 16, 40)`` (pieces as wide as the weight's scale), and a ladder of ratio 4 on both sides
    of the ray's closest approach to the element (scale: that distance), so that no piece is
    much wider than its distance to the element. Rays passing within ``near`` of the element's
    centre: ladders of ratio 4 from ``h / 4**6`` on both sides of their crossings of the edge
    lines ``x = ±h``, ``y = ±h`` (the kinks)."""
    top = 40.0 * max(shifts.max(), h)
    grow = h * 2.0 ** np.arange(int(np.ceil(np.log2(top / h))) + 1)
    small = shifts[shifts < h]
    fixed = np.concatenate([[0.0, top], grow[grow < top], (small[:, None] * [1, 2, 4, 8, 16, 40]).ravel()])
    closest = np.maximum(-(x * c + y * s), 0.0)
    dist = np.maximum(np.hypot(x + closest * c, y + closest * s), h)
    pts = [_ladder(closest[:, None], dist[:, None], top)]
    if near:
        cross = [(e - v) / u for e in (-h, h) for u, v in ((c, x), (s, y)) if abs(u) > 1e-14]
        pts.append(_ladder(np.stack(cross, axis=1), h, top))
    pts = np.concatenate(pts, axis=1)
    pts = np.where((pts > 0) & (pts < top), pts, 0.0)
    return np.sort(
        np.concatenate([np.broadcast_to(fixed[fixed <= top], (len(x), fixed[fixed <= top].size)), pts], axis=1), axis=1
    )


def _ray_integrals(x, y, c, s, width, shifts, weights, near, rule):
    """``sum_k weights[k] I_k`` and ``sum_k weights[k] (I_k - G) / L_k`` for the rows ``(x, y)``."""
    g = influence.square_elastic(x, y, width)
    total = np.zeros((2, x.size))
    probe = _breakpoints(x[:1], y[:1], c, s, width / 2, shifts, near).shape[1]
    gl_x, gl_w = rule
    rows = max(1, _CHUNK // (gl_x.size * probe))
    for a in range(0, x.size, rows):
        xb, yb = x[a : a + rows], y[a : a + rows]
        edges = _breakpoints(xb, yb, c, s, width / 2, shifts, near)
        lo, hi = edges[:, :-1, None], edges[:, 1:, None]
        t = 0.5 * (hi - lo) * (gl_x + 1) + lo  # (rows, pieces, nodes)
        dt = 0.5 * (hi - lo) * gl_w
        vals = influence.square_elastic(xb[:, None, None] + c * t, yb[:, None, None] + s * t, width) * dt
        for L, wk in zip(shifts, weights):
            i_k = np.sum(vals * np.exp(-t / L), axis=(1, 2)) / L
            total[0, a : a + rows] += wk * i_k
            total[1, a : a + rows] += wk * (i_k - g[a : a + rows]) / L
    return total


def oblique_kernels(n, width, direction, shifts, weights, *, nodes=8, near=2.0):
    """``sum_k weights[k] I_k`` and ``sum_k weights[k] (I_k - G) / L_k`` at element-centre offsets.

    Returns two arrays of shape ``(2n - 1, 2n - 1)`` (offsets ``-(n-1)..(n-1)`` per axis, axis 0
    is x), in m/Pa at ``E* = 1`` times the weights' unit. ``shifts`` are ``L_k`` (m). ``nodes``:
    Gauss–Legendre points per piece; ``near``: rays passing within this many element widths of
    the element get the pieces about its edge crossings (module docstring).
    """
    shifts = np.asarray(shifts, dtype=float)
    weights = np.asarray(weights, dtype=float)
    c, s = unit_vector(direction)
    off = width * np.arange(-(n - 1), n)
    gx, gy = np.meshgrid(off, off, indexing="ij")
    x, y = gx.ravel(), gy.ravel()
    closest = np.maximum(-(x * c + y * s), 0.0)
    close = np.hypot(x + closest * c, y + closest * s) < near * width
    rule = np.polynomial.legendre.leggauss(nodes)
    total = np.zeros((2, x.size))
    for mask, flag in ((close, True), (~close, False)):
        if np.any(mask):
            total[:, mask] = _ray_integrals(x[mask], y[mask], c, s, width, shifts, weights, flag, rule)
    shape = (2 * n - 1, 2 * n - 1)
    return total[0].reshape(shape), total[1].reshape(shape)


class DirectedIsolatedHalfSpace(IsolatedHalfSpace):
    """:class:`bem.isolated.IsolatedHalfSpace` for sliding along ``direction`` (radians), 2-D."""

    def __init__(self, shape, length, material, speed, direction):
        self.direction = float(direction)
        self.shape = tuple(int(v) for v in shape)
        self.length = float(length)
        self.material = material
        self.speed = float(speed)
        self.is_symmetric = bool(material.is_elastic or self.speed == 0.0)
        self.kernel, slope = self._kernels()
        self._pad = sfft.next_fast_len(2 * self.shape[0] - 1, real=True)
        self._khat = self._transform(self.kernel)
        self._shat = self._transform(slope)

    def _kernels(self):
        n = self.shape[0]
        d = self.length / n
        material, speed = self.material, self.speed
        elastic = material.is_elastic or speed == 0.0
        comp_el = 1.0 / (material.E0 if elastic else material.E_inf)
        terms = []
        for ck, lk in [] if elastic else zip(material.compliances, material.creep_times):
            if speed * lk < _FOLD * d:
                comp_el += ck
            elif speed * lk <= self.length / _FOLD:
                terms.append((ck, lk))
        off = d * np.arange(-(n - 1), n)
        kernel = comp_el * influence.square_elastic(off[:, None], off[None, :], d)
        slope = np.zeros_like(kernel)
        if terms:
            ck, lk = np.array(terms).T
            creep, slope = oblique_kernels(n, d, self.direction, speed * lk, ck)
            kernel = kernel + creep
        f = material.plane_strain_factor
        return kernel * f, slope * f

    def symmetric_part(self):
        """Operator with kernel ``(K(r) + K(-r)) / 2``: the symmetric part of this operator."""
        twin = super().symmetric_part()
        twin.kernel = 0.5 * (self.kernel + self.kernel[::-1, ::-1])
        twin._khat = twin._transform(twin.kernel)
        return twin
