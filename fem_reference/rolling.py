"""Steady rolling (or frictionless sliding) of a rigid cylinder on a viscoelastic block.

Sign conventions (docs/theory.md §3, stated once here): the cylinder moves in ``+x`` at speed
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
import resource
import time
from dataclasses import replace
from functools import partial
from types import SimpleNamespace

import numpy as np

from bem.checks import check_int, check_positive
from bem.errors import ConvergenceError, InputError

from .contact import complementarity_limit, complementarity_residual, gap_scale, solve_load_control
from .graded import LAYER_ELEMENTS, SINGLE_TERM_FLOOR, fold_terms, graded_half_space, graded_quadtree, initial_edges
from .kinematics import quadrature_operators
from .linsolve import available_memory, solve_on_path
from .mesh import half_space_mesh
from .rolling_inputs import check_inputs, check_uniform_fits, domain_size, hertz_half_width
from .rolling_result import RollingResult
from .steady import condensed_terms, solution_fields, steady_operator, stress_and_dissipation, system_path
from .surface import contact_edges, top_surface

__all__ = ["RollingResult", "rolling_cylinder", "domain_size"]
log = logging.getLogger(__name__)


# The moment and the dissipation form of the friction converge to the same value; where they differ
# by more than this share of the friction, the mesh does not resolve what dissipates. Measured on the
# graded mesh at resolution 6: at most 0.85 % apart at the four target speeds of three broad rubbers
# and 0.7 % on Hunter's solid (E_inf/E0 = 10-1000) from v lambda / a0 = 0.3 up; two decades below a
# broad rubber's friction peak 0.91 % apart, with both forms within 0.53 % of the BEM (2.0 % apart
# and the dissipation form 3 % off with the trailing edge meshed like the rest of the contact)
FORM_GAP = 0.01
# The error estimate solves the problem again on the mesh's twin, with every size the contact sets (edge
# elements, trailing zone, leading-edge layer) and the far elements this many times larger and the
# block this many times smaller. An error of order p >= 1 in the size is then at most the change to
# the twin (change / (2^p - 1)), which is the estimate. One above its limit warns: the accuracy a
# reference must hold, 1 % in the friction, 2 % in the peak pressure (a nodal value at a steep layer)
TWIN_COARSEN = 2.0
ESTIMATE_LIMIT = {"friction": 0.01, "friction_dissipation": 0.01, "peak_pressure": 0.02}
# Least block half-width of the graded mesh, in contact half-widths
MIN_SPAN = 8


def _peak_memory_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


class _BandEdge(Exception):
    """The contact reached an end of the candidate band."""


def _solve_mesh(hs, material, R, P, V, band, *, solver, maxiter, condense, active_width, squares=False):
    """Factor (along the system's solver path), condense onto the candidate nodes, solve the
    contact and the fields."""
    t0 = time.perf_counter()
    ops = quadrature_operators(hs.mesh, "plane", hanging=getattr(hs, "hanging", None))
    cmask = condensed_terms(ops, material, V, condense)
    top = top_surface(ops.basis)
    cand = (top.x >= band[0] - 1e-12 * abs(band[0])) & (top.x <= band[1] + 1e-12 * abs(band[1]))
    setup = time.perf_counter() - t0

    def build(step, memory):
        form = False if step.carried else cmask
        return steady_operator(ops, material, V, solver=step.solver, condense=form, memory=memory)

    def work(op, checkpoint):
        return _contact_and_fields(op, ops, top, cand, R, P, band, active_width, maxiter, checkpoint)

    out, report = solve_on_path(system_path(material, V, cmask, solver, squares=squares), build, work)
    # the fields are solved and nothing solves with this factor again: free it (keeping its name and
    # size for the result) before the next mesh (a remesh pass or the twin) is factored beside it
    factor = out["op"].factor
    out["op"] = replace(out["op"], factor=SimpleNamespace(name=factor.name, nnz=getattr(factor, "nnz", -1)))
    del factor
    out.update(mesh=hs, ops=ops, solver_path=tuple(report))
    out["timings"]["assemble"] += setup
    out["timings"]["assemble_factor"] += setup
    return out


def _contact_and_fields(op, ops, top, cand, R, P, band, active_width, maxiter, checkpoint):
    """The flexibility of the candidate nodes, the contact under load ``P`` and the fields, with the
    factored operator ``op``; ``checkpoint()`` after the flexibility leaves a factor whose solves
    missed before the contact is solved with them."""
    t1 = time.perf_counter()
    ydofs = top.ydofs[cand]
    w_top = op.flexibility(top.ydofs, ydofs)
    checkpoint()
    t2 = time.perf_counter()

    xc = top.x[cand]
    hc = -(xc**2) / (2 * R)
    centre = 0.5 * (band[0] + band[1])
    # the active set may take in every candidate and shed them one by one (nodes packed at a thin
    # leading-edge layer, whose gaps are all near zero): twice the candidates bounds that walk
    limit = maxiter if maxiter is not None else max(100, 2 * xc.size)
    sol = solve_load_control(w_top[cand], hc, P, active=np.abs(xc - centre) <= active_width, maxiter=limit)
    act = np.flatnonzero(sol.active)
    if act[0] == 0 or act[-1] == xc.size - 1:
        raise _BandEdge()
    gap_top = w_top @ sol.lam + top.x**2 / (2 * R) - sol.d
    if np.any(gap_top[~cand] < -1e-9 * abs(sol.d)):
        raise _BandEdge()
    t3 = time.perf_counter()

    f = np.zeros(ops.basis.N)
    f[ydofs] = -sol.lam  # the contact forces on the body
    u, p, alpha = op.solve(f)
    # the contact condition as the field solve satisfies it: gaps from the displaced surface
    gap_field = -u[ydofs] + xc**2 / (2 * R) - sol.d
    residual = complementarity_residual(sol.lam, gap_field, sol.active, P, gap_scale(sol.d, hc[sol.active]))
    eps, sigma, diss = stress_and_dissipation(ops, op.material, u, p, alpha)
    t4 = time.perf_counter()
    pres = sol.lam / top.weights[cand]
    lead, trail = contact_edges(xc, pres, sol.active)
    # the operator's own assembly and factorisation (the caller adds its setup)
    timings = dict(op.timings, flexibility=t2 - t1, contact=t3 - t2, fields=t4 - t3)
    timings["assemble_factor"] = timings["assemble"] + timings["factor"]
    return dict(
        op=op,
        sol=sol,
        residual=residual,
        xc=xc,
        pres=pres,
        w=w_top[cand],
        edges=(trail, lead),
        candidates=int(ydofs.size),
        u=u,
        p=p,
        alpha=alpha,
        eps=eps,
        sigma=sigma,
        diss=diss,
        timings=timings,
    )


def rolling_cylinder(
    material,
    *,
    radius,
    load,
    speed,
    resolution=6,
    contact_band=1.5,
    domain=None,
    grading=None,
    fold=1e-4,
    solver="auto",
    maxiter=None,
    keep_fields=False,
    vtk=None,
    estimate=True,
    mesh="quadtree",
    condense="auto",
    layer_floor=0.01,
    passes=8,
):
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
        ``mesh="quadtree"`` or ``"graded"``: elements (9-node) per contact half-width at the
        contact edges and at the surface. ``mesh="uniform"``: core elements per glassy Hertz half-width ``a_inf``,
        ``h = a_inf / resolution``. Node spacing is ``h / 2``.
    contact_band : float
        Uniform mesh: half-width of the candidate contact band and of the uniform core,
        in relaxed Hertz half-widths ``a_0``.
    domain : float, optional
        Block half-width = depth (m); default :func:`domain_size`.
    grading : float, optional
        Element growth ratio, in (1, 2]: outside the core (uniform mesh; 1.2 and 2 give
        the same friction to 0.1 %, the far field being smooth) or everywhere (graded; on the
        quadtree, one plus the growth of the element size per unit distance from the contact).
        Default :data:`~fem_reference.rolling_inputs.TENSOR_GRADING` (1.5) on the tensor meshes,
        :data:`~fem_reference.rolling_inputs.QUADTREE_GRADING` (1.25) on the quadtree.
    fold : float
        Tolerance for folding inactive Prony terms; 0 keeps every term. Uniform mesh:
        terms with ``V tau_k < fold * h`` are dropped and those with ``V tau_k > a_0 /
        fold`` added to the relaxed modulus (:meth:`bem.Material.folded`). Graded mesh:
        the bounds of :mod:`fem_reference.graded` (the arm's stress relative to the
        relaxed one at the smallest element and over the block). The terms used are in
        ``RollingResult.material`` and ``RollingResult.terms``.
    solver : {"auto", "splu", "pardiso"}
        The factorisations tried, in order (:func:`fem_reference.linsolve.solver_path`):
        ``"auto"`` takes PARDISO where it is installed and SuperLU where its solves miss their
        residual; an explicit one runs alone. ``result.solver_path`` reports each step.
    maxiter : int, optional
        Active-set iteration limit; default twice the candidate nodes, at least 100.
    keep_fields : bool
        Keep quadrature-point fields in ``result.fields``.
    vtk : str or path, optional
        Write the fields to this ``.vtm`` (block and contact interface) or ``.vtu`` (block)
        file, with the metadata (:mod:`fem_reference.vtk`).
    estimate : bool
        Estimate the discretisation error of the friction in both forms and of a resolved peak
        pressure from the same problem solved on the mesh's coarse twin (every size the contact
        sets and the far elements :data:`TWIN_COARSEN` times larger, the block as many times
        smaller; a graded twin settles on its own edges) and, for the friction, from the gap
        between the forms: ``result.error_estimate``, and a warning where one exceeds its
        :data:`ESTIMATE_LIMIT`. ``False`` skips the twin.
    mesh : {"quadtree", "graded", "uniform"}
        ``"quadtree"`` (the default) grades squares toward the contact edges and the leading-edge
        layers in both directions (:mod:`fem_reference.quadtree`,
        :func:`fem_reference.graded.graded_quadtree`) and remeshes until the edges settle (at most
        ``passes`` meshes): no element is longer than it is wide, the element count grows with the
        logarithm of the block over the contact, not with the block or the modulus ratio, and every
        term is carried by its outflow values (local couplings, whatever ``V tau_k``).
        ``"graded"`` grades a tensor mesh the same way (:mod:`fem_reference.graded`): its finest
        columns and rows cross the whole block. ``"uniform"`` meshes a uniform core of
        ``h = a_inf / resolution`` over the relaxed contact band, whose element count grows with
        ``E_inf / E0``; where its factor cannot fit in the memory available it is refused before
        anything is assembled (:func:`fem_reference.rolling_inputs.check_uniform_fits`).
    condense : {"auto", True, False}
        Eliminate the viscous strains through their truncated memory instead of carrying them
        by the elements' outflow values (:mod:`fem_reference.steady`); ``"auto"``: the terms
        whose memory reaches at most an element upstream (:func:`fem_reference.steady.condensable`).
    layer_floor : float
        Graded mesh: thinnest leading-edge layer ``V tau_k`` the mesh resolves, in edge elements.
        A layer at least this thick gets :data:`~fem_reference.graded.LAYER_ELEMENTS` elements;
        toward a thinner one the elements stop at this size, and the result says the peak pressure
        is not resolved. Where a single term is kept (a standard solid) its layer is resolved
        down to :data:`~fem_reference.graded.SINGLE_TERM_FLOOR` edge elements whatever this is.
        Nowhere are the elements refined below the block half-width over
        :data:`~fem_reference.graded.MAX_SPAN`: a layer that would need it is left to the edge
        elements and reported unresolved (two decades above a broad rubber's friction peak).
    passes : int
        Graded mesh: most meshes solved while the edges settle.

    Returns
    -------
    RollingResult

    Raises
    ------
    bem.errors.InputError
        Bad parameter.
    bem.errors.ConvergenceError
        The active set does not settle, the contact reaches the edge of the band, or PARDISO's
        solve misses its residual and SuperLU's factor would outgrow the available memory.
    MemoryError
        SuperLU, asked for (``solver="splu"``) or taken for terms carried by their outflow values,
        would outgrow the available memory (:data:`fem_reference.linsolve.MEMORY_SHARE` of it).
    """
    R, P, V, n_res, band, maxiter, ratio, fold = check_inputs(
        material, radius, load, speed, resolution, contact_band, maxiter, grading, fold, mesh
    )
    if condense not in ("auto", True, False):
        raise InputError(f"condense must be 'auto', True or False, got {condense!r}")
    layer_floor = check_positive("layer_floor", layer_floor)
    passes = check_int("passes", passes, 1, 50)
    t_start = time.perf_counter()
    given = material
    kw = dict(solver=solver, maxiter=maxiter, condense=condense)
    if mesh == "uniform":
        material, terms, hs, out, npass = _run_uniform(material, R, P, V, n_res, band, ratio, fold, domain, kw)
    else:
        if mesh == "quadtree":
            # every term carried by its outflow values: the couplings stay within an element and its
            # upstream faces, and on squares PARDISO solves that form (see system_path)
            kw = dict(kw, condense=False if condense == "auto" else condense, squares=True)
        plan = graded_quadtree if mesh == "quadtree" else graded_half_space
        material, terms, hs, out, npass = _run_graded(
            material, R, P, V, n_res, ratio, fold, domain, layer_floor, passes, kw, plan
        )
    if estimate and V > 0 and material.relaxation_times.size:
        # a solid that does not dissipate has no friction to estimate: its value is round-off
        _estimate(out, material, R, P, V, mesh)
    return _result(material, terms, hs, out, npass, R, P, V, ratio, mesh, keep_fields, vtk, t_start, given)


def _coarser(ratio, length, least):
    """The twin's growth ratio and block half-width: elements far from the contact, about
    ``ratio - 1`` times their distance from it, TWIN_COARSEN times larger, and the block
    TWIN_COARSEN times smaller (not below ``least``)."""
    return 1 + TWIN_COARSEN * (ratio - 1), max(length / TWIN_COARSEN, least)


FORMS = ("friction", "friction_dissipation")


def _layer(material, V, hs, mesh):
    """The thinnest leading-edge layer ``V tau_k``, the smallest element along x, how many of them a
    resolved layer spans, and whether this one is resolved."""
    taus = material.relaxation_times
    layer = float(V * np.min(taus)) if taus.size and V > 0 else float("inf")
    h_min = hs.smallest_element
    # the graded meshes put LAYER_ELEMENTS elements across a layer they resolve (graded_half_space)
    across = 1 if mesh == "uniform" else LAYER_ELEMENTS
    return layer, h_min, across, layer >= across * h_min * (1 - 1e-6)


def _readings(out, R, P, V):
    """Friction in the moment and the dissipation form of a solved mesh."""
    power = float(out["ops"].weights @ out["diss"])
    return {
        "friction": float(out["sol"].lam @ out["xc"] / (R * P)),
        "friction_dissipation": power / (P * V) if V > 0 else 0.0,
    }


def _estimate(out, material, R, P, V, mesh):
    """Solve the coarse twin of ``out``'s mesh and set ``out["estimate"]``: for either form of the
    friction, the larger of its relative change to the twin and the gap between the two forms; for
    the peak pressure its change, where the result resolves the layer (docs/theory.md §9)."""
    t0 = time.perf_counter()
    try:
        coarse = out["twin"]()
    except (_BandEdge, ConvergenceError, MemoryError) as err:
        out["estimate"] = {}
        out["estimate_failed"] = f"no error estimate: the coarse twin's solve failed ({str(err) or 'band edge'})"
        return
    finally:
        out["timings"]["estimate"] = time.perf_counter() - t0
    fine, twin = _readings(out, R, P, V), _readings(coarse, R, P, V)
    # the two forms converge to one value: each is at least as uncertain as they are apart
    gap = abs(fine["friction_dissipation"] / fine["friction"] - 1)
    estimate = {q: max(abs(twin[q] / fine[q] - 1), gap) for q in FORMS}
    if _layer(material, V, out["mesh"], mesh)[3]:
        # the twin spans the layer by half as many elements, by construction
        estimate["peak_pressure"] = abs(float(coarse["pres"].max()) / float(out["pres"].max()) - 1)
    out["estimate"] = estimate


def _run_uniform(material, R, P, V, n_res, band, ratio, fold, domain, kw):
    nu = material.nu
    a_inf = hertz_half_width(material.E_inf, nu, R, P)
    h = a_inf / n_res
    taus = material.relaxation_times
    if fold > 0 and not material.is_elastic:
        a_relaxed = hertz_half_width(material.E0, nu, R, P)
        material = material.folded(V / a_relaxed, V / h, tol=fold)
    dropped = [float(t) for t in taus if t not in material.relaxation_times]
    terms = {
        "kept": material.relaxation_times.tolist(),
        "relaxed": [t for t in dropped if V * t < fold * h],
        "glassy": [t for t in dropped if not V * t < fold * h],
    }
    a0 = hertz_half_width(material.E0, nu, R, P)
    L = domain_size(material, R, P, V) if domain is None else check_positive("domain", domain)
    xb = band * a0
    if L < 4 * xb:
        raise InputError(f"domain must be >= 4 * contact_band * a_0 = {4 * xb!r} m, got {L!r}")
    hs = half_space_mesh((-xb, xb), h, x_range=(-L, L), depth=L, core_depth=xb, ratio=ratio)
    check_uniform_fits(hs.x, hs.y, available_memory())
    try:
        out = _solve_mesh(hs, material, R, P, V, (-xb, xb), active_width=a_inf, **kw)
        r2, L2 = _coarser(ratio, L, 2 * xb)
        twin = partial(
            half_space_mesh, (-xb, xb), TWIN_COARSEN * h, x_range=(-L2, L2), depth=L2, core_depth=xb, ratio=r2
        )
        out["twin"] = lambda: _solve_mesh(twin(), material, R, P, V, (-xb, xb), active_width=a_inf, **kw)
    except _BandEdge:
        raise ConvergenceError(
            "the contact reached the edge of the candidate band, or the solid penetrates "
            "the cylinder outside it; increase contact_band"
        ) from None
    return material, terms, hs, out, 1


def _run_graded(material, R, P, V, n_res, ratio, fold, domain, layer_floor, passes, kw, plan):
    edges = initial_edges(material, R, P, V)
    L0 = domain_size(material, R, P, V) if domain is None else check_positive("domain", domain)
    a_c = 0.5 * (edges[1] - edges[0])
    given = material
    material, terms = fold_terms(given, V, layer_floor * a_c / n_res, L0, fold)
    if len(terms["kept"]) == 1:
        # a single term's layer may be meshed below the floor (graded_half_space): fold against the
        # finest elements it may get (folding against smaller elements keeps a superset of the terms)
        material, terms = fold_terms(given, V, SINGLE_TERM_FLOOR * a_c / n_res, L0, fold)
    L = domain_size(material, R, P, V) if domain is None else L0
    settle = partial(_settle, material, R, P, V, n_res, layer_floor=layer_floor, passes=passes, kw=kw, plan=plan)
    hs, out, npass = settle(edges, ratio, L)
    # the twin's block may be half the least a result takes: it only measures a change
    r2, L2 = _coarser(ratio, L, 0.5 * MIN_SPAN * 0.5 * (out["edges"][1] - out["edges"][0]))
    out["twin"] = lambda: settle(out["edges"], r2, L2, coarsen=TWIN_COARSEN, span=0.5 * MIN_SPAN)[1]
    return material, terms, hs, out, npass


def _settle(material, R, P, V, n_res, edges, ratio, L, *, layer_floor, passes, kw, plan, coarsen=1.0, span=MIN_SPAN):
    """Mesh about ``edges`` by ``plan`` (:func:`~fem_reference.graded.graded_half_space` or
    :func:`~fem_reference.graded.graded_quadtree`) and solve, remeshing about the edges found until
    they settle (at most ``passes`` meshes): ``(mesh, solved, passes used)``."""
    trail, lead = edges
    widen = 0.5
    out = hs = last_trail = None
    for npass in range(1, passes + 1):
        a_c = 0.5 * (lead - trail)
        h_edge = coarsen * a_c / n_res
        if L < span * a_c:
            raise InputError(f"domain must be >= {span:g} contact half-widths = {span * a_c!r} m, got {L!r}")
        hs = plan(
            (trail, lead),
            material,
            V,
            resolution=n_res,
            length=L,
            ratio=ratio,
            layer_floor=layer_floor,
            coarsen=coarsen,
        )
        band = (trail - widen * a_c - h_edge, lead + widen * a_c + h_edge)
        try:
            out = _solve_mesh(hs, material, R, P, V, band, active_width=0.8 * a_c, **kw)
        except _BandEdge:
            widen *= 2
            trail, lead = trail - widen * a_c, lead + widen * a_c
            continue
        new_trail, new_lead = out["edges"]
        log.info(
            "graded pass %d: edges [%.6g, %.6g] -> [%.6g, %.6g], %d unknowns, %d candidate nodes, %s",
            npass,
            trail,
            lead,
            new_trail,
            new_lead,
            out["op"].n_unknowns,
            out["candidates"],
            ", ".join(f"{k} {v:.2f} s" for k, v in out["timings"].items()),
        )
        # the trailing edge against its own elements, the leading edge within LAYER_ELEMENTS / 2 of
        # the smallest elements: where the layer is resolved, the margin of its fine zone (a focus a
        # coarse element off would leave it unresolved); where it is not, its peak is not judged
        moves = (abs(new_trail - trail), abs(new_lead - lead))
        limits = (0.25 * h_edge, 0.5 * LAYER_ELEMENTS * hs.element_size)
        # the trailing edge is located from nodal pressures near zero, and its estimate can alternate
        # between two meshes (half an edge element apart at E_inf/E0 = 1000): back at the last mesh's
        # focus, further passes would only repeat the two
        cycled = last_trail is not None and abs(new_trail - last_trail) <= limits[0]
        last_trail = trail
        trail, lead = new_trail, new_lead
        if moves[1] <= limits[1] and (moves[0] <= limits[0] or cycled):
            break
    else:
        if out is not None:
            out["unsettled"] = (
                f"the mesh did not settle on the contact in {passes} passes: the last moved the trailing / "
                f"leading edge by {moves[0]:.3g} / {moves[1]:.3g} m (limits {limits[0]:.3g} / {limits[1]:.3g} m)"
            )
    if out is None:
        raise ConvergenceError(f"the contact kept reaching the edge of the candidate band in {passes} meshes")
    return hs, out, npass


def _result(material, terms, hs, out, npass, R, P, V, ratio, mesh, keep_fields, vtk, t_start, given):
    op, sol, ops = out["op"], out["sol"], out["ops"]
    xc, pres = out["xc"], out["pres"]
    trail, lead = out["edges"]
    readings = _readings(out, R, P, V)
    mu, mu_diss = readings["friction"], readings["friction_dissipation"]
    power_fields = float(ops.weights @ out["diss"])
    lin, lin_limit = float(op.residual), float(op.residual_limit)
    problems = []
    if not lin <= lin_limit:
        problems.append(f"linear solve residual {lin:.2e} > {lin_limit:.1e}")
    residual = out["residual"]
    compl_limit = complementarity_limit(lin_limit)
    if not residual <= compl_limit:
        problems.append(f"complementarity residual {residual:.2e} > {compl_limit:.1e}")
    timings = dict(out["timings"], total=time.perf_counter() - t_start)
    taus = material.relaxation_times
    layer, h_min, across, resolved = _layer(material, V, hs, mesh)
    warnings = ()
    if not resolved:
        warnings = (
            f"peak pressure not resolved: the thinnest leading-edge layer V tau_k = {layer:.3g} m spans "
            f"{layer / h_min:.3g} of the smallest elements ({h_min:.3g} m; a resolved one spans {across})",
        )
    if "unsettled" in out:
        warnings += (out["unsettled"],)
    # an elastic solid (or every term folded) dissipates nothing, and its moment is round-off
    if V > 0 and taus.size and abs(mu_diss - mu) > FORM_GAP * abs(mu):
        warnings += (
            f"the moment and dissipation forms of the friction differ by {abs(mu_diss / mu - 1):.2%} (more than "
            f"{FORM_GAP:.0%}): the mesh does not resolve what dissipates; a higher resolution brings them together",
        )
    estimate = out.get("estimate", {})
    warnings += tuple(
        f"{q.replace('_', ' ')} error estimate {e:.2%} exceeds {ESTIMATE_LIMIT[q]:.0%} (from the mesh's coarse "
        "twin and, for the friction, the gap between its forms): a finer mesh (resolution) or a larger "
        "block (domain) lowers it"
        for q, e in estimate.items()
        if e > ESTIMATE_LIMIT[q]
    )
    if "estimate_failed" in out:
        warnings += (out["estimate_failed"],)
    keep = keep_fields or vtk is not None
    fields = solution_fields(hs.mesh, ops, out, material) if keep else {}
    res = RollingResult(
        x=xc,
        pressure=pres,
        displacement=out["w"] @ sol.lam,
        forces=sol.lam,
        leading_edge=lead,
        trailing_edge=trail,
        friction=mu,
        friction_dissipation=mu_diss,
        dissipated_power=power_fields,
        peak_pressure=float(pres.max()),
        load=P,
        speed=V,
        radius=R,
        approach=sol.d,
        element_size=hs.element_size,
        domain_width=hs.width[1],
        domain_depth=hs.depth,
        grading=ratio,
        n_elements=hs.n_elements,
        n_unknowns=op.n_unknowns,
        iterations=sol.iterations,
        residual=residual,
        material=material,
        success=not problems,
        message="; ".join(problems) if problems else "converged",
        timings=timings,
        fields=fields,
        linear_residual=lin,
        linear_residual_limit=lin_limit,
        solver=op.factor.name,
        solver_path=out["solver_path"],
        mesh=mesh,
        passes=npass,
        terms=terms,
        condensed=tuple(bool(c) for c in op.condensed),
        peak_memory=_peak_memory_mib(),
        input_material=given,
        n_nonzeros=int(op.matrix.nnz),
        factor_nonzeros=int(getattr(op.factor, "nnz", -1)),  # -1: a solver that does not report it
        thinnest_layer=layer,
        smallest_element=h_min,
        peak_resolved=resolved,
        warnings=warnings,
        error_estimate=estimate,
    )
    if vtk is not None:
        from .vtk import write_fields

        write_fields(vtk, res.fields, res)
        if not keep_fields:
            res = _drop_fields(res)
    log.info(
        "rolling V=%g (%s mesh, %d passes): mu=%.6g, edges [%g, %g], %d unknowns, %.1f s, %s",
        V,
        mesh,
        npass,
        mu,
        trail,
        lead,
        op.n_unknowns,
        timings["total"],
        res.message,
    )
    return res


def _drop_fields(res):
    return replace(res, fields={})
