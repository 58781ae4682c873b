"""Public entry points: one steady sliding solve and a sweep over speeds.

Units SI. Load is the total normal force on the cell (N) for 2-D surfaces and the force
per unit length (N/m) for 1-D profiles. The indenter slides at ``speed`` (m/s) in ``+x``.

Friction (SPEC §2.3): ``friction`` is the dissipation form
``mu = -(1/F_N) ∫ p du/dx dA`` evaluated exactly in Fourier space (non-negative on any
grid); ``friction_eq6 = -(1/F_N) ∫ p dh/dx dA`` (the seed's eq. 6) uses the spectral
derivative of the heights. They coincide in full contact and converge together as the
grid resolves the contact spots. ``dissipated_power = friction * F_N * speed`` (W, or
W/m for profiles).
"""
import logging
import time
from dataclasses import dataclass, field

import numpy as np

from . import fft
from .checks import check_array, check_int, check_positive
from .contact import solve_contact
from .errors import ConvergenceError, InputError
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
        Normal surface displacement (m, positive into the solid), zero mean (the periodic
        half-space has no defined mean displacement; the approach carries it).
    gap : ndarray
        ``displacement - (h - max(h) + approach)`` (m), >= 0, zero in contact.
    approach : float
        Rigid approach from first touch (m), relative to the mean plane of the deformed
        surface.
    contact_fraction : float
        Fraction of the cell in contact (``pressure > 0``).
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


def operator_for(surface, material, speed):
    """The (cached) periodic response operator of this grid, material and speed."""
    key = (surface.shape, surface.length, _material_key(material), float(speed))
    op = _operators.get(key)
    if op is None:
        op = PeriodicHalfSpace(surface.shape, surface.length, material, speed)
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


def solve(surface, material, *, speed, load=None, approach=None, periodic=True, method="auto",
          rtol=1e-8, maxiter=400, initial=None, raise_on_failure=True):
    """Steady sliding of a rigid surface over a viscoelastic half-space (periodic cell).

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
        Only ``True`` (periodic cell) is available in this version.
    method : {"auto", "active-set"}
        Contact algorithm; both select the primal–dual active-set solver with CG (elastic)
        or GMRES (viscoelastic) inner solves.
    rtol : float
        Tolerance on the complementarity residual (see :mod:`bem.contact`).
    maxiter : int
        Maximum active-set iterations.
    initial : ndarray, optional
        Warm-start pressure (Pa), e.g. from a neighbouring speed.
    raise_on_failure : bool
        Raise :class:`bem.errors.ConvergenceError` when the tolerance is not reached
        (default). With ``False`` the result comes back with ``success=False``.

    Returns
    -------
    SlidingResult
    """
    surface, speed, load, approach, rtol = _check_inputs(surface, material, speed, load, approach, rtol)
    if periodic is not True:
        raise InputError("periodic must be True: this version solves periodic cells only "
                         "(isolated contacts are a separate solver)")
    if method not in ("auto", "active-set"):
        raise InputError(f"method must be one of 'auto', 'active-set', got {method!r}")
    maxiter = check_int("maxiter", maxiter, 1)
    if initial is not None:
        initial = check_array("initial", initial)
        if initial.shape != surface.shape:
            raise InputError(f"initial must have the heights' shape {surface.shape}, got {initial.shape}")
    if approach is not None:
        limit = float(surface.heights.max() - surface.heights.mean())
        if not approach < limit:
            raise InputError(f"approach must be in (0, {limit!r}) m: at max(h) - mean(h) the cell is in full "
                             f"contact and the load is unbounded (zero-mean displacement), got {approach!r}")
    t0 = time.perf_counter()
    op = operator_for(surface, material, speed)
    area = op.area
    sol = solve_contact(op, surface.heights, mean_pressure=None if load is None else load / area,
                        approach=approach, rtol=rtol, maxiter=maxiter, initial=initial,
                        raise_on_failure=False)
    p = sol.pressure
    total = float(p.mean() * area)
    pq = fft.forward(p)
    if total > 0:
        friction = op.dissipation_integral(pq) / total
        dhdx = fft.inverse(1j * fft.wavevectors(surface.shape, surface.length)[0]
                           * fft.forward(surface.heights), surface.shape)
        friction_eq6 = float(-np.mean(p * dhdx) * area / total)
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
                   progress=False, callback=None):
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
                        initial=previous if warm_start else None)
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
