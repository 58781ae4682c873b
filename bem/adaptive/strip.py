"""Influence coefficients of strip elements (1-D profiles, plane strain), elastic and steady
sliding, in closed form.

``G = (2 (1 - nu**2) / pi) ln(l_ref / |x|)`` with ``l_ref`` the domain length (the
displacement of a line load is defined up to a constant times the load; ``l_ref`` fixes
it, so the approach of a profile is relative to it; creep term ``k`` uses
``l_ref + v lambda_k`` so that its kernel stays positive when ``v lambda_k >> l_ref``).
Closed forms: with
``G0(a) = a ln(|a|/l_ref) - a`` the strip ``[x1, x2]`` gives ``-(G0(x2 - x) - G0(x1 - x))``;
the creep term replaces ``G0(a)`` by ``G0(a) + L D(a/L)``,
``D(t) = exp(-t) Ei(t) - ln|t| - gamma`` (an ``a``-independent constant dropped), evaluated
by its power series for ``|t| <= 1`` so that large ``L`` does not cancel (docs/theory.md §12).
"""

import numpy as np
from scipy import special

from ..halfspace.influence import log_antiderivative

__all__ = ["matrices_1d"]


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
    return ell * log_antiderivative(a / ell)


def matrices_1d(mesh, material, speed, chunk=512):
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
