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

from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import nnls

from ..checks import check_array, check_positive
from ..errors import InputError
from ..parallel import blas_limit
from .coverage import PLATEAU_SLOPE, end_slopes

__all__ = ["FitReport", "SeriesModel", "fit_prony_series", "relative_errors", "solve_nnls", "worst_points"]


@dataclass(frozen=True)
class FitReport:
    """How well a fitted series reproduces the data it was fitted to, and what the data cover.

    Attributes
    ----------
    storage_max, storage_rms : float
        Max and root-mean-square of ``|E'_fit / E' - 1|`` over the data points.
    loss_max, loss_rms : float
        The same for ``E''``, against the measured ``E''`` (the fit's weight floor of tiny loss
        values plays no part here; a measured ``E'' = 0`` counts against that floor).
    terms : int
        Prony terms kept (non-zero).
    smoothing : float
        The regularisation parameter used.
    frequency_band : tuple of float
        ``(w_min, w_max)`` of the data, rad/s, in the frame of the material the report belongs
        to: for a master curve the reduced frequencies at its reference temperature, for the
        same material moved to ``T`` (:meth:`bem.Material.at_temperature`) the band at ``T``.
    relaxed_modulus, glassy_modulus : float
        ``E0`` and ``E_inf`` of the fit, Pa.
    end_slopes : tuple of float
        Log-slope ``d ln E' / d ln w`` at the low and high ends of the band
        (:func:`bem.materials.coverage.end_slopes`): small where the data reach a plateau.
    worst_storage, worst_loss : tuple of dict
        The points with the largest relative errors, worst first: ``frequency`` (rad/s,
        measured), ``measured`` and ``fitted`` moduli (Pa), ``error``; master curves add
        ``temperature`` (K) and ``reduced_frequency`` (rad/s).
    """

    storage_max: float
    storage_rms: float
    loss_max: float
    loss_rms: float
    terms: int
    smoothing: float
    frequency_band: tuple
    relaxed_modulus: float = float("nan")
    glassy_modulus: float = float("nan")
    end_slopes: tuple = (0.0, 0.0)
    worst_storage: tuple = ()
    worst_loss: tuple = ()

    @property
    def relaxed_reached(self):
        """True when the data reach the relaxed plateau (:mod:`bem.materials.coverage`)."""
        return self.end_slopes[0] <= PLATEAU_SLOPE

    @property
    def glassy_reached(self):
        """True when the data reach the glassy plateau."""
        return self.end_slopes[1] <= PLATEAU_SLOPE

    def shifted(self, log_shift):
        """The report of the material moved by ``log10 a_T = log_shift``: the band divided by
        ``a_T``, everything else unchanged."""
        factor = 10.0**log_shift
        lo, hi = self.frequency_band
        return replace(self, frequency_band=(lo / factor, hi / factor))

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
            "relaxed_modulus": self.relaxed_modulus,
            "glassy_modulus": self.glassy_modulus,
            "end_slopes": list(self.end_slopes),
            "relaxed_reached": self.relaxed_reached,
            "glassy_reached": self.glassy_reached,
            "worst_storage": [dict(p) for p in self.worst_storage],
            "worst_loss": [dict(p) for p in self.worst_loss],
        }


def relative_errors(fitted, storage, loss, loss_floor=None):
    """``(max, rms)`` of ``|E'_fit/E' - 1|`` and of ``|E''_fit/E'' - 1|`` (4 floats).

    ``loss_floor`` (Pa, array) stands in for measured zeros of ``E''`` only.
    """
    r1 = fitted.real / storage - 1.0
    r2 = fitted.imag / (loss if loss_floor is None else np.where(loss > 0, loss, loss_floor)) - 1.0
    return (
        float(np.max(np.abs(r1))),
        float(np.sqrt(np.mean(r1**2))),
        float(np.max(np.abs(r2))),
        float(np.sqrt(np.mean(r2**2))),
    )


def worst_points(w, measured, fitted, *, count=3, temperatures=None, measured_frequency=None):
    """The ``count`` points with the largest ``|fitted / measured - 1|``, worst first (dicts).

    ``w`` (rad/s) is the frequency of the fit's frame; with ``temperatures`` (K) the points are
    labelled by temperature and ``measured_frequency`` too (a master curve).
    """
    err = np.abs(fitted / measured - 1.0)
    out = []
    for i in np.argsort(-err, kind="stable")[:count]:
        point = {"frequency": float(w[i] if measured_frequency is None else measured_frequency[i])}
        if temperatures is not None:
            point.update(temperature=float(temperatures[i]), reduced_frequency=float(w[i]))
        point.update(measured=float(measured[i]), fitted=float(fitted[i]), error=float(err[i]))
        out.append(point)
    return tuple(out)


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


class SeriesModel:
    """Relative residuals of a Prony series (and optionally a shift law) on DMA data, and their
    exact Jacobian, in the unknowns ``p = [log E0, log E_k, log tau_k, law parameters]``.

    ``w`` (rad/s), ``e1``, ``e2`` (Pa): the data; with a shift ``law`` and each point's
    ``temperatures`` (K), ``w`` are measured frequencies and the series sees ``w a_T(T)``.
    The Jacobian of a law parameter ``c`` is ``ln 10 (d log10 a_T / dc) sum_k dr / d ln tau_k``:
    the response depends on ``w tau_k`` only.
    """

    def __init__(self, w, e1, e2, terms, *, loss_floor=1e-4, law=None, temperatures=None):
        self.w, self.e1, self.e2, self.n = w, e1, e2, terms
        self.s2 = np.maximum(e2, loss_floor * np.hypot(e1, e2))
        self.law, self.temperatures = law, temperatures
        self.m = 0 if law is None else law.parameters.size

    def pack(self, E0, moduli, times, law=None):
        return np.concatenate([[np.log(E0)], np.log(moduli), np.log(times), [] if law is None else law.parameters])

    def unpack(self, p):
        """``(E0, moduli, times, law)``."""
        n = self.n
        law = None if self.m == 0 else self.law.with_parameters(p[1 + 2 * n :])
        return float(np.exp(p[0])), np.exp(p[1 : 1 + n]), np.exp(p[1 + n : 1 + 2 * n]), law

    def _parts(self, p):
        e0, ek, tk, law = self.unpack(p)
        w = self.w if law is None else self.w * 10.0 ** law(self.temperatures)
        u = w[:, None] * tk[None, :]
        return e0, ek, u, 1.0 + u**2, law

    def residual(self, p):
        e0, ek, u, d, _ = self._parts(p)
        return np.concatenate([(e0 + (u**2 / d) @ ek) / self.e1 - 1.0, ((u / d) @ ek - self.e2) / self.s2])

    def jacobian(self, p):
        e0, ek, u, d, law = self._parts(p)
        e1, s2 = self.e1[:, None], self.s2[:, None]
        t_top = ek * 2 * u**2 / d**2 / e1
        t_bot = ek * u * (1 - u**2) / d**2 / s2
        top = [np.full((self.w.size, 1), e0) / e1, ek * u**2 / d / e1, t_top]
        bot = [np.zeros((self.w.size, 1)), ek * u / d / s2, t_bot]
        if law is not None:
            g = np.log(10.0) * law.gradient(self.temperatures).T
            top.append(t_top.sum(axis=1)[:, None] * g)
            bot.append(t_bot.sum(axis=1)[:, None] * g)
        return np.vstack([np.hstack(top), np.hstack(bot)])


def refine_terms(w, e1, e2, E0, moduli, times, *, loss_floor=1e-4, bounds=None, law=None, temperatures=None):
    """Move the times as well as the moduli: nonlinear least squares from the NNLS solution.

    The unknowns are ``log E0``, ``log E_k`` and ``log tau_k`` (so every term stays positive),
    the residuals the same relative errors as the NNLS fit, with an exact Jacobian
    (:class:`SeriesModel`). A spectrum whose terms fall between the grid's times (a sparse one)
    is then matched instead of approximated by pairs of neighbours. ``bounds`` ``(lo, hi)`` (s)
    keeps the times inside the grid's span.

    With a shift ``law`` (:mod:`bem.materials.temperature`) and each point's ``temperatures``
    (K), ``w`` are the measured frequencies and the law's parameters are unknowns too: the joint
    fit of the series and the law.

    Returns ``(E0, moduli, times, law)`` with merged equal times (``law`` None without one).
    """
    from scipy.optimize import least_squares

    model = SeriesModel(w, e1, e2, moduli.size, loss_floor=loss_floor, law=law, temperatures=temperatures)
    n = moduli.size
    p0 = model.pack(E0, moduli, times, law)
    lo = np.full(p0.size, -np.inf)
    hi = np.full(p0.size, np.inf)
    if bounds is not None:
        lo[1 + n : 1 + 2 * n], hi[1 + n : 1 + 2 * n] = np.log(bounds[0]), np.log(bounds[1])
    if model.m:
        lo[1 + 2 * n :], hi[1 + 2 * n :] = law.parameter_bounds(temperatures)
    inside = np.isfinite(lo)  # start strictly inside finite bounds
    p0[inside] = np.maximum(p0[inside], lo[inside] + 1e-9 * (1 + np.abs(lo[inside])))
    inside = np.isfinite(hi)
    p0[inside] = np.minimum(p0[inside], hi[inside] - 1e-9 * (1 + np.abs(hi[inside])))
    # small dense SVDs (BLAS threads as bem.parallel sets them); a trial step may overflow (an
    # infinite cost, rejected)
    with blas_limit(), np.errstate(over="ignore", invalid="ignore"):
        sol = least_squares(
            model.residual,
            p0,
            jac=model.jacobian,
            bounds=(lo, hi),
            method="trf",
            x_scale="jac",
            xtol=1e-12,
            ftol=1e-12,
            gtol=1e-12,
            max_nfev=300,
        )
    if not sol.cost <= 0.5 * np.sum(model.residual(p0) ** 2):
        return E0, moduli, times, law
    e0, ek, tk, fitted = model.unpack(sol.x)
    ek, t = merge_close_terms(ek, tk)
    return e0, ek, t, fitted


def merge_close_terms(moduli, times, decades=0.01, rel=1e-10):
    """Terms within ``decades`` of each other merged (moduli summed, times averaged in log
    weighted by modulus) and terms below ``rel`` of the total dropped: nearly repeated
    times make the creep interconversion ill-conditioned and add nothing to the fit."""
    order = np.argsort(times)
    ek, lt = moduli[order], np.log10(times[order])
    group = np.concatenate([[0], np.cumsum(np.diff(lt) > decades)])
    mk = np.bincount(group, weights=ek)
    keep = mk > rel * mk.sum()  # also drops groups whose moduli underflowed to zero
    tk = 10.0 ** (np.bincount(group, weights=ek * lt)[keep] / mk[keep])
    return mk[keep], tk


def grid_fit(w, e1, e2, taus, *, smoothing=0.0, loss_floor=1e-4):
    """NNLS on the times ``taus`` (s): ``(E0, moduli, times)`` of the non-zero terms, times
    ascending; ``E0`` may come out 0 (:func:`no_relaxed_modulus`)."""
    taus = np.sort(np.asarray(taus, dtype=float))
    x, _ = solve_nnls(w, e1, e2, taus, smoothing=smoothing, loss_floor=loss_floor)
    keep = x[1:] > 1e-12 * x.sum()
    return float(x[0]), x[1:][keep], taus[keep]


def no_relaxed_modulus(who, w, e1, advice):
    """The InputError of a fit whose relaxed modulus comes out <= 0, naming the data's lowest
    frequency ``w`` (rad/s, in the fit's frame) and ``E'`` (Pa) there."""
    low = int(np.argmin(w))
    return InputError(
        f"{who}: the data imply a relaxed modulus E0 <= 0: at their lowest frequency ({w[low]:.3g} rad/s, "
        f"E' = {e1[low]:.4g} Pa) the material is still relaxing steeply; {advice}"
    )


def fit_prony_series(w, e1, e2, taus, *, smoothing=0.0, loss_floor=1e-4, refine=True):
    """NNLS fit in relative error; returns ``(E0, moduli, times, report)`` (zero terms dropped).

    ``w`` (rad/s), ``e1``, ``e2`` (Pa) are validated arrays (see :func:`check_dma`); ``taus``
    (s) ascending or not. With ``refine`` and no smoothing, the terms' times are then moved
    too (:func:`refine_terms`); smoothing is defined on the fixed grid, so it keeps the times.
    Raises InputError when the fit gives ``E0 <= 0``.
    """
    smoothing = check_positive("smoothing", smoothing, allow_zero=True)
    taus = np.sort(np.asarray(taus, dtype=float))
    E0, moduli, times = grid_fit(w, e1, e2, taus, smoothing=smoothing, loss_floor=loss_floor)
    if not E0 > 0:
        raise no_relaxed_modulus("fit_prony", w, e1, "extend the data to lower frequencies or pass times covering them")
    if refine and smoothing == 0 and moduli.size:
        E0, moduli, times, _ = refine_terms(
            w, e1, e2, E0, moduli, times, loss_floor=loss_floor, bounds=(taus[0], taus[-1])
        )
    return E0, moduli, times, make_report(w, e1, e2, E0, moduli, times, smoothing=smoothing, loss_floor=loss_floor)


def make_report(
    w, e1, e2, E0, moduli, times, *, smoothing=0.0, loss_floor=1e-4, temperatures=None, measured_frequency=None
):
    """The :class:`FitReport` of the series ``(E0, moduli, times)`` on the data ``w, e1, e2``
    (labelled by ``temperatures`` and ``measured_frequency`` for a master curve)."""
    a1, a2 = _design(w, times)
    x = np.concatenate([[E0], moduli])
    fitted = a1 @ x + 1j * (a2 @ x)
    floor = loss_floor * np.hypot(e1, e2)
    e2_nz = np.where(e2 > 0, e2, floor)
    labels = {"temperatures": temperatures, "measured_frequency": measured_frequency}
    return FitReport(
        *relative_errors(fitted, e1, e2, floor),
        terms=int(moduli.size),
        smoothing=smoothing,
        frequency_band=(float(w.min()), float(w.max())),
        relaxed_modulus=float(E0),
        glassy_modulus=float(E0 + np.sum(moduli)),
        end_slopes=end_slopes(w, E0, moduli, times),
        worst_storage=worst_points(w, e1, fitted.real, **labels),
        worst_loss=worst_points(w, e2_nz, fitted.imag, **labels),
    )
