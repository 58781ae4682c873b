"""The independent reference operator of periodic cells, the exact full-contact Fourier
solution, and a dense direct solve of the elastic contact problem.

Written with ``numpy.fft`` on the full complex spectrum and the material's *relaxation*
series ``1 / E(w)``, sharing no code with :mod:`bem` (neither :mod:`bem.fft`,
:mod:`bem.halfspace.periodic` nor the creep series the solver uses), so that agreement with the BEM
checks its FFT layout, Nyquist handling, Prony/creep interconversion and contact solver.

Conventions as in docs/theory.md §3: ``u_q = 2 (1 - nu^2) / |q| / E(-q_x v) p_q`` for ``q != 0``;
heights positive toward the solid, sliding in ``+x`` (axis 0). The symbol is made
Hermitian, ``a_q -> (a_q + conj(a_-q)) / 2`` with ``-q`` taken on the grid: this changes only
the x-Nyquist modes of even grids, whose symbol becomes its real part (docs/theory.md §12), and makes
``1 / a_q`` the exact inverse of the real operator.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "wavevectors",
    "symbol",
    "displacement",
    "full_contact_pressure",
    "x_derivative",
    "full_contact",
    "influence_matrix",
    "murty_lcp",
    "dense_contact",
]


def wavevectors(shape, length):
    """Full-spectrum wavevector components (rad/m), broadcastable, axis 0 = x."""
    axes = [2 * np.pi * np.fft.fftfreq(n, d=length / n) for n in shape]
    return np.meshgrid(*axes, indexing="ij", sparse=True)


def symbol(shape, length, material, speed):
    """``a_q`` (m/Pa) on the full spectrum, Hermitian; zero at ``q = 0``."""
    q = wavevectors(shape, length)
    qn = np.sqrt(sum(c**2 for c in q))
    with np.errstate(divide="ignore"):
        green = np.where(qn > 0, 2 * (1 - material.nu**2) / np.where(qn > 0, qn, 1.0), 0.0)
    a = green / material.complex_modulus(-q[0] * speed)
    mirror = a[tuple(np.ix_(*[(-np.arange(n)) % n for n in shape]))]  # a at -q on the grid
    return 0.5 * (a + np.conj(mirror))


def displacement(pressure, a):
    """Zero-mean displacement (m) of ``pressure`` (Pa) through the full-spectrum symbol ``a``."""
    return np.real(np.fft.ifftn(np.fft.fftn(pressure) * a))


def full_contact_pressure(heights, a):
    """Zero-mean pressure (Pa) making the gap vanish everywhere; add the mean load to it.

    Full contact is the one case where the contact problem is solved exactly in Fourier
    space; ``a`` must be Hermitian (as :func:`symbol` returns it).
    """
    inv = np.where(a != 0, 1.0 / np.where(a != 0, a, 1.0), 0.0)
    return np.real(np.fft.ifftn(np.fft.fftn(heights) * inv))


def x_derivative(field, length):
    """Spectral derivative along x (axis 0) of a periodic field (docs/theory.md §12: never differences);
    the x-Nyquist mode of an even grid, whose derivative has no defined sign, is dropped."""
    qx = wavevectors(field.shape, length)[0]
    if field.shape[0] % 2 == 0:
        qx = np.where(np.abs(qx) == np.pi * field.shape[0] / length, 0.0, qx)
    return np.real(np.fft.ifftn(1j * qx * np.fft.fftn(field)))


def full_contact(heights, length, material, speed, mean_pressure):
    """Exact full-contact pressure (Pa) and friction on a periodic cell.

    ``p = p_mean + F^-1[h_q / a_q]``; the gap vanishes everywhere, so ``u`` follows ``h`` and
    ``mu = -(1/p_mean) mean(p dh/dx)`` (spectral derivative, Nyquist mode dropped) is both
    the dissipation form and eq. 6 (``nan`` for ``mean_pressure = 0``). Valid when the returned pressure is >= 0 everywhere.
    """
    h = np.asarray(heights, float)
    a = symbol(h.shape, length, material, speed)
    p = mean_pressure + full_contact_pressure(h, a)
    dhdx = x_derivative(h, length)
    mu = float(-np.mean(p * dhdx) / mean_pressure) if mean_pressure > 0 else float("nan")
    return p, mu


def influence_matrix(shape, length, material):
    """Dense elastic (relaxed, ``E0``) influence matrix (m/Pa): column ``j`` is the zero-mean
    displacement of a unit pressure at sample ``j`` (C order)."""
    a = symbol(shape, length, material, 0.0).real if material.is_elastic else None
    if a is None:
        raise ValueError("influence_matrix is for elastic materials")
    kernel = np.real(np.fft.ifftn(a))  # displacement at offset d of a unit pressure at 0
    idx = np.indices(shape).reshape(len(shape), -1)
    diff = [(idx[k][:, None] - idx[k][None, :]) % shape[k] for k in range(len(shape))]
    return kernel[tuple(diff)]


def murty_lcp(M, q, maxpivots=100000):
    """Solve ``w = M z + q >= 0, z >= 0, w.z = 0`` by Murty's least-index principal pivoting.

    For a P-matrix ``M`` it terminates from any complementary basis at the unique solution
    (K.G. Murty, Math. Program. 6 (1974) 65-78, doi:10.1007/BF01585524). Each pivot solves
    ``M_CC z_C = -q_C`` directly and flips the least index whose variable is negative.
    Returns ``(z, pivots)``.
    """
    n = q.size
    basis = -q > 0
    for pivots in range(maxpivots):
        z = np.zeros(n)
        idx = np.flatnonzero(basis)
        if idx.size:
            z[idx] = np.linalg.solve(M[np.ix_(idx, idx)], -q[idx])
        w = M @ z + q
        w[idx] = 0.0
        bad = np.flatnonzero(np.where(basis, z < 0, w < 0))
        if bad.size == 0:
            return z, pivots
        basis[bad[0]] = not basis[bad[0]]
    raise RuntimeError("Murty's pivoting did not terminate")


def dense_contact(heights, length, material, shifted_approach):
    """Dense direct solve of the elastic periodic contact at one rigid position.

    ``A`` has no ``q = 0`` response, so ``M = A + c 11^T / N`` (``c`` = self-influence) is
    used: a P-matrix, and ``M p = A p + c mean(p)``, so the LCP with gap
    ``M p - (h - max h) - d`` solves the original problem with approach
    ``delta = d - c mean(p)``. Returns ``(pressure, delta, pivots)``.
    """
    h = np.asarray(heights, float)
    A = influence_matrix(h.shape, length, material)
    c = A[0, 0]
    M = A + c / A.shape[0]
    z, pivots = murty_lcp(M, -((h - h.max()).ravel() + shifted_approach))
    return z.reshape(h.shape), shifted_approach - c * z.mean(), pivots
