"""Steady rolling (or frictionless sliding) of a rigid cylinder on a viscoelastic block.

Sign conventions (SPEC §2.2, stated once here): the cylinder moves in ``+x`` at speed
``V``; in its frame the material flows in ``-x``, so ``+x`` is upstream and the leading
edge. Heights of the cylinder are ``h(x) = -x^2 / (2R)`` (positive toward the solid,
maximum 0 at its lowest point ``x = 0``). Pressure is positive in compression. The
tangential force on the cylinder is ``F_x = int p h'(x) dx = -(P / R) x_bar`` with
``x_bar`` the pressure centroid, so the friction coefficient ``mu = x_bar / R`` is
positive when the pressure shifts toward the leading edge, i.e. when energy is
dissipated; the dissipated power per unit length is ``mu P V`` (W/m).
"""
from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field

import numpy as np

from bem.checks import check_int, check_positive
from bem.errors import ConvergenceError, InputError
from bem.material import Material

from .contact import solve_load_control
from .kinematics import quadrature_operators
from .mesh import half_space_mesh
from .steady import steady_operator, stress_and_dissipation
from .surface import contact_edges, top_surface

__all__ = ["RollingResult", "rolling_cylinder", "domain_size"]
log = logging.getLogger(__name__)


@dataclass(frozen=True)
class RollingResult:
    """Result of :func:`rolling_cylinder` (SI units; lengths in m, per unit length in z).

    Attributes
    ----------
    x : ndarray
        Top-surface node coordinates in the candidate contact band (m).
    pressure : ndarray
        Contact pressure at ``x`` (Pa): nodal force over ``int phi_i ds``.
    displacement : ndarray
        Depression (vertical displacement into the solid) at ``x`` (m).
    forces : ndarray
        Nodal contact forces at ``x`` (N/m); they sum to ``load``.
    leading_edge, trailing_edge : float
        Contact edges (m), leading at ``+x``.
    friction : float
        ``mu = x_bar / R`` from the moment of the nodal forces (SPEC eq. 6).
    friction_dissipation : float
        Viscous dissipation integrated over the block, over ``P V`` (0 at ``V = 0``). The
        two forms converge together; against Hunter's exact solution at 3 elements per
        glassy half-width the moment form is the better one at low speed (0.6 % vs
        1.8 % at ``V lambda = 0.3 a0``) and the dissipation form at high speed (0.05 %
        vs 4.6 % at ``V lambda = 100 a0``, where the pressure centroid moves by a
        hundredth of a node spacing).
    dissipated_power : float
        Viscous dissipation integrated over the block (W/m), from the internal variables;
        it matches ``friction * load * speed`` (the moment form) to the discretisation error.
    peak_pressure, load, speed, radius, approach : float
        Pa, N/m, m/s, m, m (the approach depends on the truncation depth in 2-D).
    element_size, domain_width, domain_depth, grading : float
        Core element size ``h``, half-width ``L`` and depth ``H`` of the block (m), and
        the element growth ratio outside the core.
    n_elements, n_unknowns, iterations : int
    residual : float
        Complementarity residual of the active-set solve.
    material : bem.Material
        The material actually used (after folding inactive Prony terms).
    timings : dict
        Wall times (s) of ``assemble_factor``, ``flexibility``, ``contact``, ``fields``.
    fields : dict
        Quadrature-point fields (only with ``keep_fields=True``): ``points``, ``strain``,
        ``stress``, ``pressure``, ``alpha`` (list), ``dissipation``, ``weights``, and ``u``, ``mesh``.
    """

    x: np.ndarray
    pressure: np.ndarray
    displacement: np.ndarray
    forces: np.ndarray
    leading_edge: float
    trailing_edge: float
    friction: float
    friction_dissipation: float
    dissipated_power: float
    peak_pressure: float
    load: float
    speed: float
    radius: float
    approach: float
    element_size: float
    domain_width: float
    domain_depth: float
    grading: float
    n_elements: int
    n_unknowns: int
    iterations: int
    residual: float
    material: object = None
    success: bool = True
    message: str = "converged"
    timings: dict = field(default_factory=dict)
    fields: dict = field(default_factory=dict, repr=False)


def _hertz_half_width(E, nu, radius, load):
    return float(np.sqrt(4.0 * load * radius * (1.0 - nu**2) / (np.pi * E)))


def domain_size(material, radius, load, speed, *, contact_factor=40.0, retardation_factor=30.0):
    """Half-width ``L`` = depth ``H`` of the block (m) standing for the half-space.

    ``L = max(contact_factor * a_0, retardation_factor * V * max(lambda_k))`` with ``a_0``
    the relaxed Hertz half-width and ``lambda_k`` the creep (retardation) times: the
    truncation error of the elastic problem scales as ``(a/H)^2`` and that of the
    viscoelastic one with ``V lambda / L`` (the retardation length must fit inside).
    """
    a0 = _hertz_half_width(material.E0, material.nu, radius, load)
    ell_r = speed * float(np.max(material.creep_times)) if material.creep_times.size else 0.0
    return max(contact_factor * a0, retardation_factor * ell_r)


def rolling_cylinder(material, *, radius, load, speed, resolution=6, contact_band=1.5,
                     domain=None, grading=1.5, fold=1e-4, solver="auto", maxiter=100,
                     keep_fields=False, vtk=None):
    """Steady rolling of a rigid cylinder on a viscoelastic half-space (plane strain FEM).

    Parameters
    ----------
    material : bem.Material
        Prony series (one Poisson ratio for all terms; ``nu = 0.5`` is allowed).
    radius : float
        Cylinder radius ``R`` (m).
    load : float
        Normal force per unit length ``P`` (N/m).
    speed : float
        Rolling speed ``V`` (m/s), ``>= 0``.
    resolution : int
        Core elements (9-node) per glassy Hertz half-width ``a_inf``: ``h = a_inf /
        resolution``. Node spacing is ``h / 2``.
    contact_band : float
        Half-width of the candidate contact band and of the uniform core, in relaxed
        Hertz half-widths ``a_0``.
    domain : float, optional
        Block half-width = depth (m); default :func:`domain_size`.
    grading : float
        Element growth ratio outside the core, in (1, 2]; 1.2 and 2 give the same
        friction to 0.1 % (the far field is smooth), 2 with half the unknowns.
    fold : float
        Prony terms with ``V tau_k < fold * h`` (relaxed on every element) are dropped and
        those with ``V tau_k > a_0 / fold`` (glassy over the contact) are added to the
        relaxed modulus (:meth:`bem.Material.folded`), before the domain is sized; 0
        keeps every term. The terms used are reported in ``RollingResult.material``.
    solver : {"auto", "splu", "pardiso"}
    maxiter : int
        Active-set iteration limit.
    keep_fields : bool
        Keep quadrature-point fields in ``result.fields``.
    vtk : str or path, optional
        Write the fields to this ``.vtm`` (block and contact interface) or ``.vtu`` (block)
        file, with the metadata (:mod:`fem_reference.vtk`).

    Returns
    -------
    RollingResult

    Raises
    ------
    bem.errors.InputError
        Bad parameter.
    bem.errors.ConvergenceError
        The active set does not settle, or the contact reaches the edge of the band.
    """
    if not isinstance(material, Material):
        raise InputError(f"material must be a bem.Material, got {type(material).__name__}")
    R = check_positive("radius", radius)
    P = check_positive("load", load)
    V = check_positive("speed", speed, allow_zero=True)
    n_res = check_int("resolution", resolution, 1, 200)
    band = check_positive("contact_band", contact_band)
    maxiter = check_int("maxiter", maxiter, 1)
    ratio = check_positive("grading", grading)
    if not 1.0 < ratio <= 2.0:
        raise InputError(f"grading must be in (1, 2], got {grading!r}")
    if band < 1.05:
        raise InputError(f"contact_band must be >= 1.05 relaxed half-widths, got {contact_band!r}")
    fold = check_positive("fold", fold, allow_zero=True)
    if fold >= 1:
        raise InputError(f"fold must be in [0, 1), got {fold!r}")
    nu = material.nu
    a_inf = _hertz_half_width(material.E_inf, nu, R, P)
    h = a_inf / n_res
    if fold > 0 and not material.is_elastic:
        a_relaxed = _hertz_half_width(material.E0, nu, R, P)
        material = material.folded(V / a_relaxed, V / h, tol=fold)
    a0 = _hertz_half_width(material.E0, nu, R, P)
    L = domain_size(material, R, P, V) if domain is None else check_positive("domain", domain)
    xb = band * a0
    if L < 4 * xb:
        raise InputError(f"domain must be >= 4 * contact_band * a_0 = {4 * xb!r} m, got {L!r}")

    t0 = time.perf_counter()
    hs = half_space_mesh((-xb, xb), h, x_range=(-L, L), depth=L, core_depth=xb, ratio=ratio)
    ops = quadrature_operators(hs.mesh, "plane")
    op = steady_operator(ops, material, V, solver=solver)
    t1 = time.perf_counter()

    top = top_surface(ops.basis)
    cand = np.abs(top.x) <= xb * (1 + 1e-12)
    ydofs = top.ydofs[cand]
    F = np.zeros((ops.basis.N, ydofs.size))
    F[ydofs, np.arange(ydofs.size)] = -1.0  # unit downward force on the body
    u_unit, _, _ = op.solve(F)
    w_top = -u_unit[top.ydofs]  # depression at every top node per unit force
    t2 = time.perf_counter()

    xc = top.x[cand]
    hc = -xc**2 / (2 * R)
    sol = solve_load_control(w_top[cand], hc, P, active=np.abs(xc) <= a_inf, maxiter=maxiter)
    act = np.flatnonzero(sol.active)
    if act[0] == 0 or act[-1] == xc.size - 1:
        raise ConvergenceError("the contact reached the edge of the candidate band; increase contact_band")
    gap_top = w_top @ sol.lam + top.x**2 / (2 * R) - sol.d
    if np.any(gap_top[~cand] < -1e-9 * abs(sol.d)):
        raise ConvergenceError("the solid penetrates the cylinder outside the candidate band; "
                               "increase contact_band")
    t3 = time.perf_counter()

    forces = F @ sol.lam  # downward nodal forces on the body
    u, p, alpha = op.solve(forces)
    eps, sigma, diss = stress_and_dissipation(ops, material, u, p, alpha)
    power_fields = float(ops.weights @ diss)
    t4 = time.perf_counter()

    pres = sol.lam / top.weights[cand]
    lead, trail = contact_edges(xc, pres, sol.active)
    mu = float(sol.lam @ xc / (R * P))
    res = RollingResult(
        x=xc, pressure=pres, displacement=w_top[cand] @ sol.lam, forces=sol.lam,
        leading_edge=lead, trailing_edge=trail,
        friction=mu, friction_dissipation=power_fields / (P * V) if V > 0 else 0.0,
        dissipated_power=power_fields, peak_pressure=float(pres.max()), load=P, speed=V, radius=R,
        approach=sol.d, element_size=hs.element_size, domain_width=L, domain_depth=hs.depth, grading=ratio,
        n_elements=hs.n_elements, n_unknowns=op.n_unknowns, iterations=sol.iterations,
        residual=sol.residual, material=material,
        timings={"assemble_factor": t1 - t0, "flexibility": t2 - t1, "contact": t3 - t2, "fields": t4 - t3},
        fields=dict(mesh=hs.mesh, basis=ops.basis, u=u, points=ops.points, weights=ops.weights,
                    strain=eps, stress=sigma, pressure=p, alpha=alpha, dissipation=diss) if (keep_fields or vtk) else {},
    )
    if vtk is not None:
        from .vtk import write_fields

        write_fields(vtk, res.fields, res)
        if not keep_fields:
            res = _drop_fields(res)
    log.info("rolling V=%g: mu=%.6g, edges [%g, %g], %d unknowns, %.1f s", V, mu, trail, lead,
             op.n_unknowns, t4 - t0)
    return res


def _drop_fields(res):
    from dataclasses import replace

    return replace(res, fields={})
