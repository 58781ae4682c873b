"""Independent references for periodic cells: the exact full-contact Fourier solution and a
dense direct solve of the elastic contact problem.

Written with ``numpy.fft`` on the full spectrum and an explicit dense matrix, sharing no
code with :mod:`bem` (only the material's creep series is read), so that agreement with the
BEM is a check of its FFT conventions, symbol and contact solver.

Conventions as in SPEC §2.2: ``u_q = 2 (1 - nu^2) / |q| J(-q_x v) p_q`` for ``q != 0``,
``J(w) = 1/E_inf + sum_k C_k / (1 + i w lambda_k)``; heights positive toward the solid,
sliding in ``+x`` (axis 0). On even grids the ``x``-Nyquist mode keeps only the real part of
``J`` (SPEC §7), so that the operator is real.
"""
from __future__ import annotations

import numpy as np

__all__ = ["full_contact", "influence_matrix", "murty_lcp", "dense_contact"]


def _wavevectors(shape, length):
    axes = [2 * np.pi * np.fft.fftfreq(n, d=length / n) for n in shape]
    return np.meshgrid(*axes, indexing="ij")


def _symbol(shape, length, material, speed):
    """Full-spectrum ``a_q`` (m/Pa), 0 at ``q = 0``."""
    q = _wavevectors(shape, length)
    qn = np.sqrt(sum(c**2 for c in q))
    qx = q[0]
    w = -qx * speed
    comp = 1.0 / material.E_inf + sum(c / (1 + 1j * w * lam)
                                      for c, lam in zip(material.compliances, material.creep_times))
    if shape[0] % 2 == 0:
        nyq = np.zeros(shape, bool)
        nyq[shape[0] // 2] = True
        comp = np.where(nyq, comp.real, comp)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(qn > 0, 2 * (1 - material.nu**2) / np.where(qn > 0, qn, 1.0) * comp, 0.0)


def full_contact(heights, length, material, speed, mean_pressure):
    """Exact full-contact pressure (Pa) and friction on a periodic cell.

    ``p = p_mean + F^-1[h_q / a_q]``; the gap vanishes everywhere, so ``u`` follows ``h`` and
    ``mu = -(1/p_mean) mean(p dh/dx)`` (spectral derivative, Nyquist mode dropped) is both
    the dissipation form and eq. 6 (``nan`` for ``mean_pressure = 0``). Valid when the returned pressure is >= 0 everywhere.
    """
    h = np.asarray(heights, float)
    a = _symbol(h.shape, length, material, speed)
    hq = np.fft.fftn(h)
    with np.errstate(divide="ignore", invalid="ignore"):
        pq = np.where(a != 0, hq / np.where(a != 0, a, 1.0), 0.0)
    p = mean_pressure + np.real(np.fft.ifftn(pq))
    qx = _wavevectors(h.shape, length)[0].copy()
    if h.shape[0] % 2 == 0:
        qx[h.shape[0] // 2] = 0.0
    dhdx = np.real(np.fft.ifftn(1j * qx * hq))
    mu = float(-np.mean(p * dhdx) / mean_pressure) if mean_pressure > 0 else float("nan")
    return p, mu


def influence_matrix(shape, length, material):
    """Dense elastic (relaxed, ``E0``) influence matrix (m/Pa): column ``j`` is the zero-mean
    displacement of a unit pressure at sample ``j`` (C order)."""
    a = _symbol(shape, length, material, 0.0).real if material.is_elastic else None
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
