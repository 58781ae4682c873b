"""Axisymmetric indentation of a viscoelastic half-space by a rigid sphere (step load).

The load ``P`` is applied at ``t = 0`` and held. At ``t = 0+`` the solid responds with its
glassy modulus ``E_inf``; as ``t -> inf`` with the relaxed ``E0``. While the contact
grows, Lee & Radok's solution holds (E.H. Lee, J.R.M. Radok, J. Appl. Mech. 27 (1960)
438-444, doi:10.1115/1.3644020)::

    a(t)^3 = (3 R / 4) P (1 - nu^2) J(t).

Sphere heights ``h(r) = -r^2 / (2R)`` (positive toward the solid, docs/theory.md §4); approach
``delta`` (m) positive into the solid; pressure positive in compression.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field

import numpy as np

from bem.checks import check_array, check_int, check_positive
from bem.errors import ConvergenceError, InputError
from bem.materials.material import Material

from .axisymmetric import AxisymmetricStepper, fixed_dofs_axisymmetric
from .contact import complementarity_limit, complementarity_residual, gap_scale, solve_load_control
from .indentation_mesh import indentation_mesh
from .kinematics import quadrature_operators
from .linsolve import solve_on_path, solver_path
from .steady import stress_and_dissipation
from .surface import top_surface

__all__ = [
    "IndentationResult",
    "indentation",
    "time_grid",
    "hertz_radius",
    "RESOLUTION",
    "ESTIMATE_LIMIT",
    "SHIFT_FACTOR",
    "SHIFT_PHASE",
]

log = logging.getLogger(__name__)

# Elements per local contact radius by default: the finest whose solve and its shifted twin stay
# under five minutes on an 18-term rubber at E_inf/E0 = 3000 (271 s, 1.0 GiB; docs/theory.md §9).
RESOLUTION = 12
# A result whose error estimate exceeds this share warns.
ESTIMATE_LIMIT = 0.01
# The shifted solve's change times this is the estimate: the two readings are equally good, and an
# error they share (the moving edge's layer, the mesh's) is not in their difference. Twice the change
# covered the contact radius's error at every time on four held-out rubbers at the default mesh and
# on a standard solid at 2 to 8 elements per radius, by 1.4 times at least where the error exceeded
# 0.5 % (docs/theory.md §9).
SHIFT_FACTOR = 2.0
# The shifted solve's mesh, in elements of the sweep: half a node spacing, since a 9-node element
# has a node at its middle. Its surface nodes then fall between the first mesh's, so an edge that
# sits at a node of one is halfway between two of the other (a shift of half an element would put
# its nodes on the first mesh's middle nodes, where both read the edge alike).
SHIFT_PHASE = 0.25
# The relaxed limit's step, in longest creep times: it leaves exp(-RELAXED_STEP) of the creep.
RELAXED_STEP = 1e4


@dataclass(frozen=True)
class IndentationResult:
    """Result of :func:`indentation` at the requested ``times`` (SI units).

    Attributes
    ----------
    times : ndarray
        Requested times (s).
    contact_radius : ndarray
        Contact radius ``a(t)`` (m), from the gaps of the first two free nodes (``g^(2/3)``
        extrapolated to zero).
    approach : ndarray
        Rigid approach ``delta(t)`` (m).
    peak_pressure : ndarray
        Largest nodal pressure (Pa).
    r, pressure : ndarray
        Surface node radii (m) in the candidate band and pressure (Pa) at the last time.
    element_size, domain_size : float
        Element size over the glassy contact (``a_inf / resolution``) and block radius = depth (m).
    n_elements, n_unknowns, n_steps : int
    iterations : ndarray of int
        Active-set iterations per requested time.
    contact_force : ndarray
        Sum of the nodal contact forces per requested time (N); it equals ``load`` when the
        contact carries the load it was given.
    timings : dict
        Wall time (s) of the whole run under ``total``, of the solve on the result's mesh under
        ``solve`` and of the shifted solve of the error estimate under ``estimate``.
    success, message : bool, str
        True only if every linear solve is within its limit (``linear_residual <=
        linear_residual_limit``) and every step's complementarity ``residual`` is within
        :func:`~fem_reference.contact.complementarity_limit` of that limit.
    linear_residual : float
        Relative residual of the linear solve (SuperLU or PARDISO) closest to its limit: the
        force balance against the load, ``||K u - f|| / ||f||``, the constraint rows against
        their own terms (:func:`~fem_reference.linsolve.relative_residual`).
    linear_residual_limit : float
        Its limit: 1e-8, or ten times the round-off floor of the force balance where that is
        higher (:func:`~fem_reference.linsolve.residual_limit`).
    residual : float
        Largest complementarity residual over the steps, from each step's solution
        (:func:`~fem_reference.contact.complementarity_residual`: gaps of the displaced surface in
        and out of the active set, signs of the forces).
    solver : str
        Linear solver of the result.
    solver_path : tuple of dict
        Every factorisation tried, in order, with its diagnostics and outcome
        (:func:`~fem_reference.linsolve.solve_on_path`).
    error_estimate : dict
        ``contact_radius`` and ``approach``: relative error estimates at the output times, each the
        larger of :data:`SHIFT_FACTOR` times the change from a solve on the mesh shifted by half a
        node spacing (:data:`SHIFT_PHASE`) with half the steps per decade, and the largest error of this mesh's two elastic
        limits against Hertz (``elastic_limits``).
    elastic_limits : dict
        Relative errors against Hertz of the contact radius and approach at ``t = 0+`` (``glassy``,
        modulus ``E_inf``) and after a step of ``1e4`` longest creep times past the last output
        (``relaxed``, ``E0``), on this mesh (``fine_*``) and on the shifted one (``shifted_*``).
    warnings : tuple of str
        Set when an error estimate exceeds :data:`ESTIMATE_LIMIT`.
    """

    times: np.ndarray
    contact_radius: np.ndarray
    approach: np.ndarray
    peak_pressure: np.ndarray
    r: np.ndarray
    pressure: np.ndarray
    element_size: float
    domain_size: float
    n_elements: int
    n_unknowns: int
    n_steps: int
    iterations: np.ndarray
    contact_force: np.ndarray = None
    success: bool = False
    message: str = ""
    timings: dict = field(default_factory=dict)
    linear_residual: float = float("nan")
    linear_residual_limit: float = float("nan")
    residual: float = float("nan")
    solver: str = ""
    solver_path: tuple = ()
    error_estimate: dict = field(default_factory=dict)
    elastic_limits: dict = field(default_factory=dict)
    warnings: tuple = ()


def time_grid(times, creep_times, steps_per_decade):
    """Internal step times: the requested ``times`` plus log-spaced points (s).

    Steps grow geometrically from ``1e-3 min(lambda_k)`` so that every creep time is
    resolved by ``steps_per_decade`` steps per decade (the exponential update is second
    order in the step, and exact for piecewise-linear strain in time).
    """
    times = np.asarray(times, dtype=float)
    pos = times[times > 0]
    if pos.size == 0 or creep_times.size == 0:
        return np.unique(np.concatenate([[0.0], times]))
    t0 = 1e-3 * float(np.min(creep_times))
    t1 = float(pos.max())
    extra = (
        np.geomspace(t0, t1, max(2, int(np.ceil(np.log10(t1 / t0) * steps_per_decade)) + 1)) if t1 > t0 else np.zeros(0)
    )
    # a log-spaced point within round-off of a requested time would be a second step "at" that
    # time (a step of ~1e-16 s) and a second output for it: the requested time is kept exactly
    extra = extra[~np.any(np.isclose(extra[:, None], times[None, :], rtol=1e-9, atol=0), axis=1)]
    return np.unique(np.concatenate([[0.0], times, extra]))


def _nodal_pressure(r, lam, w):
    """``lam / w``; on the axis, where ``w = int phi 2 pi r dr = 0`` for the quadratic
    element (to round-off), the pressure (an even function of ``r``) is extrapolated linearly in ``r^2``
    from the next two nodes."""
    p = np.zeros_like(lam)
    pos = w > 1e-9 * w.max()
    p[pos] = lam[pos] / w[pos]
    if not pos[0]:
        p1, p2, r1, r2 = p[1], p[2], r[1], r[2]
        p[0] = max(0.0, p1 + (p1 - p2) * r1**2 / (r2**2 - r1**2)) if lam[0] > 0 else 0.0
    return p


def indentation(
    material,
    *,
    radius,
    load,
    times,
    resolution=RESOLUTION,
    contact_band=1.5,
    domain=None,
    grading=1.3,
    steps_per_decade=20,
    solver="auto",
    maxiter=100,
    vtk=None,
):
    """Creep indentation by a rigid sphere under a step load (axisymmetric FEM).

    The mesh (:mod:`fem_reference.indentation_mesh`) holds ``resolution`` elements per contact
    radius at every radius the contact edge sweeps from the glassy to the relaxed Hertz radius. The
    same problem is solved a second time on the mesh shifted by half a node spacing with half the
    steps per decade, and each result carries the error estimate of its contact radius and approach (see
    :class:`IndentationResult`); a warning says when it exceeds :data:`ESTIMATE_LIMIT`.

    Parameters
    ----------
    material : bem.Material
    radius : float
        Sphere radius ``R`` (m).
    load : float
        Normal force ``P`` (N), applied at ``t = 0`` and held.
    times : array_like
        Output times (s), ``>= 0``; ``0`` means ``0+`` (glassy response).
    resolution : int
        Elements (9-node) per local contact radius, from the glassy to ``contact_band`` relaxed
        Hertz radii. At the default the contact radius was within 1.45 % and the approach within
        1.2 % of Lee & Radok on rubbers of 1 to 18 terms and modulus ratios 10 to 3000
        (docs/theory.md §9).
    contact_band : float
        Radius of the candidate contact band and of the graded sweep, in relaxed Hertz radii.
    domain : float, optional
        Block radius = depth (m); default 1000 relaxed Hertz radii. The approach carries
        a truncation error of order ``a / domain`` (measured -2.5 % at 40 radii, 0.1 % at
        1000); the grading makes the large block cheap.
    grading : float
        Element growth ratio beyond the contact band, in (1, 2].
    steps_per_decade : int
        Time steps per decade of time (see :func:`time_grid`).
    solver : {"auto", "splu", "pardiso"}
    maxiter : int
        Active-set iteration limit per step.
    vtk : str or path, optional
        Write a ``.pvd`` time series there: one ``.vtm`` (block and contact interface) per
        output time (:func:`fem_reference.vtk.write_indentation`).

    Returns
    -------
    IndentationResult
    """
    if not isinstance(material, Material):
        raise InputError(f"material must be a bem.Material, got {type(material).__name__}")
    R = check_positive("radius", radius)
    P = check_positive("load", load)
    t_out = check_array("times", times, ndim=1)
    if np.any(t_out < 0) or np.any(np.diff(t_out) < 0):
        raise InputError(f"times must be >= 0 s and non-decreasing, got {t_out!r}")
    n_res = check_int("resolution", resolution, 1, 200)
    spd = check_int("steps_per_decade", steps_per_decade, 1, 1000)
    maxiter = check_int("maxiter", maxiter, 1)
    band = check_positive("contact_band", contact_band)
    if band < 1.05:
        raise InputError(f"contact_band must be >= 1.05 relaxed radii, got {contact_band!r}")
    ratio = check_positive("grading", grading)
    if not 1.0 < ratio <= 2.0:
        raise InputError(f"grading must be in (1, 2], got {grading!r}")
    a0 = hertz_radius(material.E0, material.nu, R, P)
    L = 1000 * a0 if domain is None else check_positive("domain", domain)
    if L < 4 * band * a0:
        raise InputError(f"domain must be >= 4 * contact_band * a_0 = {4 * band * a0!r} m, got {L!r}")

    t_start = time.perf_counter()
    setup = dict(material=material, R=R, P=P, band=band, L=L, grading=ratio, solver=solver, maxiter=maxiter)
    run = _creep_run(t_out, n_res, spd, vtk=vtk, **setup)
    shifted = _creep_run(t_out, n_res, max(1, spd // 2), phase=SHIFT_PHASE, **setup)
    estimate, limits = _estimate(run, shifted, material, R, P)
    warnings = tuple(
        f"{name.replace('_', ' ')} error estimate {float(np.max(e)):.2%} exceeds {ESTIMATE_LIMIT:.0%} "
        f"(resolution {n_res}): raise the resolution"
        for name, e in estimate.items()
        if np.max(e, initial=0.0) > ESTIMATE_LIMIT
    )
    for w in warnings:
        log.warning(w)
    message = _message(run["linear"], run["limit"], run["worst"])
    if shifted["success"] is False:
        message = message if message != CONVERGED else "the shifted solve of the error estimate: " + shifted["message"]
    return IndentationResult(
        times=t_out,
        contact_radius=run["a"],
        approach=run["d"],
        peak_pressure=run["p"],
        r=run["r"],
        pressure=run["pressure"],
        element_size=run["mesh"].element_size,
        domain_size=L,
        n_elements=run["mesh"].n_elements,
        n_unknowns=run["n_unknowns"],
        n_steps=run["n_steps"],
        iterations=run["it"],
        contact_force=run["f"],
        timings={"total": time.perf_counter() - t_start, "solve": run["wall"], "estimate": shifted["wall"]},
        success=message == CONVERGED,
        message=message,
        linear_residual=float(run["linear"]),
        linear_residual_limit=float(run["limit"]),
        residual=run["worst"],
        solver=run["solver"],
        solver_path=run["solver_path"],
        error_estimate=estimate,
        elastic_limits=limits,
        warnings=warnings,
    )


def hertz_radius(modulus, nu, radius, load):
    """Hertz contact radius (m): ``a^3 = 3 P R (1 - nu^2) / (4 E)``."""
    return (3 * load * radius * (1 - nu**2) / (4 * modulus)) ** (1 / 3)


def _creep_run(t_out, n_res, spd, *, material, R, P, band, L, grading, solver, maxiter, phase=0.0, vtk=None):
    """Step the load through ``t_out`` on the mesh of ``n_res`` elements per contact radius; one
    more step of ``RELAXED_STEP`` longest creep times after the last gives the relaxed limit."""
    t_start = time.perf_counter()
    a_inf = hertz_radius(material.E_inf, material.nu, R, P)
    a0 = hertz_radius(material.E0, material.nu, R, P)
    hs = indentation_mesh(a_inf, a0, n_res, band=band, length=L, grading=grading, phase=phase)
    ops = quadrature_operators(hs.mesh, "axi")
    fixed = fixed_dofs_axisymmetric(ops.basis)

    def build(step, memory):
        return AxisymmetricStepper(ops, material, fixed, solver=step.solver, memory=memory)

    def work(stepper, checkpoint):
        top = top_surface(ops.basis, axisymmetric=True)
        cand = top.x <= band * a0 * (1 + 1e-12)
        rc = top.x[cand]
        hc = -(rc**2) / (2 * R)
        F = np.zeros((ops.basis.N, rc.size))
        F[top.ydofs[cand], np.arange(rc.size)] = -1.0  # unit downward ring forces (N)

        grid = time_grid(t_out, material.creep_times, spd)
        lam_max = float(np.max(material.creep_times)) if material.creep_times.size else 0.0
        t_relaxed = grid[-1] + RELAXED_STEP * lam_max
        out = {k: [] for k in ("a", "d", "p", "it", "f")}
        worst = 0.0
        U = stepper.unit_response(F)  # glassy response to unit ring forces
        checkpoint()
        w_unit = -U[top.ydofs]
        t_prev, active, pres, snaps, limits = 0.0, rc <= a_inf, None, [], {}
        for k, t in enumerate(np.append(grid, t_relaxed)):
            e, u_hist = stepper.prepare(t - t_prev)
            w = w_unit / e  # depression at all top nodes per unit force in this step
            w0 = -u_hist[top.ydofs]
            sol = solve_load_control(w[cand], hc, P, w0=w0[cand], active=active, maxiter=maxiter)
            if sol.active[-1]:
                raise ConvergenceError("the contact reached the edge of the candidate band; increase contact_band")
            u_now = U @ sol.lam / e + u_hist
            relaxed_step = k == grid.size
            out_now = 0 if relaxed_step else np.count_nonzero(t_out == t)  # the grid holds the requested times
            p_now = stepper.pressure(F @ sol.lam) if vtk is not None and out_now else None
            stepper.commit(u_now)
            # from the solution itself: the gaps of the displaced surface, the forces' signs
            gap_now = -u_now[top.ydofs[cand]] + rc**2 / (2 * R) - sol.d
            worst = max(
                worst, complementarity_residual(sol.lam, gap_now, sol.active, P, gap_scale(sol.d, hc[sol.active]))
            )
            active, t_prev = sol.active, t
            step_pres = _nodal_pressure(rc, sol.lam, top.weights[cand])
            if out_now or k == 0 or relaxed_step:
                edge = _edge_from_gap(rc, sol.gap, sol.active)
            if k == 0:  # the grid starts at t = 0+
                limits["glassy"] = (edge, sol.d)
            if relaxed_step:
                limits["relaxed"] = (edge, sol.d)
                continue
            pres = step_pres
            for _ in range(out_now):
                out["a"].append(edge)
                out["d"].append(sol.d)
                out["p"].append(float(pres.max()))
                out["it"].append(sol.iterations)
                out["f"].append(float(sol.lam.sum()))
                if vtk is not None:
                    _, stress, diss = stress_and_dissipation(ops, material, u_now, p_now, stepper.alpha)
                    snaps.append(
                        dict(
                            t=float(t),
                            u=u_now,
                            eps=stepper.eps,
                            alpha=list(stepper.alpha),
                            stress=stress,
                            dissipation=diss,
                            pressure=pres,
                            approach=sol.d,
                        )
                    )
        if vtk is not None:
            from .vtk import write_indentation

            write_indentation(vtk, snaps, ops, material, R, P, rc)
        message = _message(stepper.residual, stepper.residual_limit, worst)
        return dict(
            a=np.array(out["a"]),
            d=np.array(out["d"]),
            p=np.array(out["p"]),
            it=np.array(out["it"], dtype=int),
            f=np.array(out["f"]),
            r=rc,
            pressure=pres,
            mesh=hs,
            n_unknowns=stepper.n_unknowns,
            n_steps=grid.size,
            linear=stepper.residual,
            limit=stepper.residual_limit,
            worst=worst,
            solver=stepper.factor.name,
            limits=limits,
            success=message == CONVERGED,
            message=message,
            wall=time.perf_counter() - t_start,
        )

    run, report = solve_on_path(solver_path(solver), build, work)
    run["solver_path"] = tuple(report)
    return run


def _edge_from_gap(r, gap, active):
    """Contact radius (m) from the gaps of the first two free nodes: outside a smooth contact edge
    the gap opens as ``(r - a)^(3/2)``, so ``g^(2/3)`` is extrapolated linearly to zero, and the
    edge is kept between the last node in contact and the first free one."""
    i = np.flatnonzero(active)[-1]
    g1, g2 = (max(float(g), 0.0) ** (2 / 3) for g in gap[i + 1 : i + 3])
    if not g2 > g1:
        return float(r[i + 1])
    return float(np.clip(r[i + 1] - g1 * (r[i + 2] - r[i + 1]) / (g2 - g1), r[i], r[i + 1]))


def _estimate(run, shifted, material, R, P):
    """Error estimates of the contact radius and approach at the output times, and the errors of
    both runs' elastic limits against Hertz (docs/theory.md §9)."""
    exact = {}
    for name, modulus in (("glassy", material.E_inf), ("relaxed", material.E0)):
        a = hertz_radius(modulus, material.nu, R, P)
        exact[name] = (a, a * a / R)
    limits = {
        f"{which}_{name}": {
            q: float(run_["limits"][name][i] / exact[name][i] - 1) for i, q in enumerate(("contact_radius", "approach"))
        }
        for which, run_ in (("fine", run), ("shifted", shifted))
        for name in exact
    }
    estimate = {}
    for q, key in (("contact_radius", "a"), ("approach", "d")):
        floor = max(abs(limits[f"fine_{name}"][q]) for name in exact)
        change = np.abs(run[key] - shifted[key]) / np.abs(run[key])
        estimate[q] = np.maximum(SHIFT_FACTOR * change, floor)
    return estimate, limits


CONVERGED = "converged"


def _message(linear, limit, complementarity):
    problems = []
    if not linear <= limit:
        problems.append(f"linear solve residual {linear:.2e} > {limit:.1e}")
    compl_limit = complementarity_limit(limit)
    if not complementarity <= compl_limit:
        problems.append(f"complementarity residual {complementarity:.2e} > {compl_limit:.1e}")
    return "; ".join(problems) if problems else CONVERGED
