"""Periodic viscoelastic half-space under steady sliding: the surface response operator.

Conventions (docs/theory.md §3; SI units). The rigid indenter moves with speed ``v`` (m/s) in
``+x``; in its frame every field is stationary and material points travel in ``-x``.
``p`` is the normal pressure (Pa, compressive positive) and ``u`` the normal surface
displacement (m, positive into the solid). With the FFT convention of :mod:`bem.fft`,

    u_q = 2 (1 - nu**2) / |q| * J(w = -q_x v) * p_q,        q != 0,

with ``J(w) = 1/E_inf + sum_k C_k / (1 + i w lambda_k)`` the complex creep compliance.
The same symbol serves 1-D profiles (plane strain, load per unit length). The ``q = 0``
mode of ``u`` is not defined for a half-space: the operator returns zero-mean
displacements and the rigid approach carries the mean (see :mod:`bem.contact`).

Check of the sign: the symbol's imaginary part has the sign of ``q_x``, so the
dissipation ``-∫ p du/dx dA = A sum_q q_x Im(a_q) |p_q|**2 >= 0`` for every ``p``.
"""

import numpy as np

from .. import fft

__all__ = ["PeriodicHalfSpace"]


def _reciprocal(a):
    """``1 / a`` where ``a != 0``, else 0 (the mean mode of a symbol)."""
    out = np.zeros_like(a)
    np.divide(1.0, a, out=out, where=a != 0)
    return out


class PeriodicHalfSpace:
    """Steady-sliding response operator of a periodic cell, built once and reused.

    Parameters
    ----------
    shape : tuple of int
        ``(n,)`` for a profile or ``(n, n)`` for a surface.
    length : float
        Side of the periodic cell, m.
    material : bem.Material
        The viscoelastic solid.
    speed : float
        Sliding speed, m/s (``0`` gives the relaxed elastic response with ``E0``).

    Attributes
    ----------
    symbol : ndarray
        ``a_q`` on the half spectrum (m/Pa); real for elastic solids or zero speed.
    dtype : numpy.dtype
        Precision of the products: float64, or float32 for :meth:`single_precision`.
    """

    dtype = np.dtype(np.float64)

    def __init__(self, shape, length, material, speed):
        self.shape = tuple(shape)
        self.length = float(length)
        self.material = material
        self.speed = float(speed)
        q = fft.wavevectors(self.shape, self.length)
        qx = q[0]
        qnorm = np.sqrt(sum(c**2 for c in q))
        with np.errstate(divide="ignore"):
            green = np.where(qnorm > 0, 2.0 * material.plane_strain_factor / qnorm, 0.0)
        self._green = green  # the symbol is green(|q|) * J(-q_x v): an elastic factor and a
        self._creep = None  # creep factor that acts along x only (bem.contact.line_preconditioner)
        if material.is_elastic or self.speed == 0.0:
            modulus = material.E0
            self.symbol = green / modulus
            self.is_symmetric = True
        else:
            comp = material.complex_compliance(-qx * self.speed)
            self.symbol = fft.hermitian_multiplier(green * comp, self.shape)
            if len(self.shape) == 2:
                creep = np.array(comp[:, 0], dtype=complex)
                if self.shape[0] % 2 == 0:  # as hermitian_multiplier: real at the x-Nyquist mode
                    creep[self.shape[0] // 2] = creep[self.shape[0] // 2].real
                self._creep = creep
            self.is_symmetric = bool(np.all(self.symbol.imag == 0))
            if self.is_symmetric:
                self.symbol = self.symbol.real
        self._qx = np.broadcast_to(qx, self.symbol.shape)
        self._weights = fft.full_spectrum_weights(self.shape)

    @property
    def size(self):
        return int(np.prod(self.shape))

    @property
    def area(self):
        """Cell area (m²) for surfaces, cell length (m) for profiles."""
        return self.length ** len(self.shape)

    def self_influence(self):
        """Displacement (m) at a point per unit uniform-mean-free pressure there (m/Pa).

        The diagonal of the real-space operator: the mean of the real symbol.
        """
        return float(np.sum(self._weights * np.real(self.symbol)) / self.size)

    def displacement(self, pressure):
        """Zero-mean surface displacement (m) under ``pressure`` (Pa), same shape."""
        return self._multiply(pressure, self.symbol)

    def pressure_from_displacement(self, displacement):
        """Zero-mean pressure (Pa) whose displacement is ``displacement`` up to its mean.

        The exact inverse of :meth:`displacement` on zero-mean fields (full contact).
        """
        return self._multiply(displacement, self._inverse_symbol())

    def _multiply(self, field, multiplier):
        """Real-space action of a Fourier multiplier, in the precision ``self.dtype``; the
        spectrum is a temporary, so the multiplication and the inverse transform's first
        pass work in place."""
        fq = fft.forward(np.asarray(field, dtype=self.dtype))
        fq *= multiplier
        return fft.inverse(fq, self.shape, overwrite=True)

    def _inverse_symbol(self):
        """``1 / a_q`` (0 for the mean mode), computed once."""
        inv = self.__dict__.get("_inv")
        if inv is None:
            inv = self._inv = _reciprocal(self.symbol)
        return inv

    @property
    def factors_along_x(self):
        """Whether the symbol factors into an elastic operator and a creep convolution along x
        (:mod:`bem.contact.line_preconditioner`): a viscoelastic 2-D operator in motion."""
        return self._creep is not None

    def creep_line_kernel(self, dtype=np.float64):
        """The creep factor's line kernel ``c[k]`` (response at ``x_i + k`` of a unit load at
        ``x_i`` on one x-line), unwrapped for gathers without a modulo: ``kernel[d + n0 - 1] =
        c[d mod n0]``; in ``dtype``, computed once per dtype. For
        :func:`bem.contact.line_preconditioner.line_preconditioner`."""
        key = f"_line_kernel_{np.dtype(dtype).name}"
        kernel = self.__dict__.get(key)
        if kernel is None:
            c = np.fft.ifft(self._creep).real
            kernel = np.concatenate([c[1:], c]).astype(dtype)
            setattr(self, key, kernel)
        return kernel

    def elastic_inverse(self, field):
        """``G^-1 field``: the inverse of the elastic factor ``green(|q|)`` of the symbol (zero
        mean), in the precision ``self.dtype``."""
        green_inverse = self.__dict__.get("_green_inverse")
        if green_inverse is None:
            green_inverse = self._green_inverse = _reciprocal(self._green)
        return self._multiply(field, green_inverse)

    def approximate_inverse(self, displacement):
        """:meth:`pressure_from_displacement`: on a periodic cell the inverse is exact."""
        return self.pressure_from_displacement(displacement)

    def max_phase(self):
        """Largest phase ``|arg a_q|`` (rad) of the symbol: 0 when symmetric, above ``pi/4``
        strongly non-symmetric for the contact solver."""
        phase = self.__dict__.get("_max_phase")
        if phase is None:
            phase = self._max_phase = 0.0 if self.is_symmetric else float(np.max(np.abs(np.angle(self.symbol))))
        return phase

    def coarsened(self):
        """The same operator on the grid with half the points per axis (even sides only, else
        ``None``); the symmetric part's is the symmetric part of the coarse operator."""
        if any(n % 2 for n in self.shape):
            return None
        coarse = PeriodicHalfSpace(tuple(n // 2 for n in self.shape), self.length, self.material, self.speed)
        return coarse.symmetric_part() if self.__dict__.get("_symmetric_part") else coarse

    @staticmethod
    def restrict(field):
        """``field`` at the points of :meth:`coarsened` (coarse point ``i`` is fine point ``2i``)."""
        return np.ascontiguousarray(field[tuple(slice(0, None, 2) for _ in field.shape)])

    @staticmethod
    def prolong(field):
        """``field`` from the grid of :meth:`coarsened` to this one: periodic linear interpolation
        (coarse point ``i`` sits on fine point ``2i``); keeps ``field >= 0`` and the mean."""
        for axis in range(field.ndim):
            mid = 0.5 * (field + np.roll(field, -1, axis=axis))
            fine = np.empty(tuple(2 * k if a == axis else k for a, k in enumerate(field.shape)))
            index = [slice(None)] * field.ndim
            index[axis] = slice(0, None, 2)
            fine[tuple(index)] = field
            index[axis] = slice(1, None, 2)
            fine[tuple(index)] = mid
            field = fine
        return field

    def _twin(self, *stale):
        """A copy sharing this operator's arrays, without the caches named in ``stale`` (and
        without its single-precision twin): for operators that change a symbol."""
        twin = object.__new__(PeriodicHalfSpace)
        twin.__dict__.update(self.__dict__)
        for name in ("_single", "_max_phase") + stale:
            twin.__dict__.pop(name, None)
        return twin

    def single_precision(self):
        """The same operator with its products in single precision (float32 fields,
        complex64 spectra), for the contact solver's inner Krylov solves: see
        :attr:`bem.contact.ContactOptions.single_precision`. Built once and kept."""
        twin = self.__dict__.get("_single")
        if twin is None:
            twin = self._twin("_inv", "_green_inverse")  # recomputed from the single symbols
            twin.dtype = np.dtype(np.float32)
            spectrum = np.complex64 if np.iscomplexobj(self.symbol) else np.float32
            twin.symbol = self.symbol.astype(spectrum)
            twin._green = self._green.astype(np.float32)
            self._single = twin
        return twin

    def symmetric_part(self):
        """Operator with the symbol's real part: the symmetric part of this operator."""
        twin = self._twin("_inv")
        twin.symbol = np.real(self.symbol).copy()
        twin._symmetric_part = True
        twin._creep = None
        twin.is_symmetric = True
        return twin

    def dissipation_integral(self, pressure_q):
        """``-∫ p du/dx dA`` (N·m/m = N for surfaces, N/m·m for profiles; i.e. force × length
        per unit length) from the half-spectrum coefficients of the pressure.

        Equals the tangential (friction) force: dissipated power is this times ``v``.
        Non-negative for any pressure, since ``q_x Im(a_q) >= 0``.
        """
        term = self._qx * np.imag(self.symbol) * np.abs(pressure_q) ** 2
        return float(self.area * np.sum(self._weights * term))
