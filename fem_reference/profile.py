"""Steady sliding of a rigid periodic profile over a viscoelastic half-space (plane strain FEM).

Conventions, those of ``bem`` (docs/theory.md §4, stated once here for the FEM): the profile slides
in ``+x`` at speed ``V``; in its frame the material flows in ``-x``, so ``+x`` is upstream. Its
heights ``h(x)`` are positive toward the solid, sampled at ``x_j = j L / n`` over one period ``L``
and continued between the samples by their trigonometric interpolant (:func:`profile_nodes`). The
load ``P`` is the normal force per period and per unit length in ``z`` (N/m); pressure is positive
in compression. Friction, in the two forms ``bem`` reports:

- moment form ``mu = -(1/P) int p h'(x) dx``: the tangential force of the pressure on the sloped
  profile (``bem``'s ``friction_eq6``), here ``-sum_i lam_i h'(x_i) / P`` over the nodal forces;
- dissipation form ``mu_d = D / (P V)`` with ``D`` the viscous dissipation of one period (W/m),
  integrated over the strip (``bem``'s ``friction``).

Both are positive where energy is dissipated and converge to one value.

The solid is one period of a strip ``[0, L] x [-depth L, 0]`` of squares
(:func:`fem_reference.quadtree.quadtree_strip`): of side ``L / elements`` along the surface,
:data:`EDGE_REFINE` times smaller about each contact spot's edges, growing away from them and with
depth. The spots are not known before the solve: the first mesh is uniform along the surface, and
the strip is remeshed about the edges each solve finds until they settle. A surface
field of wavelength ``lambda`` decays as ``exp(-2 pi z / lambda)``, so the fixed bottom two periods
down changes the longest wavelength's field by ``exp(-4 pi) ~ 3e-6``. The sides are periodic
(:mod:`fem_reference.periodic`) and so is each streamline of the memory: an element at the upstream
end takes its inflow from the downstream end of its row, and the viscous strains are the steady
periodic solution for every ``V tau_k``, from far below an element to far beyond the period (there
a term relaxes only the strain's mean along the streamline). Everything else is the rolling model's:
the 9-node mixed elements, each term carried by its elements' outflow values
(:mod:`fem_reference.steady`), the solver path (:func:`fem_reference.linsolve.solver_path`) and the
active-set contact on the flexibility of the surface nodes (:mod:`fem_reference.contact`).
"""

from __future__ import annotations

import logging
import math
import resource
import time
from dataclasses import dataclass, field, replace
from types import SimpleNamespace

import numpy as np

from bem.checks import check_array, check_int, check_positive
from bem.errors import ConvergenceError, InputError
from bem.materials.material import Material

from .contact import complementarity_limit, solve_corrected
from .graded import fold_terms
from .kinematics import quadrature_operators
from .linsolve import STALL, solve_on_path
from .quadtree import quadtree_strip
from .rolling import FORM_GAP, TWIN_COARSEN
from .rolling_inputs import QUADTREE_GRADING
from .steady import solution_fields, steady_operator, stress_and_dissipation, system_path
from .surface import contact_edges, top_surface

__all__ = ["ProfileResult", "sliding_profile", "profile_nodes", "spot_edges"]
log = logging.getLogger(__name__)

# Periods of depth below the surface (see the module docstring)
DEPTH = 2
# The squares about each contact spot's edge are this many times smaller than along the rest of the
# surface: the edge is placed to a fraction of the node spacing there. On a rough profile at 10 %
# contact (4 spots) the contact fraction was +5.9 % off the BEM on 128 uniform squares a period,
# +1.9 % with 32 squares refined 8 times about the edges (or 64 refined 4 times: the edge squares set
# it) and -0.4 % with 64 refined 8 times; 128 refined 4 times places the edges as 64 refined 8 times
EDGE_REFINE = 4
# Most meshes solved while the spot edges settle
PASSES = 4
# Surface squares where none are asked for: two a sample, so that the shortest wavelength the samples
# carry (two samples) spans four squares, and at least this many. A short memory dissipates the
# square of the strain's slope along the flow, most of it in the shortest wavelengths, so in (nearly)
# full contact the dissipation form needs them resolved: two decades below the friction peak, +4.5 %
# / +3.1 % / +2.6 % off the BEM on one square a sample, +1.9 % / +1.1 % / +0.95 % on two (three rubbers
# and profiles). Spots cost columns, not squares: with EDGE_REFINE halved, the squares about the edges
# stay as small, and at the friction peak the unknowns and time stay the same (106,687 against
# 106,828 unknowns, 81 against 79 s, on the validation profile)
MIN_ELEMENTS = 128
# The accuracy a reference must hold in the friction (as the rolling model's)
ESTIMATE_LIMIT = {"friction": 0.01, "friction_dissipation": 0.01}
FORMS = ("friction", "friction_dissipation")


@dataclass(frozen=True)
class ProfileResult:
    """Result of :func:`sliding_profile` (SI units; per period and per unit length in z).

    Attributes
    ----------
    x : ndarray
        Surface nodes over one period, ``[0, L)`` (m).
    heights, slopes : ndarray
        The profile's interpolant and its slope at ``x`` (m, 1).
    pressure : ndarray
        Contact pressure at ``x`` (Pa): nodal force over ``int phi_i ds``.
    forces : ndarray
        Nodal contact forces (N/m); they sum to ``load``.
    displacement : ndarray
        Depression (into the solid) at ``x`` (m).
    gap : ndarray
        Deformed gap at ``x`` (m): the depression less the profile's reach into the solid (its heights
        plus the approach); zero on the contact spots and positive between them.
    contact : ndarray of bool
        The nodes in contact.
    spots : (m, 2) ndarray
        Trailing and leading edge of each contact spot (m; the leading edge at ``+x`` of the
        trailing one, possibly beyond ``L`` for a spot that wraps).
    contact_fraction : float
        Total length of the spots over ``L``.
    friction, friction_dissipation : float
        The moment and the dissipation form (module docstring).
    dissipated_power : float
        Viscous dissipation of one period (W/m).
    peak_pressure, approach, load, speed, length : float
        Largest nodal pressure (Pa), rigid approach (m), ``P`` (N/m), ``V`` (m/s), ``L`` (m).
    elements : int
        Squares along the surface of one period away from the spot edges.
    passes : int
        Meshes solved while the spot edges settled.
    n_elements, n_unknowns, iterations : int
    residual : float
        Complementarity residual of the contact solution.
    linear_residual, linear_residual_limit : float
    success : bool
    message : str
    solver : str
    solver_path : tuple of dict
    material, input_material : bem.Material
        The terms used (fast ones folded) and the material as given.
    terms : dict
        ``kept`` and ``relaxed`` relaxation times.
    warnings : tuple of str
    error_estimate : dict
        Relative error estimates of ``friction`` and ``friction_dissipation`` from the coarse twin
        (every size and growth twice as large) and the gap between the forms; empty without
        dissipation.
    timings : dict
    peak_memory : float
        Peak resident memory of the process (MiB).
    n_nonzeros, factor_nonzeros : int
    fields : dict
        Quadrature-point fields where asked for (``keep_fields`` or ``vtk``).
    """

    x: np.ndarray
    heights: np.ndarray
    slopes: np.ndarray
    pressure: np.ndarray
    forces: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    contact: np.ndarray
    spots: np.ndarray
    contact_fraction: float
    friction: float
    friction_dissipation: float
    dissipated_power: float
    peak_pressure: float
    approach: float
    load: float
    speed: float
    length: float
    elements: int
    passes: int
    n_elements: int
    n_unknowns: int
    iterations: int
    residual: float
    linear_residual: float
    linear_residual_limit: float
    success: bool
    message: str
    solver: str
    solver_path: tuple
    material: object
    input_material: object
    terms: dict
    warnings: tuple = ()
    error_estimate: dict = field(default_factory=dict)
    timings: dict = field(default_factory=dict)
    peak_memory: float = 0.0
    n_nonzeros: int = -1
    factor_nonzeros: int = -1
    fields: dict = field(default_factory=dict)


def profile_nodes(heights, length, x):
    """Heights and slopes ``(h, h')`` (m, 1) at the points ``x`` (m) of the trigonometric interpolant of
    ``heights`` sampled at ``x_j = j L / n``. A Nyquist component (even ``n``) is taken as the cosine
    through the samples."""
    h = np.asarray(heights, dtype=float)
    n = h.size
    c = np.fft.rfft(h) / n
    c[1:] *= 2.0  # one-sided: h(x) = Re sum_k c_k exp(i q_k x)
    if n % 2 == 0:
        c[-1] *= 0.5  # the Nyquist bin has no partner at -n/2
    q = 2 * np.pi * np.arange(c.size) / length
    x = np.asarray(x, dtype=float)
    out_h, out_s = np.empty(x.size), np.empty(x.size)
    for lo in range(0, x.size, 1024):  # blocks bound the (points, modes) work array
        e = c[None, :] * np.exp(1j * np.outer(x[lo : lo + 1024], q))
        out_h[lo : lo + 1024] = e.real.sum(axis=1)
        out_s[lo : lo + 1024] = (1j * q[None, :] * e).real.sum(axis=1)
    return out_h, out_s


def spot_edges(x, p, active, length):
    """``(m, 2)`` trailing and leading edges of each run of ``active`` nodes on the periodic surface
    ``x`` (``[0, L)``, sorted), located as :func:`fem_reference.surface.contact_edges` locates them; a run
    that wraps past ``x = L`` has its leading edge beyond ``L``."""
    active = np.asarray(active, bool)
    n = x.size
    if not np.any(active):
        return np.zeros((0, 2))
    if np.all(active):
        return np.array([[0.0, float(length)]])
    # start after an inactive node and end with it again, a period on: runs that wrap stay whole, and
    # every run has its inactive neighbours in the window
    shift = int(np.flatnonzero(~active)[0])
    idx = (np.arange(n + 1) + shift) % n
    xs = x[idx] + np.where(np.arange(n + 1) + shift >= n, length, 0.0)
    acts, ps = active[idx], p[idx]
    edges = []
    for s in np.flatnonzero(acts[1:] & ~acts[:-1]) + 1:
        e = s
        while acts[e + 1]:
            e += 1
        lead, trail = contact_edges(xs[s - 1 : e + 2], ps[s - 1 : e + 2], acts[s - 1 : e + 2])
        edges.append((trail, lead))
    out = np.array(sorted(edges))
    return np.where(out[:, :1] >= length, out - length, out)


def _check(material, heights, length, load, speed, elements, depth, grading, fold, maxiter):
    if not isinstance(material, Material):
        raise InputError(f"material must be a bem.Material, got {type(material).__name__}")
    h = check_array("heights", heights, ndim=(1,))
    if h.size < 4:
        raise InputError(f"heights must hold at least 4 samples of the period, got {h.size}")
    if np.ptp(h) <= 0:
        raise InputError("heights must not all be equal: a flat profile has no contact spots")
    L = check_positive("length", length)
    P = check_positive("load", load)
    V = check_positive("speed", speed, allow_zero=True)
    least = 2 ** math.ceil(math.log2(h.size / 2))
    if elements is None:
        elements = max(MIN_ELEMENTS, 2 ** math.ceil(math.log2(2 * h.size)))
    elements = check_int("elements", elements, 4, 2**16)
    if elements & (elements - 1) or elements < least:
        raise InputError(f"elements must be a power of two and at least half the samples ({least}): got {elements}")
    depth = check_int("depth", depth, 1, 16)
    ratio = QUADTREE_GRADING if grading is None else check_positive("grading", grading)
    if not 1.0 < ratio <= 2.0:
        raise InputError(f"grading must be in (1, 2], got {ratio!r}")
    fold = check_positive("fold", fold, allow_zero=True)
    if maxiter is not None:
        maxiter = check_int("maxiter", maxiter, 1, 10**7)
    return h, L, P, V, elements, depth, ratio, fold, maxiter


def sliding_profile(
    material,
    *,
    heights,
    length,
    load,
    speed,
    elements=None,
    depth=DEPTH,
    grading=None,
    fold=1e-4,
    solver="auto",
    maxiter=None,
    keep_fields=False,
    vtk=None,
    estimate=True,
):
    """Steady sliding of a rigid periodic profile over a viscoelastic half-space (plane strain FEM).

    Parameters
    ----------
    material : bem.Material
        Prony series (one Poisson ratio for all terms; ``nu = 0.5`` is allowed).
    heights : array_like, (n,)
        Profile heights over one period (m), positive toward the solid, at ``x_j = j L / n``
        (a ``bem.surfaces.Surface``'s ``heights`` of a 1-D profile).
    length : float
        Period ``L`` (m).
    load : float
        Normal force per period and unit length ``P`` (N/m), ``> 0``.
    speed : float
        Sliding speed ``V`` (m/s), ``>= 0``.
    elements : int, optional
        Squares along the surface of one period, a power of two of at least half the samples;
        default twice the samples' count rounded up to a power of two (at least :data:`MIN_ELEMENTS`).
        Node spacing is ``L / (2 elements)``.
    depth : int
        Depth of the strip in periods (:data:`DEPTH`).
    grading : float, optional
        Growth of the squares with depth (one plus their growth per unit depth), in (1, 2];
        default :data:`~fem_reference.rolling_inputs.QUADTREE_GRADING` (the rolling model's: the
        dissipation form's error in depth falls with it, 1.4 % at 1.5 and 0.25 % at 1.25 on a
        sinusoid in full contact).
    fold : float
        Drop a term whose arm carries less than this share of the relaxed stress at the smallest
        element (:func:`fem_reference.graded.fold_terms`, relaxed side only: on a periodic cell a slow
        term still relaxes the strain's mean along each streamline, so it is never folded into a
        spring); 0 keeps every term.
    solver : {"auto", "splu", "pardiso"}
        :func:`fem_reference.linsolve.solver_path`; ``result.solver_path`` reports each step.
    maxiter : int, optional
        Active-set iteration limit; default twice the surface nodes, at least 100.
    keep_fields : bool
        Keep quadrature-point fields in ``result.fields``.
    vtk : str or path, optional
        Write the strip and its surface to this ``.vtm`` (or the strip to a ``.vtu``) file
        (:mod:`fem_reference.vtk`).
    estimate : bool
        Solve the same problem on the coarse twin (every square and the growth of the squares
        :data:`~fem_reference.rolling.TWIN_COARSEN` times larger, about the same spots) and estimate
        the error of the friction in both forms (``result.error_estimate``), with a warning where one
        exceeds its :data:`ESTIMATE_LIMIT`.

    Returns
    -------
    ProfileResult

    Raises
    ------
    bem.errors.InputError
        Bad parameter.
    bem.errors.ConvergenceError
        The active set does not settle, or every factorisation's solves missed their residual.
    """
    h, L, P, V, N, depth, ratio, fold, maxiter = _check(
        material, heights, length, load, speed, elements, depth, grading, fold, maxiter
    )
    t_start = time.perf_counter()
    given = material
    node = L / (2 * N * EDGE_REFINE)
    # relaxed side only: a block of infinite length never makes a term glassy
    used, terms = fold_terms(given, V, node, np.inf, fold)
    terms = {"kept": terms["kept"], "relaxed": terms["relaxed"]}
    out = _settle(used, h, L, P, V, N, depth, ratio, solver, maxiter, keep_fields or vtk is not None)
    estimate_out = {}
    if estimate:
        t0 = time.perf_counter()
        try:
            # every size and the growth of the sizes TWIN_COARSEN times larger, about the same spots
            twin = _segments(L, N / TWIN_COARSEN, out["edges"])
            coarse = _solve(
                used, h, L, P, V, twin, depth, 1 + TWIN_COARSEN * (ratio - 1), solver, maxiter, False, out["edges"]
            )
        except ConvergenceError as err:
            out["estimate_failed"] = f"no error estimate: the coarse twin's solve failed ({err})"
        else:
            estimate_out = _estimate(out, coarse, V)
        out["timings"]["estimate"] = time.perf_counter() - t0
    return _result(out, estimate_out, used, given, terms, h, L, P, V, N, vtk, keep_fields, t_start)


def _readings(out, P, V):
    return {
        "friction": -float(out["sol"].lam @ out["slopes"]) / P,
        "friction_dissipation": float(out["ops"].weights @ out["diss"]) / (P * V) if V > 0 else 0.0,
        "contact_fraction": out["fraction"],
    }


def _estimate(fine_out, coarse, V):
    """For either form of the friction, the larger of its change to the twin (an error of order
    ``p >= 1`` in the element size is at most that) and the gap between the forms, which converge to
    one value. (The contact fraction has none: its edges are placed to within a fraction of a node
    spacing, an error that changes sign from one mesh to the next, so that the change to the twin
    can be smaller than the error itself.)"""
    P = fine_out["load"]
    fine, twin = _readings(fine_out, P, V), _readings(coarse, P, V)
    if not (V > 0 and fine["friction"] != 0):
        return {}
    gap = abs(fine["friction_dissipation"] / fine["friction"] - 1)
    return {q: max(abs(twin[q] / fine[q] - 1), gap) for q in FORMS}


class _Flexibility:
    """Columns of the surface nodes' flexibility, solved when the contact first asks for them: only
    nodes that enter the active set need theirs (a few tenths of the surface at most), and each
    column is a solve with the factor. The solves are not refined: the contact is refined as a
    whole against exact field solves instead (:func:`~fem_reference.contact.solve_corrected`), which
    halves the solves where the factor's first solve misses the target (SuperLU's on these cells:
    relative residual ~1e-7)."""

    def __init__(self, op, dofs):
        self.op, self.dofs = op, dofs
        self.cols = np.full((dofs.size, dofs.size), np.nan)
        self.have = np.zeros(dofs.size, dtype=bool)
        self.time = 0.0

    def __call__(self, idx):
        new = idx[~self.have[idx]]
        if new.size:
            t0 = time.perf_counter()
            self.cols[:, new] = self.op.flexibility(self.dofs, self.dofs[new], refine=False)
            self.have[new] = True
            self.time += time.perf_counter() - t0
        return self.cols[:, idx]


def _on_spots(x, spots, L):
    """Mask of the surface points ``x`` on the ``spots`` (edges as :func:`spot_edges` gives them,
    a leading edge past ``L`` wrapping), or None where that leaves no point."""
    on = np.zeros(x.size, dtype=bool)
    for trail, lead in np.reshape(spots, (-1, 2)):
        on |= ((x >= trail) & (x <= lead)) | ((x + L >= trail) & (x + L <= lead))
    return on if np.any(on) else None


def _segments(L, N, spots):
    """The surface's squares: ``L / N`` along the period, :data:`EDGE_REFINE` times smaller within half
    of one of them about each spot edge."""
    base = L / N
    segments = [(0.0, L, base)]
    for edge in np.ravel(spots):
        segments.append((edge - 0.5 * base, edge + 0.5 * base, base / EDGE_REFINE))
    return segments


def _settle(material, heights, L, P, V, N, depth, ratio, solver, maxiter, keep):
    """Solve on squares of ``L / N`` along the surface, then remesh about the spot edges found until
    they stay within the middle half of the zones refined about them (a quarter of a surface square; at
    most :data:`PASSES` meshes)."""
    base = L / N
    spots = np.zeros((0, 2))
    for npass in range(1, PASSES + 1):
        out = _solve(material, heights, L, P, V, _segments(L, N, spots), depth, ratio, solver, maxiter, keep, spots)
        new = out["spots"] if not np.all(out["sol"].active) else np.zeros((0, 2))  # full contact: no edges
        moved = np.inf if new.shape != spots.shape else float(np.max(np.abs(new - spots), initial=0.0))
        log.info(
            "profile pass %d: %d spots, edges moved %.3g m, %d unknowns", npass, len(new), moved, out["op"].n_unknowns
        )
        spots = new
        if moved <= 0.25 * base or (npass == 1 and not spots.size):
            break
    else:
        out["unsettled"] = (
            f"the mesh did not settle on the contact spots in {PASSES} passes: the last moved an edge by "
            f"{moved:.3g} m (limit {0.25 * base:.3g} m) or changed the number of spots"
        )
    out["passes"], out["edges"] = npass, spots
    return out


def _solve(material, heights, L, P, V, segments, depth, ratio, solver, maxiter, keep, spots=()):
    """Mesh the strip for ``segments`` of the surface, factor, solve the contact and the fields; the
    contact starts from the nodes on ``spots`` (edges found on another mesh), if any: the nodes the
    active set visits on its way are columns solved for nothing."""
    t0 = time.perf_counter()
    strip = quadtree_strip(L, segments, depth=depth, ratio=ratio)
    ops = quadrature_operators(strip.mesh, "plane", hanging=strip.hanging, periodic=True)
    top = top_surface(ops.basis)
    # the node at x = L is the one at x = 0: its DOFs are constrained to that node's, its weight joins it
    x, ydofs = top.x[:-1], top.ydofs[:-1]
    weights = top.weights[:-1].copy()
    weights[0] += top.weights[-1]
    hn, slopes = profile_nodes(heights, L, x)
    start = _on_spots(x, spots, L)
    setup = time.perf_counter() - t0
    carried = np.zeros(material.relaxation_times.size, dtype=bool)

    def build(step, memory):
        return steady_operator(ops, material, V, solver=step.solver, condense=False, memory=memory)

    def work(op, checkpoint):
        t1 = time.perf_counter()
        w = _Flexibility(op, ydofs)
        limit = maxiter if maxiter is not None else max(100, 2 * x.size)
        fields = {"time": 0.0}

        def depression(lam):
            t = time.perf_counter()
            f = np.zeros(ops.basis.N)
            f[ydofs] = -lam  # the contact forces on the body
            u, p, alpha = op.solve(f, strains=True)
            checkpoint()  # a factor whose solves missed is left before its fields are used
            fields["time"] += time.perf_counter() - t
            return -u[ydofs], (u, p, alpha)

        # the contact condition as the field solve satisfies it: gaps from the displaced surface
        sol, (u, p, alpha) = solve_corrected(
            w,
            depression,
            hn,
            P,
            target=complementarity_limit(op.residual_limit) / 100,
            stall=STALL,
            active=start,
            maxiter=limit,
        )
        residual = sol.residual
        t3 = time.perf_counter()
        eps, sigma, diss = stress_and_dissipation(ops, op.material, u, p, alpha)
        t4 = time.perf_counter()
        contact = t3 - t1 - w.time - fields["time"]
        timings = dict(op.timings, flexibility=w.time, contact=contact, fields=fields["time"] + t4 - t3)
        return dict(
            op=op,
            sol=sol,
            depression=-u[ydofs],  # the exact field's, not the unrefined columns'
            u=u,
            p=p,
            alpha=alpha,
            eps=eps,
            sigma=sigma,
            diss=diss,
            residual=residual,
            timings=timings,
        )

    out, report = solve_on_path(system_path(material, V, carried, solver, squares=True, closed=True), build, work)
    factor = out["op"].factor
    # nothing solves with this factor again: free it before the twin is factored beside it
    matrix = out["op"].matrix
    out["op"] = replace(
        out["op"],
        factor=SimpleNamespace(name=factor.name, nnz=getattr(factor, "nnz", -1)),
        matrix=SimpleNamespace(nnz=matrix.nnz),
    )
    del matrix
    del factor
    pres = out["sol"].lam / weights
    spots = spot_edges(x, pres, out["sol"].active, L)
    out.update(
        strip=strip,
        ops=ops,
        x=x,
        heights=hn,
        slopes=slopes,
        pres=pres,
        spots=spots,
        load=P,
        fraction=float(np.sum(spots[:, 1] - spots[:, 0]) / L),
        solver_path=tuple(report),
    )
    out["timings"]["assemble"] += setup
    if not keep:
        for k in ("eps", "sigma", "alpha", "p"):
            out[k] = None
    return out


def _more_squares(N):
    """What a warning about the mesh suggests: the squares used and finer counts to pass. Far below
    the friction peak, in full contact, the dissipation form's error roughly halves with each
    doubling (the profile page's Convergence)."""
    return f"elements={N} here; elements={2 * N} or {4 * N}"


def _result(out, estimate, material, given, terms, h, L, P, V, N, vtk, keep_fields, t_start):
    op, sol, ops = out["op"], out["sol"], out["ops"]
    readings = _readings(out, P, V)
    mu, mu_d = readings["friction"], readings["friction_dissipation"]
    lin, lin_limit = float(op.residual), float(op.residual_limit)
    problems = []
    if not lin <= lin_limit:
        problems.append(f"linear solve residual {lin:.2e} > {lin_limit:.1e}")
    compl_limit = complementarity_limit(lin_limit)
    if not out["residual"] <= compl_limit:
        problems.append(f"complementarity residual {out['residual']:.2e} > {compl_limit:.1e}")
    warnings = ()
    if V > 0 and material.relaxation_times.size and abs(mu_d - mu) > FORM_GAP * abs(mu):
        warnings += (
            f"the moment and dissipation forms of the friction differ by {abs(mu_d / mu - 1):.2%} (more than "
            f"{FORM_GAP:.0%}): the mesh does not resolve what dissipates; more squares a period bring them "
            f"together ({_more_squares(N)})",
        )
    warnings += tuple(
        f"{q.replace('_', ' ')} error estimate {e:.2%} exceeds {ESTIMATE_LIMIT[q]:.0%} (from the coarse twin, "
        f"every size twice as large, and the gap between the forms): more squares a period lower it ({_more_squares(N)})"
        for q, e in estimate.items()
        if e > ESTIMATE_LIMIT[q]
    )
    if "estimate_failed" in out:
        warnings += (out["estimate_failed"],)
    if "unsettled" in out:
        warnings += (out["unsettled"],)
    keep = keep_fields or vtk is not None
    fields = solution_fields(out["strip"].mesh, ops, out, material) if keep else {}
    timings = dict(out["timings"], total=time.perf_counter() - t_start)
    depression = out["depression"]
    res = ProfileResult(
        x=out["x"],
        heights=out["heights"],
        slopes=out["slopes"],
        pressure=out["pres"],
        forces=sol.lam,
        displacement=depression,
        gap=depression - out["heights"] - float(sol.d),
        contact=sol.active,
        spots=out["spots"],
        contact_fraction=out["fraction"],
        friction=mu,
        friction_dissipation=mu_d,
        dissipated_power=float(ops.weights @ out["diss"]),
        peak_pressure=float(out["pres"].max()),
        approach=float(sol.d),
        load=P,
        speed=V,
        length=L,
        elements=N,
        passes=out["passes"],
        n_elements=out["strip"].n_elements,
        n_unknowns=op.n_unknowns,
        iterations=sol.iterations,
        residual=float(out["residual"]),
        linear_residual=lin,
        linear_residual_limit=lin_limit,
        success=not problems,
        message="; ".join(problems) if problems else "converged",
        solver=op.factor.name,
        solver_path=out["solver_path"],
        material=material,
        input_material=given,
        terms=terms,
        warnings=warnings,
        error_estimate=estimate,
        timings=timings,
        peak_memory=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
        n_nonzeros=int(op.matrix.nnz),
        factor_nonzeros=int(getattr(op.factor, "nnz", -1)),
        fields=fields,
    )
    if vtk is not None:
        from .vtk import write_fields

        write_fields(vtk, res.fields, res)
        if not keep_fields:
            res = replace(res, fields={})
    log.info(
        "profile V=%g (%d elements): mu=%.6g / %.6g, contact %.4f, %d unknowns, %.1f s, %s",
        V,
        N,
        mu,
        mu_d,
        out["fraction"],
        op.n_unknowns,
        timings["total"],
        res.message,
    )
    return res
