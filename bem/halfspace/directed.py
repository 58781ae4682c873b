"""Steady-sliding operators for motion along any direction ``d = (cos theta, sin theta)`` (2-D).

Angles are radians from ``+x`` (axis 0) toward ``+y`` (axis 1). A direction within 1e-12 rad
of a multiple of ``pi/2`` is that quarter turn exactly (:func:`quarter_turns`), so that the
solvers can take their exact routes along the grid axes (:mod:`bem.direction`).

Periodic cells (:class:`DirectedPeriodicHalfSpace`). The symbol becomes
``a_q = 2 (1 - nu**2) / |q| * J(w = -(q.d) v)``. A Nyquist mode (even side) stands for two
aliased wavevectors ``±q_N`` along that axis; its symbol is the mean of the symbols of its
aliases along both axes (four at the corner), which makes the operator real and reduces, at
``theta = 0``, to the real part at the x-Nyquist mode that the x-operator takes. The
derivative along ``d`` (for the dissipation) is the same alias mean of ``i q.d``. The creep
factor then acts along ``d``, not along x-lines, so the operator declares
``factors_along_x = False`` and the contact solver uses its general path.

Isolated domains (:class:`DirectedIsolatedHalfSpace`).
The operator of :mod:`bem.halfspace.isolated` with each creep term's shift along ``d``:

    K(r) = (1 - nu**2) [G(r) / E_inf + sum_k C_k I_k(r)],   I_k(r) = ∫_0^inf exp(-z) G(r + L_k z d) dz,

with ``L_k = v lambda_k`` and ``G`` Love's uniformly loaded square (:func:`bem.halfspace.influence.square_elastic`)
evaluated at the shifted, off-grid points, and the slope along ``d`` of the creep part,
``S = (1 - nu**2) sum_k C_k (I_k - G) / L_k`` (integration by parts, as for x). Terms are folded
as in :mod:`bem.halfspace.isolated` (``L < 1e-6 d``: relaxed; ``L > 1e6 length``: a constant, dropped).

Quadrature. ``I_k(r) = ∫_0^inf exp(-t/L)/L G(r + t d) dt`` along the ray from each element-centre
offset ``r``. ``G`` is smooth except on the element's edge lines ``x = ±w/2``, ``y = ±w/2``, where
it has ``u ln|u|`` kinks. Rays passing within two element widths of the element are split where
they cross those lines, with pieces growing geometrically (ratio 4) on both sides of each
crossing from ``w/2 / 4**6`` to the ray's end; every ray also gets such pieces about its
closest approach (scaled by that distance), pieces doubling from ``w/2`` to ``40 max L``, and
``L_k (1, 2, 4, 8, 16, 40)`` for the weights of terms with ``L_k < w/2``; 8-point
Gauss–Legendre on every piece (see :func:`_breakpoints`). All terms
share the nodes (only the weights differ). The accuracy is measured in the tests against the
exact-shift x-quadrature of :func:`bem.halfspace.influence.square_creep_sum` run along ``+x`` and ``+y``.
"""

import math

import numpy as np
import scipy.fft as sfft

from .. import fft
from ..errors import InputError
from . import influence
from .isolated import IsolatedHalfSpace
from .periodic import PeriodicHalfSpace

__all__ = ["DirectedIsolatedHalfSpace", "DirectedPeriodicHalfSpace", "oblique_kernels", "quarter_turns", "unit_vector"]

_TOL = 1e-12  # an angle within this of a multiple of pi/2 (radians) counts as a quarter turn


def quarter_turns(theta):
    """``k`` in ``0..3`` if ``theta`` is ``k pi/2`` (mod ``2 pi``, within 1e-12 rad), else ``None``."""
    r = (theta % (2 * math.pi)) / (math.pi / 2)
    k = round(r)
    return k % 4 if abs(r - k) * (math.pi / 2) < _TOL else None


def unit_vector(theta):
    """``(cos theta, sin theta)``, exactly ``0`` and ``±1`` at quarter turns (``cos(pi/2)`` is
    6e-17 in floating point, and a creep time of 1e9 s would see that component)."""
    k = quarter_turns(theta)
    if k is not None:
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[k]
    return math.cos(theta), math.sin(theta)


def _alias_mean(f, qx, qy, shape):
    """``f(qx, qy)`` on the half spectrum, averaged over the aliases ``±q_N`` of each Nyquist
    mode (even sides): the x-Nyquist row and the y-Nyquist column (four aliases at the corner)."""
    gx, gy = np.broadcast_arrays(qx, qy)
    out = np.array(f(gx, gy))
    if shape[0] % 2 == 0:
        r = shape[0] // 2
        out[r] = 0.5 * (f(gx[r], gy[r]) + f(-gx[r], gy[r]))
    if shape[1] % 2 == 0:
        cx, cy = gx[:, -1], gy[:, -1]
        col = 0.5 * (f(cx, cy) + f(cx, -cy))
        if shape[0] % 2 == 0:
            r = shape[0] // 2
            col[r] = 0.25 * (f(cx[r], cy[r]) + f(cx[r], -cy[r]) + f(-cx[r], cy[r]) + f(-cx[r], -cy[r]))
        out[:, -1] = col
    return out


class DirectedPeriodicHalfSpace(PeriodicHalfSpace):
    """Periodic steady-sliding operator for motion along ``d = (cos theta, sin theta)`` (2-D).

    Parameters as :class:`bem.halfspace.periodic.PeriodicHalfSpace`, plus ``direction`` (radians). Every
    method of the x-operator applies; the dissipation integral is ``-∫ p du/ds dA``. The
    operator does not factor along x-lines (``factors_along_x`` is ``False``).
    """

    def __init__(self, shape, length, material, speed, direction):
        if len(shape) != 2:
            raise InputError(f"shape must be 2-D for an oblique sliding direction, got {tuple(shape)}")
        super().__init__(shape, length, material, speed)
        self.direction = float(direction)
        c, s = unit_vector(self.direction)
        qx, qy = fft.wavevectors(self.shape, self.length)
        self._creep = None
        self._qx = np.broadcast_to(_alias_mean(lambda a, b: a * c + b * s, qx, qy, self.shape), self.symbol.shape)
        if material.is_elastic or self.speed == 0.0:
            return
        v = self.speed
        symbol = _alias_mean(lambda a, b: material.complex_compliance(-(a * c + b * s) * v), qx, qy, self.shape)
        # real operator: the alias means make the q_y = 0 and y-Nyquist columns Hermitian in q_x
        # (J(-w) = conj J(w)); the other columns have no partner on the half spectrum
        self.symbol = self._green * symbol
        self.is_symmetric = bool(np.all(self.symbol.imag == 0))
        if self.is_symmetric:
            self.symbol = self.symbol.real

    @property
    def factors_along_x(self):
        """``False``: the creep factor acts along ``d``, so x-line preconditioners do not apply."""
        return False

    def line_preconditioner(self, contact, cache=None):
        """``None``: the operator does not factor along x-lines (the solver's general path)."""
        return

    @property
    def slope_multiplier(self):
        """The multiplier of the derivative along ``d`` divided by ``i`` (rad/m), half spectrum."""
        return self._qx

    def coarsened(self):
        """The same operator on the grid with half the points per axis (even sides only, else ``None``)."""
        if any(n % 2 for n in self.shape):
            return None
        coarse = DirectedPeriodicHalfSpace(
            tuple(n // 2 for n in self.shape), self.length, self.material, self.speed, self.direction
        )
        return coarse.symmetric_part() if self.__dict__.get("_symmetric_part") else coarse

    def _twin(self, *stale):
        twin = super()._twin(*stale)
        twin.__class__ = type(self)
        return twin


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
    """:class:`bem.halfspace.isolated.IsolatedHalfSpace` for sliding along ``direction`` (radians), 2-D."""

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

    def _periodic_cell(self, shape, length):
        return DirectedPeriodicHalfSpace(shape, length, self.material, self.speed, self.direction)

    def _with_shape(self, shape):
        return DirectedIsolatedHalfSpace(shape, self.length, self.material, self.speed, self.direction)

    def symmetric_part(self):
        """Operator with kernel ``(K(r) + K(-r)) / 2``: the symmetric part of this operator."""
        twin = super().symmetric_part()
        twin.kernel = 0.5 * (self.kernel + self.kernel[::-1, ::-1])
        twin._khat = twin._transform(twin.kernel)
        return twin
