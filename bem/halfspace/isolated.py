"""Isolated (non-periodic) viscoelastic half-space under steady sliding: the response operator.

Conventions (docs/theory.md §3, §4; SI units) as in :mod:`bem.halfspace.periodic`: the indenter moves with
speed ``v`` in ``+x`` (axis 0), material points travel in ``-x``; pressure ``p`` (Pa) is
compressive positive, displacement ``u`` (m) positive into the solid. The domain is the
user's array: ``n`` elements per side of width ``d = length / n``, each carrying a uniform
pressure; pressure outside the domain is zero. ``u`` is collocated at element centres:

    u_i = sum_j K(x_i - x_j) p_j,
    K = (1 - nu**2) [G / E_inf + sum_k C_k ∫_0^inf exp(-z) G(. + v lambda_k z) dz],

(docs/theory.md §11: creep terms with ``v lambda_k < 1e-6 d`` act as fully relaxed and join the elastic
term; those with ``v lambda_k > 1e6 length`` add only a constant and are dropped; both
errors are ``O(1e-6)`` relative), with ``G`` the influence coefficient of one element at
``E* = 1`` (:mod:`bem.halfspace.influence`:
Love's uniformly loaded square on a 3-D half-space for 2-D surfaces, the plane-strain
strip for 1-D profiles). For 2-D surfaces ``u`` is the absolute displacement (zero at
infinity). For 1-D profiles plane strain defines ``u`` only up to a constant; here the
elastic coefficient is referred to the distance ``length`` and each creep term is
referred to ``ln(v lambda_k) - gamma_Euler``; the rigid approach absorbs the constant.

Convolution (DC-FFT): the Toeplitz product is a circular convolution on a zero-padded grid
of ``M >= 2n - 1`` points per axis (``scipy.fft.next_fast_len``), kernel entry of offset
``i`` stored at ``i mod M``; real FFTs along the last axis on :func:`bem.parallel.get_threads` threads. Exact: no
periodic images.
"""

import numpy as np
import scipy.fft as sfft

from ..parallel import get_threads
from . import influence
from .periodic import PeriodicHalfSpace

__all__ = ["IsolatedHalfSpace"]

_FOLD = 1e-6  # creep terms with v lambda < 1e-6 d (relaxed) or > 1e6 length (glassy) are folded


def _embed(kernel, n, m_pad):
    """Circulant embedding: offsets ``-(n-1)..(n-1)`` along axis 0 (and axis 1 if 2-D) at ``i mod M``."""
    idx = np.arange(-(n - 1), n) % m_pad
    if kernel.ndim == 1:
        out = np.zeros(m_pad)
        out[idx] = kernel
        return out
    out = np.zeros((m_pad, m_pad))
    out[np.ix_(idx, idx)] = kernel
    return out


def _offset_kernels(shape, length, material, speed):
    """Kernels at element-centre offsets: ``(K, S)`` with ``S`` the x-slope of the creep part,
    ``S = (1 - nu**2) sum_k C_k (K_k - G) / (v lambda_k)`` (``d/dx ∫_0^inf exp(-z) G(x + L z) dz
    = (K_L - G) / L``, integrating by parts: no derivative of ``G`` is needed).

    Shapes ``(2n - 1,)`` in 1-D and ``(2n - 1, 2n - 1)`` in 2-D (offsets ``-(n-1)..n-1`` per axis).
    """
    n = shape[0]
    d = length / n
    elastic = material.is_elastic or speed == 0.0
    comp_el = 1.0 / (material.E0 if elastic else material.E_inf)
    terms = []
    for ck, lk in [] if elastic else zip(material.compliances, material.creep_times):
        if speed * lk < _FOLD * d:  # fully relaxed over one element: C_k G (error O(v lambda / d))
            comp_el += ck
        elif speed * lk <= length / _FOLD:  # else glassy over the domain: a constant plus O(length / v lambda)
            terms.append((ck, lk))
    x = d * np.arange(-(n - 1), n)  # element-centre offsets
    if len(shape) == 1:
        g = influence.strip_elastic(x, d, length)
        kernel, slope = comp_el * g, np.zeros_like(g)
        for ck, lk in terms:
            L = speed * lk
            creep = influence.strip_creep(x, d, L)
            kernel = kernel + ck * creep
            # with the dropped constant restored (strip_creep is relative to ln(L) - gamma)
            slope = slope + ck / L * (creep - (2 / np.pi) * d * (np.log(L / length) - np.euler_gamma) - g)
    else:
        y = d * np.arange(n)
        g = influence.square_elastic(x[n - 1 :, None], y[None, :], d)  # x >= 0 half, mirrored below
        kernel, slope = comp_el * g, np.zeros_like(g)
        full = lambda a: np.concatenate([a[:0:-1], a], axis=0)  # noqa: E731  (G is even in x)
        kernel, slope, g = full(kernel), full(slope), full(g)
        if terms:
            ck, lk = np.array(terms).T
            both = influence.square_creep_sum(n, d, speed * lk, np.array([ck, ck / (speed * lk)]))[:, 1:-1:2]
            kernel = kernel + both[0]
            slope = both[1] - np.sum(ck / (speed * lk)) * g
        mirror = lambda a: np.concatenate([a[:, :0:-1], a], axis=1)  # noqa: E731  (y >= 0 to y < 0)
        kernel, slope = mirror(kernel), mirror(slope)
    f = material.plane_strain_factor
    return kernel * f, slope * f


class IsolatedHalfSpace:
    """Steady-sliding response operator of an isolated contact domain, built once and reused.

    Parameters
    ----------
    shape : tuple of int
        ``(n,)`` for a profile (plane strain, per unit length) or ``(n, n)`` for a surface.
    length : float
        Side of the (square) domain, m; element width ``length / n``.
    material : bem.Material
        The viscoelastic solid.
    speed : float
        Sliding speed, m/s (``0`` gives the relaxed elastic response with ``E0``).

    Attributes
    ----------
    kernel : ndarray
        ``K`` at element-centre offsets ``-(n-1)..(n-1)`` per axis (m/Pa), axis 0 is x.
    is_symmetric : bool
        True for an elastic response (elastic material or zero speed).
    """

    def __init__(self, shape, length, material, speed):
        self.shape = tuple(int(s) for s in shape)
        self.length = float(length)
        self.material = material
        self.speed = float(speed)
        n = self.shape[0]
        self.is_symmetric = bool(material.is_elastic or self.speed == 0.0)
        self.kernel, slope = _offset_kernels(self.shape, self.length, material, self.speed)
        self._pad = sfft.next_fast_len(2 * n - 1, real=True)
        self._khat = self._transform(self.kernel)
        self._shat = self._transform(slope)

    # ------------------------------------------------------------------ convolution
    def _transform(self, kernel):
        return sfft.rfftn(_embed(kernel, self.shape[0], self._pad), workers=get_threads())

    def _apply(self, khat, field):
        s = (self._pad,) * len(self.shape)
        workers = get_threads()
        out = sfft.irfftn(sfft.rfftn(field, s=s, workers=workers) * khat, s=s, workers=workers)
        return out[tuple(slice(0, k) for k in self.shape)]

    @property
    def size(self):
        return int(np.prod(self.shape))

    @property
    def spacing(self):
        """Element width (m)."""
        return self.length / self.shape[0]

    @property
    def area(self):
        """Domain area (m²) for surfaces, domain length (m) for profiles."""
        return self.length ** len(self.shape)

    def displacement(self, pressure):
        """Surface displacement (m) at element centres under element pressures (Pa)."""
        return self._apply(self._khat, pressure)

    def self_influence(self):
        """Displacement (m) of an element per unit pressure on it alone (m/Pa).

        For profiles, relative to the elements at the far ends of the offset range (the
        plane-strain displacement has no absolute level).
        """
        c = self.shape[0] - 1
        k0 = self.kernel[(c,) * len(self.shape)]
        if len(self.shape) == 1:
            k0 = k0 - 0.5 * (self.kernel[0] + self.kernel[-1])
        return float(k0)

    def symmetric_part(self):
        """Operator with kernel ``(K(x) + K(-x)) / 2``: the symmetric part of this operator."""
        twin = object.__new__(IsolatedHalfSpace)
        twin.__dict__.update(self.__dict__)
        twin.kernel = 0.5 * (self.kernel + self.kernel[::-1])
        twin._khat = twin._transform(twin.kernel)
        twin._shat = np.zeros_like(self._shat)  # a symmetric kernel dissipates nothing
        twin.is_symmetric = True
        twin._symmetric_part = True
        twin.__dict__.pop("_cell", None)
        return twin

    # ------------------------------------------------------------------ for the contact solver
    def _padded_cell(self):
        """The periodic cell of the zero-padded grid (side ``M d``) with the continuous operator's
        symbol; this operator's symmetric part takes the cell's. Built once."""
        cell = self.__dict__.get("_cell")
        if cell is None:
            shape = (self._pad,) * len(self.shape)
            cell = self._periodic_cell(shape, self._pad * self.spacing)
            if self.__dict__.get("_symmetric_part"):
                cell = cell.symmetric_part()
            self._cell = cell
        return cell

    def _periodic_cell(self, shape, length):
        return PeriodicHalfSpace(shape, length, self.material, self.speed)

    def approximate_inverse(self, displacement):
        """Pressure (Pa) whose displacement is about ``displacement`` (m) on the domain: the exact
        inverse of the continuous operator on the periodic cell of the zero-padded grid, cropped
        to the domain (one FFT pair of the padded size, as a product). It is not this operator's
        inverse (point values instead of element averages, periodic images beyond the padding):
        the contact solver uses it as a preconditioner."""
        cell = self._padded_cell()
        padded = np.zeros(cell.shape)
        inside = tuple(slice(0, k) for k in self.shape)
        padded[inside] = displacement
        return cell.pressure_from_displacement(padded)[inside]

    def coarsened(self):
        """The same operator with half the elements per axis over the same domain (even sides
        only), or ``None``; the symmetric part's is the symmetric part of the coarse operator."""
        if any(n % 2 for n in self.shape):
            return None
        coarse = self._with_shape(tuple(n // 2 for n in self.shape))
        return coarse.symmetric_part() if self.__dict__.get("_symmetric_part") else coarse

    def _with_shape(self, shape):
        return IsolatedHalfSpace(shape, self.length, self.material, self.speed)

    def restrict(self, field):
        """``field`` on the grid of :meth:`coarsened`: the mean of the two (four) elements each
        coarse element covers, whose centre is their midpoint."""
        for axis in range(field.ndim):
            field = 0.5 * (
                np.take(field, range(0, field.shape[axis], 2), axis=axis)
                + np.take(field, range(1, field.shape[axis], 2), axis=axis)
            )
        return field

    def prolong(self, field):
        """``field`` from the grid of :meth:`coarsened` to this one: linear between coarse element
        centres (a fine centre lies a quarter of a coarse element from the nearest), zero beyond the
        domain, where there is no pressure; keeps ``field >= 0``."""
        for axis in range(field.ndim):
            n = field.shape[axis]
            padded = np.pad(field, [(1, 1) if a == axis else (0, 0) for a in range(field.ndim)])
            fine = np.empty(tuple(2 * k if a == axis else k for a, k in enumerate(field.shape)))
            for offset, side in ((0, 0), (1, 2)):  # fine 2i leans to coarse i - 1, fine 2i + 1 to i + 1
                index = [slice(None)] * field.ndim
                index[axis] = slice(offset, None, 2)
                fine[tuple(index)] = 0.75 * field + 0.25 * np.take(padded, range(side, side + n), axis=axis)
            field = fine
        return field

    def max_phase(self):
        """Largest phase ``|arg J(w)|`` (rad) of the continuous symbol ``2(1-nu^2)/|q| J(-q_x v)``
        over the wavenumbers the domain resolves, ``pi/length <= |q_x| <= pi/d``."""
        if self.is_symmetric:
            return 0.0
        w = self.speed * np.geomspace(np.pi / self.length, np.pi / self.spacing, 400)
        return float(np.max(np.abs(np.angle(self.material.complex_compliance(w)))))

    def dissipation_integral(self, pressure):
        """``-∫ p du/dx dA`` (N for surfaces; N/m for profiles): the friction force.

        Collocated like the displacement: ``-sum_j p_j u'(x_j) d**ndim`` with ``u'`` the exact
        x-slope at the element centres (the elastic part of the kernel has an odd slope and
        adds exactly nothing to the sum, so only the creep terms' slope ``S`` enters).

        Not the exact dissipation of the piecewise-constant pressure
        (``-sum_j p_j [u(x_j + d/2) - u(x_j - d/2)]``, used before): that field dissipates also at
        its steps between elements, where ``u'`` of a creep term is log-singular, an excess of
        about ``(2/pi)(1 - nu**2) C L ln(d/L) sum (Δp)**2`` per unit step length, which a smooth
        pressure does not have. It grows without bound as ``L = v lambda`` falls below the cell
        (sphere, 16 cells per radius: +13 % at ``L = 0.023 d``, +29 % on 8 cells); the collocated
        form has no ``ln(d/L)`` and converges like the rest of the collocation (-1.4 % there,
        as the adaptive solver, which uses the same form). Positive for a sliding material:
        its quadratic form has the even part of ``-S``, ``q_x**2 L / (1 + q_x**2 L**2)`` times the
        elastic symbol for the continuous kernel (not proved for the sampled one; checked in the
        tests).
        """
        slope = self._apply(self._shat, pressure)
        return float(-np.sum(pressure * slope) * self.spacing ** len(self.shape))

    def initial_pressure(self, ht, *, mean_pressure=None, approach=None):
        """A first iterate for :func:`bem.contact.solve_contact` (no full-contact inverse here).

        Hertz-like ``p ∝ sqrt(ht + delta)`` on ``{ht > -delta}``. Displacement control takes
        ``delta = approach / 2`` (a paraboloid's contact reaches half the rigid overlap depth);
        load control picks ``delta`` by bisection so that the displacement drop across the
        set, ``max u - min u``, matches the height drop ``delta`` (about 14 products).
        """
        if approach is not None:
            over = np.sqrt(np.maximum(ht + 0.5 * approach, 0.0))
            return over * np.sqrt(0.5 * approach) / self.self_influence()
        total = mean_pressure * ht.size
        drops = np.unique(-ht.ravel())
        lo, hi = np.log(max(drops[min(4, drops.size - 1)], 1e-300)), np.log(max(drops[-1], 1e-300))

        def trial(log_delta):
            shape = np.sqrt(np.maximum(ht + np.exp(log_delta), 0.0))
            if not shape.any():
                shape = (ht == 0).astype(float)
            p = shape * (total / shape.sum())
            u = self.displacement(p)
            ins = shape > 0
            return p, np.log(max(np.ptp(u[ins]), 1e-300)) - log_delta

        p_hi, f_hi = trial(hi)
        if f_hi >= 0 or hi <= lo:
            return p_hi
        p = p_hi
        for _ in range(14):
            mid = 0.5 * (lo + hi)
            p_mid, f_mid = trial(mid)
            if f_mid > 0:
                lo = mid
            else:
                hi, p = mid, p_mid
        return p
