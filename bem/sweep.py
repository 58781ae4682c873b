"""Friction curves: warm-started sweeps over speeds, for one or several loads and surfaces.

One loop, :func:`sweep`, serves both the API (:func:`friction_curve`) and the command
line's resumable sweeps: the speeds are visited in increasing order, and each surface's
solve starts from its own pressure at the previous speed (the contact changes little
between neighbouring speeds, so the active set is nearly right from the start). Within a
speed every surface is solved before the next speed, so the operator of that speed (built
once and cached by :func:`bem.solve`) serves all of them. A point that does not converge is
reported with ``None`` and the sweep goes on; the next point then starts cold.

Units SI: speeds in m/s, loads in N (N/m for 1-D profiles).
"""

import logging
from dataclasses import dataclass, field

import numpy as np

from . import sliding
from .accuracy import QUANTITIES, Finding, gather
from .accuracy.assess import check_estimate
from .checks import check_positive, show
from .contact.options import MAXITER, RTOL
from .errors import ConvergenceError, InputError

__all__ = ["FrictionCurve", "friction_curve", "curve_from", "sweep", "check_sweep"]

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False)
class FrictionCurve:
    """A sweep over speeds at one load (arrays in the order of ``speeds``; failed points are NaN).

    ``results[i]`` is the :class:`~bem.sliding.SlidingResult` of ``speeds[i]`` or ``None`` if it
    failed; ``messages[i]`` says why. ``error_estimate[q]`` is the array of the points' estimated
    relative errors of ``q`` in ``friction``, ``contact_fraction``, ``peak_pressure`` (NaN where a
    point has none: see its result's ``error_estimate.reasons``); ``warnings`` gathers every point's
    warnings, one sentence per kind of finding with the speeds it comes from
    (:func:`bem.accuracy.gather`).
    """

    speeds: np.ndarray
    friction: np.ndarray
    friction_eq6: np.ndarray
    contact_fraction: np.ndarray
    dissipated_power: np.ndarray
    iterations: np.ndarray
    residual: np.ndarray
    success: np.ndarray
    messages: list
    results: list = field(repr=False)
    load: float = float("nan")
    error_estimate: dict = field(default_factory=dict, repr=False)
    warnings: tuple = ()

    @property
    def all_converged(self):
        return bool(np.all(self.success))

    def __repr__(self):
        mu = self.friction[np.isfinite(self.friction)]
        peak = f", peak friction {mu.max():.4g}" if mu.size else ""
        return (
            f"FrictionCurve(load={self.load:g}, {self.speeds.size} speeds from {self.speeds.min():.3g} to "
            f"{self.speeds.max():.3g} m/s, {int(np.sum(self.success))} converged{peak})"
        )


def sweep(
    surfaces,
    material,
    *,
    speeds,
    load,
    rtol=RTOL,
    maxiter=MAXITER,
    warm_start=True,
    periodic=True,
    method="auto",
    skip=None,
    on_point=None,
    keep=True,
    direction=0.0,
    error_estimate="indicators",
    contact_options=None,
):
    """Solve every surface at every speed, in increasing speed, warm-starting each surface.

    Parameters
    ----------
    surfaces : list of bem.surfaces.Surface
        Realisations of one study, solved side by side (one operator per speed).
    speeds : ndarray
        Sliding speeds (m/s), >= 0, in any order.
    load : float
        Normal force (N; N/m for profiles).
    skip : callable, optional
        ``skip(i, r) -> bool``: points not to solve (e.g. finished in an earlier run); the
        surface's next point starts from its last solved one.
    on_point : callable, optional
        ``on_point(i, r, result_or_None, message)`` after every solved point, e.g. to
        write it to disk at once.
    keep : bool
        Return the results; ``False`` keeps no fields in memory (a callback stores them).
    rtol, maxiter, periodic, method, direction
        As in :func:`bem.solve`; the warm start is skipped for ``method="adaptive"`` (its
        mesh differs from the surface's grid).

    Returns
    -------
    results, messages : list of lists
        ``results[r][i]`` (None if failed, skipped or not kept) and ``messages[r][i]``.
    """
    n = len(speeds)
    results = [[None] * n for _ in surfaces]
    messages = [[""] * n for _ in surfaces]
    previous = [None] * len(surfaces)
    for i in (int(k) for k in np.argsort(speeds, kind="stable")):
        for r, surface in enumerate(surfaces):
            if skip is not None and skip(i, r):
                continue
            start = previous[r] if warm_start and method != "adaptive" else None
            try:
                res = sliding.solve(
                    surface,
                    material,
                    speed=float(speeds[i]),
                    load=load,
                    rtol=rtol,
                    maxiter=maxiter,
                    initial=start,
                    periodic=periodic,
                    method=method,
                    direction=direction,
                    error_estimate=error_estimate,
                    contact_options=contact_options,
                )
            except ConvergenceError as err:
                res, message = None, str(err)
                log.warning("%s", err)
            else:
                message = res.message
            previous[r] = None if res is None else res.pressure
            messages[r][i] = message
            if keep:
                results[r][i] = res
            if on_point is not None:
                on_point(i, r, res, message)
    return results, messages


def check_sweep(surface, material, *, speeds, loads, rtol):
    """Raise :class:`~bem.errors.InputError` if any (speed, load) of a sweep is bad input for
    :func:`bem.solve`; nothing is solved."""
    for f_n in loads:
        for speed in (float(np.min(speeds)), float(np.max(speeds))):
            sliding.check_inputs(surface, material, speed, f_n, None, rtol)


def _loads(surface, load, nominal_pressure):
    """The loads of :func:`friction_curve` (from ``nominal_pressure`` if that is given) and
    whether a list was given."""
    if (load is None) == (nominal_pressure is None):
        raise InputError(
            "give exactly one of load (N, or N/m for profiles; on the scanned patch for a measured surface) "
            "and nominal_pressure (Pa, the mean pressure)"
        )
    name, given = ("load", load) if load is not None else ("nominal_pressure", nominal_pressure)
    several = isinstance(given, (list, tuple, np.ndarray))
    if several and len(given) == 0:
        raise InputError(f"{name} must be a number > 0 or a non-empty list of them, got {show(given)}")
    values = [check_positive(name, x) for x in given] if several else [given]
    if nominal_pressure is not None:
        values = [sliding.load_of_pressure(surface, p) for p in values]
    return values, several


def friction_curve(
    surface,
    material,
    *,
    speeds,
    load=None,
    nominal_pressure=None,
    rtol=RTOL,
    maxiter=MAXITER,
    warm_start=True,
    progress=False,
    callback=None,
    periodic=True,
    method="auto",
    direction=0.0,
    error_estimate="indicators",
    contact_options=None,
):
    """Friction against speed: solve at each speed, warm-starting from the neighbour.

    Parameters
    ----------
    speeds : array_like
        Sliding speeds (m/s), >= 0.
    load : float or list of float
        Normal force (N; N/m for profiles; on the scanned patch for a measured surface). A list
        gives one curve per load.
    nominal_pressure : float or list of float
        Mean pressure (Pa) instead of ``load`` (exactly one of the two); a list gives one curve
        per pressure. Each curve's ``load`` is the force it puts on the cell (on the patch).
    progress : bool
        Show a progress bar (tqdm).
    callback : callable, optional
        ``callback(index, speed, result_or_None, message)`` after each point (with a list of
        loads, ``index`` counts the points of all loads: ``load_index * len(speeds) + i``);
        a point that fails to converge is reported with ``None`` and the sweep goes on.
    periodic, method, rtol, maxiter, direction, error_estimate, contact_options
        As in :func:`bem.solve` (``periodic=False``: isolated contact; ``direction``: sliding
        direction, radians from +x; ``error_estimate``: ``"indicators"``, ``"refined"`` or
        ``None``; ``contact_options``: the contact solver's :class:`~bem.contact.ContactOptions`).
        The warm start is skipped for ``method="adaptive"``.

    Returns
    -------
    FrictionCurve, or a list of them (one per load) when ``load`` is a list; each with the
    points' error estimates and their gathered warnings.
    """
    given = speeds
    try:
        speeds = np.atleast_1d(np.asarray(speeds))
    except (TypeError, ValueError):
        speeds = np.array([given], dtype=object)
    if speeds.dtype.kind not in "iuf":  # strings, booleans, objects: not speeds
        raise InputError(f"speeds must be a list of numbers (m/s), got {show(given)}")
    speeds = speeds.astype(float)
    if speeds.ndim != 1 or speeds.size == 0 or not np.all(np.isfinite(speeds)) or np.any(speeds < 0):
        raise InputError(f"speeds must be a non-empty 1-D list of finite speeds >= 0 m/s, got {show(speeds.tolist())}")
    loads, several = _loads(surface, load, nominal_pressure)
    check_estimate(error_estimate)
    checked = [sliding.check_inputs(surface, material, 0.0, x, None, rtol) for x in loads]
    surface, rtol = checked[0][0], checked[0][4]
    from tqdm.auto import tqdm

    curves = []
    with tqdm(total=speeds.size * len(loads), disable=not progress, desc="friction curve", unit="speed") as bar:
        for j, (_, _, f_n, _, _) in enumerate(checked):

            def on_point(i, r, res, message, j=j):
                bar.update(1)
                if callback is not None:
                    callback(j * speeds.size + i if several else i, float(speeds[i]), res, message)

            results, messages = sweep(
                [surface],
                material,
                speeds=speeds,
                load=f_n,
                rtol=rtol,
                maxiter=maxiter,
                warm_start=warm_start,
                periodic=periodic,
                method=method,
                on_point=on_point,
                direction=direction,
                error_estimate=error_estimate,
                contact_options=contact_options,
            )
            curves.append(curve_from(speeds, results[0], messages[0], f_n))
    return curves if several else curves[0]


def curve_from(speeds, results, messages, load):
    """The :class:`FrictionCurve` of the solves ``results`` at ``speeds`` (None where one failed,
    ``messages`` saying why), with their error estimates and gathered warnings."""

    def column(attr):
        return np.array([getattr(r, attr) if r is not None else np.nan for r in results], dtype=float)

    estimates = {
        q: np.array(
            [np.nan if r is None or r.error_estimate[q] is None else r.error_estimate[q] for r in results], dtype=float
        )
        for q in QUANTITIES
    }
    found = [
        (f"v = {v:.3g} m/s", r.warnings if r is not None else (Finding(f"the solve failed: {m}", "not_converged"),))
        for v, r, m in zip(speeds, results, messages)
    ]
    return FrictionCurve(
        speeds=speeds,
        friction=column("friction"),
        friction_eq6=column("friction_eq6"),
        contact_fraction=column("contact_fraction"),
        dissipated_power=column("dissipated_power"),
        iterations=column("iterations"),
        residual=column("residual"),
        success=np.array([r is not None for r in results]),
        messages=messages,
        results=results,
        load=float(load),
        error_estimate=estimates,
        warnings=tuple(gather(found, noun="speeds")),
    )
