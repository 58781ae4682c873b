"""Brute-force reference for steady rolling of a rigid cylinder on a viscoelastic half-space.

A deliberately plain, independent check of :mod:`validation.references.hunter`: dense collocation of
the plane-strain surface displacement with piecewise-constant pressure on a uniform grid,
and a textbook active-set loop for the unilateral contact under load control. It is slow
(dense ``O(N^3)``) and first-order accurate, and meant only for tests.

Conventions as in :mod:`validation.references.hunter` (docs/theory.md §3): the cylinder moves in ``+x``,
material flows in ``-x``, displacement ``u`` is positive into the solid, and

    u(x) = (1/E_inf) w(x) + sum_k C_k * integral_0^inf exp(-z) w(x + V lambda_k z) dz,

with ``w`` the displacement of a half-space of unit Young's modulus,
``w(x) = -(2 (1 - nu**2) / pi) * integral p(s) ln|x - s| ds`` (plus a constant that the
rigid approach absorbs).
"""

from __future__ import annotations

import numpy as np
from scipy.special import expi, factorial

__all__ = ["strip_kernel", "solve_line_contact"]


def _phi(t):
    """Antiderivative of ``ln|t|``: ``t ln|t| - t`` (0 at t = 0)."""
    t = np.asarray(t, dtype=float)
    out = -t.copy()
    nz = t != 0
    out[nz] += t[nz] * np.log(np.abs(t[nz]))
    return out


def _phi_creep(t, shift):
    """``integral_0^inf exp(-z) _phi(t + shift z) dz`` up to a constant independent of ``t``.

    Integration by parts gives ``_phi(t) + shift * Psi(t / shift)`` with
    ``Psi(al) = integral_0^inf exp(-z) ln|al + z| dz = ln|al| - exp(al) Ei(-al)``
    (``-gamma`` at ``al = 0``); the dropped constant is ``shift * ln(shift)``. For
    ``|al| > 40`` the asymptotic series ``-exp(al) Ei(-al) ~ sum_k (-1)^k k! / al^(k+1)``
    (30 terms, truncation error < 1e-16) avoids overflow.
    """
    al = np.asarray(t, dtype=float) / shift
    psi = np.full_like(al, -np.euler_gamma)
    mid = (al != 0) & (np.abs(al) <= 40)
    psi[mid] = np.log(np.abs(al[mid])) - np.exp(al[mid]) * expi(-al[mid])
    big = np.abs(al) > 40
    k = np.arange(30)
    series = np.sum((-1.0) ** k * factorial(k) / al[big, None] ** (k + 1), axis=1)
    psi[big] = np.log(np.abs(al[big])) + series
    return _phi(t) + shift * psi


def strip_kernel(offsets, width, material, speed):
    """Displacement (m) at ``offsets`` (m) from the centre of a strip of ``width`` (m)
    carrying unit pressure (1 Pa), for the steady viscoelastic half-space of docs/theory.md §3."""
    y = np.asarray(offsets, dtype=float)
    c = -2.0 * (1.0 - material.nu**2) / np.pi
    out = c * (_phi(y + width / 2) - _phi(y - width / 2)) / material.E_inf
    for ck, lk in zip(material.compliances, material.creep_times):
        shift = speed * lk
        out += ck * c * (_phi_creep(y + width / 2, shift) - _phi_creep(y - width / 2, shift))
    return out


def solve_line_contact(material, *, radius, load, speed, x_min, x_max, n, maxiter=200):
    """Collocation BEM for a rigid cylinder ``h(x) = -x**2 / (2 radius)`` under ``load`` (N/m).

    Returns ``(x, p, delta)``: cell centres (m), cell pressures (Pa) and rigid approach (m).
    The active set starts from the cells with ``h`` above the Hertz (E_inf) estimate and is
    updated (drop ``p < 0``, add ``gap < 0``) until it no longer changes.
    """
    dx = (x_max - x_min) / n
    x = x_min + dx * (np.arange(n) + 0.5)
    kern = strip_kernel(dx * np.arange(-(n - 1), n), dx, material, speed)
    idx = np.arange(n)
    K = kern[(idx[:, None] - idx[None, :]) + n - 1]  # K[i, j]: at x_i due to cell j
    h = -(x**2) / (2 * radius)
    active = np.abs(x) < 0.5 * np.sqrt(4 * load * radius * (1 - material.nu**2) / (np.pi * material.E_inf))
    for _ in range(maxiter):
        s = np.flatnonzero(active)
        m = s.size
        A = np.zeros((m + 1, m + 1))
        A[:m, :m] = K[np.ix_(s, s)]
        A[:m, m] = -1.0
        A[m, :m] = dx
        sol = np.linalg.solve(A, np.concatenate([h[s], [load]]))
        p = np.zeros(n)
        p[s] = sol[:m]
        delta = sol[m]
        gap = K @ p - h - delta
        new = active.copy()
        if np.any(p[s] < 0):
            new[s[p[s] < 0]] = False
        else:
            new |= gap < -1e-14 * np.abs(h).max()
        if np.array_equal(new, active):
            return x, p, delta
        active = new
    raise RuntimeError("active set did not settle")
