"""The refinement loop of the adaptive BEM and its public entry point, :func:`solve_adaptive`.

Friction: ``friction`` is the dissipation form ``-(1/F) sum_i f_i u'(x_i)`` with the slope of
the displacement at the element centres (closed form; the creep slope is
``(k - g) / L``), ``friction_eq6 = -(1/F) sum_i f_i h'(x_i)`` with the indenter's slope there.
Both converge to ``F_x / F_N`` with refinement. Output fields are mapped back to the fine
grid piecewise constant per element (``gap >= 0`` and ``p gap = 0`` hold exactly there).
"""

import logging
import time
from dataclasses import dataclass, field

import numpy as np

from ..checks import check_int, check_positive, show
from ..contact import solve_contact
from ..contact.options import MAXITER, RTOL
from ..errors import ConvergenceError, InputError
from ..materials.material import Material
from ..result import SlidingResult
from ..surfaces.surface import Surface
from .assembly import ForceOperator, influence_matrix, phase_symbol
from .mesh import element_values, marked_elements, owner, refine, uniform_mesh

__all__ = ["AdaptiveResult", "solve_adaptive"]

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False, repr=False)
class AdaptiveResult(SlidingResult):
    """:class:`~bem.result.SlidingResult` of :func:`solve_adaptive`, with the meshes it built.

    Attributes
    ----------
    meshes : tuple of AdaptiveMesh
        The mesh of every level solved, coarsest first; ``meshes[-1]`` carries the fields.
    """

    meshes: tuple = field(default=(), repr=False)


def _indenter(surface, height, sampling):
    """Functions ``mesh -> (heights, x-slopes)`` at the element centres."""
    dx = surface.spacing
    if height is not None:

        def values(c):
            return np.broadcast_to(np.asarray(height(*c.T), dtype=float), (len(c),))

        def at(mesh):
            c = mesh.centres()
            e = np.zeros(c.shape[1])
            e[0] = 0.25 * dx  # central difference: exact for quadratic indenters
            return values(c), (values(c + e) - values(c - e)) / (0.5 * dx)

        return at
    h = np.asarray(surface.heights, dtype=float)
    dh = np.gradient(h, dx, axis=0)  # second order inside; the contact must stay off the border
    return lambda mesh: (element_values(mesh, h, sampling), element_values(mesh, dh, sampling))


def _solve_level(mesh, material, speed, load, heights, initial, rtol, maxiter, with_slope):
    """One contact solve on ``mesh``; returns (solution in forces, K, S)."""
    K, S = influence_matrix(mesh, material, speed, with_slope)
    areas = mesh.areas()
    op = ForceOperator(K, areas, phase_symbol(material, speed, mesh))
    # initial None on the coarsest level: the contact solver starts strongly non-symmetric
    # problems from its symmetric part's contact, others from op.initial_pressure
    sol = solve_contact(
        op, heights, mean_pressure=load / len(mesh), rtol=rtol, maxiter=maxiter, initial=initial, raise_on_failure=False
    )
    return sol, K, S


def _check(surface, material, speed, load, rtol, levels, buffer, gradient, sampling, height):
    if not isinstance(surface, Surface):
        raise InputError(f"surface must be a bem.surfaces.Surface, got {type(surface).__name__}")
    if not isinstance(material, Material):
        raise InputError(f"material must be a bem.Material, got {type(material).__name__}")
    speed = check_positive("speed", speed, allow_zero=True)
    load = check_positive("load", load)
    rtol = check_positive("rtol", rtol)
    if rtol >= 1:
        raise InputError(f"rtol must be in (0, 1), got {show(rtol)}")
    levels = check_int("levels", levels, 0, 12)
    if surface.n % 2**levels:
        raise InputError(
            f"levels must leave whole coarse elements: surface.n = {surface.n} must be divisible "
            f"by 2**levels = {2**levels}; got levels = {levels}"
        )
    buffer = check_positive("buffer", buffer, allow_zero=True)
    gradient = check_positive("gradient", gradient)
    if sampling not in ("centre", "mean"):
        raise InputError(f"sampling must be 'centre' or 'mean', got {show(sampling)}")
    if height is not None and not callable(height):
        raise InputError(f"height must be a callable h(x[, y]) (m), got {type(height).__name__}")
    return speed, load, rtol, levels, buffer, gradient


def _run(
    surface,
    material,
    speed,
    load,
    rtol,
    levels,
    buffer,
    gradient,
    refine_contact,
    sampling,
    height,
    maxiter,
    max_elements,
):
    """The refinement loop; returns ``(meshes, last solution, K, S, heights, slopes, totals)``."""
    speed, load, rtol, levels, buffer, gradient = _check(
        surface, material, speed, load, rtol, levels, buffer, gradient, sampling, height
    )
    indenter = _indenter(surface, height, sampling)
    mesh = uniform_mesh(surface.n, surface.length, surface.ndim, 2**levels)
    meshes, initial, iterations, matvecs = [], None, 0, 0
    for level in range(levels + 1):
        if len(mesh) > max_elements:
            raise InputError(
                f"max_elements: level {level} needs {len(mesh)} elements > max_elements = "
                f"{max_elements}; use fewer levels, a coarser surface or a larger limit"
            )
        hts, slopes = indenter(mesh)
        sol, K, S = _solve_level(mesh, material, speed, load, hts, initial, rtol, maxiter, with_slope=level == levels)
        iterations, matvecs = iterations + sol.iterations, matvecs + sol.matvecs
        meshes.append(mesh)
        log.info("adaptive level %d: %d elements, %s", level, len(mesh), sol.message)
        if level == levels or not sol.success:
            break
        p = sol.pressure / mesh.areas()
        mark = marked_elements(mesh, p, buffer=buffer, gradient=gradient, refine_contact=refine_contact)
        fine = refine(mesh, mark)
        # warm start: the parent's pressure on its children
        parent = owner(mesh, fine)
        initial = p[parent] * fine.areas()
        mesh = fine
    return meshes, sol, K, S, hts, slopes, iterations, matvecs


def solve_adaptive(
    surface,
    material,
    *,
    speed,
    load,
    rtol=RTOL,
    levels=3,
    buffer=1.0,
    gradient=0.05,
    refine_contact=True,
    sampling="centre",
    height=None,
    maxiter=MAXITER,
    max_elements=20000,
    raise_on_failure=True,
):
    """Steady sliding of an isolated indenter on the adaptive non-uniform mesh.

    Parameters
    ----------
    surface : bem.surfaces.Surface
        Indenter on the fine grid (the finest level): 1-D profile (plane strain, strips) or
        square 2-D map (squares), heights (m) positive toward the half-space, coordinates
        centred on the domain (``surface.centered``; see the module docstring).
    material : bem.Material
    speed : float
        Sliding speed (m/s) in ``+x``, >= 0.
    load : float
        Normal force (N), or per unit length (N/m) for a profile, > 0.
    rtol : float
        Complementarity residual in forces (module docstring), in (0, 1).
    levels : int
        Refinement levels, 0..12: the coarse mesh has blocks of ``2**levels`` fine cells
        (``surface.n`` must be divisible by it); ``0`` is the dense uniform fine mesh.
    buffer : float
        Elements within ``buffer`` times their own size of the contact edge are refined (>= 0).
    gradient : float
        Elements across a pressure jump larger than ``gradient * max(p)`` are refined (> 0).
    refine_contact : bool
        Refine every element in contact (the seed's rule, default) or only those flagged by
        ``buffer`` and ``gradient``.
    sampling : {"centre", "mean"}
        Element heights from the fine grid (module docstring); ignored with ``height``.
    height : callable, optional
        ``height(x)`` or ``height(x, y)`` (m, arrays of centre coordinates in m): exact heights
        at the element centres instead of sampling ``surface.heights``.
    maxiter : int
        Active-set iterations per level.
    max_elements : int
        Refuse meshes with more elements (the dense matrix has ``N_e**2`` entries).
    raise_on_failure : bool
        Raise :class:`bem.errors.ConvergenceError` if a level does not converge.

    Returns
    -------
    AdaptiveResult
        Fields on the fine grid (piecewise constant per element; ``displacement`` absolute,
        see the module docstring for profiles); ``iterations`` and ``matvecs`` summed over
        the levels; ``residual`` and ``message`` those of the finest level; ``meshes`` the
        mesh of every level, coarsest first.
    """
    t0 = time.perf_counter()
    maxiter = check_int("maxiter", maxiter, 1)
    max_elements = check_int("max_elements", max_elements, 1)
    meshes, sol, K, S, hts, slopes, iterations, matvecs = _run(
        surface,
        material,
        speed,
        load,
        rtol,
        levels,
        buffer,
        gradient,
        refine_contact,
        sampling,
        height,
        maxiter,
        max_elements,
    )
    mesh = meshes[-1]
    f = sol.pressure
    areas = mesh.areas()
    p = f / areas
    total = float(f.sum())
    if S is None:  # a coarser level failed: its slope matrix was not built
        S = influence_matrix(mesh, material, speed)[1]
    slope_u = S @ p
    friction = float(-np.dot(f, slope_u) / total)
    friction_eq6 = float(-np.dot(f, slopes) / total)
    speed = float(speed)
    message = f"{len(meshes) - 1} refinement levels, {len(mesh)} elements; {sol.message}"
    result = AdaptiveResult(
        pressure=mesh.to_fine(p),
        displacement=mesh.to_fine(sol.displacement),
        gap=mesh.to_fine(sol.gap),
        approach=float(sol.approach),
        contact_fraction=float(np.sum(areas[p > 0]) / mesh.length**mesh.ndim),
        friction=friction,
        friction_eq6=friction_eq6,
        dissipated_power=friction * total * speed,
        load=total,
        speed=speed,
        iterations=iterations,
        matvecs=matvecs,
        residual=sol.residual,
        success=sol.success,
        message=message,
        wall_time=time.perf_counter() - t0,
        meshes=tuple(meshes),
    )
    if not sol.success and raise_on_failure:
        raise ConvergenceError(f"speed {show(speed)} m/s: {message}", result)
    return result
