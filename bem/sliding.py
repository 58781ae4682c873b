"""Public entry points: one steady sliding solve and a sweep over speeds.

Units SI. Load is the total normal force on the cell (N) for 2-D surfaces and the force
per unit length (N/m) for 1-D profiles. The indenter slides at ``speed`` (m/s) in ``+x``.

Friction (SPEC §2.3): ``friction`` is the dissipation form
``mu = -(1/F_N) ∫ p du/dx dA`` evaluated exactly in Fourier space (non-negative on any
grid); ``friction_eq6 = -(1/F_N) ∫ p dh/dx dA`` (the seed's eq. 6) uses the spectral
derivative of the heights. They coincide in full contact and converge together as the
grid resolves the contact spots. ``dissipated_power = friction * F_N * speed`` (W, or
W/m for profiles).

Isolated contacts (``periodic=False``, :mod:`bem.isolated`): the domain is the array and
pressure outside it is zero. ``friction`` is again the dissipation form, collocated like the
displacement: ``-sum_j p_j u'(x_j) d**ndim`` with the exact slope of the displacement at the
element centres (see ``IsolatedHalfSpace.dissipation_integral``: the exact dissipation of the
piecewise-constant pressure would add that of its steps between elements, ~ ``L ln(d/L)``,
percent-level when ``v lambda`` is far below a cell); ``friction_eq6`` uses central
differences of the heights between element centres (one-sided at the domain's ends, where
the pressure vanishes).
"""
import logging
import time
from dataclasses import dataclass, field

import numpy as np

from . import direction as sliding_direction
from . import fft
from .checks import check_array, check_int, check_positive
from .contact import solve_contact
from .errors import ConvergenceError, InputError
from .isolated import IsolatedHalfSpace
from .material import Material
from .periodic import PeriodicHalfSpace
from .surfaces import Surface

__all__ = ["SlidingResult", "FrictionCurve", "solve", "friction_curve"]

log = logging.getLogger(__name__)

_CACHE_SIZE = 4
_operators = {}


@dataclass(frozen=True, eq=False)
class SlidingResult:
    """Steady sliding contact solution (arrays shaped like the heights).

    Attributes
    ----------
    pressure : ndarray
        Contact pressure (Pa), >= 0.
    displacement : ndarray
        Normal surface displacement (m, positive into the solid). Periodic cells: zero mean
        (the periodic half-space has no defined mean displacement; the approach carries it).
        Isolated 2-D contacts: absolute (zero at infinity); isolated profiles: up to the
        constant of plane strain (see :mod:`bem.isolated`).
    gap : ndarray
        ``displacement - (h - max(h) + approach)`` (m), >= 0, zero in contact.
    approach : float
        Rigid approach from first touch (m): relative to the mean plane of the deformed
        surface on periodic cells, to the undeformed surface far away for isolated 2-D
        contacts, and with the displacement's constant for isolated profiles.
    contact_fraction : float
        Fraction of the cell (isolated contacts: of the domain) in contact (``pressure > 0``).
    friction, friction_eq6 : float
        Viscoelastic friction coefficient, dissipation form and eq. 6 (see module doc).
    dissipated_power : float
        ``friction * load * speed`` (W; W/m for profiles).
    load, speed : float
        Normal force (N; N/m for profiles) and sliding speed (m/s).
    iterations, matvecs : int
        Active-set iterations and operator applications (FFT pairs).
    residual : float
        Complementarity residual reached (see :mod:`bem.contact`).
    success : bool
    message : str
    wall_time : float
        Seconds spent in the solve.
    """

    pressure: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    approach: float
    contact_fraction: float
    friction: float
    friction_eq6: float
    dissipated_power: float
    load: float
    speed: float
    iterations: int
    matvecs: int
    residual: float
    success: bool
    message: str
    wall_time: float = 0.0


def _as_surface(surface):
    if isinstance(surface, Surface):
        return surface
    if hasattr(surface, "heights") and hasattr(surface, "length"):
        return Surface(surface.heights, surface.length)
    raise InputError(f"surface must be a bem.surfaces.Surface (or have .heights and .length), "
                     f"got {type(surface).__name__}")


def _material_key(material):
    return (material.E0, material.nu, material.moduli.tobytes(), material.relaxation_times.tobytes())


def operator_for(surface, material, speed, periodic=True):
    """The (cached) response operator of this grid, material and speed: periodic cell or
    isolated domain (:class:`~bem.isolated.IsolatedHalfSpace`)."""
    key = (bool(periodic), surface.shape, surface.length, _material_key(material), float(speed))
    op = _operators.get(key)
    if op is None:
        kind = PeriodicHalfSpace if periodic else IsolatedHalfSpace
        op = kind(surface.shape, surface.length, material, speed)
        if len(_operators) >= _CACHE_SIZE:
            _operators.pop(next(iter(_operators)))
        _operators[key] = op
    return op


def _check_inputs(surface, material, speed, load, approach, rtol):
    surface = _as_surface(surface)
    if not isinstance(material, Material):
        raise InputError(f"material must be a bem.Material, got {type(material).__name__}")
    speed = check_positive("speed", speed, allow_zero=True)
    if (load is None) == (approach is None):
        raise InputError("give exactly one of load (N, or N/m for profiles; load control) "
                         "or approach (m; displacement control)")
    if load is not None:
        load = check_positive("load", load)
    else:
        approach = check_positive("approach", approach)
    rtol = check_positive("rtol", rtol)
    if rtol >= 1:
        raise InputError(f"rtol must be in (0, 1), got {rtol!r}")
    return surface, speed, load, approach, rtol


_ISOLATED_METHODS = ("auto", "uniform", "adaptive")
_PERIODIC_METHODS = ("auto", "active-set")


def _choose_isolated_method(surface, material, *, speed, load, rtol):
    """The isolated-contact method that ``method="auto"`` selects: ``"uniform"`` or ``"adaptive"``.

    Always the uniform DC-FFT grid, the faster one in ``benchmarks/isolated.py`` (tables:
    ``benchmarks/results/isolated_benchmark.json`` and ``..._xwide.json`` with their commits,
    dates and machine load, 2 shared cores at load 6-8, bem/ frozen for each run; figures
    ``isolated_pareto*.png``). Problems: rolling cylinder vs Hunter and sliding sphere vs a
    Richardson-extrapolated reference, each at ``V lambda / a0 = 0.3, 1, 5``, plus the sphere
    on domains 12 and 24 contact radii wide; error = max of the friction and peak-pressure
    errors. At equal fine grid both reach the same peak-pressure error (the same collocation
    inside the contact) and the uniform grid is faster or equal everywhere (adaptive/uniform
    time: cylinder 0.94-171, sphere 3-27, wide domains 1.0-6.6). At equal error the uniform
    grid is faster in 55 of the 65 (problem, tolerance 1e-1..1e-5) cells reached; of the
    others, 7 are the fast cylinder at 128 cells where both take 0.05 s (3 ms apart, timing
    noise) and 3 are wide sphere domains, within noise or owed to the adaptive solver's
    friction evaluation (its slope-matrix dissipation form converges faster), not its mesh.
    Nothing here depends on ``speed``, ``load``, ``rtol`` or the material; the arguments are
    kept for a future rule.
    """
    return "uniform"


def solve(surface, material, *, speed, load=None, approach=None, periodic=True, method="auto",
          rtol=1e-8, maxiter=400, initial=None, raise_on_failure=True, direction=0.0, **adaptive_options):
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
        Total normal force (N) on the cell, or per unit length (N/m) for a 1-D profile.
    approach : float, optional
        Displacement control instead of ``load``: rigid approach (m) from first touch.
    periodic : bool
        ``True``: periodic cell (:mod:`bem.periodic`). ``False``: isolated contact on a
        half-space, the array being the whole loaded domain (:mod:`bem.isolated`), e.g.
        :func:`bem.surfaces.sphere` or :func:`bem.surfaces.cylinder`.
    method : str
        Periodic cells: ``"auto"`` or ``"active-set"`` (the same primal–dual active-set
        solver with CG (elastic) or GMRES (viscoelastic) inner solves). Isolated contacts:
        ``"uniform"`` (DC-FFT on the uniform grid), ``"adaptive"`` (non-uniform mesh,
        :func:`bem.adaptive.solve_adaptive`, given ``adaptive_options``) or ``"auto"``.
    rtol : float
        Tolerance on the complementarity residual (see :mod:`bem.contact`).
    maxiter : int
        Maximum active-set iterations.
    initial : ndarray, optional
        Warm-start pressure (Pa), e.g. from a neighbouring speed.
    raise_on_failure : bool
        Raise :class:`bem.errors.ConvergenceError` when the tolerance is not reached
        (default). With ``False`` the result comes back with ``success=False``.
    direction : float
        Sliding direction (radians from ``+x`` toward ``+y``; default 0), see
        :mod:`bem.direction`: ``speed`` is along it, ``friction`` opposes it, fields stay on the
        surface's grid. 1-D profiles: 0 or pi only.

    Returns
    -------
    SlidingResult
    """
    surface, speed, load, approach, rtol = _check_inputs(surface, material, speed, load, approach, rtol)
    # sliding direction (bem.direction): a quarter turn solves along +x on turned heights
    theta, turns = sliding_direction.plan(direction, surface.ndim, periodic, method)
    if turns:
        return sliding_direction.solve_turned(
            solve, surface, material, turns, speed=speed, load=load, approach=approach, periodic=periodic,
            method=method, rtol=rtol, maxiter=maxiter, initial=initial, raise_on_failure=raise_on_failure,
            **adaptive_options)
    if not isinstance(periodic, (bool, np.bool_)):
        raise InputError(f"periodic must be True (periodic cell) or False (isolated contact), got {periodic!r}")
    methods = _PERIODIC_METHODS if periodic else _ISOLATED_METHODS
    if method not in methods:
        raise InputError(f"method must be one of {', '.join(repr(m) for m in methods)} for "
                         f"periodic={bool(periodic)}, got {method!r}")
    if adaptive_options and method != "adaptive":
        raise InputError(f"unexpected keyword(s) {sorted(adaptive_options)}: only method='adaptive' "
                         f"takes extra options")
    if not periodic and method == "auto":
        method = _choose_isolated_method(surface, material, speed=speed, load=load, rtol=rtol)
    if method == "adaptive":
        if load is None:
            raise InputError("approach (displacement control) is not available with method='adaptive'; "
                             "give load (N, or N/m for profiles)")
        from .adaptive import solve_adaptive

        return solve_adaptive(surface, material, speed=speed, load=load, rtol=rtol, maxiter=maxiter,
                              raise_on_failure=raise_on_failure, **adaptive_options)
    maxiter = check_int("maxiter", maxiter, 1)
    if initial is not None:
        initial = check_array("initial", initial)
        if initial.shape != surface.shape:
            raise InputError(f"initial must have the heights' shape {surface.shape}, got {initial.shape}")
    if approach is not None and periodic:
        limit = float(surface.heights.max() - surface.heights.mean())
        if not approach < limit:
            raise InputError(f"approach must be in (0, {limit!r}) m: at max(h) - mean(h) the cell is in full "
                             f"contact and the load is unbounded (zero-mean displacement), got {approach!r}")
    t0 = time.perf_counter()
    op = sliding_direction.operator(operator_for, surface, material, speed, periodic, theta)
    area = op.area
    sol = solve_contact(op, surface.heights, mean_pressure=None if load is None else load / area,
                        approach=approach, rtol=rtol, maxiter=maxiter, initial=initial,
                        raise_on_failure=False)
    p = sol.pressure
    total = float(p.mean() * area)
    if total > 0:
        friction, friction_eq6 = (_friction_periodic if periodic else _friction_isolated)(op, surface, p, total)
        friction_eq6 = sliding_direction.eq6(op, surface.heights, p, total, friction_eq6)
    else:
        friction = friction_eq6 = 0.0
    result = SlidingResult(
        pressure=p, displacement=sol.displacement, gap=sol.gap, approach=sol.approach,
        contact_fraction=float(np.count_nonzero(p > 0) / p.size), friction=float(friction),
        friction_eq6=friction_eq6, dissipated_power=float(friction * total * speed),
        load=total, speed=speed, iterations=sol.iterations, matvecs=sol.matvecs,
        residual=sol.residual, success=sol.success, message=sol.message,
        wall_time=time.perf_counter() - t0)
    log.info("speed %.3e m/s: %s", speed, sol.message)
    if not sol.success and raise_on_failure:
        raise ConvergenceError(f"speed {speed!r} m/s: {sol.message}", result)
    return result


def _friction_periodic(op, surface, p, total):
    """Dissipation form (exact in Fourier space) and eq. 6 (spectral dh/dx) on a periodic cell."""
    friction = op.dissipation_integral(fft.forward(p)) / total
    dhdx = fft.inverse(1j * fft.wavevectors(surface.shape, surface.length)[0]
                       * fft.forward(surface.heights), surface.shape)
    return friction, float(-np.mean(p * dhdx) * op.area / total)


def _friction_isolated(op, surface, p, total):
    """Dissipation form (slope collocated at element centres) and eq. 6 (central differences)."""
    friction = op.dissipation_integral(p) / total
    dhdx = np.gradient(surface.heights, op.spacing, axis=0)
    return friction, float(-np.sum(p * dhdx) * op.spacing ** surface.ndim / total)


@dataclass(frozen=True, eq=False)
class FrictionCurve:
    """A sweep over speeds (arrays in the order of ``speeds``; failed points are NaN).

    ``results[i]`` is the :class:`SlidingResult` of ``speeds[i]`` or ``None`` if it failed;
    ``messages[i]`` says why.
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

    @property
    def all_converged(self):
        return bool(np.all(self.success))


def friction_curve(surface, material, *, speeds, load, rtol=1e-8, maxiter=400, warm_start=True,
                   progress=False, callback=None, periodic=True, method="auto", direction=0.0):
    """Solve at each speed; warm-start each from its neighbour (in increasing speed).

    Parameters
    ----------
    speeds : array_like
        Sliding speeds (m/s), >= 0.
    load : float
        Normal force (N; N/m for profiles).
    progress : bool
        Show a progress bar (tqdm).
    callback : callable, optional
        ``callback(index, speed, result_or_None, message)`` after each point, e.g. to
        write it to disk at once; a point that fails to converge is reported with
        ``None`` and the sweep goes on.
    periodic, method, direction
        As in :func:`solve` (``periodic=False``: isolated contact; ``direction``: sliding
        direction, radians from +x). The warm start is skipped for ``method="adaptive"``
        (its mesh differs from the surface's grid).

    Returns
    -------
    FrictionCurve
    """
    try:
        speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    except (TypeError, ValueError):
        raise InputError(f"speeds must be a list of numbers (m/s), got {speeds!r}") from None
    if speeds.ndim != 1 or speeds.size == 0 or not np.all(np.isfinite(speeds)) or np.any(speeds < 0):
        raise InputError(f"speeds must be a non-empty 1-D list of finite speeds >= 0 m/s, got {speeds!r}")
    surface, _, load, _, rtol = _check_inputs(surface, material, 0.0, load, None, rtol)
    from tqdm.auto import tqdm

    n = speeds.size
    results, messages = [None] * n, [""] * n
    previous = None
    for i in tqdm(np.argsort(speeds, kind="stable"), total=n, disable=not progress,
                  desc="friction curve", unit="speed"):
        try:
            res = solve(surface, material, speed=speeds[i], load=load, rtol=rtol, maxiter=maxiter,
                        initial=previous if warm_start and method != "adaptive" else None,
                        periodic=periodic, method=method, direction=direction)
        except ConvergenceError as err:
            res, messages[i] = None, str(err)
            log.warning("%s", err)
        else:
            messages[i] = res.message
            previous = res.pressure
        results[i] = res
        if callback is not None:
            callback(int(i), float(speeds[i]), res, messages[i])

    def column(attr, dtype=float):
        return np.array([getattr(r, attr) if r is not None else np.nan for r in results], dtype=dtype)

    return FrictionCurve(speeds=speeds, friction=column("friction"), friction_eq6=column("friction_eq6"),
                         contact_fraction=column("contact_fraction"),
                         dissipated_power=column("dissipated_power"), iterations=column("iterations"),
                         residual=column("residual"), success=np.array([r is not None for r in results]),
                         messages=messages, results=results)
