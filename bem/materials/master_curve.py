"""Master curves: isothermal DMA sweeps shifted onto one curve, a shift law, a Prony series.

Time-temperature superposition (see :mod:`bem.materials.temperature`) says that the sweep measured at
temperature ``T`` is the reference master curve seen at reduced frequencies
``a_T(T) w``. Given sweeps at several temperatures:

1. **Segments.** Points whose temperatures lie within ``temperature_tolerance`` (K) of
   their neighbour in sorted order form one isothermal segment at their mean temperature.
2. **Pairwise shifts by overlap.** For two segments ``i`` (colder) and ``j`` the shift
   ``d = log10 a_j - log10 a_i`` minimises the mean squared mismatch of both ``log E'`` and
   ``log E''`` where the shifted segment overlaps the other (each segment's points against
   the other's linear interpolant in ``log w``): a grid search (0.02 decades) over every
   shift that leaves at least ``min_overlap`` of the narrower span in common, then a
   bounded scalar refinement. ``E''`` as well as ``E'`` keeps the rubbery and glassy
   plateaus, where ``E'`` is flat, determined.
3. **All overlapping pairs.** Neighbours must overlap; pairs up to ``reach`` segments apart
   are added when they overlap around the chained estimate, and the shifts solve
   ``a_j - a_i = d_ij`` in least squares, which averages pairwise errors instead of summing
   them along the chain.
4. **Anchoring.** The shifts are made zero at the reference temperature (linear
   interpolation between the two nearest segments when it was not measured).
5. **Law.** WLF (nonlinear least squares) or Arrhenius (linear) through the shifts.
6. **Series.** The data are shifted by the fitted law (not by the measured shifts), so that
   the returned material and law reproduce the data together,
   ``material.at_temperature(T, law)``, and the Prony series is fitted to them.

Where the shifts are uncertain (1 % noise: a few hundredths of a decade), the reference
curve far from the reference temperature's own window carries that uncertainty, while the
material at each measured temperature still matches its data.

The Prony fit itself is :func:`bem.materials.prony_fit.fit_prony_series` (relative error in each
modulus).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

from ..checks import check_array, check_positive, check_range
from ..errors import InputError
from .prony_fit import FitReport, check_dma, default_times, fit_prony_series
from .temperature import fit_arrhenius, fit_wlf

__all__ = ["MasterCurveReport", "fit_master_curve", "segments"]

LAWS = {"wlf": fit_wlf, "arrhenius": fit_arrhenius}


@dataclass(frozen=True)
class MasterCurveReport(FitReport):
    """A Prony fit report (relative errors of the fit against the data shifted by the law)
    plus the shifts.

    Attributes
    ----------
    temperatures : tuple of float
        Segment temperatures, K, ascending.
    log_shift : tuple of float
        ``log10 a_T`` of each segment from the overlap shifting, anchored
        at the reference temperature.
    law_log_shift : tuple of float
        ``log10 a_T`` of the fitted law at the same temperatures.
    law_rms : float
        Root-mean-square of ``log_shift - law_log_shift``, decades.
    law : WLF or Arrhenius
        The fitted law (also returned beside the material).
    """

    temperatures: tuple = ()
    log_shift: tuple = ()
    law_log_shift: tuple = ()
    law_rms: float = 0.0
    law: object = None

    def as_dict(self):
        out = super().as_dict()
        out.update(
            temperatures=list(self.temperatures),
            log_shift=list(self.log_shift),
            law_log_shift=list(self.law_log_shift),
            law_rms=self.law_rms,
            law={"name": type(self.law).__name__, **vars(self.law)} if self.law is not None else None,
        )
        return out


def segments(temperatures, tolerance=0.5):
    """Segment index of each point (0 = coldest) and the segment temperatures (K, mean)."""
    T = np.asarray(temperatures, dtype=float)
    order = np.argsort(T, kind="stable")
    starts = np.concatenate([[True], np.diff(T[order]) > tolerance])
    label = np.empty(T.size, dtype=int)
    label[order] = np.cumsum(starts) - 1
    means = np.array([T[label == k].mean() for k in range(label.max() + 1)])
    return label, means


class _Segment:
    """One isothermal sweep: log10 w, log10 E', log10 E'' and their linear interpolants."""

    def __init__(self, lw, l1, l2):
        order = np.argsort(lw)
        self.lw, self.l1, self.l2 = lw[order], l1[order], l2[order]
        self.lo, self.hi = self.lw[0], self.lw[-1]

    def p1(self, x):
        return np.interp(x, self.lw, self.l1)

    def p2(self, x):
        return np.interp(x, self.lw, self.l2)


def _mismatch(a, b, d, min_overlap):
    """Mean squared log-modulus mismatch of ``a`` and ``b`` shifted by ``d`` decades."""
    lo, hi = max(a.lo, b.lo + d), min(a.hi, b.hi + d)
    need = min_overlap * min(a.hi - a.lo, b.hi - b.lo)
    if hi - lo < need:
        return np.inf
    ib = (b.lw + d >= lo) & (b.lw + d <= hi)
    ia = (a.lw >= lo) & (a.lw <= hi)
    if ia.sum() + ib.sum() < 3:
        return np.inf
    r = np.concatenate(
        [
            a.p1(b.lw[ib] + d) - b.l1[ib],
            a.p2(b.lw[ib] + d) - b.l2[ib],
            a.l1[ia] - b.p1(a.lw[ia] - d),
            a.l2[ia] - b.p2(a.lw[ia] - d),
        ]
    )
    return float(np.mean(r**2))


def pairwise_shift(a, b, min_overlap=0.3, step=0.02, around=None, window=0.5):
    """Shift ``d`` (decades of frequency) of segment ``b`` that best overlays it on ``a``.

    The grid spans every shift with some overlap, or ``around +- window`` when given; None
    when no shift on it leaves ``min_overlap`` in common (with ``around``: when any fails to).
    """
    if around is None:
        grid = np.arange(a.lo - b.hi, a.hi - b.lo + step, step)
    else:
        grid = np.arange(around - window, around + window + step, step)
    cost = np.array([_mismatch(a, b, d, min_overlap) for d in grid])
    if not np.isfinite(cost).any() or (around is not None and not np.isfinite(cost).all()):
        return None  # a search near an estimate must not end on the edge of the overlap
    best = grid[np.argmin(cost)]
    res = minimize_scalar(
        lambda d: min(_mismatch(a, b, d, min_overlap), 1e30),
        bounds=(best - step, best + step),
        method="bounded",
        options={"xatol": 1e-6},
    )
    return float(res.x) if res.fun <= cost.min() else float(best)


def chain_shifts(segs, min_overlap=0.3, reach=3, max_mismatch=0.05, temps=None):
    """``log10 a`` of every segment (the first at 0) from the shifts of all overlapping pairs.

    Neighbours must overlap; segments up to ``reach`` apart contribute when they do, searched
    near the chained estimate. The shifts solve ``a_j - a_i = d_ij`` in least squares, which
    averages the pairwise errors instead of summing them along the chain. Neighbours whose
    best overlay still differs by more than ``max_mismatch`` (rms of log10 moduli) do not
    superpose: too far apart in temperature, or not thermorheologically simple.
    """
    temps = np.arange(len(segs)) if temps is None else temps
    steps = []
    for k in range(len(segs) - 1):
        d = pairwise_shift(segs[k], segs[k + 1], min_overlap)
        if d is None:
            raise InputError(
                f"master curve: the sweeps at {temps[k]:g} K and {temps[k + 1]:g} K cannot overlap "
                f"by min_overlap = {min_overlap:g} of their span; measure closer temperatures or "
                "wider frequency sweeps"
            )
        misfit = np.sqrt(_mismatch(segs[k], segs[k + 1], d, min_overlap))
        if misfit > max_mismatch:
            raise InputError(
                f"master curve: the sweeps at {temps[k]:g} K and {temps[k + 1]:g} K do not overlay "
                f"(rms log10 mismatch {misfit:.3g} > max_mismatch = {max_mismatch:g}); they are "
                "too far apart in temperature to overlap, or the material is not "
                "thermorheologically simple there"
            )
        steps.append(d)
    chained = np.concatenate([[0.0], np.cumsum(steps)])
    rows, rhs = [], []
    for i in range(len(segs)):
        for j in range(i + 1, min(i + reach + 1, len(segs))):
            d = (
                steps[i]
                if j == i + 1
                else pairwise_shift(segs[i], segs[j], min_overlap, around=chained[j] - chained[i])
            )
            if d is not None:
                row = np.zeros(len(segs))
                row[i], row[j] = -1.0, 1.0
                rows.append(row)
                rhs.append(d)
    a = np.array(rows)[:, 1:]
    sol = np.linalg.lstsq(a, np.array(rhs), rcond=None)[0]
    return np.concatenate([[0.0], sol])


def _anchor(temps, chained, reference_temperature):
    if not temps[0] <= reference_temperature <= temps[-1]:
        raise InputError(
            f"reference_temperature must lie within the measured temperatures "
            f"[{temps[0]:g}, {temps[-1]:g}] K, got {reference_temperature!r}"
        )
    return chained - np.interp(reference_temperature, temps, chained)


def _check_inputs(frequencies, temperatures, storage, loss, hz):
    w, e1, e2 = check_dma(frequencies, storage, loss, hz=hz)
    T = check_array("temperatures", temperatures, ndim=1, positive=True)
    if T.shape != w.shape:
        raise InputError(f"temperatures must have one entry per frequency ({w.size}), got {T.size}")
    if np.any(e2 <= 0):
        raise InputError("loss must be > 0 Pa everywhere for a master curve (its logarithm is shifted)")
    return w, T, e1, e2


def fit_master_curve(
    frequencies,
    temperatures,
    storage,
    loss,
    *,
    reference_temperature,
    shift="wlf",
    hz=False,
    terms_per_decade=3.0,
    smoothing=0.0,
    temperature_tolerance=0.5,
    min_overlap=0.3,
    reach=3,
    max_mismatch=0.05,
):
    """Master curve, shift law and Prony series from multi-temperature DMA data.

    Parameters are those of :meth:`bem.Material.fit_master_curve`. Returns
    ``(E0, moduli, times, law, report)`` with ``report`` a :class:`MasterCurveReport`.
    """
    w, T, e1, e2 = _check_inputs(frequencies, temperatures, storage, loss, hz)
    if shift not in LAWS:
        raise InputError(f"shift must be one of {', '.join(map(repr, LAWS))}, got {shift!r}")
    tref = check_positive("reference_temperature (K)", reference_temperature)
    tol = check_positive("temperature_tolerance (K)", temperature_tolerance)
    min_overlap = check_range("min_overlap", min_overlap, 0.0, 1.0)
    label, temps = segments(T, tol)
    if temps.size < 3:
        raise InputError(f"master curve needs sweeps at >= 3 temperatures (to fit a law), got {temps.size}")
    lw, l1, l2 = np.log10(w), np.log10(e1), np.log10(e2)
    segs = [_Segment(lw[label == k], l1[label == k], l2[label == k]) for k in range(temps.size)]
    log_a = _anchor(temps, chain_shifts(segs, min_overlap, reach, max_mismatch, temps), tref)
    taus = default_times(np.concatenate([w * 10.0 ** log_a.min(), w * 10.0 ** log_a.max()]), terms_per_decade)
    law = LAWS[shift](temps, log_a, tref)
    E0, moduli, times, rep = fit_prony_series(w * 10.0 ** law(T), e1, e2, taus, smoothing=smoothing)
    law_a = law(temps)
    report = MasterCurveReport(
        **{f: getattr(rep, f) for f in FitReport.__dataclass_fields__},
        temperatures=tuple(temps.tolist()),
        log_shift=tuple(log_a.tolist()),
        law_log_shift=tuple(np.atleast_1d(law_a).tolist()),
        law_rms=float(np.sqrt(np.mean((log_a - law_a) ** 2))),
        law=law,
    )
    return E0, moduli, times, law, report
