"""Fitting a non-negative Prony series to dynamic (DMA) data, in relative error.

The model is ``E*(w) = E0 + sum_k E_k i w tau_k / (1 + i w tau_k)`` on fixed, log-spaced
relaxation times ``tau_k``; it is linear in the unknowns ``E0 >= 0`` and ``E_k >= 0``, so
the fit is a non-negative least-squares problem (Lawson-Hanson, :func:`scipy.optimize.nnls`).

Each residual is divided by its own datum, ``(E'_fit - E') / E'`` and
``(E''_fit - E'') / E''``, so both moduli are fitted in relative error: the loss modulus of
a glassy tail, where ``tan delta`` is 0.01 and ``E''`` is a hundredth of ``|E*|``, weighs
as much as the storage modulus. (Weighting both by ``|E*|`` would let ``E''`` there be off
by tens of per cent for a residual below the noise of ``E'``.) Loss values below
``loss_floor * |E*|`` are weighted as if they were that size.

Optional smoothing adds the Tikhonov rows ``smoothing * D2 (E_k / |E*(1/tau_k)|)``: the
second difference, over the log-spaced times, of the spectrum relative to the modulus where
each term relaxes. It damps the alternating spectra that noise induces without biasing a
smooth spectrum; ``smoothing = 0`` is the plain least-squares fit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import nnls

from ..checks import check_array, check_positive
from ..errors import InputError
from ..parallel import blas_limit

__all__ = ["FitReport", "fit_prony_series", "relative_errors", "solve_nnls"]


@dataclass(frozen=True)
class FitReport:
    """How well a fitted series reproduces the data it was fitted to (relative errors).

    Attributes
    ----------
    storage_max, storage_rms : float
        Max and root-mean-square of ``|E'_fit / E' - 1|`` over the data points.
    loss_max, loss_rms : float
        The same for ``E''``.
    terms : int
        Prony terms kept (non-zero).
    smoothing : float
        The regularisation parameter used.
    frequency_band : tuple of float
        ``(w_min, w_max)`` of the data, rad/s.
    """

    storage_max: float
    storage_rms: float
    loss_max: float
    loss_rms: float
    terms: int
    smoothing: float
    frequency_band: tuple

    def as_dict(self):
        """Plain-number dictionary (for JSON)."""
        return {
            "storage_max": self.storage_max,
            "storage_rms": self.storage_rms,
            "loss_max": self.loss_max,
            "loss_rms": self.loss_rms,
            "terms": self.terms,
            "smoothing": self.smoothing,
            "frequency_band": list(self.frequency_band),
        }


def relative_errors(fitted, storage, loss):
    """``(max, rms)`` of ``|E'_fit/E' - 1|`` and of ``|E''_fit/E'' - 1|`` (4 floats)."""
    r1 = fitted.real / storage - 1.0
    r2 = fitted.imag / loss - 1.0
    return (
        float(np.max(np.abs(r1))),
        float(np.sqrt(np.mean(r1**2))),
        float(np.max(np.abs(r2))),
        float(np.sqrt(np.mean(r2**2))),
    )


def check_dma(frequencies, storage, loss, hz=False):
    """Validated ``(w (rad/s), E' (Pa), E'' (Pa))`` arrays of one length."""
    w = check_array("frequencies", frequencies, ndim=1, positive=True)
    if hz:
        w = 2 * np.pi * w
    e1 = check_array("storage", storage, ndim=1, positive=True)
    e2 = check_array("loss", loss, ndim=1)
    if not (w.shape == e1.shape == e2.shape):
        raise InputError(f"frequencies, storage and loss must have the same length, got {w.size}, {e1.size}, {e2.size}")
    if np.any(e2 < 0):
        raise InputError(f"loss must be >= 0 Pa everywhere (a passive material dissipates), got min {e2.min():g}")
    return w, e1, e2


def default_times(w, terms_per_decade, extend=1.0):
    """Log-spaced times over ``[1/w_max, 1/w_min]`` widened by ``extend`` decades each side."""
    per = check_positive("terms_per_decade", terms_per_decade)
    lo, hi = np.log10(1 / w.max()) - extend, np.log10(1 / w.min()) + extend
    n = max(int(np.ceil((hi - lo) * per)) + 1, 1)
    return np.logspace(lo, hi, n)


def _design(w, taus):
    wt = w[:, None] * taus[None, :]
    n = w.size
    a1 = np.hstack([np.ones((n, 1)), wt**2 / (1 + wt**2)])
    a2 = np.hstack([np.zeros((n, 1)), wt / (1 + wt**2)])
    return a1, a2


def _smoothing_rows(w, e1, e2, taus, smoothing):
    """``smoothing * D2 diag(1/|E*(1/tau_k)|)`` on the ``E_k`` columns (none for < 3 terms)."""
    if smoothing == 0 or taus.size < 3:
        return np.zeros((0, taus.size + 1))
    order = np.argsort(w)
    mag = np.interp(np.log(1 / taus), np.log(w[order]), np.hypot(e1, e2)[order])
    d2 = np.diff(np.eye(taus.size), 2, axis=0) / mag[None, :]
    return smoothing * np.hstack([np.zeros((d2.shape[0], 1)), d2])


def solve_nnls(w, e1, e2, taus, *, smoothing=0.0, loss_floor=1e-4):
    """``(x, rnorm)``: ``x = [E0, E_1..E_n]`` on the ascending ``taus`` and the residual norm."""
    a1, a2 = _design(w, taus)
    s2 = np.maximum(e2, loss_floor * np.hypot(e1, e2))
    a = np.vstack([a1 / e1[:, None], a2 / s2[:, None], _smoothing_rows(w, e1, e2, taus, smoothing)])
    b = np.concatenate([np.ones(w.size), e2 / s2, np.zeros(a.shape[0] - 2 * w.size)])
    colnorm = np.linalg.norm(a, axis=0)
    colnorm[colnorm == 0] = 1.0
    x, rnorm = nnls(a / colnorm, b, maxiter=50 * a.shape[1])
    return x / colnorm, float(rnorm)


def refine_terms(w, e1, e2, E0, moduli, times, *, loss_floor=1e-4, bounds=None):
    """Move the times as well as the moduli: nonlinear least squares from the NNLS solution.

    The unknowns are ``log E0``, ``log E_k`` and ``log tau_k`` (so every term stays positive),
    the residuals the same relative errors as the NNLS fit, with an exact Jacobian. A
    spectrum whose terms fall between the grid's times (a sparse one) is then matched
    instead of approximated by pairs of neighbours. ``bounds`` ``(lo, hi)`` (s) keeps the
    times inside the grid's span. Returns ``(E0, moduli, times)`` with merged equal times.
    """
    from scipy.optimize import least_squares

    s2 = np.maximum(e2, loss_floor * np.hypot(e1, e2))
    n = moduli.size

    def parts(p):
        u = w[:, None] * np.exp(p[1 + n :])[None, :]
        d = 1.0 + u**2
        return np.exp(p[0]), np.exp(p[1 : 1 + n]), u, d

    def residual(p):
        e0, ek, u, d = parts(p)
        return np.concatenate([(e0 + (u**2 / d) @ ek) / e1 - 1.0, ((u / d) @ ek - e2) / s2])

    def jacobian(p):
        e0, ek, u, d = parts(p)
        top = np.hstack([np.full((w.size, 1), e0), ek * u**2 / d, ek * 2 * u**2 / d**2]) / e1[:, None]
        bot = np.hstack([np.zeros((w.size, 1)), ek * u / d, ek * u * (1 - u**2) / d**2]) / s2[:, None]
        return np.vstack([top, bot])

    p0 = np.concatenate([[np.log(E0)], np.log(moduli), np.log(times)])
    lo = np.full(p0.size, -np.inf)
    hi = np.full(p0.size, np.inf)
    if bounds is not None:
        lo[1 + n :], hi[1 + n :] = np.log(bounds[0]), np.log(bounds[1])
        p0[1 + n :] = np.clip(p0[1 + n :], lo[1 + n :] + 1e-9, hi[1 + n :] - 1e-9)
    with blas_limit():  # small dense SVDs (bem.parallel)
        sol = least_squares(
            residual,
            p0,
            jac=jacobian,
            bounds=(lo, hi),
            method="trf",
            x_scale="jac",
            xtol=1e-12,
            ftol=1e-12,
            gtol=1e-12,
            max_nfev=100,
        )
    if not sol.cost <= 0.5 * np.sum(residual(p0) ** 2):
        return E0, moduli, times
    ek, t = merge_close_terms(np.exp(sol.x[1 : 1 + n]), np.exp(sol.x[1 + n :]))
    return float(np.exp(sol.x[0])), ek, t


def merge_close_terms(moduli, times, decades=0.01, rel=1e-10):
    """Terms within ``decades`` of each other merged (moduli summed, times averaged in log
    weighted by modulus) and terms below ``rel`` of the total dropped: nearly repeated
    times make the creep interconversion ill-conditioned and add nothing to the fit."""
    order = np.argsort(times)
    ek, lt = moduli[order], np.log10(times[order])
    group = np.concatenate([[0], np.cumsum(np.diff(lt) > decades)])
    mk = np.bincount(group, weights=ek)
    tk = 10.0 ** (np.bincount(group, weights=ek * lt) / mk)
    keep = mk > rel * mk.sum()
    return mk[keep], tk[keep]


def fit_prony_series(w, e1, e2, taus, *, smoothing=0.0, loss_floor=1e-4, refine=True):
    """NNLS fit in relative error; returns ``(E0, moduli, times, report)`` (zero terms dropped).

    ``w`` (rad/s), ``e1``, ``e2`` (Pa) are validated arrays (see :func:`check_dma`); ``taus``
    (s) ascending or not. With ``refine`` and no smoothing, the terms' times are then moved
    too (:func:`refine_terms`); smoothing is defined on the fixed grid, so it keeps the times.
    Raises InputError when the fit gives ``E0 <= 0``.
    """
    smoothing = check_positive("smoothing", smoothing, allow_zero=True)
    taus = np.sort(np.asarray(taus, dtype=float))
    x, _ = solve_nnls(w, e1, e2, taus, smoothing=smoothing, loss_floor=loss_floor)
    if not x[0] > 0:
        raise InputError(
            "fit_prony: the data imply a relaxed modulus E0 <= 0; extend the data to lower "
            "frequencies or pass times covering them"
        )
    keep = x[1:] > 1e-12 * x.sum()
    E0, moduli, times = float(x[0]), x[1:][keep], taus[keep]
    if refine and smoothing == 0 and moduli.size:
        E0, moduli, times = refine_terms(
            w, e1, e2, E0, moduli, times, loss_floor=loss_floor, bounds=(taus[0], taus[-1])
        )
    a1, a2 = _design(w, times)
    x = np.concatenate([[E0], moduli])
    fitted = a1 @ x + 1j * (a2 @ x)
    errs = relative_errors(fitted, e1, np.maximum(e2, loss_floor * np.hypot(e1, e2)))
    report = FitReport(
        *errs, terms=int(moduli.size), smoothing=smoothing, frequency_band=(float(w.min()), float(w.max()))
    )
    return E0, moduli, times, report
