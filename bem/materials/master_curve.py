"""Master curves: isothermal DMA sweeps shifted onto one curve, a shift law, a Prony series.

Time-temperature superposition (see :mod:`bem.materials.temperature`) says that the sweep
measured at temperature ``T`` is the reference master curve seen at reduced frequencies
``a_T(T) w``. Given sweeps at several temperatures:

1. **Segments.** Points whose temperatures lie within ``temperature_tolerance`` (K) of
   their neighbour in sorted order form one isothermal segment at their mean temperature.
2. **Overlap shifts.** For two segments ``i`` (colder) and ``j`` the shift
   ``d = log10 a_j - log10 a_i`` minimises the mean squared mismatch of both ``log E'`` and
   ``log E''`` where the shifted segment overlaps the other (each segment's points against
   the other's cubic spline in ``log w``): a grid search (0.02 decades) over every shift
   that leaves at least ``min_overlap`` decades in common, then a bounded scalar
   refinement. ``E''`` as well as ``E'`` keeps the plateaus, where ``E'`` is flat,
   determined. Neighbours whose best overlay leaves more than ``max_mismatch`` (rms, decades)
   do not overlap: the data there are a gap. Neighbours that overlap form a chain; pairs up to
   ``reach`` segments apart in a chain are added when they overlap around the chained
   estimate, and the chain's shifts solve ``a_j - a_i = d_ij`` in least squares (relative to
   its first segment).
3. **Law, anchored.** The law is fitted to the chains' shifts with a free additive constant
   per chain (:func:`bem.materials.temperature.fit_law`), and the constants are removed: the
   law is zero at the reference temperature by its form, whether or not a sweep was
   measured there. Where the chains hold too few shifts for the law (sweeps that do not
   overlap), the start is the best of a coarse grid of laws, each scored by the Prony fit to
   the data it shifts.
4. **Joint fit.** The law's parameters are then fitted together with the series: first by
   variable projection (for each law the non-negative Prony fit on a fixed grid of times,
   the law's parameters moved to minimise its residual), then by one nonlinear least-squares
   fit of the law's parameters, the moduli and the times
   (:func:`bem.materials.prony_fit.refine_terms`). No overlap is needed: the law's form and
   the series' Kramers-Kronig consistency between ``E'`` and ``E''`` place each sweep. An
   imposed law (``shift`` a :class:`~bem.materials.temperature.WLF` or
   :class:`~bem.materials.temperature.Arrhenius`) is used as it is: only the series is fitted.
5. **Check.** Every sweep must be reproduced by the master curve under the law within
   ``max_mismatch`` (rms of log10 moduli); otherwise the material is not thermorheologically
   simple there, or a temperature is wrong, and an InputError names the sweeps. A sweep missed
   by more than 4 times the median sweep's misfit (and by more than 0.01 decade) is named in
   the report's ``notes`` and the material's ``warnings``.

The report (:class:`MasterCurveReport`) gives the fit's errors against the data, its worst
points, the data's reduced-frequency band and plateau flags (:mod:`bem.materials.coverage`),
the overlap shifts anchored by the law's constant, the law's shifts, and the gaps.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import least_squares, minimize_scalar

from ..checks import check_array, check_positive
from ..errors import InputError
from ..parallel import blas_limit
from .prony_fit import (
    FitReport,
    SeriesModel,
    check_dma,
    default_times,
    grid_fit,
    make_report,
    no_relaxed_modulus,
    refine_terms,
    solve_nnls,
)
from .temperature import WLF, Arrhenius, check_kelvin, fit_law, wlf_c2_min

__all__ = ["MasterCurveReport", "fit_master_curve", "segments", "neighbour_shifts", "overlap_shifts", "band_gaps"]

LAWS = {"wlf": WLF, "arrhenius": Arrhenius}
NNLS_FLOOR = 1e-4  # E'' below this fraction of |E*| is weighted as if it were that size
MAX_TRIAL_SHIFT = 30.0  # decades: a trial law shifting data further is not a candidate (and w tau stays < 1e70)
LAW_NOISE_FLOOR = 1e-3  # relative noise assumed at least in the law's uncertainty (DMA moduli are not known better)
LAW_SIGMA_WARN = 0.05  # decades of log10 a_T (12 % in a_T): a fitted law less certain than this is named
OUTLIER_RATIO = 4.0  # a sweep missed by this many times the median sweep's misfit is named...
OUTLIER_FLOOR = 0.01  # ...when its misfit also exceeds this (rms decades; noise-free fits are exact)


@dataclass(frozen=True)
class MasterCurveReport(FitReport):
    """A Prony fit report (relative errors of the fit against the data shifted by the law)
    plus the shifts.

    Attributes
    ----------
    temperatures : tuple of float
        Segment temperatures, K, ascending.
    log_shift : tuple of float
        ``log10 a_T`` of each segment from overlaying it on its neighbours, anchored by the
        law's constant (step 3 of :mod:`bem.materials.master_curve`); NaN for a segment that
        overlaps none of its neighbours.
    law_log_shift : tuple of float
        ``log10 a_T`` of the law at the same temperatures.
    law_rms : float
        Root-mean-square of ``log_shift - law_log_shift`` over the segments that overlap,
        decades (NaN when none do).
    law : WLF or Arrhenius
        The law (also returned beside the material).
    law_imposed : bool
        True when the law was given, False when it was fitted.
    gaps : tuple of (float, float)
        Temperatures (K) of neighbouring segments that do not overlap: the shift between
        them rests on the law's form and the series' continuity alone.
    band_gaps : tuple of (float, float, float, float)
        Holes wider than 0.1 decade in the band the shifted sweeps cover:
        ``(w_1, w_2, T_1, T_2)``, no data between ``w_1`` and ``w_2`` (rad/s, in the report's
        frame), the sweeps at ``T_1`` and ``T_2`` (K) ending and starting there. The material
        there is the fit's interpolation.
    """

    temperatures: tuple = ()
    log_shift: tuple = ()
    law_log_shift: tuple = ()
    law_rms: float = float("nan")
    law: object = None
    law_imposed: bool = False
    gaps: tuple = ()
    band_gaps: tuple = ()
    law_sigma: tuple = ()
    notes: tuple = ()

    def shifted(self, log_shift):
        factor = 10.0**log_shift
        out = super().shifted(log_shift)
        return replace(out, band_gaps=tuple((a / factor, b / factor, t1, t2) for a, b, t1, t2 in self.band_gaps))

    def as_dict(self):
        def number(x):
            return None if not np.isfinite(x) else float(x)

        out = super().as_dict()
        out.update(
            temperatures=list(self.temperatures),
            log_shift=[number(x) for x in self.log_shift],
            law_log_shift=list(self.law_log_shift),
            law_rms=number(self.law_rms),
            law={"name": type(self.law).__name__, **vars(self.law)} if self.law is not None else None,
            law_imposed=self.law_imposed,
            gaps=[list(g) for g in self.gaps],
            band_gaps=[list(g) for g in self.band_gaps],
            law_sigma=list(self.law_sigma),
            notes=list(self.notes),
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
    """One isothermal sweep: log10 w, log10 E', log10 E'' and their cubic splines in log10 w
    (tabulated every 0.002 decade and read by linear interpolation, which is as accurate and
    far faster in the overlap search)."""

    def __init__(self, lw, l1, l2):
        order = np.argsort(lw)
        lw, l1, l2 = lw[order], l1[order], l2[order]
        keep = np.concatenate([[True], np.diff(lw) > 1e-12])  # repeated frequencies: the first
        self.lw, self.l1, self.l2 = lw[keep], l1[keep], l2[keep]
        self.lo, self.hi = self.lw[0], self.lw[-1]
        if self.lw.size >= 2:
            self.x = np.linspace(self.lo, self.hi, max(int((self.hi - self.lo) / 0.002), 1) + 1)
            self.t1 = CubicSpline(self.lw, self.l1)(self.x)
            self.t2 = CubicSpline(self.lw, self.l2)(self.x)

    def p1(self, x):
        return np.interp(x, self.x, self.t1)

    def p2(self, x):
        return np.interp(x, self.x, self.t2)


def _mismatch(a, b, d, min_overlap):
    """Mean squared log-modulus mismatch of ``a`` and ``b`` shifted by ``d`` decades."""
    lo, hi = max(a.lo, b.lo + d), min(a.hi, b.hi + d)
    if hi - lo < min_overlap or a.lw.size < 2 or b.lw.size < 2:
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


def _mismatch_grid(a, b, grid, min_overlap):
    """:func:`_mismatch` at every shift of ``grid`` at once (the same numbers, vectorised)."""
    if a.lw.size < 2 or b.lw.size < 2:
        return np.full(grid.size, np.inf)
    d = grid[:, None]
    lo, hi = np.maximum(a.lo, b.lo + d), np.minimum(a.hi, b.hi + d)
    xb = b.lw[None, :] + d  # b's points in a's frame
    ib = (xb >= lo) & (xb <= hi)
    ia = (a.lw[None, :] >= lo) & (a.lw[None, :] <= hi)
    xa = a.lw[None, :] - d  # a's points in b's frame
    rb = (a.p1(xb) - b.l1) ** 2 + (a.p2(xb) - b.l2) ** 2
    ra = (a.l1 - b.p1(xa)) ** 2 + (a.l2 - b.p2(xa)) ** 2
    count = ia.sum(axis=1) + ib.sum(axis=1)
    total = np.where(ib, rb, 0.0).sum(axis=1) + np.where(ia, ra, 0.0).sum(axis=1)
    ok = (hi[:, 0] - lo[:, 0] >= min_overlap) & (count >= 3)
    return np.where(ok, total / np.maximum(2 * count, 1), np.inf)


def pairwise_shift(a, b, min_overlap=0.25, step=0.02, around=None, window=0.5):
    """Shift ``d`` (decades of frequency) of segment ``b`` that best overlays it on ``a``.

    The grid spans every shift with some overlap, or ``around +- window`` when given; None
    when no shift on it leaves ``min_overlap`` decades in common (with ``around``: when any
    fails to), or when the best one leaves just ``min_overlap`` (it sits on the edge of the
    feasible shifts: the curves do not really overlap).
    """
    if around is None:
        grid = np.arange(a.lo - b.hi, a.hi - b.lo + step, step)
    else:
        grid = np.arange(around - window, around + window + step, step)
    cost = _mismatch_grid(a, b, grid, min_overlap)
    if not np.isfinite(cost).any() or (around is not None and not np.isfinite(cost).all()):
        return None  # a search near an estimate must not end on the edge of the overlap
    k = int(np.argmin(cost))
    if around is None and (k == 0 or k == grid.size - 1 or not np.isfinite(cost[[k - 1, k + 1]]).all()):
        return None  # the best overlay sits on the edge of the overlap: a coincidence, not an overlap
    best = grid[k]
    res = minimize_scalar(
        lambda d: min(_mismatch(a, b, d, min_overlap), 1e30),
        bounds=(best - step, best + step),
        method="bounded",
        options={"xatol": 1e-6},
    )
    return float(res.x) if res.fun <= cost.min() else float(best)


def neighbour_shifts(segs, min_overlap=0.25, max_mismatch=0.05):
    """``(steps, linked)``: the best overlay shift of each segment on the next (None where none
    leaves ``min_overlap`` decades in common) and whether it overlays within ``max_mismatch``
    (rms of log10 moduli)."""
    steps = [pairwise_shift(segs[k], segs[k + 1], min_overlap) for k in range(len(segs) - 1)]
    linked = np.array(
        [
            d is not None and np.sqrt(_mismatch(segs[k], segs[k + 1], d, min_overlap)) <= max_mismatch
            for k, d in enumerate(steps)
        ],
        dtype=bool,
    )
    return steps, linked


def overlap_shifts(segs, steps, linked, min_overlap=0.25, reach=3):
    """Shifts of the segments from overlaying neighbours: ``(log_a, chain)``.

    ``steps`` and ``linked`` are :func:`neighbour_shifts`. ``chain[k]`` labels the chain of
    linked neighbours segment ``k`` belongs to; ``log_a`` is relative to the chain's first
    segment (zero there).
    """
    n = len(segs)
    chain = np.concatenate([[0], np.cumsum(~np.asarray(linked, dtype=bool))]).astype(int)
    log_a = np.zeros(n)
    for c in np.unique(chain):
        members = np.flatnonzero(chain == c)
        if members.size == 1:
            continue
        chained = np.concatenate([[0.0], np.cumsum([steps[k] for k in members[:-1]])])
        rows, rhs = [], []
        for p, i in enumerate(members):
            for q in range(p + 1, min(p + reach + 1, members.size)):
                j = members[q]
                d = (
                    steps[i]
                    if q == p + 1
                    else pairwise_shift(segs[i], segs[j], min_overlap, around=chained[q] - chained[p])
                )
                if d is not None:
                    row = np.zeros(members.size)
                    row[p], row[q] = -1.0, 1.0
                    rows.append(row)
                    rhs.append(d)
        sol = np.linalg.lstsq(np.array(rows)[:, 1:], np.array(rhs), rcond=None)[0]
        log_a[members] = np.concatenate([[0.0], sol])
    return log_a, chain


def _overlapping_under(law, segs, temps, min_overlap):
    """Whether each segment and the next share ``min_overlap`` decades once shifted by ``law``."""
    a = np.atleast_1d(law(temps))
    return np.array(
        [
            min(s.hi + a[k], t.hi + a[k + 1]) - max(s.lo + a[k], t.lo + a[k + 1]) >= min_overlap
            for k, (s, t) in enumerate(zip(segs[:-1], segs[1:]))
        ],
        dtype=bool,
    )


class _Data:
    """Validated measured points and their logs: ``w`` (rad/s), ``T`` (K), ``e1``, ``e2`` (Pa)."""

    def __init__(self, w, T, e1, e2, terms_per_decade):
        self.w, self.T, self.e1, self.e2 = w, T, e1, e2
        self.per = terms_per_decade

    def projected_norm(self, law, taus):
        """Norm of the relative residuals of the NNLS Prony fit on ``taus`` to the data shifted by ``law``."""
        wr = self.w * 10.0 ** law(self.T)
        return solve_nnls(wr, self.e1, self.e2, taus, loss_floor=NNLS_FLOOR)[1]

    def times_for(self, law, extend=1.0):
        return default_times(self.w * 10.0 ** law(self.T), self.per, extend)


def _grid_start(kind, data, tref):
    """The law on a coarse grid whose Prony fit to the shifted data leaves the least residual."""
    if kind == "wlf":
        c2_min = wlf_c2_min(data.T, tref)
        laws = [
            WLF(c1, c2, tref)
            for c2 in np.geomspace(c2_min + 2.0, max(10 * c2_min, 500.0), 10)
            for c1 in np.geomspace(2.0, 40.0, 10)
        ]
    else:
        laws = [Arrhenius(ea, tref) for ea in np.geomspace(2e4, 1e6, 30)]
    laws = [law for law in laws if np.max(np.abs(law(data.T))) <= MAX_TRIAL_SHIFT]
    if not laws:
        raise InputError(
            f"master curve: every trial {kind} law shifts these sweeps by more than {MAX_TRIAL_SHIFT:g} decades; "
            "check the temperatures, or impose the law"
        )
    scores = [data.projected_norm(law, data.times_for(law)) for law in laws]
    return laws[int(np.argmin(scores))]


def _projected_fit(law, data):
    """Variable projection: the law's parameters that minimise the residual of the NNLS Prony
    fit (times fixed on a grid around the start law's band) to the data they shift."""
    taus = data.times_for(law, extend=2.0)
    T, lo_hi = data.T, law.parameter_bounds(data.T)

    def residual(p):
        trial = law.with_parameters(p)
        log_a = trial(T)
        if np.max(np.abs(log_a)) > MAX_TRIAL_SHIFT:
            return np.full(2 * T.size, 1e3)  # far outside any measured shift: rejected
        wr = data.w * 10.0**log_a
        x, _ = solve_nnls(wr, data.e1, data.e2, taus, loss_floor=NNLS_FLOOR)
        u = wr[:, None] * np.sort(taus)[None, :]
        s2 = np.maximum(data.e2, NNLS_FLOOR * np.hypot(data.e1, data.e2))
        e1 = x[0] + (u**2 / (1 + u**2)) @ x[1:]
        e2 = (u / (1 + u**2)) @ x[1:]
        return np.concatenate([e1 / data.e1 - 1.0, (e2 - data.e2) / s2])

    p0 = np.clip(law.parameters, lo_hi[0] * (1 + 1e-9), None)
    with blas_limit():  # small dense problems: BLAS threads as bem.parallel sets them (1 by default)
        sol = least_squares(residual, p0, bounds=lo_hi, x_scale="jac", diff_step=1e-6, max_nfev=60, xtol=1e-10)
    return law.with_parameters(sol.x)


def _law_choice(shift, reference_temperature):
    """``(kind, imposed law or None, T_ref)`` from the ``shift`` and ``reference_temperature`` arguments."""
    if isinstance(shift, (WLF, Arrhenius)):
        if reference_temperature is None:
            return None, shift, shift.reference_temperature
        tref = check_kelvin("reference_temperature (K)", reference_temperature)
        return None, (shift if tref == shift.reference_temperature else shift.referenced_to(tref)), tref
    if shift not in LAWS:
        raise InputError(
            f"shift must be one of {', '.join(map(repr, LAWS))} (fitted) or a bem.materials.temperature.WLF "
            f"or Arrhenius law (imposed), got {shift!r}"
        )
    if reference_temperature is None:
        raise InputError(f"reference_temperature (K) is required to fit a {shift!r} law")
    return shift, None, check_kelvin("reference_temperature (K)", reference_temperature)


def _check_inputs(frequencies, temperatures, storage, loss, hz):
    w, e1, e2 = check_dma(frequencies, storage, loss, hz=hz)
    T = check_array("temperatures", temperatures, ndim=1)
    T = np.atleast_1d(check_kelvin("temperatures", T))
    if T.shape != w.shape:
        raise InputError(f"temperatures must have one entry per frequency ({w.size}), got {T.size}")
    if np.any(e2 <= 0):
        raise InputError("loss must be > 0 Pa everywhere for a master curve (its logarithm is shifted)")
    return w, T, e1, e2


def _anchored(log_a, chain, law_a):
    """The overlap shifts with each chain's constant removed against the law (NaN for a
    segment alone in its chain)."""
    out = np.full(log_a.size, np.nan)
    for c in np.unique(chain):
        members = chain == c
        if members.sum() > 1:
            out[members] = log_a[members] - np.mean(log_a[members] - law_a[members])
    return out


def _start_law(kind, log_a, chain, temps, data, tref):
    """The law through the chains' shifts with a free constant per chain, or the grid start
    when they hold too few shifts for it."""
    multi = np.isin(chain, [c for c in np.unique(chain) if np.sum(chain == c) > 1])
    information = multi.sum() - np.unique(chain[multi]).size
    if information >= (2 if kind == "wlf" else 1):
        try:
            return fit_law(kind, temps[multi], log_a[multi], tref, groups=chain[multi])[0]
        except InputError:
            pass  # shifts that no law of this kind fits: let the data choose
    return _grid_start(kind, data, tref)


def band_gaps(w_r, label, temps, min_decades=0.1):
    """Holes in the union of the segments' reduced bands: ``(w_1, w_2, T_1, T_2)`` tuples."""
    spans = sorted((w_r[label == k].min(), w_r[label == k].max(), temps[k]) for k in range(temps.size))
    out, reach, at = [], spans[0][1], spans[0][2]
    for lo, hi, t in spans[1:]:
        if np.log10(lo / reach) > min_decades:
            out.append((float(reach), float(lo), float(at), float(t)))
        if hi > reach:
            reach, at = hi, t
    return tuple(out)


def law_sigma(data, E0, moduli, times, law, temps):
    """1-sigma uncertainty (decades) of the jointly fitted law's ``log10 a_T`` at ``temps``.

    Linearised at the joint fit: the covariance of all its unknowns (series and law) is
    ``s^2 (J^T J)^-1``, with ``s`` the fit's rms relative residual but at least
    ``LAW_NOISE_FLOOR``; directions the data do not determine get a huge variance (the
    inverse is taken on singular values floored at 1e-10 of the largest), not none. The
    series' freedom to compensate a shift is thus counted: sweeps with gaps between them
    give a large ``sigma`` there.
    """
    model = SeriesModel(data.w, data.e1, data.e2, moduli.size, loss_floor=NNLS_FLOOR, law=law, temperatures=data.T)
    p = model.pack(E0, moduli, times, law)
    jac, r = model.jacobian(p), model.residual(p)
    s = max(float(np.sqrt(np.mean(r**2))), LAW_NOISE_FLOOR)
    scale = np.linalg.norm(jac, axis=0)
    scale[scale == 0] = 1.0
    _, sv, vt = np.linalg.svd(jac / scale, full_matrices=False)
    cov = (vt.T / np.maximum(sv, 1e-10 * sv[0]) ** 2) @ vt / np.outer(scale, scale) * s**2
    m = law.parameters.size
    g = law.gradient(np.atleast_1d(temps))
    return np.sqrt(np.maximum(np.einsum("it,ij,jt->t", g, cov[-m:, -m:], g), 0.0))


def _check_superposition(label, temps, w_r, data, E0, moduli, times, max_mismatch):
    u = w_r[:, None] * times[None, :]
    e1 = E0 + (u**2 / (1 + u**2)) @ moduli
    e2 = (u / (1 + u**2)) @ moduli
    seen = data.e2 >= NNLS_FLOOR * np.hypot(data.e1, data.e2)
    misfit = np.empty(temps.size)
    for k in range(temps.size):
        at = label == k
        r = np.concatenate([np.log10(e1[at] / data.e1[at]), np.log10(e2[at & seen] / data.e2[at & seen])])
        misfit[k] = np.sqrt(np.mean(r**2))
    bad = [f"{t:g} K ({rms:.3g})" for t, rms in zip(temps, misfit) if rms > max_mismatch]
    if bad:
        raise InputError(
            "master curve: the sweeps do not superpose under one law: the master curve misses the sweep(s) at "
            f"{', '.join(bad)} by more than max_mismatch = {max_mismatch:g} (rms log10 moduli); the material is "
            "not thermorheologically simple there, or a temperature is wrong"
        )
    typical = float(np.median(misfit))
    return tuple(
        f"the DMA sweep at {t:g} K is off the master curve by {rms:.2g} decades (rms of log10 moduli), "
        f"{rms / max(typical, 1e-300):.2g} times the median sweep's {typical:.2g}: check its temperature; the "
        "material may not be thermorheologically simple there"
        for t, rms in zip(temps, misfit)
        if rms > max(OUTLIER_RATIO * typical, OUTLIER_FLOOR)
    )


def fit_master_curve(
    frequencies,
    temperatures,
    storage,
    loss,
    *,
    reference_temperature=None,
    shift="wlf",
    hz=False,
    terms_per_decade=3.0,
    smoothing=0.0,
    temperature_tolerance=0.5,
    min_overlap=0.25,
    reach=3,
    max_mismatch=0.05,
    joint=True,
):
    """Master curve, shift law and Prony series from multi-temperature DMA data.

    Parameters are those of :meth:`bem.Material.fit_master_curve`. Returns
    ``(E0, moduli, times, law, report)`` with ``report`` a :class:`MasterCurveReport`.
    """
    w, T, e1, e2 = _check_inputs(frequencies, temperatures, storage, loss, hz)
    kind, law, tref = _law_choice(shift, reference_temperature)
    tol = check_positive("temperature_tolerance (K)", temperature_tolerance)
    min_overlap = check_positive("min_overlap (decades)", min_overlap)
    max_mismatch = check_positive("max_mismatch (decades)", max_mismatch)
    label, temps = segments(T, tol)
    needed = {None: 1, "arrhenius": 2, "wlf": 3}[kind]
    if temps.size < needed:
        raise InputError(f"fitting a {kind!r} master curve needs sweeps at >= {needed} temperatures, got {temps.size}")
    data = _Data(w, T, e1, e2, terms_per_decade)
    lw, l1, l2 = np.log10(w), np.log10(e1), np.log10(e2)
    segs = [_Segment(lw[label == k], l1[label == k], l2[label == k]) for k in range(temps.size)]
    steps, linked = neighbour_shifts(segs, min_overlap, max_mismatch)
    log_a, chain = overlap_shifts(segs, steps, linked, min_overlap, reach)
    if law is None and not joint and np.unique(chain).size > 1:
        k = int(np.flatnonzero(np.diff(chain))[0])
        raise InputError(
            f"master curve: the sweeps at {temps[k]:g} K and {temps[k + 1]:g} K do not overlay (no shift leaves "
            f"{min_overlap:g} decades in common within max_mismatch = {max_mismatch:g}); a law fitted to the "
            "overlap shifts alone (joint=False) needs every sweep to overlap a neighbour: fit it jointly with "
            "the series (joint=True), impose it, or measure closer temperatures"
        )
    if law is None:
        law = _start_law(kind, log_a, chain, temps, data, tref)
        if joint:
            law = _projected_fit(law, data)
    taus = data.times_for(law)
    w_r = w * 10.0 ** law(T)
    E0, moduli, times = grid_fit(w_r, e1, e2, taus, smoothing=smoothing, loss_floor=NNLS_FLOOR)
    if not E0 > 0:
        _check_superposition(label, temps, w_r, data, 0.0, moduli, times, max_mismatch)  # a misfit says more
        raise no_relaxed_modulus(
            f"master curve at {tref:g} K", w_r, e1, "add sweeps at higher temperatures (or lower frequencies)"
        )
    if smoothing == 0 and moduli.size:
        fitted = kind is not None and joint
        E0, moduli, times, joint_law = refine_terms(
            w if fitted else w * 10.0 ** law(T),
            e1,
            e2,
            E0,
            moduli,
            times,
            loss_floor=NNLS_FLOOR,
            bounds=(taus.min(), taus.max()),
            law=law if fitted else None,
            temperatures=T,
        )
        law = joint_law if fitted else law
    w_r = w * 10.0 ** law(T)
    notes = _check_superposition(label, temps, w_r, data, E0, moduli, times, max_mismatch)
    sigma = law_sigma(data, E0, moduli, times, law, temps) if kind is not None and joint else np.zeros(0)
    if sigma.size and sigma.max() > LAW_SIGMA_WARN:
        k = int(np.argmax(sigma))
        notes += (
            f"the shift law is weakly determined by these sweeps: log10 a_T is uncertain by about "
            f"{sigma[k]:.2g} decades at {temps[k]:g} K (1 sigma, linearised); impose known constants "
            "(shift = WLF(C1, C2, T_ref)) or measure at temperatures between the sweeps",
        )
    law_a = np.atleast_1d(law(temps))
    final = linked & _overlapping_under(law, segs, temps, min_overlap)  # an overlay the law contradicts: a gap
    if np.any(final != linked):
        log_a, chain = overlap_shifts(segs, steps, final, min_overlap, reach)
    anchored = _anchored(log_a, chain, law_a)
    seen = np.isfinite(anchored)
    rep = make_report(
        w_r, e1, e2, E0, moduli, times, smoothing=smoothing, loss_floor=NNLS_FLOOR, temperatures=T, measured_frequency=w
    )
    report = MasterCurveReport(
        **{f: getattr(rep, f) for f in FitReport.__dataclass_fields__},
        temperatures=tuple(temps.tolist()),
        log_shift=tuple(anchored.tolist()),
        law_log_shift=tuple(law_a.tolist()),
        law_rms=float(np.sqrt(np.mean((anchored[seen] - law_a[seen]) ** 2))) if seen.any() else float("nan"),
        law=law,
        law_imposed=kind is None,
        gaps=tuple((float(temps[k]), float(temps[k + 1])) for k in range(temps.size - 1) if chain[k] != chain[k + 1]),
        band_gaps=band_gaps(w_r, label, temps),
        law_sigma=tuple(sigma.tolist()),
        notes=notes,
    )
    return E0, moduli, times, law, report
