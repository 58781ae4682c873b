"""First iterate of the contact solver.

In order of preference:

1. on large periodic grids with even sides, the same problem solved on the grid with half
   the points per axis (itself warm-started from the caller's warm start, sampled there) and
   interpolated linearly (nested iteration, :func:`coarse_start`); the first contact set is
   then the one a Newton step would pick from that pressure and its gap at the coarse
   approach, ``p - c g > 0`` (interpolation makes the pressure positive around every coarse
   contact point). A warm start is kept instead when, sampled on the coarse grid, its contact
   set differs from the coarse solution's at fewer points than the round trip through the
   coarse grid moves its own set: then it is the nearer of the two (along a friction curve,
   where the contact changes little between neighbouring speeds);
2. a warm start given by the caller (e.g. the solution at a neighbouring speed);
3. for strongly non-symmetric operators (and non-symmetric 1-D ones, where smooth
   indenters on long cells need it), the contact of the operator's symmetric part, a
   robust CG solve stopped once its set cycles, unless under load control the clipped
   full-contact pressure is nearly the answer;
4. the operator's own first iterate (``op.initial_pressure``, isolated half-spaces);
5. the full-contact solution (exact in Fourier space) clipped to ``p >= 0``.
"""

import logging

import numpy as np

log = logging.getLogger(__name__)


def prolong(p):
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


def restrict(p):
    """The values at the points of the grid with half the points per axis (coarse point ``i``
    is fine point ``2i``, as in :func:`prolong`)."""
    return np.ascontiguousarray(p[tuple(slice(0, None, 2) for _ in p.shape)])


def coarse_start(op, heights, solve, min_size):
    """First iterate from the same problem on the grid with half the points per axis.

    ``solve(coarse_op, coarse_heights)`` solves it (itself starting from its own coarser grid,
    down to ``min_size`` points) without raising. Returns ``(pressure or None, products,
    approach or None)``: the coarse products counted at their share of grid points (a 512²
    product as 1/4 of a 1024² one), and the coarse approach (m) measured from this grid's
    first touch.
    """
    coarsened = getattr(op, "coarsened", None)
    if coarsened is None or heights.size < min_size or any(n % 2 for n in heights.shape):
        return None, 0.0, None
    coarse_op = coarsened()
    coarse_heights = heights[tuple(slice(0, None, 2) for _ in heights.shape)]
    coarse = solve(coarse_op, coarse_heights)
    share = coarse.matvecs * coarse_op.size / op.size
    if not coarse.success:
        log.info("coarse start discarded: %s", coarse.message)
        return None, share, None
    # the same rigid position: the approach counts from first touch, on each grid's own maximum
    approach = coarse.approach + float(heights.max() - coarse_heights.max())
    return prolong(coarse.pressure), share, approach


def wants_symmetric_start(op, ht, strongly_nonsymmetric, options):
    """Whether the first iterate comes from the symmetric part's contact (module docstring)."""
    one_d = options.symmetric_start_1d and ht.ndim == 1 and not op.is_symmetric
    return strongly_nonsymmetric or one_d


def _full_contact_start(op, pb):
    """The clipped full-contact pressure, which makes the gap vanish everywhere."""
    if pb.load_control:
        return np.maximum(op.pressure_from_displacement(pb.ht) + pb.p_ref, 0.0)
    return np.where(pb.ht + pb.approach > 0, np.maximum(op.pressure_from_displacement(pb.ht), 0.0), 0.0)


def _start_pressure(op, pb, initial, symmetric_start, solve_symmetric, options):
    """``(pressure, products, given)``: the first iterate, and whether it came from
    somewhere other than the full-contact fallback."""
    matvecs = 0
    if initial is None and pb.load_control and symmetric_start and hasattr(op, "pressure_from_displacement"):
        # full contact is one Fourier division; where it is nearly the answer (tension on a
        # small share of the cell) the symmetric-part start would lose it
        full = op.pressure_from_displacement(pb.ht) + pb.p_ref
        if np.mean(full < 0) < options.near_full_contact:
            initial = np.maximum(full, 0.0)
    if initial is None and symmetric_start:
        sym = solve_symmetric()
        initial, matvecs = sym.pressure, sym.matvecs
    if initial is None and hasattr(op, "initial_pressure"):
        # operators without an exact full-contact inverse supply their own first iterate
        initial = op.initial_pressure(pb.ht, mean_pressure=pb.p_ref if pb.load_control else None, approach=pb.approach)
    if initial is None:
        return _full_contact_start(op, pb), matvecs, False
    return np.maximum(np.asarray(initial, dtype=float), 0.0), matvecs, True


def first_iterate(op, pb, *, initial, initial_approach, symmetric_start, solve_symmetric, options):
    """``(pressure, contact set, products)`` to start the Newton iteration from.

    ``solve_symmetric()`` solves the symmetric part's problem (used when ``symmetric_start``
    and no better start is known); ``initial_approach`` (m), given with ``initial``, chooses
    the first set from the iterate's gap (one product) instead of ``p > 0``.
    """
    p, matvecs, given = _start_pressure(op, pb, initial, symmetric_start, solve_symmetric, options)
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
