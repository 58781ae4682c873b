"""Friction against speed and temperature from one curve, by time-temperature superposition.

For a thermorheologically simple material every relaxation and creep time at temperature ``T``
is the reference time times one factor ``a_T`` (:meth:`bem.Material.at_temperature`). The steady
sliding kernel depends on the speed only through ``v lambda_k``, so sliding at speed ``v`` and
temperature ``T`` *is* sliding at the reduced speed ``v a_T`` on the reference material: the
friction, contact area and every field coincide exactly. :func:`friction_map` therefore solves
one curve, on the reference material, over the reduced speeds the map needs, and reads every
``(T, v)`` point off it.

The curve's nodes are log-spaced over the union of the reduced-speed ranges, starting at
:data:`NODES_PER_DECADE`; the map is interpolated in ``log v`` by a cubic spline through them
(of ``log mu``, which is smooth where the friction's flanks are steep; a reduced speed that coincides
with a node takes the node's solve as is). The interpolation
error at each map point is estimated by Richardson's rule for a fourth-order interpolant, from
the difference between the spline through all nodes and the splines through every other node:
``|S_h - S_2h| / 15``. Where that estimate exceeds ``rtol_map`` (relative to the friction), the
nodes about the point are halved in spacing and solved, until every point is within it or
:data:`MAX_REFINEMENTS` rounds have run (the map then says where it is not).

A ``material`` given as a callable ``T -> Material`` (e.g. separate fits per temperature) is
checked: when a temperature's material is not the reference material with every time scaled by
one factor, superposition does not hold and the map is made of direct solves, one friction curve
per temperature, and says so in its warnings.

Units SI: speeds in m/s, temperatures in K, loads in N (N/m for 1-D profiles).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline

from . import sliding
from .checks import show
from .errors import InputError
from .materials.temperature import check_kelvin
from .sweep import curve_from, friction_curve

__all__ = ["FrictionMap", "friction_map", "NODES_PER_DECADE", "MAX_REFINEMENTS", "RTOL_MAP"]

log = logging.getLogger(__name__)

NODES_PER_DECADE = 3.0
"""Starting density of the reduced-speed curve. A Prony series with one term a decade ripples the
friction by about 1 % with a period of one decade; at two nodes a decade the spline, and the
estimate from every other node, alias that ripple (the map was 1.6 % off with an estimate of
0.3 %), at three they resolve it (0.26 %, estimated 0.26 %). Refinement adds nodes only where the
estimate asks for them."""

MAX_REFINEMENTS = 4
"""Rounds of halving the node spacing about points above ``rtol_map``: four rounds reach 48 nodes a
decade, beyond which a friction curve is not smoother and a point still above the tolerance is
reported rather than chased."""

RTOL_MAP = 5e-3
"""Default target of the estimated interpolation error, relative to the friction: 0.5 %, below the
discretisation error of a typical rough-surface solve, so the map adds no error that matters."""

_SAME = 1e-9  # relative distance in speed below which a map point is a node (its own solve)


@dataclass(frozen=True, eq=False)
class FrictionMap:
    """Friction and contact area on a grid of temperatures (rows) and speeds (columns).

    ``friction`` and ``contact_fraction`` are shaped ``(temperatures, speeds)`` (NaN where a solve
    failed). ``reduced_speeds[i, j] = speeds[j] * 10**log10_shift[i]`` is the speed on the
    reference material that stands for the point. ``curve`` is the one friction curve solved over
    the reduced speeds (``results`` its solves); with ``method = "direct"`` it is None and
    ``curves`` holds one curve per temperature. ``interpolated[i, j]`` is True where the point was
    interpolated between the curve's nodes, and ``interpolation_error[i, j]`` is the estimated
    relative error of its friction there (0 at a node, NaN where no estimate exists).
    ``error_estimate[q]`` is the solves' own estimated relative error of ``q`` (friction, contact
    fraction, peak pressure) at the nearest node; ``warnings`` gathers the solves' warnings and
    says where the map is not within ``rtol_map``.
    """

    temperatures: np.ndarray
    speeds: np.ndarray
    log10_shift: np.ndarray
    reduced_speeds: np.ndarray
    friction: np.ndarray
    contact_fraction: np.ndarray
    interpolated: np.ndarray
    interpolation_error: np.ndarray
    method: str
    reference_temperature: float
    curve: object = field(default=None, repr=False)
    curves: tuple = field(default=(), repr=False)
    error_estimate: dict = field(default_factory=dict, repr=False)
    warnings: tuple = ()
    load: float = float("nan")

    @property
    def results(self):
        """The solves the map was made of (the curve's, or every direct curve's)."""
        curves = [self.curve] if self.curve is not None else list(self.curves)
        return [r for c in curves for r in c.results]

    @property
    def matvecs(self):
        """Operator products of all the solves."""
        return int(sum(r.matvecs for r in self.results if r is not None))


def _check_axis(name, values, unit, positive):
    try:
        arr = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a list of numbers ({unit}), got {show(values)}") from None
    if arr.ndim != 1 or arr.size == 0 or not np.all(np.isfinite(arr)) or (positive and np.any(arr <= 0)):
        raise InputError(
            f"{name} must be a non-empty 1-D list of finite numbers{' > 0' if positive else ''} ({unit}), "
            f"got {show(arr.tolist())}"
        )
    return arr


def _simple(reference, at_T):
    """``log10`` of the one factor that scales every time of ``reference`` to ``at_T``, or None when
    the moduli differ or the times do not scale together (not thermorheologically simple)."""
    same_moduli = np.allclose(at_T.moduli, reference.moduli, rtol=1e-9, atol=0) and np.isclose(
        at_T.E0, reference.E0, rtol=1e-9
    )
    if not same_moduli or at_T.relaxation_times.shape != reference.relaxation_times.shape:
        return None
    ratios = np.log10(at_T.relaxation_times / reference.relaxation_times)
    if ratios.size and np.ptp(ratios) > 1e-9 * max(1.0, np.max(np.abs(ratios))):
        return None
    return float(ratios[0]) if ratios.size else 0.0


def _nodes(lo, hi, per_decade):
    """Log-spaced reduced speeds from ``lo`` to ``hi`` (log10 m/s), both ends included."""
    n = max(2, int(np.ceil((hi - lo) * per_decade)) + 1)
    return np.linspace(lo, hi, n)


def _needed(log_v, log_a):
    """The union of the reduced-speed ranges ``[min log v + log a_T, max log v + log a_T]``, as
    disjoint intervals."""
    spans = sorted((log_v.min() + a, log_v.max() + a) for a in log_a)
    merged = [list(spans[0])]
    for lo, hi in spans[1:]:
        if lo <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    return merged


def _interpolate_friction(x, mu, at):
    """The friction at ``at`` and the estimate of its relative error: interpolated as ``log mu``
    when every node's friction is positive, because a friction curve's flanks span decades and
    ``log mu`` is smooth where ``mu`` is steep (the relative error of ``mu`` is then the absolute
    error of ``log mu``); as ``mu`` otherwise."""
    if np.all(mu > 0):
        value, est = _interpolate(x, np.log(mu), at)
        return np.exp(value), np.expm1(est)
    value, est = _interpolate(x, mu, at)
    return value, est / np.maximum(np.abs(value), 1e-300)


def _interpolate(x, y, at):
    """The spline through ``(x, y)`` at ``at`` and its Richardson error estimate ``|S_h - S_2h| / 15``
    (the larger over the two sub-grids of every other node; NaN with too few nodes)."""
    if x.size < 2:
        return np.full(at.shape, y[0]), np.full(at.shape, np.nan)
    full = CubicSpline(x, y)(at) if x.size >= 4 else np.interp(at, x, y)
    diffs = []
    for start in (0, 1):
        xs, ys = x[start::2], y[start::2]
        if xs.size >= 4:
            diffs.append(np.abs(CubicSpline(xs, ys, extrapolate=True)(at) - full))
    est = np.max(diffs, axis=0) / 15.0 if diffs else np.full(at.shape, np.nan)
    return full, est


def friction_map(
    surface,
    material,
    *,
    speeds,
    temperatures,
    shift,
    load,
    reference_temperature=None,
    rtol_map=RTOL_MAP,
    progress=False,
    **solve_options,
):
    """Friction and contact area over speeds and temperatures, from one curve on the reference
    material (time-temperature superposition; module docstring).

    Parameters
    ----------
    surface, load
        As in :func:`bem.friction_curve` (one load: N, or N/m for a profile).
    material : Material or callable
        The material at the reference temperature, or a callable ``T -> Material`` (checked for
        thermorheological simplicity; direct solves where it fails).
    speeds : array_like
        Sliding speeds (m/s), > 0.
    temperatures : array_like
        Temperatures (K).
    shift : callable
        ``log10 a_T`` as a function of ``T`` (:class:`bem.temperature.WLF`, ``Arrhenius``).
    reference_temperature : float, optional
        The temperature of ``material`` (default: ``shift.reference_temperature``).
    rtol_map : float
        Target of the estimated interpolation error, relative to the friction (default 0.5 %).
    progress : bool
        Show a progress bar per curve.
    **solve_options
        Passed to :func:`bem.friction_curve` (``rtol``, ``periodic``, ``method``, ...).

    Returns
    -------
    FrictionMap
    """
    speeds = _check_axis("speeds", speeds, "m/s", positive=True)
    temperatures = np.array(
        [
            check_kelvin("temperatures (K, absolute)", T)
            for T in _check_axis("temperatures", temperatures, "K", positive=True)
        ]
    )
    if not callable(shift):
        raise InputError(f"shift must be a callable giving log10 a_T(T) (e.g. bem.temperature.WLF), got {shift!r}")
    if not (isinstance(rtol_map, (int, float)) and 0 < rtol_map < 1):
        raise InputError(f"rtol_map must be a number in (0, 1), got {show(rtol_map)}")
    t_ref = (
        reference_temperature if reference_temperature is not None else getattr(shift, "reference_temperature", None)
    )
    if t_ref is None:
        raise InputError("reference_temperature is required when shift has no reference_temperature")
    if callable(material) and not hasattr(material, "at_temperature"):
        at = material
        reference = material(t_ref)
    else:
        reference = material
        at = lambda T: material.at_temperature(T, shift)  # noqa: E731
    log_a = np.array([float(shift(T)) for T in temperatures])
    materials = [at(T) for T in temperatures]
    factors = [_simple(reference, m) for m in materials]
    simple = all(f is not None and abs(f - a) <= 1e-9 * max(1.0, abs(a)) for f, a in zip(factors, log_a))
    if not simple:
        return _direct(surface, materials, speeds, temperatures, log_a, load, t_ref, progress, solve_options)
    return _superposed(surface, reference, speeds, temperatures, log_a, load, t_ref, rtol_map, progress, solve_options)


def _superposed(surface, reference, speeds, temperatures, log_a, load, t_ref, rtol_map, progress, options):
    log_v = np.log10(speeds)
    reduced = log_v[None, :] + log_a[:, None]  # (T, v), log10 m/s
    targets = reduced.ravel()
    nodes = np.concatenate([_nodes(lo, hi, NODES_PER_DECADE) for lo, hi in _needed(log_v, log_a)])
    solved = {}  # log10 reduced speed -> result (None if it failed)

    def solve(new):
        """Refinement nodes, each warm-started from the pressure of its nearest solved node (the
        contact changes little over a fraction of a decade), as a sweep warm-starts its next speed."""
        new = sorted(x for x in new if not any(abs(x - k) < 1e-12 for k in solved))
        done = [k for k, r in solved.items() if r is not None]
        for x in new:
            near = solved[min(done, key=lambda k: abs(k - x))] if done else None
            r = sliding.solve(
                surface,
                reference,
                speed=10.0**x,
                load=load,
                initial=None if near is None else near.pressure,
                raise_on_failure=False,
                **{k: v for k, v in options.items() if k not in ("warm_start", "callback")},
            )
            solved[x] = r if r.success else None
            if r.success:
                done.append(x)

    first = friction_curve(surface, reference, speeds=10.0**nodes, load=load, progress=progress, **options)
    solved.update(zip(nodes.tolist(), first.results))
    for round_ in range(MAX_REFINEMENTS + 1):
        x = np.array(sorted(k for k, r in solved.items() if r is not None))
        mu = np.array([solved[k].friction for k in x])
        _, rel = _interpolate_friction(x, mu, targets)
        bad = ~(rel <= rtol_map)  # NaN (too few nodes for an estimate) counts as above
        if not np.any(bad):
            break
        # halve the spacing about each point above the tolerance: midpoints of its interval and both neighbours'
        idx = np.clip(np.searchsorted(x, targets[bad]), 1, x.size - 1)
        mids = {float(0.5 * (x[i] + x[i - 1])) for j in idx for i in (j - 1, j, j + 1) if 1 <= i < x.size}
        if not mids or round_ == MAX_REFINEMENTS:
            break
        solve(mids)
    return _assemble(solved, speeds, temperatures, log_a, reduced, load, t_ref, rtol_map)


def _assemble(solved, speeds, temperatures, log_a, reduced, load, t_ref, rtol_map):
    """The map read off the solved curve: node values where a point is a node, else the spline."""
    from .accuracy import QUANTITIES

    keys = np.array(sorted(solved))
    results = [solved[k] for k in keys]
    ok = np.array([r is not None for r in results])
    x = keys[ok]
    targets = reduced.ravel()
    mu = np.array([r.friction for r in results if r is not None])
    contact = np.array([r.contact_fraction for r in results if r is not None])
    friction, est = _interpolate_friction(x, mu, targets)
    fraction, _ = _interpolate(x, contact, targets)
    near = np.abs(targets[:, None] - x[None, :])
    nearest = np.argmin(near, axis=1)
    at_node = np.abs(10.0 ** (targets - x[nearest]) - 1.0) < _SAME
    friction[at_node] = mu[nearest[at_node]]
    fraction[at_node] = contact[nearest[at_node]]
    rel = np.where(at_node, 0.0, est)
    outside = (targets < x.min() - 1e-12) | (targets > x.max() + 1e-12)  # a failed end node: no curve there
    friction[outside], fraction[outside], rel[outside] = np.nan, np.nan, np.nan
    good = [r for r in results if r is not None]
    estimates = {
        q: np.array(
            [np.nan if good[k].error_estimate[q] is None else good[k].error_estimate[q] for k in nearest]
        ).reshape(reduced.shape)
        for q in QUANTITIES
    }
    one = curve_from(10.0**keys, results, ["" if r is not None else "failed" for r in results], load)
    shape = reduced.shape
    warnings = list(one.warnings)
    above = ~(rel.reshape(shape) <= rtol_map) & ~outside.reshape(shape)
    if np.any(above):
        where = ", ".join(f"({temperatures[i]:g} K, {speeds[j]:.3g} m/s)" for i, j in zip(*np.nonzero(above)))
        warnings.append(
            f"the map is interpolated to worse than rtol_map = {rtol_map:g} (estimated), or without an estimate, at {int(above.sum())} "
            f"point(s) after {MAX_REFINEMENTS} refinements: {where}"
        )
    return FrictionMap(
        temperatures=temperatures,
        speeds=speeds,
        log10_shift=log_a,
        reduced_speeds=10.0**reduced,
        friction=friction.reshape(shape),
        contact_fraction=fraction.reshape(shape),
        interpolated=~at_node.reshape(shape),
        interpolation_error=rel.reshape(shape),
        method="superposition",
        reference_temperature=float(t_ref),
        curve=one,
        error_estimate=estimates,
        warnings=tuple(warnings),
        load=float(load),
    )


def _direct(surface, materials, speeds, temperatures, log_a, load, t_ref, progress, options):
    """One friction curve per temperature, on that temperature's own material."""
    curves = tuple(
        friction_curve(surface, m, speeds=speeds, load=load, progress=progress, **options) for m in materials
    )
    message = (
        "not thermorheologically simple: the materials at these temperatures are not the reference material "
        "with every time scaled by one factor 10**shift(T), so the map was solved directly, one curve per "
        "temperature (superposition would be wrong)"
    )
    log.warning(message)
    shape = (temperatures.size, speeds.size)
    return FrictionMap(
        temperatures=temperatures,
        speeds=speeds,
        log10_shift=log_a,
        reduced_speeds=speeds[None, :] * 10.0 ** log_a[:, None],
        friction=np.array([c.friction for c in curves]),
        contact_fraction=np.array([c.contact_fraction for c in curves]),
        interpolated=np.zeros(shape, dtype=bool),
        interpolation_error=np.zeros(shape),
        method="direct",
        reference_temperature=float(t_ref),
        curves=curves,
        error_estimate={q: np.array([c.error_estimate[q] for c in curves]) for q in curves[0].error_estimate},
        warnings=(message, *(w for c in curves for w in c.warnings)),
        load=float(load),
    )
