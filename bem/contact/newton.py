"""The active-set (semismooth Newton) iteration of the contact solver: one attempt.

Each step picks the contact set ``C = {p - c g > 0}`` from the current iterate, computes
the Newton point on it (:mod:`bem.contact.inner`) and moves toward it; the line search on
the merit ``||min(p, c g)||**2`` costs no operator product, since pressure, displacement
and gap are affine along the step. How an attempt steps, tightens and gives up is fixed by
its :class:`Attempt`; the retry policy between attempts is in :mod:`bem.contact`.
"""

import logging
from dataclasses import dataclass, replace

import numpy as np

from .inner import InnerSolver, Problem, max_phase
from .start import first_iterate, wants_symmetric_start

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class ContactSolution:
    """Raw output of :func:`bem.contact.solve_contact` (fields shaped like the heights)."""

    pressure: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    approach: float
    iterations: int
    matvecs: int
    residual: float
    success: bool
    message: str


@dataclass(frozen=True)
class Attempt:
    """How one attempt iterates. ``precondition``: None (by grid size and phase), True,
    False or ``"lines"``; ``relax_inner``: loosen the forcing term after full steps;
    ``stop_when_cycling``: stop once set changes stall (``options.stall_limit``);
    ``residual_stall``: stop once the residual has had no new low for this many steps;
    ``guard``: take a full step only if it lowers the max-norm residual as well as the merit."""

    maxiter: int
    inner_eta: float
    relax_inner: bool = True
    precondition: object = None
    stop_when_cycling: bool = False
    residual_stall: int | None = None
    guard: bool = False


def complementarity_residual(p, g, p_ref, h_ref):
    """``max |min(p / p_ref, g / h_ref)|`` (dimensionless); 0 iff the contact conditions hold.

    Evaluated as ``max |min(p, g p_ref / h_ref)| / p_ref``: one temporary, no division."""
    m = g * (p_ref / h_ref)
    np.minimum(m, p, out=m)
    return float(max(m.max(), -m.min())) / p_ref


def line_search(p, g, p_new, g_new, c, *, full, decrease, halvings):
    """Step ``t`` in (0, 1] that (nearly) minimises the merit ``||min(p, c g)||**2`` along the
    segment from ``(p, g)`` to ``(p_new, g_new)``: the full step if allowed (``full``) and it
    lowers the merit by the share ``decrease``, else the best of ``1/2 ... 1/2**halvings``."""
    # only points with pressure or negative gap at either end can contribute
    live = ((p != 0) | (p_new != 0) | (g < 0) | (g_new < 0)).reshape(-1)
    p0, g0 = p.reshape(-1)[live], g.reshape(-1)[live]
    dp, dg = p_new.reshape(-1)[live] - p0, g_new.reshape(-1)[live] - g0

    def merit(t):
        f = np.minimum(p0 + t * dp, c * (g0 + t * dg))
        return float(np.dot(f, f))

    m0 = merit(0.0)
    if full and merit(1.0) <= (1 - decrease) * m0:
        return 1.0
    ts = 0.5 ** np.arange(1, halvings + 1)
    values = [merit(t) for t in ts]
    k = int(np.argmin(values))
    return float(ts[k]) if values[k] < m0 else float(ts[-1])


def problem_scales(op, heights, mean_pressure, approach, rtol, options, *, strong, p_mean=None):
    """The scaled :class:`~bem.contact.inner.Problem`: ``p_ref`` the mean pressure (under
    displacement control ``p_mean``, that of the first Newton point, once known) and ``h_ref =
    gap_scale a0 p_ref``, ``gap_scale`` times the displacement of one cell under it
    (``gap_scale_strong`` for strongly non-symmetric operators, ``strong``), kept between
    ``gap_floor_share`` of the surface's height range and that range (near full contact of
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
    h_ref = (options.gap_scale_strong if strong else options.gap_scale) * a0 * p_ref
    ptp = float(np.ptp(ht))
    if ptp > 0:  # between round-off of the heights and their range (see ContactOptions)
        h_ref = min(max(h_ref, options.gap_floor_share * ptp), ptp)
    return Problem(
        ht=ht,
        load_control=load_control,
        approach=None if load_control else float(approach),
        p_ref=p_ref,
        h_ref=h_ref,
        c=1.0 / a0,
        final_atol=options.final_atol_share * rtol * h_ref,
    )


class ActiveSet:
    """One attempt's iteration state; :meth:`run` iterates and returns the solution."""

    def __init__(self, op, pb, inner, attempt, rtol, options):
        self.op, self.pb, self.inner, self.attempt, self.rtol, self.o = op, pb, inner, attempt, rtol, options
        self.eta = attempt.inner_eta  # forcing term: tightened whenever a step had to be damped
        self.eta_max = attempt.inner_eta  # ... and for good once the set oscillates
        self.flips, self.changes = None, 0  # the points whose set membership the last step changed, and their count
        self.damped, self.ascents = not op.is_symmetric, 0
        self.fewest_changes, self.stalled = None, 0

    def start(self, p, contact):
        self.p, self.u, self.delta = self.inner.newton_point(contact, p, None, self.eta)
        self.g = self.u - self.pb.ht - self.delta
        self.contact = contact
        self.residual = complementarity_residual(self.p, self.g, self.pb.p_ref, self.pb.h_ref)
        self.outer = 1
        self.lowest, self.since_lowest = self.residual, 0

    def rescale(self, pb):
        """Use the scales of ``pb`` from here on."""
        self.pb = self.inner.problem = pb
        self.residual = self.lowest = complementarity_residual(self.p, self.g, pb.p_ref, pb.h_ref)

    def _go_on(self):
        a = self.attempt
        if not self.residual > self.rtol or self.outer >= a.maxiter:
            return False
        if a.stop_when_cycling and self.stalled >= self.o.stall_limit:
            return False
        return a.residual_stall is None or self.since_lowest < a.residual_stall

    def _count_changes(self, new):
        """``(changes, converging)``: the set changes, and whether the set is still converging;
        cycling counts steps without a new low in set changes.

        Not converging: a step changes more than ``oscillation_decrease`` of the last step's
        changes, and either more than the last step (the set diverges) or mostly by undoing
        it (it oscillates); counts below ``tighten_changes`` are a settling set's and pass."""
        flips = new != self.contact
        changed = np.count_nonzero(flips)
        undone = 0 if self.flips is None else np.count_nonzero(flips & self.flips)
        before, self.flips, self.changes = self.changes, flips, changed
        if self.fewest_changes is None or changed < self.fewest_changes:
            self.fewest_changes, self.stalled = changed, 0
        elif changed:
            self.stalled += 1
        slow = before and changed > self.o.oscillation_decrease * before and changed > self.o.tighten_changes
        return changed, not (slow and (changed > before or 2 * undone > changed))

    def _step_length(self, changed, p_new, g_new, residual_new):
        """Non-symmetric problems are damped by the line search; symmetric ones take plain
        active-set steps unless the residual rises ``ascents`` times running. An unchanged set
        (the same system solved more accurately) always takes the full step."""
        t = 1.0
        if changed and self.damped:
            full = residual_new <= self.residual or not self.attempt.guard
            t = line_search(
                self.p,
                self.g,
                p_new,
                g_new,
                self.pb.c,
                full=full,
                decrease=self.o.search_decrease,
                halvings=self.o.search_halvings,
            )
        self.ascents = self.ascents + 1 if residual_new > self.residual else 0
        self.damped = self.damped or self.ascents >= self.o.ascents
        return t

    def _adapt_eta(self, t, changed, converging, new):
        """A damped step on a nearly settled set: the inner solves were too loose; a full step:
        loosen them again (fast attempt). Earlier, damping comes from the set itself. Once the
        set stops converging the forcing term drops a decade, once, for the rest of the attempt:
        the Newton points' errors flip points at the margin of the contact, and broad-band
        roughness has many. The line-preconditioned attempt keeps its own tight forcing term;
        the symmetric-part start only places the set, and its own cycling ends it."""
        o = self.o
        settled = changed <= max(o.tighten_changes, o.tighten_share * np.count_nonzero(new))
        own = self.inner.precondition != "lines" and not self.attempt.stop_when_cycling
        if not converging and own and self.eta_max == self.attempt.inner_eta:
            self.eta = self.eta_max = max(o.inner_tighten * self.eta_max, o.inner_eta_min)
        elif t < 1.0 and self.inner.precondition != "lines" and settled:
            self.eta = max(o.inner_tighten * self.eta, o.inner_eta_min)
        elif self.attempt.relax_inner:
            self.eta = min(self.eta_max, o.inner_relax * self.eta)

    def step(self):
        pb = self.pb
        self.outer += 1
        new = np.greater(self.p, pb.c * self.g)  # p - c g > 0
        if not new.any():
            new = self.g == self.g.min()
        changed, converging = self._count_changes(new)
        # inexact Newton: loose inner solves while the set changes, tight once it has settled
        p_new, u_new, d_new = self.inner.newton_point(new, self.p, self.u, self.eta if changed else 0.0)
        g_new = u_new - pb.ht - d_new
        residual_new = complementarity_residual(p_new, g_new, pb.p_ref, pb.h_ref)
        t = self._step_length(changed, p_new, g_new, residual_new)
        self._adapt_eta(t, changed, converging, new)
        if t == 1.0:
            self.p, self.u, self.g, self.delta = p_new, u_new, g_new, d_new
        else:  # damped step: everything is affine along the segment
            self.p = self.p + t * (p_new - self.p)
            self.u = self.u + t * (u_new - self.u)
            self.g = self.g + t * (g_new - self.g)
            self.delta += t * (d_new - self.delta)
        self.contact = new
        previous = self.residual
        self.residual = residual_new if t == 1.0 else complementarity_residual(self.p, self.g, pb.p_ref, pb.h_ref)
        if self.residual < self.lowest:
            self.lowest, self.since_lowest = self.residual, 0
        else:
            self.since_lowest += 1
        if not changed and self.residual > self.o.stall_ratio * previous:
            self.inner.tighten *= self.o.inner_tighten  # settled but stalled: inner accuracy too low
        if log.isEnabledFor(logging.DEBUG):
            log.debug(
                "active set %d: %d changes%s, step %.3g, residual %.3e, contact %.4f, %d products",
                self.outer,
                changed,
                "" if converging else " (not converging)",
                t,
                self.residual,
                np.mean(self.p > 0),
                self.inner.matvecs,
            )

    def run(self):
        while self._go_on():
            self.step()
        p = np.maximum(self.p, 0.0)
        if self.pb.load_control and p.sum() > 0:
            p *= self.pb.p_ref * p.size / p.sum()
        success = self.residual <= self.rtol
        state, rel = ("converged", "<=") if success else ("not converged", ">")
        message = (
            f"{state}: complementarity residual {self.residual:.2e} {rel} rtol {self.rtol:.1e} after "
            f"{self.outer} active-set iterations ({self.inner.matvecs} operator products)"
        )
        return ContactSolution(
            p, self.u, self.g, self.delta, self.outer, self.inner.matvecs, self.residual, success, message
        )


def attempt_solve(op, heights, *, mean_pressure, approach, rtol, attempt, options, initial=None, initial_approach=None):
    """One attempt of the active-set iteration (never raises; see :class:`Attempt`)."""
    strongly_nonsymmetric = max_phase(op) > options.strong_phase
    pb = problem_scales(op, heights, mean_pressure, approach, rtol, options, strong=strongly_nonsymmetric)
    precondition = attempt.precondition
    if precondition is None:
        precondition = options.precondition
    if precondition is None:  # elsewhere it costs more products than it saves
        precondition = pb.ht.size >= options.precondition_min_size and not strongly_nonsymmetric
    inner = InnerSolver(op, pb, precondition, options)

    def solve_symmetric():  # a robust CG solve that puts the set near its place
        sym = Attempt(maxiter=attempt.maxiter, inner_eta=options.inner_eta, precondition=False, stop_when_cycling=True)
        return attempt_solve(
            op.symmetric_part(),
            heights,
            mean_pressure=mean_pressure,
            approach=approach,
            rtol=max(rtol, options.symmetric_start_rtol),
            attempt=sym,
            options=options,
        )

    p, contact, inner.matvecs = first_iterate(
        op,
        pb,
        initial=initial,
        initial_approach=initial_approach,
        solve_symmetric=solve_symmetric,
        symmetric_start=wants_symmetric_start(op, pb.ht, strongly_nonsymmetric, options),
        options=options,
    )
    if initial_approach is not None and initial is not None and op.is_symmetric:
        # nested iteration: the set is nearly right, Newton's local convergence needs tight solves
        attempt = replace(attempt, inner_eta=min(attempt.inner_eta, options.nested_eta))
    it = ActiveSet(op, pb, inner, attempt, rtol, options)
    it.start(p, contact)
    if not pb.load_control and it.p.mean() > 0:  # displacement control: now the mean pressure is known
        it.rescale(
            problem_scales(
                op, heights, mean_pressure, approach, rtol, options, strong=strongly_nonsymmetric, p_mean=it.p.mean()
            )
        )
    return it.run()
