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

from .checks import check_array, check_positive
from .errors import InputError

__all__ = ["FitReport", "fit_prony_series", "relative_errors"]


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
        return {"storage_max": self.storage_max, "storage_rms": self.storage_rms,
                "loss_max": self.loss_max, "loss_rms": self.loss_rms, "terms": self.terms,
                "smoothing": self.smoothing, "frequency_band": list(self.frequency_band)}


def relative_errors(fitted, storage, loss):
    """``(max, rms)`` of ``|E'_fit/E' - 1|`` and of ``|E''_fit/E'' - 1|`` (4 floats)."""
    r1 = fitted.real / storage - 1.0
    r2 = fitted.imag / loss - 1.0
    return (float(np.max(np.abs(r1))), float(np.sqrt(np.mean(r1**2))),
            float(np.max(np.abs(r2))), float(np.sqrt(np.mean(r2**2))))


def check_dma(frequencies, storage, loss, hz=False):
    """Validated ``(w (rad/s), E' (Pa), E'' (Pa))`` arrays of one length."""
    w = check_array("frequencies", frequencies, ndim=1, positive=True)
    if hz:
        w = 2 * np.pi * w
    e1 = check_array("storage", storage, ndim=1, positive=True)
    e2 = check_array("loss", loss, ndim=1)
    if not (w.shape == e1.shape == e2.shape):
        raise InputError(f"frequencies, storage and loss must have the same length, got "
                         f"{w.size}, {e1.size}, {e2.size}")
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


def fit_prony_series(w, e1, e2, taus, *, smoothing=0.0, loss_floor=1e-4):
    """NNLS fit in relative error; returns ``(E0, moduli, times, report)`` (zero terms dropped).

    ``w`` (rad/s), ``e1``, ``e2`` (Pa) are validated arrays (see :func:`check_dma`); ``taus``
    (s) ascending or not. Raises InputError when the fit gives ``E0 <= 0``.
    """
    smoothing = check_positive("smoothing", smoothing, allow_zero=True)
    taus = np.sort(np.asarray(taus, dtype=float))
    a1, a2 = _design(w, taus)
    mag = np.hypot(e1, e2)
    s2 = np.maximum(e2, loss_floor * mag)
    a = np.vstack([a1 / e1[:, None], a2 / s2[:, None], _smoothing_rows(w, e1, e2, taus, smoothing)])
    b = np.concatenate([np.ones(w.size), e2 / s2, np.zeros(a.shape[0] - 2 * w.size)])
    colnorm = np.linalg.norm(a, axis=0)
    colnorm[colnorm == 0] = 1.0
    x, _ = nnls(a / colnorm, b, maxiter=50 * a.shape[1])
    x = x / colnorm
    if not x[0] > 0:
        raise InputError("fit_prony: the data imply a relaxed modulus E0 <= 0; extend the data to lower "
                         "frequencies or pass times covering them")
    keep = x[1:] > 1e-12 * x.sum()
    moduli, times = x[1:][keep], taus[keep]
    fitted = a1 @ x + 1j * (a2 @ x)
    errs = relative_errors(fitted, e1, np.maximum(e2, loss_floor * mag))
    report = FitReport(*errs, terms=int(moduli.size), smoothing=smoothing,
                       frequency_band=(float(w.min()), float(w.max())))
    return float(x[0]), moduli, times, report
