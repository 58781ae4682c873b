"""Isolated contacts sliding along an oblique direction ``d = (cos theta, sin theta)`` (2-D).

The operator of :mod:`bem.isolated` with each creep term's shift along ``d``:

    K(r) = (1 - nu**2) [G(r) / E_inf + sum_k C_k I_k(r)],   I_k(r) = ∫_0^inf exp(-z) G(r + L_k z d) dz,

with ``L_k = v lambda_k`` and ``G`` Love's uniformly loaded square (:func:`bem.influence.square_elastic`)
evaluated at the shifted, off-grid points, and the slope along ``d`` of the creep part,
``S = (1 - nu**2) sum_k C_k (I_k - G) / L_k`` (integration by parts, as for x). Terms are folded
as in :mod:`bem.isolated` (``L < 1e-6 d``: relaxed; ``L > 1e6 length``: a constant, dropped).

Quadrature. ``I_k(r) = ∫_0^inf exp(-t/L)/L G(r + t d) dt`` along the ray from each element-centre
offset ``r``. ``G`` is smooth except on the element's edge lines ``x = ±w/2``, ``y = ±w/2``, where
it has ``u ln|u|`` kinks; the ray is split where it crosses them, with pieces growing
geometrically (ratio 4) on both sides of each crossing from ``w/2 / 4**6`` to the ray's end,
at ``L_k (1, 2, 4, 8, 16, 40)`` for the weights, and in pieces doubling from ``w/2`` to
``40 max L``; 8-point Gauss–Legendre on every piece. All terms
share the nodes (only the weights differ). The accuracy is measured in the tests against the
exact-shift x-quadrature of :func:`bem.influence.square_creep_sum` run along ``+x`` and ``+y``.
"""
import numpy as np
import scipy.fft as sfft

from . import influence
from .isolated import IsolatedHalfSpace

__all__ = ["DirectedIsolatedHalfSpace", "oblique_kernels"]

_FOLD = 1e-6
_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)
_GRADE = 0.25 ** np.arange(1, 7)  # pieces toward a kink: w/2 times these
_CHUNK = 2**21  # node evaluations per block (bounded memory)


def _breakpoints(x, y, c, s, h, shifts):
    """Per-offset sorted breakpoints along the ray (rows: offsets), 0 first."""
    cross = []
    for edge in (-h, h):
        if abs(c) > 1e-14:
            cross.append((edge - x) / c)
        if abs(s) > 1e-14:
            cross.append((edge - y) / s)
    cross = np.stack(cross, axis=1)  # (M, up to 4)
    top = 40.0 * max(shifts.max(), h)
    # geometric in ratio 4 on both sides of each kink, from h / 4**6 up to the ray's end
    steps = h * np.concatenate([_GRADE, 4.0 ** np.arange(int(np.ceil(np.log(top / h) / np.log(4))) + 1)])
    graded = (cross[:, :, None] + np.concatenate([-steps, steps])[None, None, :]).reshape(len(x), -1)
    pts = np.concatenate([cross, graded], axis=1)
    grow = h * 2.0 ** np.arange(int(np.ceil(np.log2(top / h))) + 1)
    fixed = np.unique(np.concatenate([[0.0, top], grow[grow < top], (shifts[:, None] * [1, 2, 4, 8, 16, 40]).ravel()]))
    fixed = fixed[fixed <= top]
    pts = np.where((pts > 0) & (pts < top), pts, 0.0)
    return np.sort(np.concatenate([np.broadcast_to(fixed, (len(x), fixed.size)), pts], axis=1), axis=1)


def oblique_kernels(n, width, direction, shifts, weights):
    """``sum_k weights[k] I_k`` and ``sum_k weights[k] (I_k - G) / L_k`` at element-centre offsets.

    Returns two arrays of shape ``(2n - 1, 2n - 1)`` (offsets ``-(n-1)..(n-1)`` per axis, axis 0
    is x), in m/Pa at ``E* = 1`` times the weights' unit. ``shifts`` are ``L_k`` (m).
    """
    shifts = np.asarray(shifts, dtype=float)
    weights = np.asarray(weights, dtype=float)
    c, s = np.cos(direction), np.sin(direction)
    off = width * np.arange(-(n - 1), n)
    gx, gy = np.meshgrid(off, off, indexing="ij")
    x, y = gx.ravel(), gy.ravel()
    g = influence.square_elastic(x, y, width)
    total = np.zeros((2, x.size))
    rows = max(1, _CHUNK // (8 * (160 + 6 * shifts.size)))
    for a in range(0, x.size, rows):
        xb, yb = x[a:a + rows], y[a:a + rows]
        edges = _breakpoints(xb, yb, c, s, width / 2, shifts)
        lo, hi = edges[:, :-1, None], edges[:, 1:, None]
        t = 0.5 * (hi - lo) * (_GL_X + 1) + lo  # (rows, pieces, 8)
        dt = 0.5 * (hi - lo) * _GL_W
        vals = influence.square_elastic(xb[:, None, None] + c * t, yb[:, None, None] + s * t, width) * dt
        for L, wk in zip(shifts, weights):
            i_k = np.sum(vals * np.exp(-t / L), axis=(1, 2)) / L
            total[0, a:a + rows] += wk * i_k
            total[1, a:a + rows] += wk * (i_k - g[a:a + rows]) / L
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
        for ck, lk in ([] if elastic else zip(material.compliances, material.creep_times)):
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
