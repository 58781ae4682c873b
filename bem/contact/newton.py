"""The active-set (semismooth Newton) iteration of the contact solver: one attempt.

Each step picks the contact set ``C = {p - c g > 0}`` from the current iterate, computes
the Newton point on it (:mod:`bem.contact.inner`) to the forcing term of
:mod:`bem.contact.forcing`, and moves toward it; the line search on the merit
``||min(p, c g)||**2`` costs no operator product, since pressure, displacement and gap are
affine along the step. How an attempt steps and gives up is fixed by its :class:`Attempt`;
the retry policy between attempts is in :mod:`bem.contact.solver`.

A solve asked for more than round-off allows stops at the floor: once the set has settled and
the residual no longer falls although it is within :data:`FLOOR_MARGIN` of its round-off floor
(:func:`roundoff_floor`), the attempt ends and says which residual it attained.
"""

import logging
import math
from dataclasses import dataclass

import numpy as np

from . import forcing as fc
from .inner import InnerSolver, Problem
from .operator import ExactInverse, strongly_nonsymmetric
from .start import first_iterate, start_rtol, wants_symmetric_start

__all__ = ["Attempt", "ContactSolution", "attempt_solve", "complementarity_residual", "line_search", "roundoff_floor"]

log = logging.getLogger(__name__)

GAP_SCALE = 0.3
"""The residual's gap scale in one cell's displacement under the mean pressure: it makes the
stopping test bound the pressure error (``tests/bem/test_rtol_meaning.py``), one value for every
operator. Strongly non-symmetric operators move the pressure most per gap error and set it:
ablation row "gap scale 0.3" (1 instead): 0.98x the products and a pressure error of 9.8 rtol, at
the 10 rtol bound; row "gap scale 0.3 vs 10": 1.01x and 72 rtol. At 0.3 the largest error on the
case set is 1.9 rtol. Symmetric operators alone would allow 10, which saves them too little to
keep a second scale (one scale for all costs 1.006x the products against 10 for them)."""
GAP_FLOOR_SHARE = 1e-4
"""Smallest gap scale as a share of the height range: below it round-off of the gap would stop
tight solves (ablation row "gap floor": no product on the set, but the 4096-point profile of
``tests/bem/contact/test_roundoff.py`` reaches rtol 1e-11 only with it)."""
PRECONDITION_MIN_SIZE = 2**17
"""Grid points from which the exact full-contact inverse pays its extra FFT pair as a
preconditioner: smaller restricted systems are well conditioned. Below it the preconditioner is
also a hazard: applied in single precision to approach-controlled solves at rtol 1e-12 on 32²
cells (tests/bem/test_solver.py, slow), its GMRES correction overflowed float32. Ablation row
"large-grid exact preconditioner": 1.017x products on the quick set without the size limit."""
CYCLING_STEPS = 3
"""Steps in a row that show an iteration cycling. A symmetric problem whose residual rises this
many times in a row is damped by the line search from then on: its plain Newton steps cycle. An
attempt that only places the set (the symmetric-part start) ends once its set changes have had no
new low for this many steps. No case of the ablation set needs either (row "cycling stop": 1.00x
the products), nor, from its coarse start, the elastic Westergaard profile (2 active-set steps
from 4096 to 16384 points). From the full-contact start (``coarsen=False``) 16384 points need the
damping: 66 steps with it, 400 without, cycling at residual ~800 (``tests/bem/test_westergaard.py``,
slow). Without the stop, with ``coarsen=False``, the symmetric-part start of a 512² rubber cycles
(``tests/bem/contact/test_krylov.py``). Row "cycling steps 3" (2 instead): 0.65x the products, all
of it the sinusoid near full contact (2488 against 9832), and 15 steps instead of 66 on the
16384-point Westergaard profile from full contact, but over the stress suite 0.99x as stored and
1.05x with the heights perturbed by 1e-12, and 1.00x on the quick friction curves of
``viscobem bench curve``; row "cycling steps 3 vs 5": 1.00x."""
FLOOR_MARGIN = 30.0
"""A residual within this factor of its round-off floor (:func:`roundoff_floor`) that stops
falling on a settled set is at the floor: the floor is an estimate of the precision of the
gap and pressure, and the stalled residual measured a few times to tens of times above it.
Ablation row "round-off floor stop": no product on the set (no case asks below its floor);
without it a solve asked for too much crawls to ``maxiter`` (``tests/bem/contact/test_roundoff.py``).
The first settled step at the floor without a new low stops the attempt: row "floor stalls" (one
such step instead of two) costs no product on the set."""


@dataclass(frozen=True)
class ContactSolution:
    """Raw output of :func:`bem.contact.solve_contact` (fields shaped like the heights).

    ``attainable``: when the solve stopped at its round-off floor, the lowest residual it
    reached plus that floor, which any path reaches (ask for an ``rtol`` at least this); otherwise
    ``None``."""

    pressure: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    approach: float
    iterations: int
    matvecs: int
    residual: float
    success: bool
    message: str
    attainable: float | None = None


@dataclass(frozen=True)
class Attempt:
    """How one attempt iterates. ``precondition``: None (by grid size and phase), True,
    False or ``"lines"``; ``own_forcing``: keep ``eta`` whatever the steps do (the
    line-preconditioned attempt); ``stop_when_cycling``: only place the set, and stop once its
    changes stall; ``residual_stall``: stop once the residual has had no new low for this many
    steps."""

    maxiter: int
    eta: float
    precondition: object = None
    own_forcing: bool = False
    stop_when_cycling: bool = False
    residual_stall: int | None = None


@dataclass(frozen=True)
class Iterate:
    """Pressure (Pa), displacement and gap (m), approach (m), contact set and residual."""

    p: np.ndarray
    u: np.ndarray
    g: np.ndarray
    delta: float
    contact: np.ndarray
    residual: float

    def toward(self, other, t, pb):
        """The iterate a share ``t`` of the way to ``other`` (everything is affine along it)."""
        if t == 1.0:
            return other
        p, u, g = (a + t * (b - a) for a, b in ((self.p, other.p), (self.u, other.u), (self.g, other.g)))
        residual = complementarity_residual(p, g, pb.p_ref, pb.h_ref)
        return Iterate(p, u, g, self.delta + t * (other.delta - self.delta), other.contact, residual)


@dataclass(frozen=True)
class SetTrack:
    """The fewest set changes so far and the steps since (an attempt that only places the set
    stops once they stall)."""

    fewest: int | None = None
    stalled: int = 0

    def after(self, old, new):
        """``(track, changes)`` after a step from set ``old`` to set ``new``."""
        changed = int(np.count_nonzero(new != old))
        if self.fewest is None or changed < self.fewest:
            return SetTrack(changed, 0), changed
        return SetTrack(self.fewest, self.stalled + (changed > 0)), changed


@dataclass(frozen=True)
class ResidualTrack:
    """The lowest residual and the steps since; whether the last step stalled at the floor; rises
    in a row."""

    lowest: float
    since_lowest: int = 0
    at_floor: bool = False
    ascents: int = 0

    def after(self, previous, residual, *, unchanged, floor):
        lower = residual < self.lowest
        stuck = unchanged and not lower and residual <= FLOOR_MARGIN * floor
        return ResidualTrack(
            lowest=min(self.lowest, residual),
            since_lowest=0 if lower else self.since_lowest + 1,
            at_floor=stuck,
            ascents=self.ascents + 1 if residual > previous else 0,
        )


def complementarity_residual(p, g, p_ref, h_ref):
    """``max |min(p / p_ref, g / h_ref)|`` (dimensionless); 0 iff the contact conditions hold.

    Evaluated as ``max |min(p, g p_ref / h_ref)| / p_ref``: one temporary, no division."""
    m = g * (p_ref / h_ref)
    np.minimum(m, p, out=m)
    return float(max(m.max(), -m.min())) / p_ref


def roundoff_floor(pb, it):
    """Round-off floor of the residual at iterate ``it``: the spacing of floating-point numbers
    at the size of the gap's terms (heights, displacement, approach) over ``h_ref``, and at the
    size of the largest pressure over ``p_ref``."""
    eps = np.finfo(float).eps
    gap_terms = max(float(np.max(np.abs(pb.ht))), float(np.max(np.abs(it.u))), abs(it.delta))
    return eps * (gap_terms / pb.h_ref + float(np.max(np.abs(it.p))) / pb.p_ref)


def line_search(p, g, p_new, g_new, c, *, full):
    """Step ``t`` in (0, 1] that lowers the merit ``||min(p, c g)||**2`` along the segment from
    ``(p, g)`` to ``(p_new, g_new)``: the full step if allowed (``full``) and it lowers the merit
    at all, else the first local minimum of the merit over ``1/2, 1/4, ...`` below its value at 0
    (halve until the merit is lower, then while it keeps falling). The halvings cost no product;
    they end, at the latest, where the step no longer moves any point the merit sees, and an
    inner solve too loose to give a descent direction is then solved tight on the unchanged set.
    Ablation row "line search" (off: full steps): 1.52x the products and three cases lost
    (``docs/theory.md`` §4.2)."""
    # only points with pressure or negative gap at either end can contribute
    live = ((p != 0) | (p_new != 0) | (g < 0) | (g_new < 0)).reshape(-1)
    p0, g0 = p.reshape(-1)[live], g.reshape(-1)[live]
    dp, dg = p_new.reshape(-1)[live] - p0, g_new.reshape(-1)[live] - g0

    def merit(t):
        f = np.minimum(p0 + t * dp, c * (g0 + t * dg))
        return float(np.dot(f, f))

    m0 = merit(0.0)
    if full and merit(1.0) < m0:
        return 1.0

    def moves(t):
        return bool(np.any(p0 + t * dp != p0) or np.any(g0 + t * dg != g0))

    t, m = 0.5, merit(0.5)
    while m >= m0 and moves(t):
        t *= 0.5
        m = merit(t)
    while m < m0:  # merit(0.5 t) >= m0 once the step moves nothing: this ends
        lower = merit(0.5 * t)
        if lower >= m:
            break
        t, m = 0.5 * t, lower
    return t


def problem_scales(op, heights, mean_pressure, approach, rtol, *, p_mean=None):
    """The scaled :class:`~bem.contact.inner.Problem`: ``p_ref`` the mean pressure (under
    displacement control ``p_mean``, that of the first Newton point, once known) and ``h_ref =
    GAP_SCALE a0 p_ref``, the displacement of :data:`GAP_SCALE` cells under it, held between
    :data:`GAP_FLOOR_SHARE` of the surface's height range and that range (near full contact of
    soft solids)."""
    ht = heights - heights.max()
    load_control = mean_pressure is not None
    a0 = op.self_influence()
    if load_control:
        p_ref = float(mean_pressure)
    elif p_mean:
        p_ref = float(p_mean)
    else:  # before the first iterate: the pressure that pushes one cell by the approach
        p_ref = max(float(approach), np.ptp(ht) * 1e-3) / a0
    h_ref = GAP_SCALE * a0 * p_ref
    ptp = float(np.ptp(ht))
    if ptp > 0:  # between round-off of the heights and their range
        h_ref = min(max(h_ref, GAP_FLOOR_SHARE * ptp), ptp)
    return Problem(
        ht=ht,
        load_control=load_control,
        approach=None if load_control else float(approach),
        p_ref=p_ref,
        h_ref=h_ref,
        c=1.0 / a0,
        final_atol=rtol * h_ref,
    )


class _Run:
    """The fixed parts of one attempt: operator, problem, inner solver, attempt, tolerance."""

    def __init__(self, op, pb, inner, attempt, rtol):
        self.op, self.pb, self.inner, self.attempt, self.rtol = op, pb, inner, attempt, rtol

    def point(self, contact, it, eta, tighten):
        """The Newton point on ``contact`` from ``it`` as an :class:`Iterate`, and ``tighten``."""
        pb = self.pb
        p, u, d, tighten = self.inner.newton_point(pb, contact, it.p, it.u, eta, tighten)
        g = u - pb.ht - d
        return Iterate(p, u, g, d, contact, complementarity_residual(p, g, pb.p_ref, pb.h_ref)), tighten

    def step_length(self, it, new, changed, damped):
        """Non-symmetric problems are damped by the line search; symmetric ones take the Newton
        point until their residual rises :data:`CYCLING_STEPS` times in a row, and so does an unchanged
        set (the same system solved more accurately)."""
        if not (changed and damped):
            return 1.0
        return line_search(it.p, it.g, new.p, new.g, self.pb.c, full=True)

    def go_on(self, it, outer, sets, residuals):
        a = self.attempt
        if not it.residual > self.rtol or outer >= a.maxiter or residuals.at_floor:
            return False
        if a.stop_when_cycling and sets.stalled >= CYCLING_STEPS:
            return False
        return a.residual_stall is None or residuals.since_lowest < a.residual_stall


def _iterate(run, it):
    """The active-set loop from the first Newton point ``it``; returns the last iterate, its
    step count and the residual track."""
    a = run.attempt
    eta = a.eta
    sets, residuals = SetTrack(), ResidualTrack(it.residual)
    tighten, outer = 1.0, 1
    damped = not run.op.is_symmetric
    while run.go_on(it, outer, sets, residuals):
        outer += 1
        contact = np.greater(it.p, run.pb.c * it.g)  # p - c g > 0
        if not contact.any():
            contact = it.g == it.g.min()
        sets, changed = sets.after(it.contact, contact)
        # inexact Newton: loose inner solves while the set changes, tight once it has settled
        new, tighten = run.point(contact, it, eta if changed else 0.0, tighten)
        t = run.step_length(it, new, changed, damped)
        if not a.own_forcing:
            eta = fc.next_eta(eta, damped=t < 1.0)
        previous, it = it.residual, it.toward(new, t, run.pb)
        residuals = residuals.after(previous, it.residual, unchanged=not changed, floor=roundoff_floor(run.pb, it))
        damped = damped or residuals.ascents >= CYCLING_STEPS
        _log_step(outer, changed, t, it, run.inner.matvecs)
    return it, outer, residuals


def _log_step(outer, changed, t, it, matvecs):
    if log.isEnabledFor(logging.DEBUG):
        log.debug(
            "active set %d: %d changes, step %.3g, residual %.3e, contact %.4f, %d products",
            outer,
            changed,
            t,
            it.residual,
            np.mean(it.p > 0),
            matvecs,
        )


def _solution(run, it, outer, residuals):
    """The :class:`ContactSolution` of the last iterate: ``p >= 0``, the load rescaled."""
    pb, rtol = run.pb, run.rtol
    p = np.maximum(it.p, 0.0)
    if pb.load_control and p.sum() > 0:
        p *= pb.p_ref * p.size / p.sum()
    success = it.residual <= rtol
    state, rel = ("converged", "<=") if success else ("not converged", ">")
    message = (
        f"{state}: complementarity residual {it.residual:.2e} {rel} rtol {rtol:.1e} after "
        f"{outer} active-set iterations ({run.inner.matvecs} operator products)"
    )
    attainable = None
    if not success and residuals.at_floor:
        # at the floor the residual is round-off: another path (another processor's rounding)
        # settles up to a floor higher, so what a solve can count on is the lowest plus the floor
        floor = roundoff_floor(pb, it)
        attainable = residuals.lowest + floor
        message += (
            f"; the residual stopped falling near its round-off floor (about {floor:.1e}) at "
            f"{residuals.lowest:.2e}: this problem attains {attainable:.2e} on any path, ask for rtol >= "
            f"{_rounded_up(attainable)}"
        )
    return ContactSolution(p, it.u, it.g, it.delta, outer, run.inner.matvecs, it.residual, success, message, attainable)


def _rounded_up(x):
    """``x`` in two significant figures, rounded up (a tolerance quoted to ask for must not be below it)."""
    step = 10.0 ** (math.floor(math.log10(x)) - 1)
    return f"{math.ceil(x / step) * step:.1e}"


def attempt_solve(op, heights, *, mean_pressure, approach, rtol, attempt, options, initial=None, initial_approach=None):
    """One attempt of the active-set iteration (never raises; see :class:`Attempt`)."""
    strong = strongly_nonsymmetric(op)
    pb = problem_scales(op, heights, mean_pressure, approach, rtol)
    inner = InnerSolver(op, _preconditioner(op, pb, attempt, options, strong), options)

    def solve_symmetric():  # a robust CG solve that puts the set near its place
        sym = Attempt(maxiter=attempt.maxiter, eta=options.inner_eta, precondition=False, stop_when_cycling=True)
        return attempt_solve(
            op.symmetric_part(),
            heights,
            mean_pressure=mean_pressure,
            approach=approach,
            rtol=start_rtol(rtol),
            attempt=sym,
            options=options,
        )

    p, contact, inner.matvecs = first_iterate(
        op,
        pb,
        initial=initial,
        initial_approach=initial_approach,
        solve_symmetric=solve_symmetric,
        symmetric_start=wants_symmetric_start(op, pb.ht, strong, options),
    )
    p, u, d, _ = inner.newton_point(pb, contact, p, None, attempt.eta)
    if not pb.load_control and p.mean() > 0:  # displacement control: now the mean pressure is known
        pb = problem_scales(op, heights, mean_pressure, approach, rtol, p_mean=p.mean())
    g = u - pb.ht - d
    first = Iterate(p, u, g, d, contact, complementarity_residual(p, g, pb.p_ref, pb.h_ref))
    run = _Run(op, pb, inner, attempt, rtol)
    return _solution(run, *_iterate(run, first))


def _preconditioner(op, pb, attempt, options, strong):
    """The attempt's preconditioner: its own choice, else the options', else by operator, where
    it has an approximate inverse (:class:`~bem.contact.operator.ApproximateInverse`): on isolated
    domains it always pays; so does the exact one of periodic cells whose operator is not strongly
    non-symmetric, on any grid (ablation rows "exact preconditioner" and "exact
    preconditioner on small grids"; ``tests/bem/contact/test_krylov.py`` at 512²). Strongly
    non-symmetric periodic operators have the line preconditioner or none: the full-contact
    inverse does not remove their non-normality."""
    choice = attempt.precondition if attempt.precondition is not None else options.precondition
    if choice is None:
        approximate_only = not isinstance(op, ExactInverse)
        choice = approximate_only or (pb.ht.size >= PRECONDITION_MIN_SIZE and not strong)
    return choice
