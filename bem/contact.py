"""Unilateral frictionless contact of a rigid indenter: the complementarity solver.

Problem (SPEC §2.3). Heights ``h`` (m) are positive toward the half-space, so contact
starts at ``max(h)``. With ``A`` the surface response operator (zero-mean displacement
per pressure, m/Pa; any linear operator whose symmetric part is positive definite, so
the non-symmetric steady-sliding operator is included), find the pressure ``p`` (Pa) and
the rigid approach ``delta`` (m) with

    g = A p - (h - max(h) + delta) >= 0,   p >= 0,   p g = 0,

and either ``mean(p) = p_mean`` (load control) or ``delta`` given (displacement control).

Algorithm: primal–dual active set, i.e. a semismooth Newton method on
``min(p, c g) = 0`` with ``c`` the stiffness of one grid cell (Hintermüller, Ito &
Kunisch, SIAM J. Optim. 13 (2002) 865, doi:10.1137/S1052623401383558), damped by a line
search on ``||min(p, c g)||`` along the Newton step (pressure, displacement and gap are
affine along it, so the search costs no operator product). Each Newton point solves, on
the contact set ``C``, ``A_CC p_C = h_C + delta`` with the load constraint (``sum p_C``
fixed, enforced by projecting out the mean on ``C``): conjugate gradients when ``A`` is
symmetric, GMRES otherwise, loosely while the set still changes and tightly once it
settles. The inner solves are preconditioned by ``R A^-1 R^T``, the exact full-contact
inverse (one FFT pair) restricted to ``C``: on the benchmark surface (about 10 % contact)
it cut the operator products from 264 to 184 (elastic, 1024²), 824 to 293 (seed SLS, 512²)
and 4587 to 2296 (20-term rubber, 512²). Not on small grids (below
``PRECONDITION_MIN_SIZE`` = 2^17 points): at 128² and 256² the restricted system is well
enough conditioned that the extra pair does not pay (elastic 91 -> 96 products at 128²;
seed 181 -> 203 at 256²).

Strongly non-symmetric operators (symbol phase above 45 degrees: high ``E_inf/E0`` near the
loss peak) are preconditioned differently, on 2-D grids of every size: by the *line
preconditioner* ``(R C R^T)^-1 R G^-1 R^T`` of
:meth:`bem.periodic.PeriodicHalfSpace.line_preconditioner`, where ``A = G C`` splits into the
elastic operator and the creep convolution along x, and ``C`` is inverted exactly on the
contact set, one x-line at a time. ``R A^-1 R^T`` does not help them (benchmark rubber at
1024²: 7707 products for 23 damped steps, unconverged, against 3792 for the whole solve
without it); the line preconditioner does: GMRES on the rubber's final 512² contact set took
1095 products unpreconditioned and 43 with it, and in the periodic benchmark whole solves
went from 1615 to 961 products (512², 8.3 s -> 6.5 s) and from 3836 to 1604 (1024², 102 s ->
51 s); with the nested start's first set and the guarded steps below, 1173 products and 38 s
at 1024², and 2048² (skipped before: over 1000 s) solves in 253 s (1572 products, 2.1 GiB). Its dense line inverses cost
``sum m^3`` flops per Newton point (``m`` contact points on a line; lines whose contact did
not change keep theirs) and at most ``bem.periodic.LINE_BUDGET`` = 1 GiB (otherwise the
solve goes unpreconditioned). Such a line-preconditioned
attempt gives up once its residual has not reached a new low for ``RESIDUAL_STALL`` = 30
steps, and the solve is redone without it: one case of the 32² robustness sweep (SLS,
``E_inf/E0`` 1e4, xi = 1, near full contact) cycles with it and converges without (55 steps);
the sweep as a whole went from 73082 products to 59672 (with the guarded steps below in both
attempts; that case 42411 -> 33284). The attempt may also take at most
``LINES_MAXITER_SHARE`` = half of ``maxiter``: the same material at 128² (xi = 1, a few
contact spots) creeps in it without stalling (steps of 1/16-1/64, residual 6e2 -> 0.8 in 400
steps) and used to fail; with the rest of ``maxiter`` the second attempt converges (72 steps,
134k products, 280 s).
The line-preconditioned attempt solves its inner systems to ``LINES_ETA`` = 0.01 of the
right-hand side (not 0.1): looser Newton points sent the rubber's finer grids into long
runs of damped steps (step 0.25, 20-40 steps). Rubber, products with 0.1 -> 0.01: 256²
563 -> 596, 512² 401 -> 624, 1024² 1626 -> 633 (39 s -> 18 s), 2048² 1572 -> 627 (253 s ->
117 s); 0.03 gave 506 at 512², 675 at 1024² and 1430 at 2048². Over load perturbations of
1e-6 to 1 % the 1024² rubber took 1173-1458 products (30-40 s) with 0.1 and 620-680 (16-18 s)
with 0.01. Being tight already, this attempt does not tighten further on damped steps (the
rule below): rubber 512² 624 -> 558, 1024² 633 -> 589, 2048² 595 -> 609; 32² robustness
sweep 59529 -> 56338 products.

First iterate. On grids of at least ``COARSEN_MIN_SIZE`` = 2^18 points (512²) with even
sides: the same problem solved on the grid with half the points per axis (to
``COARSE_RTOL``) and interpolated linearly (nested iteration; see :func:`solve_contact`).
Benchmark surface, products before -> after (coarse products counted at their share of
points): elastic 140 -> 99 (512²), 184 -> 108 (1024²); seed 293 -> 174, 381 -> 211;
rubber 1837 -> 1616 (512²), 4013 -> 3792 (1024²). The first contact set is then the one a
Newton step would pick from the interpolated pressure and its gap at the coarse approach,
``p - c g > 0``, not ``p > 0`` (interpolation makes the pressure positive around every
coarse contact point: the rubber's first fine step changed 30095 of ~74k points): elastic
108 -> 85 products (1024²), seed 211 -> 163, rubber 961 -> 446 (512²). Otherwise the full-contact solution,
exact in Fourier space, clipped; strongly non-symmetric operators, and every non-symmetric
1-D one (``SYMMETRIC_START_1D``), start from the contact of their symmetric part instead (a CG
solve that stops once it cycles), unless under load control the clipped full-contact pressure
is nearly the answer. For a smooth indenter the clipped full-contact pressure is far off (a
rolling cylinder on a long 1-D cell: contact on 22 % of the cell against 3.8 %), and damped
steps then shave the set a few edge points at a time: the validation's three-term Prony
cylinder (5104-30376 points, rtol 1e-10) took 262-15162 products and failed at s = 0.3 (400
steps); from the symmetric part it takes 4-9 steps and 150-335 products at every speed. Not in
2-D: on the benchmark's rough surface the seed SLS at 256² went from 181 to 295 products (the
32² robustness sweep: 77309 -> 77406 with the 1-D rule, 77952 with it in 2-D too).

Steps. Undamped steps are taken whenever they reduce the merit, so easy problems see plain
primal–dual active-set convergence. Strongly non-symmetric 2-D periodic problems (the
line-preconditioned ones) take a full step only if it lowers both the merit (L2) and the
residual (max norm), else the best shorter one: full steps that raised the residual sent the
rubber's 1024² set wandering (thousands of changes a step; 1655 -> 1250 products). Not
elsewhere: the isolated rolling cylinder with ``E_inf/E0`` = 100 (1-D) then no longer
converged in 400 steps. A damped step (outside the line-preconditioned attempt) tightens the
inner tolerance (x0.1, to 1e-4) only once the set is nearly settled (at most
``TIGHTEN_CHANGES`` = 100 changes or ``TIGHTEN_SHARE`` = 1 % of the set): earlier, damping comes from the set, not from loose
inner solves, and tight GMRES solves there cost hundreds of products each (rubber, 512²
without the coarse start: 2883 -> 1837 products; 32² robustness sweep 90829 -> 73082).

A step that keeps the set and whose right-hand side is already under the tolerance floor
would change nothing: the floor is tightened (x0.1, as below) before its solve instead of after.
A settled set whose residual stalls tightens the inner tolerance x0.1 per step, down to
``ATOL_FLOOR`` = 1e-3 of the final absolute tolerance (it stopped at 1x before: the
symmetric-part warm start of a 128² rubber then sat for 1000 steps at residual 2e-3 with a
point of slightly negative pressure and gap held in the set by the inner solve's error).

Precision. The inner solves' operator products and preconditioners run in single precision
(float32 fields, complex64 spectra: :meth:`bem.periodic.PeriodicHalfSpace.single_precision`)
whenever the solve stops at ``SINGLE_PRECISION_RTOL`` = 1e-3 of its right-hand side or
above, i.e. far above the products' round-off (about 1e-7 of the largest value, times the
restricted system's conditioning); tighter solves use float64. The solves work on
corrections, and each Newton point's displacement, gap and complementarity residual are
float64, so the solution is as accurate as before. A 1024² FFT pair takes 5.4 ms in float32
and 8.8 ms in float64 here. Periodic benchmark, one run each, products unchanged (87, 168,
591-592 at 1024²): elastic 1.86 -> 1.36 s at 1024² and 9.15 -> 7.77 s at 2048²; seed SLS
3.28 -> 2.49 s and 18.3 -> 14.2 s; 20-term rubber 15.9 -> 12.9 s and 75.3 -> 55.7 s. The
32² robustness sweep still converges everywhere; its products went 56160 -> 77309, all of
it one case (SLS, ``E_inf/E0`` 1e4, 2-D, xi = 1, 31460 -> 55931) whose unpreconditioned
fallback hits the inner cap with either precision and takes another path; the other cases
went 24700 -> 21378.

Convergence test, stated exactly: the solve succeeds when the complementarity residual

    r = max_i | min(p_i / p_ref, g_i / h_ref) |

is ``<= rtol``, where ``p_ref`` is the mean pressure and ``h_ref`` the peak-to-valley
height (or the displacement ``A p_ref`` at one point for a flat surface). ``r = 0`` iff
``p >= 0``, ``g >= 0`` and ``p g = 0``. Under load control the load balance holds to
round-off. Otherwise :class:`bem.errors.ConvergenceError` is raised.
"""
import logging
from dataclasses import dataclass, replace

import numpy as np
from threadpoolctl import threadpool_limits

from . import krylov
from .errors import ConvergenceError

log = logging.getLogger(__name__)

PRECONDITION_MIN_SIZE = 2**17  # grid points; see the module docstring
ATOL_FLOOR = 1e-3  # stalled inner solves tighten down to this share of final_atol (module docstring)
LINES = True  # line-preconditioned first attempt for strongly non-symmetric 2-D operators
LINES_ETA = 0.01  # inner forcing term of that attempt (module docstring)
RESIDUAL_STALL = 30  # steps without a new low in the residual that end that attempt
LINES_MAXITER_SHARE = 0.5  # ... as does this share of maxiter (module docstring)
STALL_LIMIT = 5  # steps without a new low in set changes that count as cycling
COARSEN = True  # start large grids from the next coarser grid (module docstring)
COARSEN_MIN_SIZE = 2**18  # grid points
COARSE_RTOL = 1e-4  # complementarity residual of the coarse solve (at least the caller's rtol)
TIGHTEN_CHANGES, TIGHTEN_SHARE = 100, 0.01  # "nearly settled" set, for tightening on damping
SYMMETRIC_START_1D = True  # every non-symmetric 1-D problem starts from its symmetric part's contact
SINGLE_PRECISION_INNER = True  # inner solves' products in float32 (module docstring) ...
SINGLE_PRECISION_RTOL = 1e-3  # ... when they stop at least this share of their right-hand side


@dataclass(frozen=True)
class ContactSolution:
    """Raw output of :func:`solve_contact` (fields shaped like the heights)."""

    pressure: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    approach: float
    iterations: int
    matvecs: int
    residual: float
    success: bool
    message: str


def complementarity_residual(p, g, p_ref, h_ref):
    """``max |min(p / p_ref, g / h_ref)|`` (dimensionless); 0 iff the contact conditions hold.

    Evaluated as ``max |min(p, g p_ref / h_ref)| / p_ref``: one temporary instead of two and
    no division (in the 1024² elastic solve 1.45 -> 1.22 ms per call, 26 calls)."""
    m = g * (p_ref / h_ref)
    np.minimum(m, p, out=m)
    return float(max(m.max(), -m.min())) / p_ref


def _full_contact_pressure(op, ht):
    """Pressure that makes the gap vanish everywhere (zero mean), exact in Fourier space."""
    return op.pressure_from_displacement(ht)


def _prolong(p):
    """Periodic linear interpolation from a grid to the one with twice the points per axis
    (coarse point ``i`` sits on fine point ``2i``); keeps ``p >= 0`` and the mean."""
    for axis in range(p.ndim):
        mid = 0.5 * (p + np.roll(p, -1, axis=axis))
        shape = list(p.shape)
        shape[axis] *= 2
        fine = np.empty(shape)
        index = [slice(None)] * p.ndim
        index[axis] = slice(0, None, 2)
        fine[tuple(index)] = p
        index[axis] = slice(1, None, 2)
        fine[tuple(index)] = mid
        p = fine
    return p


def _coarse_start(op, heights, kwargs):
    """First iterate from the same problem on the grid with half the points per axis.

    Returns ``(pressure or None, products, approach or None)`` with the coarse products
    counted at their share of grid points and the coarse approach (m) measured from this
    grid's first touch. The coarse solve starts from its own coarser grid, down to
    ``COARSEN_MIN_SIZE`` points (nested iteration).
    """
    coarsened = getattr(op, "coarsened", None)
    if coarsened is None or heights.size < COARSEN_MIN_SIZE or any(n % 2 for n in heights.shape):
        return None, 0.0, None
    coarse_op = coarsened()
    keep = ("mean_pressure", "approach", "inner_eta", "relax_inner", "maxiter")
    options = {k: v for k, v in kwargs.items() if k in keep}
    options["rtol"] = max(kwargs.get("rtol", 1e-8), COARSE_RTOL)
    coarse_heights = heights[tuple(slice(0, None, 2) for _ in heights.shape)]
    coarse = solve_contact(coarse_op, coarse_heights, raise_on_failure=False, **options)
    share = coarse.matvecs * coarse_op.size / op.size
    if not coarse.success:
        log.info("coarse start discarded: %s", coarse.message)
        return None, share, None
    # the same rigid position: the approach counts from first touch, on each grid's own maximum
    approach = coarse.approach + float(heights.max() - coarse_heights.max())
    return _prolong(coarse.pressure), share, approach


def solve_contact(op, heights, **kwargs):
    """Solve the contact problem for operator ``op``; see :func:`_solve_contact`.

    Without ``initial``, on periodic grids of at least ``COARSEN_MIN_SIZE`` points with even
    sides, the first iterate is the solution on the grid with half the points per axis
    (solved to ``COARSE_RTOL``, itself started the same way) interpolated linearly: the
    Newton iteration then starts with its contact set almost in place. ``matvecs`` counts
    the coarse grids' products at their share of grid points (a 512² product as 1/4 of a
    1024² one; its FFTs cost 0.26-0.31 of the finer ones here, so this does not flatter).

    Two attempts share ``maxiter`` (default 400): a fast one whose inner solves loosen again
    after full Newton steps, then, if it fails, one whose inner tolerances only tighten.
    Strongly non-symmetric operators (symbol phase above 45 degrees) use the second
    strategy at once; on 2-D periodic grids its first attempt is line-preconditioned and
    gives up when its residual stalls (``RESIDUAL_STALL``), the second is not (module
    docstring).
    """
    # SPEC §7: threaded BLAS on vectors of this size is slow, and 1000x slower when the other
    # core is busy; the FFTs keep their own workers.
    with threadpool_limits(limits=1, user_api="blas"):
        raise_on_failure = kwargs.pop("raise_on_failure", True)
        maxiter = kwargs.pop("maxiter", 400)
        coarse_matvecs = 0.0
        if kwargs.get("initial") is None and COARSEN:
            initial, coarse_matvecs, approach = _coarse_start(op, heights, dict(kwargs, maxiter=maxiter))
            if initial is not None:
                kwargs["initial"] = initial
                kwargs["initial_approach"] = approach
        sol = _solve_twice(op, heights, maxiter, kwargs)
        if coarse_matvecs:
            sol = replace(sol, matvecs=sol.matvecs + int(np.ceil(coarse_matvecs)),
                          message=sol.message[:-1] + f" on this grid, plus {coarse_matvecs:.1f} on "
                          "coarser grids counted at their share of points)")
        if not sol.success and raise_on_failure:
            raise ConvergenceError(sol.message, sol)
        return sol


def _solve_twice(op, heights, maxiter, kwargs):
    """The fast attempt, then if needed the careful one (see :func:`solve_contact`)."""
    # strongly non-symmetric operators (phase > 45 degrees) go straight to the careful strategy
    careful = _max_phase(op) > np.pi / 4
    lines = careful and LINES and kwargs.get("precondition") is None and getattr(op, "factors_along_x", False)
    if lines:
        first = _solve_contact(op, heights, raise_on_failure=False, relax_inner=False,
                               maxiter=max(1, int(LINES_MAXITER_SHARE * maxiter)),
                               precondition="lines", residual_stall=RESIDUAL_STALL, guard=True,
                               **{"inner_eta": LINES_ETA, **kwargs})
        if first.success or maxiter < 2:
            return first
        log.info("retrying without the line preconditioner: %s", first.message)
        second = _solve_contact(op, heights, raise_on_failure=False, relax_inner=False, guard=True,
                                maxiter=max(1, maxiter - first.iterations), **kwargs)
        return _after(first, second)
    first = _solve_contact(op, heights, raise_on_failure=False,
                           maxiter=maxiter if careful else (maxiter + 1) // 2,
                           relax_inner=not careful, **kwargs)
    if first.success or maxiter < 2 or careful:
        return first
    # the fast strategy (inner accuracy relaxed again after full steps) failed: redo with
    # inner solves that only ever tighten, which is slower but converges more reliably
    log.info("retrying with monotone inner tolerances: %s", first.message)
    second = _solve_contact(op, heights, raise_on_failure=False, relax_inner=False,
                            maxiter=maxiter - first.iterations, **kwargs)
    return _after(first, second)


def _after(first, second):
    """The second attempt's solution, with the first attempt's work added to its counts."""
    return replace(second, matvecs=first.matvecs + second.matvecs,
                   iterations=first.iterations + second.iterations,
                   message=second.message.replace(
                       f"active-set iterations ({second.matvecs} operator products)",
                       f"active-set iterations after a first attempt of {first.iterations} "
                       f"({first.matvecs + second.matvecs} operator products in all)"))


def _restricted(apply, idx, shape, project, dtype=float):
    """``z -> (apply(E z))[idx]`` with ``E`` the zero extension from ``idx``; with ``project``,
    in and out are made zero-mean on ``idx`` (the load constraint). ``apply`` must not
    modify its argument: the buffer (of ``dtype``, the precision ``apply`` works in) is zero
    off ``idx`` once and for all. The result is float64."""
    z_full = np.zeros(shape, dtype=dtype)
    z_flat = z_full.reshape(-1)  # a view: scatter/gather by index, not by mask

    def f(z):
        z_flat[idx] = z
        return np.take(apply(z_full).reshape(-1), idx).astype(float, copy=False)

    return _projected(f) if project else f


def _projected(f):
    """``z -> P f(P z)`` with ``P`` the removal of the mean (the load constraint)."""
    def g(z):
        out = f(z - z.mean())
        return out - out.mean()
    return g


def _max_phase(op):
    """Largest phase ``|arg a_q|`` of the operator's symbol (0 when symmetric)."""
    if op.is_symmetric:
        return 0.0
    if hasattr(op, "max_phase"):  # operators without a Fourier symbol (isolated half-space)
        return float(op.max_phase())
    return float(np.max(np.abs(np.angle(op.symbol))))


def _line_search(p, g, p_new, g_new, c, full=True):
    """Step ``t`` in (0, 1] that (nearly) minimises the merit ``||min(p, c g)||**2`` along the
    segment from ``(p, g)`` to ``(p_new, g_new)``; both are affine in ``t``, so no operator
    product is needed."""
    # only points with pressure or negative gap at either end can contribute
    live = ((p != 0) | (p_new != 0) | (g < 0) | (g_new < 0)).reshape(-1)
    p0, g0 = p.reshape(-1)[live], g.reshape(-1)[live]
    dp, dg = p_new.reshape(-1)[live] - p0, g_new.reshape(-1)[live] - g0

    def merit(t):
        f = np.minimum(p0 + t * dp, c * (g0 + t * dg))
        return float(np.dot(f, f))

    m0 = merit(0.0)
    if full and merit(1.0) <= (1 - 1e-4) * m0:
        return 1.0
    ts = 0.5 ** np.arange(1, 13)
    values = [merit(t) for t in ts]
    k = int(np.argmin(values))
    return float(ts[k]) if values[k] < m0 else float(ts[-1])


def _solve_contact(op, heights, *, mean_pressure=None, approach=None, rtol=1e-8, maxiter=200,
                   inner_maxiter=None, inner_eta=0.1, initial=None, raise_on_failure=True,
                   relax_inner=True, precondition=None, stop_when_cycling=False, residual_stall=None,
                   initial_approach=None, guard=False):
    """Solve the contact problem for operator ``op`` (see module docstring).

    Parameters
    ----------
    op : PeriodicHalfSpace or compatible
        Provides ``displacement(p)``, ``self_influence()``, ``is_symmetric``,
        ``symmetric_part()``, and either ``pressure_from_displacement(u)`` (exact
        full-contact inverse, used for the first iterate) or
        ``initial_pressure(ht, mean_pressure=, approach=)``; optionally ``max_phase()``
        instead of a Fourier ``symbol``.
    heights : ndarray
        Indenter heights (m), positive toward the half-space.
    mean_pressure : float, optional
        Load control: mean pressure over the cell (Pa) = load / area.
    approach : float, optional
        Displacement control: rigid approach ``delta`` (m) from first touch.
    rtol : float
        Tolerance on the complementarity residual.
    maxiter : int
        Maximum number of active-set (outer, Newton) iterations.
    inner_maxiter : int, optional
        Maximum operator products per inner solve (default ``20 sqrt(N) + 200``).
    inner_eta : float
        Relative tolerance of the inner solves while the contact set still changes.
    initial : ndarray, optional
        Warm start pressure (Pa), e.g. the solution at a neighbouring speed.
    initial_approach : float, optional
        The approach (m) that goes with ``initial``: the first contact set is then chosen
        from its gap, ``p - c g > 0`` (one product), instead of ``p > 0``.
    relax_inner : bool
        Loosen the inner tolerance again (x3, up to ``inner_eta``) after each full step;
        with ``False`` it only ever tightens (x0.1 after each damped step).
    stop_when_cycling : bool
        Stop (unconverged) once the number of set changes has not reached a new low for
        ``STALL_LIMIT`` steps. Used for the symmetric-part warm start, which needs only the
        rough place of the contact set: on the 20-term rubber of the periodic benchmark its
        plain active-set steps cycle between two sets (512²: 167 steps and 1985 products
        before; 28 steps and 335 products now; 1024²: it ran into the 1000-step cap).
    precondition : bool or "lines", optional
        ``"lines"``: the line preconditioner (module docstring; one FFT pair per application,
        counted in ``matvecs``, plus the line solves). ``True``:
        precondition the inner solves with the full-space inverse restricted to the contact
        set, ``R A^-1 R^T`` (one FFT pair, counted in ``matvecs``); needs
        ``op.pressure_from_displacement``. Default: on for grids of at least
        ``PRECONDITION_MIN_SIZE`` points unless the operator is strongly non-symmetric (symbol
        phase above 45 degrees; its symmetric-part warm start is not preconditioned either):
        elsewhere it was measured to cost more products than it saves. :func:`solve_contact`
        asks for ``"lines"`` for strongly non-symmetric 2-D periodic operators.
    residual_stall : int, optional
        Stop (unconverged) once the residual has not reached a new low for this many steps.
    guard : bool
        Damped steps: take the full step only if it lowers the max-norm residual as well as
        the merit (module docstring); used for strongly non-symmetric 2-D periodic operators.
    """
    shape = heights.shape
    ht = heights - heights.max()
    load_control = mean_pressure is not None
    a0 = op.self_influence()
    if load_control:
        p_ref = float(mean_pressure)
    else:
        p_ref = max(float(approach), np.ptp(ht) * 1e-3) / a0
    h_ref = float(np.ptp(ht)) or a0 * p_ref
    c = 1.0 / a0  # active-set weight: the stiffness of one grid cell (Pa/m)
    inner_maxiter = inner_maxiter or int(20 * np.sqrt(ht.size) + 200)
    solve_inner = krylov.cg if op.is_symmetric else krylov.gmres
    # the inner solves' products and preconditioners (module docstring)
    inner = op.single_precision() if SINGLE_PRECISION_INNER and hasattr(op, "single_precision") else op
    strongly_nonsymmetric = _max_phase(op) > np.pi / 4
    if precondition is None:
        precondition = ht.size >= PRECONDITION_MIN_SIZE and not strongly_nonsymmetric
    if precondition != "lines":
        precondition = precondition and hasattr(op, "pressure_from_displacement")
    final_atol = 0.1 * rtol * h_ref
    matvecs = 0

    # non-symmetric operators start from the contact of their symmetric part (module docstring)
    symmetric_start = strongly_nonsymmetric or (SYMMETRIC_START_1D and ht.ndim == 1 and not op.is_symmetric)
    if initial is None and load_control and symmetric_start and hasattr(op, "pressure_from_displacement"):
        # Full contact is one Fourier division. Where it is (nearly) the answer - tension on
        # under a tenth of the cell - start from it, clipped: the symmetric-part start below
        # would lose it (1-D 512, E_inf/E0 1e4, 0.9x the closing load: 39924 -> 2619 products;
        # above the closing load it is the exact solution, found in one iteration).
        full = _full_contact_pressure(op, ht) + p_ref
        if np.mean(full < 0) < 0.1:  # near (or at) full contact
            initial = np.maximum(full, 0.0)
    if initial is None and symmetric_start:
        # strongly non-symmetric (high E_inf/E0 near the loss peak): start from the contact of
        # the symmetric part (symbol Re a_q), a robust CG solve that puts the set near its place
        sym = _solve_contact(op.symmetric_part(), heights, mean_pressure=mean_pressure, approach=approach,
                             rtol=max(rtol, 1e-3), maxiter=maxiter, raise_on_failure=False,
                             precondition=False, stop_when_cycling=True)
        initial, matvecs = sym.pressure, sym.matvecs
    if initial is None and hasattr(op, "initial_pressure"):
        # operators without an exact full-contact inverse supply their own first iterate
        initial = op.initial_pressure(ht, mean_pressure=mean_pressure, approach=approach)
    if initial is not None:
        p = np.maximum(np.asarray(initial, dtype=float), 0.0)
    elif load_control:
        p = np.maximum(_full_contact_pressure(op, ht) + p_ref, 0.0)
    else:
        p = np.where(ht + approach > 0, np.maximum(_full_contact_pressure(op, ht), 0.0), 0.0)
    if not np.any(p > 0):
        p = np.where(ht == 0, p_ref, 0.0)
    contact = p > 0
    if initial_approach is not None and initial is not None:
        # first set from the iterate's gap at the given approach, as a Newton step would choose
        # it (the interpolated pressure is positive around every coarse contact point)
        g0 = op.displacement(p) - ht - (initial_approach if load_control else approach)
        matvecs += 1
        guess = np.greater(p, c * g0)  # p - c g0 > 0, one temporary fewer
        if guess.any():
            contact = guess

    tighten = 1.0
    line_cache = {}  # the line preconditioner's inverses, kept while a line's contact is unchanged

    def newton_point(contact, p, u, eta):
        """Pressure and approach solving the linear problem with ``contact`` as the contact set,
        starting from ``p`` (whose displacement is ``u``, if known)."""
        nonlocal matvecs, tighten
        idx = np.flatnonzero(contact)
        if u is None or np.count_nonzero(p) != np.count_nonzero(p.reshape(-1)[idx]):  # p off the set
            p = np.where(contact, p, 0.0)
            if load_control:
                p *= p_ref * p.size / p.sum() if p.sum() > 0 else 0.0
                if not p.any():
                    p[contact] = p_ref * p.size / np.count_nonzero(contact)
            u = op.displacement(p)
            matvecs += 1
        else:
            p = p.copy()
        misfit = ht.reshape(-1)[idx] - u.reshape(-1)[idx]
        d = float(approach) if not load_control else -float(np.mean(misfit))
        b = misfit + d
        if load_control:
            b -= b.mean()
        norm_b = float(np.linalg.norm(b))
        while eta == 0.0 and 0 < norm_b <= final_atol * np.sqrt(idx.size) * tighten and (
                np.sqrt(idx.size) * tighten > ATOL_FLOOR):
            # the same set again, and the floor would skip its solve (a step that changes
            # nothing): tighten now instead of after the wasted step
            tighten *= 0.1
        atol = max(final_atol * max(np.sqrt(idx.size) * tighten, ATOL_FLOOR), eta * norm_b)
        # float32 products where the solve stops far above their round-off (module docstring)
        work = inner if atol >= SINGLE_PRECISION_RTOL * norm_b else op
        work_dtype = getattr(work, "dtype", float)
        M = None
        inverse = None
        if precondition == "lines":  # None where the dense line inverses would be too large
            inverse = work.line_preconditioner(contact, cache=line_cache)
            if inverse is not None and load_control:
                inverse = _projected(inverse)
        elif precondition:
            inverse = _restricted(work.pressure_from_displacement, idx, shape, load_control, work_dtype)
        if inverse is not None:

            def M(r):
                nonlocal matvecs
                matvecs += 1
                return inverse(r)
        z, _, k = solve_inner(_restricted(work.displacement, idx, shape, load_control, work_dtype), b, atol=atol,
                              maxiter=inner_maxiter, M=M)
        matvecs += k
        if load_control:
            z -= z.mean()
        p.reshape(-1)[idx] += z
        u = op.displacement(p)
        matvecs += 1
        if load_control:
            d = float(np.mean(u.reshape(-1)[idx] - ht.reshape(-1)[idx]))
        return p, u, d

    eta = inner_eta  # inner forcing term: tightened whenever the step had to be damped
    p, u, delta = newton_point(contact, p, None, eta)
    g = u - ht - delta
    residual = complementarity_residual(p, g, p_ref, h_ref)
    outer = 1
    damped, ascents = not op.is_symmetric, 0
    fewest_changes, stalled = None, 0

    lowest, since_lowest = residual, 0
    while residual > rtol and outer < maxiter and not (stop_when_cycling and stalled >= STALL_LIMIT):
        if residual_stall is not None and since_lowest >= residual_stall:
            break
        outer += 1
        new = np.greater(p, c * g)  # p - c g > 0
        if not new.any():
            new = g == g.min()
        changed = np.count_nonzero(new != contact)
        # cycling: the number of set changes has not reached a new low for STALL_LIMIT steps
        if fewest_changes is None or changed < fewest_changes:
            fewest_changes, stalled = changed, 0
        elif changed:
            stalled += 1
        # inexact Newton: loose inner solves while the set changes, tight once it has settled
        p_new, u_new, d_new = newton_point(new, p, u, eta if changed else 0.0)
        g_new = u_new - ht - d_new
        # Non-symmetric problems are damped by the line search; symmetric ones take plain
        # active-set steps unless the residual rises three times running. An unchanged set
        # (the same system solved more accurately) always takes the full step.
        residual_new = complementarity_residual(p_new, g_new, p_ref, h_ref)
        # a full step that raises the (max-norm) residual is not taken even when it lowers the
        # (L2) merit: 32² robustness sweep 73786 -> 57954 products; rubber 1024² 1655 -> 1250
        t = (_line_search(p, g, p_new, g_new, c, full=residual_new <= residual or not guard)
             if changed and damped else 1.0)
        ascents = ascents + 1 if residual_new > residual else 0
        damped = damped or ascents >= 3
        # damped step: the inner solves were too loose for this stage; full step: loosen again
        if (t < 1.0 and precondition != "lines"
                and changed <= max(TIGHTEN_CHANGES, TIGHTEN_SHARE * np.count_nonzero(new))):
            eta = max(0.1 * eta, 1e-4)
        elif relax_inner:
            eta = min(inner_eta, 3.0 * eta)
        if t == 1.0:
            p, u, g, delta = p_new, u_new, g_new, d_new
        else:  # damped step: everything is affine along the segment
            p, u, g = p + t * (p_new - p), u + t * (u_new - u), g + t * (g_new - g)
            delta += t * (d_new - delta)
        contact = new
        previous = residual
        residual = residual_new if t == 1.0 else complementarity_residual(p, g, p_ref, h_ref)
        lowest, since_lowest = (residual, 0) if residual < lowest else (lowest, since_lowest + 1)
        if not changed and residual > 0.5 * previous:  # settled but stalled: inner accuracy too low
            tighten *= 0.1
        if log.isEnabledFor(logging.DEBUG):
            log.debug("active set %d: %d changes, step %.3g, residual %.3e, contact %.4f, %d products",
                      outer, changed, t, residual, np.mean(p > 0), matvecs)

    p = np.maximum(p, 0.0)
    if load_control and p.sum() > 0:
        p *= p_ref * p.size / p.sum()
    success = residual <= rtol
    state = "converged" if success else "not converged"
    rel = "<=" if success else ">"
    message = (f"{state}: complementarity residual {residual:.2e} {rel} rtol {rtol:.1e} after {outer} "
               f"active-set iterations ({matvecs} operator products)")
    sol = ContactSolution(p, u, g, delta, outer, matvecs, residual, success, message)
    if not success and raise_on_failure:
        raise ConvergenceError(message, sol)
    return sol
