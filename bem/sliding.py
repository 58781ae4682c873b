"""Public entry point: one steady sliding solve (sweeps over speeds: :mod:`bem.sweep`).

Units SI. Load is the total normal force on the cell (N) for 2-D surfaces and the force
per unit length (N/m) for 1-D profiles. The indenter slides at ``speed`` (m/s) in ``+x``.

Friction (docs/theory.md §4): ``friction`` is the dissipation form
``mu = -(1/F_N) ∫ p du/dx dA`` evaluated exactly in Fourier space (non-negative on any
grid); ``friction_eq6 = -(1/F_N) ∫ p dh/dx dA`` (the seed's eq. 6) uses the spectral
derivative of the heights. They coincide in full contact and converge together as the
grid resolves the contact spots. ``dissipated_power = friction * F_N * speed`` (W, or
W/m for profiles).

Isolated contacts (``periodic=False``, :mod:`bem.halfspace.isolated`): the domain is the array and
pressure outside it is zero. ``friction`` is again the dissipation form, collocated like the
displacement: ``-sum_j p_j u'(x_j) d**ndim`` with the exact slope of the displacement at the
element centres (see ``IsolatedHalfSpace.dissipation_integral``: the exact dissipation of the
piecewise-constant pressure would add that of its steps between elements, ~ ``L ln(d/L)``,
percent-level when ``v lambda`` is far below a cell); ``friction_eq6`` uses central
differences of the heights between element centres (one-sided at the domain's ends, where
the pressure vanishes).
"""

import dataclasses
import logging
import time

import numpy as np

from . import direction as sliding_direction
from . import fft
from .accuracy.assess import assess, check_estimate
from .accuracy.findings import Finding
from .checks import check_array, check_int, check_keywords, check_positive, show
from .contact import ContactOptions, solve_contact
from .contact.options import MAXITER, RTOL
from .errors import ConvergenceError, InputError
from .halfspace.cache import clear_operator_cache, operator_for
from .materials.material import Material
from .plausibility import height_checks
from .result import SlidingResult
from .surfaces.measured import patch as measured_patch
from .surfaces.surface import Surface

__all__ = ["SlidingResult", "clear_operator_cache", "operator_for", "solve"]

log = logging.getLogger(__name__)


def _as_surface(surface):
    if isinstance(surface, Surface):
        return surface
    if hasattr(surface, "heights") and hasattr(surface, "length"):
        return Surface(surface.heights, surface.length)
    raise InputError(
        f"surface must be a bem.surfaces.Surface (or have .heights and .length), got {type(surface).__name__}"
    )


def check_inputs(surface, material, speed, load, approach, rtol):
    """Validate the arguments :func:`solve` shares with every caller that plans solves ahead
    (e.g. a study checking its range before it writes anything); return them converted,
    ``(surface, speed, load, approach, rtol)``. Raises :class:`~bem.errors.InputError`."""
    surface = _as_surface(surface)
    if not surface.centered:  # a periodic cell's heights span less than the cell (bem.plausibility)
        height_checks(surface.heights, surface.length, name="surface heights")
    if not isinstance(material, Material):
        raise InputError(f"material must be a bem.Material, got {type(material).__name__}")
    speed = check_positive("speed", speed, allow_zero=True)
    if (load is None) == (approach is None):
        raise InputError(
            "give exactly one of load (N, or N/m for profiles; load control) or approach (m; displacement control)"
        )
    if load is not None:
        load = check_positive("load", load)
    else:
        approach = check_positive("approach", approach)
    rtol = check_positive("rtol", rtol)
    if rtol >= 1:
        raise InputError(f"rtol must be in (0, 1), got {show(rtol)}")
    return surface, speed, load, approach, rtol


_ISOLATED_METHODS = ("auto", "uniform", "adaptive")
# keywords of bem.adaptive.solve_adaptive that solve() passes on with method="adaptive"
ADAPTIVE_OPTIONS = ("levels", "buffer", "gradient", "refine_contact", "sampling", "height", "max_elements")
_SOLVE_KEYWORDS = (
    "speed",
    "load",
    "nominal_pressure",
    "approach",
    "periodic",
    "method",
    "rtol",
    "maxiter",
    "initial",
    "raise_on_failure",
    "contact_options",
    "direction",
    "error_estimate",
)
_PERIODIC_METHODS = ("auto", "active-set")


def solve(
    surface,
    material,
    *,
    speed,
    load=None,
    approach=None,
    nominal_pressure=None,
    periodic=True,
    method="auto",
    rtol=RTOL,
    maxiter=MAXITER,
    initial=None,
    raise_on_failure=True,
    contact_options=None,
    direction=0.0,
    error_estimate="indicators",
    **adaptive_options,
):
    """Steady sliding of a rigid surface over a viscoelastic half-space.

    Parameters
    ----------
    surface : bem.surfaces.Surface
        Rigid surface; heights (m) positive toward the half-space.
    material : bem.Material
        Viscoelastic solid.
    speed : float
        Sliding speed (m/s) of the surface in ``+x``; 0 gives the relaxed elastic answer.
    load : float, optional
        Total normal force (N) on the cell, or per unit length (N/m) for a 1-D profile. For a
        measured surface (:func:`bem.surfaces.from_scan`) the force on the scanned patch: a
        mirrored cell holds the patch 4 times (twice for a profile) and gets that many times the
        load, the same nominal pressure; the result's ``load`` and ``dissipated_power`` are the
        patch's again, and its ``warnings`` say when ``speed`` is above the patch's
        :func:`~bem.surfaces.measured.speed_limit`.
    approach : float, optional
        Displacement control instead of ``load``: rigid approach (m) from first touch.
    nominal_pressure : float, optional
        Load control by the mean pressure (Pa) instead of ``load``: the load is this pressure times
        the cell's area (its length for a 1-D profile, giving N/m). For a measured surface the same
        pressure on the scanned patch, whatever the boundary treatment made of its cell. Give
        exactly one of ``load``, ``nominal_pressure`` and ``approach``.
    periodic : bool
        ``True``: periodic cell (:mod:`bem.halfspace.periodic`). ``False``: isolated contact on a
        half-space, the array being the whole loaded domain (:mod:`bem.halfspace.isolated`), e.g.
        :func:`bem.surfaces.sphere` or :func:`bem.surfaces.cylinder`.
    method : str
        Periodic cells: ``"auto"`` or ``"active-set"`` (the same primal–dual active-set
        solver with CG (elastic) or GMRES (viscoelastic) inner solves). Isolated contacts:
        ``"uniform"`` (DC-FFT on the uniform grid), ``"adaptive"`` (non-uniform mesh,
        :func:`bem.adaptive.solve_adaptive`, given ``adaptive_options``) or ``"auto"``,
        the uniform grid (as fast or faster at equal error in ``viscobem bench isolated``).
    rtol : float
        Tolerance on the complementarity residual (see :mod:`bem.contact`).
    maxiter : int
        Maximum active-set iterations.
    initial : ndarray, optional
        Warm-start pressure (Pa), e.g. from a neighbouring speed.
    raise_on_failure : bool
        Raise :class:`bem.errors.ConvergenceError` when the tolerance is not reached
        (default). With ``False`` the result comes back with ``success=False``.
    contact_options : bem.contact.ContactOptions, optional
        Tunables of the contact solver (uniform grids); default ``ContactOptions()``.
    direction : float
        Sliding direction (radians from ``+x`` toward ``+y``; default 0), see
        :mod:`bem.direction`: ``speed`` is along it, ``friction`` opposes it, fields stay on the
        surface's grid. 1-D profiles: 0 or pi only.
    error_estimate : {"indicators", "refined", None}
        How ``result.error_estimate`` (the relative discretisation error of ``friction``,
        ``contact_fraction`` and ``peak_pressure``) is obtained, see :mod:`bem.accuracy`:
        ``"indicators"`` from the solution itself (default; a few FFTs), ``"refined"`` by solving
        the same surface content on the grid with twice the points per axis (the cost of that
        solve), ``None`` for no estimate and no warnings.

    Returns
    -------
    SlidingResult
        With ``error_estimate`` and ``warnings`` (plain sentences saying what to change).

    Raises
    ------
    bem.errors.InputError
        For an argument out of range, a string where a number is meant, or an unknown
        keyword (named, with the closest valid one).

    Examples
    --------
    A rigid sinusoid (amplitude 1 µm, wavelength 1 mm) pressed with 1 N on a 1 mm cell of
    an elastic half-space:

    >>> import bem
    >>> s = bem.surfaces.sinusoid(64, 1e-3, amplitude=1e-6)
    >>> r = bem.solve(s, bem.Material.elastic(1e7), speed=0.0, load=1.0)
    >>> r.success, round(r.friction, 12)
    (True, 0.0)
    >>> bem.solve(s, bem.Material.elastic(1e7), speed=0.0, lod=1.0)
    Traceback (most recent call last):
    ...
    bem.errors.InputError: solve() got unknown keyword argument 'lod' (did you mean 'load'?); valid: ...
    """
    check_keywords("solve", adaptive_options, ADAPTIVE_OPTIONS + _SOLVE_KEYWORDS)
    factor = measured_patch.load_factor(surface)
    if nominal_pressure is not None or (load is None and approach is None):
        load = _load_of_pressure(surface, nominal_pressure, load, approach, factor)
    if factor is not None:  # a measured patch: the load asked is the patch's
        options = dict(speed=speed, load=load, approach=approach, periodic=periodic, method=method, rtol=rtol)
        options.update(maxiter=maxiter, initial=initial, raise_on_failure=raise_on_failure)
        options.update(contact_options=contact_options, direction=direction, error_estimate=error_estimate)
        return _on_patch(surface, material, factor, options, adaptive_options)
    surface, speed, load, approach, rtol = check_inputs(surface, material, speed, load, approach, rtol)
    check_estimate(error_estimate)
    # sliding direction (bem.direction): a quarter turn solves along +x on turned heights
    theta, turns = sliding_direction.plan(direction, surface.ndim, periodic, method)
    common = dict(speed=speed, load=load, approach=approach, periodic=periodic, method=method, rtol=rtol)
    common.update(maxiter=maxiter, raise_on_failure=raise_on_failure, contact_options=contact_options)
    if turns:
        return _solve_turned(
            surface, material, turns, initial=initial, error_estimate=error_estimate, **common, **adaptive_options
        )
    method = _check_method(periodic, method, adaptive_options)
    if method == "adaptive":
        return _solve_adaptive(surface, material, common, adaptive_options, error_estimate)
    maxiter = check_int("maxiter", maxiter, 1)
    _check_uniform(surface, periodic, approach, initial)
    t0 = time.perf_counter()
    op = operator_for(surface, material, speed, periodic, theta)
    sol = solve_contact(
        op,
        surface.heights,
        mean_pressure=None if load is None else load / op.area,
        approach=approach,
        rtol=rtol,
        maxiter=maxiter,
        initial=initial,
        raise_on_failure=False,
        options=contact_options or ContactOptions(),
    )
    result = _result(op, surface, speed, sol, periodic, time.perf_counter() - t0)
    log.info("speed %.3e m/s: %s", speed, sol.message)
    rerun = dict(speed=speed, load=load, approach=approach, periodic=periodic, method=method, rtol=rtol)
    rerun.update(maxiter=maxiter, contact_options=contact_options, direction=theta, warm=True)
    return _assessed(result, surface, material, error_estimate, raise_on_failure, rerun, theta=theta)


def _load_of_pressure(surface, nominal_pressure, load, approach, factor):
    """The load (N, or N/m for profiles; on the scanned patch for a measured surface) that puts
    ``nominal_pressure`` (Pa) on the cell; :class:`~bem.errors.InputError` unless exactly one of
    ``load``, ``nominal_pressure`` and ``approach`` is given."""
    given = [
        name
        for name, v in (("load", load), ("nominal_pressure", nominal_pressure), ("approach", approach))
        if v is not None
    ]
    if len(given) != 1:
        raise InputError(
            "give exactly one of load (N, or N/m for profiles; on the scanned patch for a measured surface), "
            "nominal_pressure (Pa, the mean pressure) or approach (m; displacement control), got "
            + (" and ".join(given) if given else "none of them")
        )
    return load_of_pressure(surface, nominal_pressure, factor)


def load_of_pressure(surface, nominal_pressure, factor=None):
    """The ``load`` argument of :func:`solve` (N, or N/m for profiles; on the scanned patch for a
    measured surface) that puts the mean pressure ``nominal_pressure`` (Pa) on ``surface``.
    ``factor``: :func:`bem.surfaces.measured.load_factor` of the surface, if already known."""
    surface = _as_surface(surface)
    if factor is None:
        factor = measured_patch.load_factor(surface)
    cell_load = check_positive("nominal_pressure", nominal_pressure) * surface.length**surface.ndim
    return cell_load if factor is None else cell_load / factor


def _on_patch(surface, material, factor, options, adaptive_options):
    """:func:`solve` of a measured patch as the user means it: the cell (which holds the patch
    ``factor`` times) gets ``factor`` times the patch's ``load``; the result gives ``load`` and
    ``dissipated_power`` on the patch (fields stay the cell's) and the patch's speed-limit
    warning (:func:`bem.surfaces.measured.speed_limit`)."""
    if options["load"] is not None:
        options["load"] = measured_patch.cell_load(surface, check_positive("load", options["load"]))
    meta = {key: value for key, value in surface.metadata.items() if key != "measured"}
    cell = dataclasses.replace(surface, metadata=meta)  # solved as the cell it is
    try:
        result = solve(cell, material, **options, **adaptive_options)
    except ConvergenceError as err:
        if err.result is not None:
            err.result = _as_asked(err.result, surface, material, factor)
        raise
    return _as_asked(result, surface, material, factor)


def _as_asked(result, surface, material, factor):
    """The cell's result on the patch (:func:`_on_patch`)."""
    text = measured_patch.speed_limit_warning(surface, material, result.speed)
    found = result.warnings + ((Finding(text, "patch_speed_limit", result.speed),) if text else ())
    return dataclasses.replace(
        result, load=result.load / factor, dissipated_power=result.dissipated_power / factor, warnings=found
    )


def _check_method(periodic, method, adaptive_options):
    """``method``, checked against ``periodic`` and the adaptive solver's options."""
    if not isinstance(periodic, (bool, np.bool_)):
        raise InputError(f"periodic must be True (periodic cell) or False (isolated contact), got {show(periodic)}")
    methods = _PERIODIC_METHODS if periodic else _ISOLATED_METHODS
    if method not in methods:
        raise InputError(
            f"method must be one of {', '.join(repr(m) for m in methods)} for "
            f"periodic={bool(periodic)}, got {show(method)}"
        )
    if adaptive_options and method != "adaptive":
        names = ", ".join(repr(k) for k in sorted(adaptive_options))
        raise InputError(
            f"{names} {'is an option' if len(adaptive_options) == 1 else 'are options'} of "
            f"method='adaptive' (isolated contacts) only, got method={method!r}"
        )
    return method


def _solve_adaptive(surface, material, common, adaptive_options, error_estimate):
    """``method="adaptive"``: :func:`bem.adaptive.solve_adaptive` (load control only),
    with its error estimate and warnings (:func:`_assessed`)."""
    if common["load"] is None:
        raise InputError(
            "approach (displacement control) is not available with method='adaptive'; "
            "give load (N, or N/m for profiles)"
        )
    from .adaptive.solver import solve_adaptive

    keep = ("speed", "load", "rtol", "maxiter")
    result = solve_adaptive(
        surface, material, **{k: common[k] for k in keep}, raise_on_failure=False, **adaptive_options
    )
    finer = {**adaptive_options, "levels": len(result.meshes)}  # the same coarse mesh, one level more
    rerun = dict(periodic=False, method="adaptive", **{k: common[k] for k in keep}, **finer)
    return _assessed(result, surface, material, error_estimate, common["raise_on_failure"], rerun, theta=0.0)


def _check_uniform(surface, periodic, approach, initial):
    """The warm start's shape, and on periodic cells an approach below full contact."""
    if initial is not None:
        initial = check_array("initial", initial)
        if initial.shape != surface.shape:
            raise InputError(f"initial must have the heights' shape {surface.shape}, got {initial.shape}")
    if approach is not None and periodic:
        limit = float(surface.heights.max() - surface.heights.mean())
        if not approach < limit:
            raise InputError(
                f"approach must be in (0, {show(limit)}) m: at max(h) - mean(h) the cell is in full "
                f"contact and the load is unbounded (zero-mean displacement), got {show(approach)}"
            )


def _result(op, surface, speed, sol, periodic, wall_time):
    """The :class:`SlidingResult` of a contact solution: friction in both forms, power, contact."""
    p = sol.pressure
    total = float(p.mean() * op.area)
    if total > 0:
        friction, friction_eq6 = (_friction_periodic if periodic else _friction_isolated)(op, surface, p, total)
        friction_eq6 = sliding_direction.eq6(op, surface.heights, p, total, friction_eq6)
    else:
        friction = friction_eq6 = 0.0
    return SlidingResult(
        pressure=p,
        displacement=sol.displacement,
        gap=sol.gap,
        approach=sol.approach,
        contact_fraction=float(np.count_nonzero(p > 0) / p.size),
        friction=float(friction),
        friction_eq6=friction_eq6,
        dissipated_power=float(friction * total * speed),
        load=total,
        speed=speed,
        iterations=sol.iterations,
        matvecs=sol.matvecs,
        residual=sol.residual,
        success=sol.success,
        message=sol.message,
        wall_time=wall_time,
        attainable=sol.attainable,
    )


def _assessed(result, surface, material, error_estimate, raise_on_failure, rerun, *, theta):
    """``result`` with its error estimate and warnings (:mod:`bem.accuracy`); raises
    :class:`~bem.errors.ConvergenceError` (carrying it) if it failed and ``raise_on_failure``.
    ``rerun``: the keywords that solve the same problem on the finer grid of the refined estimate
    (``warm``: whether it takes the coarse pressure as its first iterate)."""
    warm = rerun.pop("warm", False)

    def resolve(finer, initial):
        return solve(finer, material, initial=initial if warm else None, error_estimate=None, **rerun)

    periodic = rerun["periodic"]
    result = assess(
        result, surface, material, periodic=periodic, direction=theta, estimate=error_estimate, resolve=resolve
    )
    if not result.success and raise_on_failure:
        raise ConvergenceError(f"speed {show(result.speed)} m/s: {result.message}", result)
    return result


def _friction_periodic(op, surface, p, total):
    """Dissipation form (exact in Fourier space) and eq. 6 (spectral dh/dx) on a periodic cell."""
    friction = op.dissipation_integral(fft.forward(p)) / total
    dhdx = fft.inverse(
        1j * fft.wavevectors(surface.shape, surface.length)[0] * fft.forward(surface.heights), surface.shape
    )
    return friction, float(-np.mean(p * dhdx) * op.area / total)


def _friction_isolated(op, surface, p, total):
    """Dissipation form (slope collocated at element centres) and eq. 6 (central differences)."""
    friction = op.dissipation_integral(p) / total
    dhdx = np.gradient(surface.heights, op.spacing, axis=0)
    return friction, float(-np.sum(p * dhdx) * op.spacing**surface.ndim / total)


def _solve_turned(surface, material, turns, *, initial=None, **options):
    """:func:`solve` along ``+x`` on the heights turned by ``-turns`` quarter turns, fields turned
    back (:mod:`bem.direction`). A :class:`~bem.errors.ConvergenceError` carries the turned-back
    result too."""
    if options.get("height") is not None:
        raise InputError(
            "direction must be 0 with an exact height function (height=...): the function is "
            "given in the surface's frame; turn the surface instead"
        )
    try:
        result = solve(
            sliding_direction.turn_surface(surface, turns),
            material,
            initial=sliding_direction.turn_array(initial, turns),
            direction=0.0,
            **options,
        )
    except ConvergenceError as err:
        if err.result is not None:
            err.result = sliding_direction.turn_back(err.result, turns)
        raise
    return sliding_direction.turn_back(result, turns)
