"""Exact interconversion of the relaxation (Prony) and creep (retardation) series.

With ``s = i w``, ``E(s) = E0 + sum_k E_k s tau_k / (1 + s tau_k)`` and
``J(s) = 1/E(s) = 1/E_inf + sum_k C_k / (1 + s lambda_k)``. The retardation rates
``1/lambda_k`` are the roots of ``E(-sigma)``, which are real and interlace the relaxation
rates ``1/tau_k`` (one root per interval), so each is found by a bracketed root search; the
residues follow from the derivative of ``E``, a sum of positive terms, so no cancellation
occurs. The converse uses the same construction on ``J``. Both are exact to round-off.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

__all__ = ["prony_to_creep", "creep_to_prony"]


def _interlaced_roots(func, poles, upper=None):
    """Roots of ``func(sigma)`` between consecutive ``poles`` (ascending).

    If ``upper`` is None the first root lies in ``(0, poles[0])``; otherwise the last lies in
    ``(poles[-1], inf)``. ``func`` must change sign once in each interval.
    """
    poles = np.asarray(poles, dtype=float)
    if upper is None:
        brackets = [(0.0, poles[0])] + list(zip(poles[:-1], poles[1:]))
    else:
        brackets = list(zip(poles[:-1], poles[1:])) + [(poles[-1], np.inf)]
    roots = []
    for lo, hi in brackets:
        if np.isinf(hi):
            hi = 2.0 * lo
            while func(hi) * func(lo * (1 + 1e-15) + 1e-300) > 0:
                hi *= 2.0
        # open interval: step off the poles by a relative round-off amount
        a = lo * (1 + 1e-14) if lo > 0 else 0.0
        b = hi * (1 - 1e-14)
        roots.append(brentq(func, a, b, xtol=1e-300, rtol=8.9e-16, maxiter=500))
    return np.array(roots)


def prony_to_creep(E0, moduli, taus):
    """Relaxation series -> (C_k, lambda_k). Exact partial fractions of 1/E(s)."""
    rates = np.sort(1.0 / taus)  # ascending relaxation rates

    def e_neg(sig):  # E(s = -sig), a monotone decreasing function between poles
        return E0 + np.sum(moduli * sig * taus / (sig * taus - 1.0))

    roots = _interlaced_roots(e_neg, rates)  # retardation rates 1/lambda
    lambdas = 1.0 / roots
    # residue of 1/E(s) at s_k = -1/lambda_k is C_k / lambda_k = 1 / E'(s_k)
    s = -roots[:, None]
    dE = np.sum(moduli * taus / (1.0 + s * taus) ** 2, axis=1)
    compliances = lambdas / dE
    return compliances, lambdas


def creep_to_prony(E0, compliances, lambdas):
    """Creep series -> (E_k, tau_k). Exact partial fractions of 1/J(s)."""
    j_inf = 1.0 / E0 - np.sum(compliances)
    rates = np.sort(1.0 / lambdas)

    def j_neg(sig):  # J(s = -sig)
        return j_inf + np.sum(compliances / (1.0 - sig * lambdas))

    roots = _interlaced_roots(j_neg, rates, upper=True)  # relaxation rates 1/tau
    taus = 1.0 / roots
    s = -roots[:, None]
    dJ = np.sum(compliances * lambdas / (1.0 + s * lambdas) ** 2, axis=1)  # = -J'(s)
    moduli = taus / dJ
    return moduli, taus
