"""Periodic viscoelastic half-space under steady sliding: the surface response operator.

Conventions (SPEC §2.2; SI units). The rigid indenter moves with speed ``v`` (m/s) in
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
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from . import fft
from .parallel import get_threads

__all__ = ["PeriodicHalfSpace"]

LINE_CHUNK = 32  # x-lines per batched dense inverse in line_preconditioner
LINE_DTYPE = np.float32  # storage of the dense line inverses (see line_preconditioner)
LINE_BUDGET = 2**30  # bytes of dense line inverses (with their cache) line_preconditioner may hold
_POOL = None  # (pid, workers), executor: see _run


def _run(func, items):
    """``func(item)`` for every item, on :func:`bem.parallel.get_threads` threads (1 runs them
    here). For the line preconditioner's batched inverses and
    products: numpy releases the GIL in both, and BLAS itself stays single-threaded."""
    global _POOL
    workers = get_threads()
    if workers == 1 or len(items) < 2:
        for item in items:
            func(item)
        return
    key = (os.getpid(), workers)  # a forked child does not inherit the threads
    if _POOL is None or _POOL[0] != key:
        _POOL = (key, ThreadPoolExecutor(max_workers=workers))
    for _ in _POOL[1].map(func, items):
        pass


def _reciprocal(a):
    """``1 / a`` where ``a != 0``, else 0 (the mean mode of a symbol)."""
    out = np.zeros_like(a)
    np.divide(1.0, a, out=out, where=a != 0)
    return out


def _chunks(order):
    """``order`` (line numbers sorted by size) cut into batches of ``LINE_CHUNK``."""
    order = list(order)
    return [np.array(order[i: i + LINE_CHUNK]) for i in range(0, len(order), LINE_CHUNK)]


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
        self._creep = None   # creep factor that acts along x only (see line_preconditioner)
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
        """Whether :meth:`line_preconditioner` applies: a viscoelastic 2-D operator in motion."""
        return self._creep is not None

    def line_preconditioner(self, contact, cache=None):
        """Approximate inverse of the operator restricted to ``contact`` (boolean, grid
        shaped), for strongly non-symmetric 2-D operators; ``None`` where it does not apply.

        The symbol factors as ``a_q = green(|q|) J(-q_x v)``: a symmetric elastic operator
        ``G`` times the creep operator ``C``, a convolution along x alone (the memory of the
        material, causal in the sliding direction). With ``R`` the restriction to the
        contact set, the returned map is ``(R C R^T)^-1 R G^-1 R^T``: ``G`` inverted in full
        space (one FFT pair), ``C`` inverted *exactly on the contact set*, line by line (each
        x-line of the set is one small dense system with the line kernel ``c[i - j]``). The
        restricted creep inverse is what removes the non-normality: ``R C^-1 R^T`` (the full
        space inverse, i.e. ``R A^-1 R^T``) does not, since the memory of a contact spot
        reaches the gaps behind it. Unpreconditioned GMRES took 1095 products for 8 decades on
        the 20-term rubber of the periodic benchmark at 512² (its final contact set), ``R
        A^-1 R^T`` 397, this one 43. ``cache`` (a dict kept by the caller across Newton
        points) keeps the inverses of lines whose contact has not changed.

        The inverses are stored and applied in ``LINE_DTYPE`` (float32): the line systems
        are well conditioned (condition numbers up to ~56 on the benchmark rubber's 1024²
        contact set, where the float32 inverse of its longest line, 250 points, is within
        1.5e-7 of the float64 one), so the preconditioner changes by ~1e-7 relative, far
        below the inner solves' tolerance, while the memory traffic of its products halves.
        Lines are formed in batches of ``LINE_CHUNK`` (sorted by length, padded with the
        identity), inverted and applied on the FFT's cores (:func:`_run`). The rubber's
        recorded contact sets, replayed (all Newton points of one solve on the finest grid):
        building 3.96 s -> 2.24 s at 1024² and 31.7 s -> 14.1 s at 2048², one application
        per set 29 -> 21 ms and 136 -> 108 ms (with its FFT pair), against float64, one thread,
        a gather through a modulo and a second padding pass; the operator products of the
        benchmark solves are unchanged (593, 556, 591 at 256²-1024²).
        """
        if not self.factors_along_x:
            return None
        n1 = self.shape[1]
        kernel = self.__dict__.get("_line_kernel")
        if kernel is None:  # c[k]: response at x_i + k of a unit load at x_i (one line)
            c = np.fft.ifft(self._creep).real
            # unwrapped for gathers without a modulo: kernel[d + n0 - 1] = c[d mod n0]
            kernel = self._line_kernel = np.concatenate([c[1:], c]).astype(LINE_DTYPE)
        idx = np.flatnonzero(contact)
        xs, ys = np.divmod(idx, n1)
        order = np.lexsort((xs, ys))  # by line (y), then along it (x)
        lines, starts, counts = np.unique(ys[order], return_index=True, return_counts=True)
        itemsize = np.dtype(LINE_DTYPE).itemsize
        if 2 * itemsize * float(np.sum(counts.astype(float) ** 2)) > LINE_BUDGET:
            return None  # dense line inverses (and their cache) would exceed the budget
        positions = [order[a: a + c] for a, c in zip(starts, counts)]  # in idx, along x
        keys = [xs[pos].tobytes() for pos in positions]
        xs_padded = np.append(xs, 0)  # read through ``pos``, whose padding is idx.size
        cache = {} if cache is None else cache
        kept = {}
        blocks, jobs = [], []
        for chunk in _chunks(np.argsort(counts, kind="stable")):
            m = int(counts[chunk].max())
            pos = np.full((len(chunk), m), idx.size)  # idx.size: padding, reads a zero
            for row, k in enumerate(chunk):
                pos[row, : counts[k]] = positions[k]
            valid = pos < idx.size
            mats = np.zeros((len(chunk), m, m), dtype=LINE_DTYPE)
            missing = []
            for row, k in enumerate(chunk):
                hit = cache.get(lines[k])
                if hit is not None and hit[0] == keys[k]:
                    mats[row, : counts[k], : counts[k]] = hit[1]
                else:
                    missing.append(row)
            if missing:
                jobs.append((mats, missing, xs_padded[pos[missing]], valid[missing]))
            for row, k in enumerate(chunk):  # views: the cache keeps these blocks alive
                kept[lines[k]] = (keys[k], mats[row, : counts[k], : counts[k]])
            blocks.append((pos, valid, pos[valid], mats))

        def invert(job):
            mats, rows, x, valid = job
            mats[rows] = np.linalg.inv(self._line_matrices(kernel, x, valid))

        _run(invert, jobs)
        cache.clear()
        cache.update(kept)
        green_inverse = self.__dict__.get("_green_inverse")
        if green_inverse is None:
            green_inverse = self._green_inverse = _reciprocal(self._green)
        full = np.zeros(self.shape, dtype=self.dtype)
        flat = full.reshape(-1)

        def apply(r):
            flat[idx] = r
            w = np.append(np.take(self._multiply(full, green_inverse).reshape(-1), idx), 0.0)
            w = w.astype(LINE_DTYPE)
            z = np.empty_like(r)

            def solve(block):
                pos, valid, dest, inv = block
                z[dest] = np.matmul(inv, w[pos][:, :, None])[:, :, 0][valid]

            _run(solve, blocks)
            return z

        return apply

    @staticmethod
    def _line_matrices(kernel, x, valid):
        """Dense creep matrices ``c[x_i - x_j]`` of a batch of lines (``x``: positions along
        x, padded; ``valid``: the real entries), with the identity on the padding."""
        n0 = (kernel.size + 1) // 2
        x = x.astype(np.int32)
        mats = kernel[(x + (n0 - 1))[:, :, None] - x[:, None, :]]
        weight = valid.astype(LINE_DTYPE)
        mats *= weight[:, :, None]
        mats *= weight[:, None, :]
        rows, cols = np.nonzero(~valid)
        mats[rows, cols, cols] = 1.0
        return mats

    def coarsened(self):
        """The same operator on the grid with half the points per axis (even sides only)."""
        if any(n % 2 for n in self.shape):
            raise ValueError(f"coarsening needs even grid sides, got {self.shape}")
        coarse = PeriodicHalfSpace(tuple(n // 2 for n in self.shape), self.length, self.material, self.speed)
        return coarse.symmetric_part() if self.__dict__.get("_symmetric_part") else coarse

    def _twin(self, *stale):
        """A copy sharing this operator's arrays, without the caches named in ``stale`` (and
        without its single-precision twin): for operators that change a symbol."""
        twin = object.__new__(PeriodicHalfSpace)
        twin.__dict__.update(self.__dict__)
        for name in ("_single",) + stale:
            twin.__dict__.pop(name, None)
        return twin

    def single_precision(self):
        """The same operator with its products in single precision (float32 fields,
        complex64 spectra), for the contact solver's inner Krylov solves: see
        :data:`bem.contact.SINGLE_PRECISION_INNER`. Built once and kept."""
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
