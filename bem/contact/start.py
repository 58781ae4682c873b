"""First iterate of the contact solver.

In order of preference:

1. the same problem solved on the grid with half the points per axis (nested iteration,
   :func:`coarse_start`), itself warm-started from the caller's warm start sampled there, and
   interpolated back (:class:`~bem.contact.operator.Coarsening`): on grids from
   :data:`COARSEN_MIN_SIZE` points, unless the clipped full-contact pressure is nearly the
   answer. The first contact set is then the one a Newton step would pick from that pressure and
   its gap at the coarse approach, ``p - c g > 0``. A warm start is kept instead when, sampled on
   the coarse grid, its contact set differs from the coarse solution's at fewer points than the
   round trip through the coarse grid moves its own set (:func:`nearer`): then it is the nearer
   of the two (along a friction curve, where the contact changes little between neighbouring
   speeds);
2. a warm start given by the caller (e.g. the solution at a neighbouring speed);
3. under load control, the clipped full-contact pressure when it is nearly the answer (tension
   on less than :data:`NEAR_FULL_CONTACT` of the cell);
4. for strongly non-symmetric operators (and non-symmetric 1-D ones, where smooth indenters on
   long cells need it), the contact of the operator's symmetric part, a robust CG solve stopped
   once its set cycles;
5. the operator's own first iterate (:class:`~bem.contact.operator.OwnStart`, isolated domains);
6. the full-contact solution (exact in Fourier space) clipped to ``p >= 0``.

Why the nested start pays for strongly non-symmetric operators at any size: their Newton point on
a set that reaches past the answer puts a tension spike on the outermost cell of a contact edge
alone (the material ahead of the edge responds with its glassy modulus), so the edge retreats by
about a cell per step; the coarse grid brings it within a cell or two first.
"""

import logging
import math

import numpy as np

from .operator import Coarsening, ExactInverse, OwnStart

__all__ = [
    "COARSEN_MIN_SIZE",
    "NEAR_FULL_CONTACT",
    "coarse_start",
    "first_iterate",
    "nearer",
    "start_rtol",
    "wants_coarse_start",
    "wants_symmetric_start",
]

log = logging.getLogger(__name__)

COARSEN_MIN_SIZE = 128
"""Grid points from which the coarse start is used: below it the coarse problem no longer
resembles the fine one. Ablation row "coarse start" (off): 1.22x the products, 1.35x the geometric
mean of the cases; row "coarse start on small grids" (from 2**18 points instead): the same, since
it pays most for strongly non-symmetric operators, whose contact edges move a cell per step on any
grid (module docstring); row "symmetric coarse start on small grids" (from 2**18 points for the
others only): 1.00x the products, 1.05x the geometric mean."""
NEAR_FULL_CONTACT = 0.1
"""Tension share under which the clipped full-contact pressure is the start, and no coarse start
is made (it is nearly the answer). Ablation row "near-full start": no quick case is this near
full contact; the 32² cell at 0.9 of its full-contact load (``E_inf/E0`` = 1e4, xi = 1) of the
full set takes 28 products with it and 21,390 without, the same pressure to 0.01 rtol; that cell
and a second seed at 0.8 and 0.9 of the load take 152 products with it and 51,761 without
(``docs/theory.md`` §4.2, near full contact)."""


def start_rtol(rtol):
    """Residual at which a start stops, the coarse solve and the symmetric-part start alike:
    ``sqrt(rtol)``. A start only has to place the set; Newton's local convergence is quadratic, so
    from a residual of ``sqrt(rtol)`` one step on the right set reaches ``rtol``, and a start
    asked for less than that spends products the fine grid would spend anyway. A solve asked for
    less than its round-off floor asks its starts only for the square root of it, so they do not
    crawl to the floor as well (starts asked for ``rtol`` took 1716 products against at most 669
    at 1e-3 on ``tests/bem/contact/test_roundoff.py``'s profile). Ablation row "loose starts" (the
    caller's rtol instead): 1.03x the products, 1.06x the geometric mean of the cases; row
    "square-root start" (1e-3 instead, a tuned constant): 1.02x."""
    return max(rtol, math.sqrt(rtol))


def full_contact_pressure(op, ht, mean_pressure):
    """Under load control (``mean_pressure``, Pa) with an exact inverse, the full-contact pressure
    for the heights ``ht`` (m, maximum 0), else None."""
    if mean_pressure is None or not isinstance(op, ExactInverse):
        return None
    return op.pressure_from_displacement(ht) + mean_pressure


def nearly_full_contact(full):
    """Whether the full-contact pressure ``full`` is nearly the answer: tension on little of the cell."""
    return full is not None and np.mean(full < 0) < NEAR_FULL_CONTACT


def wants_coarse_start(op, heights, mean_pressure, options):
    """Whether to start from the coarser grid (module docstring, item 1)."""
    if not (options.coarsen and isinstance(op, Coarsening)):
        return False
    if heights.size < COARSEN_MIN_SIZE:
        return False
    return not nearly_full_contact(full_contact_pressure(op, heights - heights.max(), mean_pressure))


def coarse_start(op, heights, solve):
    """First iterate from the same problem on the grid with half the points per axis.

    ``solve(coarse_op, coarse_heights)`` solves it (itself starting from its own coarser grid)
    without raising. Returns ``(pressure or None, products, approach or None)``: the coarse
    products counted at their share of grid points (a 512² product as 1/4 of a 1024² one), and
    the coarse approach (m) measured from this grid's first touch.
    """
    coarse_op = op.coarsened()
    if coarse_op is None:
        return None, 0.0, None
    coarse_heights = op.restrict(heights)
    coarse = solve(coarse_op, coarse_heights)
    share = coarse.matvecs * coarse_op.size / op.size
    if not coarse.success:
        log.info("coarse start discarded: %s", coarse.message)
        return None, share, None
    # the same rigid position: the approach counts from first touch, on each grid's own maximum
    approach = coarse.approach + float(heights.max() - coarse_heights.max())
    return op.prolong(coarse.pressure), share, approach


def nearer(op, warm, coarse):
    """Whether the warm start ``warm`` is nearer the answer than the interpolated coarse solution
    ``coarse``: its set differs from the coarse solution's (on the coarse grid, counted in fine
    points) at fewer points than the round trip through the coarse grid moves its own set."""
    differ = 2**warm.ndim * np.count_nonzero((op.restrict(warm) > 0) != (op.restrict(coarse) > 0))
    round_trip = np.count_nonzero((op.prolong(op.restrict(warm)) > 0) != (warm > 0))
    return differ <= round_trip


def wants_symmetric_start(op, ht, strong, options):
    """Whether the first iterate comes from the symmetric part's contact (module docstring)."""
    return options.symmetric_start and (strong or (ht.ndim == 1 and not op.is_symmetric))


def _full_contact_start(op, pb):
    """The clipped full-contact pressure, which makes the gap vanish everywhere."""
    if pb.load_control:
        return np.maximum(op.pressure_from_displacement(pb.ht) + pb.p_ref, 0.0)
    return np.where(pb.ht + pb.approach > 0, np.maximum(op.pressure_from_displacement(pb.ht), 0.0), 0.0)


def _start_pressure(op, pb, initial, symmetric_start, solve_symmetric):
    """``(pressure, products, given)``: the first iterate, and whether it came from
    somewhere other than the full-contact fallback."""
    matvecs = 0
    if initial is None and symmetric_start:
        # full contact is one Fourier division; where it is nearly the answer the
        # symmetric-part start would lose it
        full = full_contact_pressure(op, pb.ht, pb.p_ref if pb.load_control else None)
        if nearly_full_contact(full):
            initial = np.maximum(full, 0.0)
    if initial is None and symmetric_start:
        sym = solve_symmetric()
        initial, matvecs = sym.pressure, sym.matvecs
    if initial is None and isinstance(op, OwnStart):
        # operators without an exact full-contact inverse supply their own first iterate
        initial = op.initial_pressure(pb.ht, mean_pressure=pb.p_ref if pb.load_control else None, approach=pb.approach)
    if initial is None:
        return _full_contact_start(op, pb), matvecs, False
    return np.maximum(np.asarray(initial, dtype=float), 0.0), matvecs, True


def first_iterate(op, pb, *, initial, initial_approach, symmetric_start, solve_symmetric):
    """``(pressure, contact set, products)`` to start the Newton iteration from.

    ``solve_symmetric()`` solves the symmetric part's problem (used when ``symmetric_start``
    and no better start is known); ``initial_approach`` (m), given with ``initial``, chooses
    the first set from the iterate's gap (one product) instead of ``p > 0``.
    """
    p, matvecs, given = _start_pressure(op, pb, initial, symmetric_start, solve_symmetric)
    if not np.any(p > 0):
        p = np.where(pb.ht == 0, pb.p_ref, 0.0)
    contact = p > 0
    if initial_approach is not None and given:
        g0 = op.displacement(p) - pb.ht - (initial_approach if pb.load_control else pb.approach)
        matvecs += 1
        guess = np.greater(p, pb.c * g0)  # p - c g0 > 0
        if guess.any():
            contact = guess
    return p, contact, matvecs
