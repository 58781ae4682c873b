"""Unilateral frictionless contact of a rigid indenter: the complementarity solver.

Problem. Heights ``h`` (m) point into the half-space. With ``A`` the surface response
operator (zero-mean displacement per pressure, m/Pa; its symmetric part positive definite,
which includes the non-symmetric steady-sliding operator), find the pressure ``p`` (Pa) and
the rigid approach ``delta`` (m) with ``mean(p) = p_mean`` (load control) or ``delta`` given:

    g = A p - (h - max(h) + delta) >= 0,   p >= 0,   p g = 0.

Algorithm. Primal–dual active set, i.e. semismooth Newton on ``min(p, c g) = 0`` with ``c``
the stiffness of one grid cell [1]: each step solves the linear problem on the contact set
``C = {p - c g > 0}`` (:mod:`bem.contact.inner`) by CG when ``A`` is symmetric, GMRES
otherwise [2]; non-symmetric problems are damped by a line search on ``||min(p, c g)||``,
which costs no product (:mod:`bem.contact.newton`).

- Inexact Newton [3]: inner solves stop at a share ``eta`` of their right-hand side while
  the set changes, tightly once it has settled; ``eta`` tightens when a step on a nearly
  settled set is damped, when the residual stalls, and for good once the set stops
  converging; it starts smaller on symmetric problems started from a coarser grid.
- Preconditioners: ``R A^-1 R^T`` (full-contact inverse restricted to ``C``) on large grids;
  for strongly non-symmetric 2-D operators :mod:`bem.contact.line_preconditioner`.
- Nested iteration [4]: large grids start from the grid with half the points per axis,
  which takes any warm start (kept where nearer the answer, :mod:`bem.contact.start`).
- Retry (:func:`solve_contact`): a fast attempt, then one whose inner tolerances only
  tighten; strongly non-symmetric 2-D operators first try the line preconditioner.
Every tunable is a field of :class:`ContactOptions`, with what it trades and why.

Convergence test, stated exactly: success when ``r = max_i |min(p_i / p_ref, g_i / h_ref)|
<= rtol`` (``r = 0`` iff the contact conditions hold), with ``p_ref`` the mean pressure and
``h_ref = gap_scale a0 p_ref``, the displacement of ``gap_scale`` cells under it, held between
``gap_floor_share`` of the peak-to-valley height and that height. A gap error ``e`` moves the
pressure by about ``e / a0``, so this scale bounds the pressure error: the relative L2 error
is at most ``10 rtol`` (``tests/bem/test_rtol_meaning.py``). Inner solves stop a decade lower.
Under load control the load balance holds to round-off. A solve that fails raises
:class:`bem.errors.ConvergenceError`.

[1] Hintermüller, Ito & Kunisch, SIAM J. Optim. 13 (2002) 865, doi:10.1137/S1052623401383558.
[2] Saad & Schultz, SIAM J. Sci. Stat. Comput. 7 (1986) 856, doi:10.1137/0907058.
[3] Eisenstat & Walker, SIAM J. Sci. Comput. 17 (1996) 16, doi:10.1137/0917003.
[4] Hackbusch, Multi-Grid Methods and Applications, Springer (1985), ch. 5.
"""

import logging
import math
from dataclasses import replace

import numpy as np
from threadpoolctl import threadpool_limits

from ..errors import ConvergenceError, InputError
from .inner import max_phase
from .newton import Attempt, ContactSolution, attempt_solve, complementarity_residual
from .options import ContactOptions
from .start import coarse_start, prolong, restrict

__all__ = ["ContactOptions", "ContactSolution", "complementarity_residual", "solve_contact"]

log = logging.getLogger(__name__)
DEFAULT_OPTIONS = ContactOptions()


def solve_contact(
    op,
    heights,
    *,
    mean_pressure=None,
    approach=None,
    rtol=1e-8,
    maxiter=400,
    initial=None,
    raise_on_failure=True,
    options=DEFAULT_OPTIONS,
):
    """Solve the contact problem for operator ``op`` (see the module docstring).

    Parameters
    ----------
    op : bem.halfspace.periodic.PeriodicHalfSpace or compatible
        Provides ``displacement(p)``, ``self_influence()``, ``is_symmetric``,
        ``symmetric_part()``, and either ``pressure_from_displacement(u)`` (exact full-contact
        inverse) or ``initial_pressure(ht, mean_pressure=, approach=)``; optionally
        ``max_phase()`` instead of a Fourier ``symbol``, ``coarsened()``,
        ``single_precision()`` and ``factors_along_x``.
    heights : ndarray
        Indenter heights (m), positive toward the half-space.
    mean_pressure : float, optional
        Load control: mean pressure over the cell (Pa) = load / area.
    approach : float, optional
        Displacement control: rigid approach ``delta`` (m) from first touch.
    rtol : float
        Tolerance on the complementarity residual (module docstring).
    maxiter : int
        Maximum number of active-set (Newton) iterations, over all attempts.
    initial : ndarray, optional
        Warm start pressure (Pa), e.g. the solution at a neighbouring speed.
    raise_on_failure : bool
        Raise :class:`bem.errors.ConvergenceError` if the tolerance is not reached;
        otherwise return the solution with ``success=False``.
    options : ContactOptions
        The solver's tunables.

    Returns
    -------
    ContactSolution
        ``matvecs`` counts operator products (one FFT pair each, preconditioner
        applications included), coarser grids' at their share of grid points.
    """
    if (mean_pressure is None) == (approach is None):
        raise InputError(f"give exactly one of mean_pressure and approach, got {mean_pressure!r} and {approach!r}")
    if not isinstance(options, ContactOptions):
        raise InputError(f"options must be a bem.contact.ContactOptions, got {type(options).__name__}")
    problem = {"mean_pressure": mean_pressure, "approach": approach, "rtol": rtol, "options": options}
    # BLAS is single-threaded: its calls here are small (GMRES's Hessenberg, the line
    # preconditioner's batches, which run on the FFT's cores themselves)
    with threadpool_limits(limits=1, user_api="blas"):
        coarse_matvecs, initial_approach = 0.0, None
        if options.coarsen and (initial is None or options.coarsen_warm):
            warm = None if initial is None else np.asarray(initial, dtype=float)

            def solve_coarse(coarse_op, coarse_heights):
                return solve_contact(
                    coarse_op,
                    coarse_heights,
                    mean_pressure=mean_pressure,
                    approach=approach,
                    rtol=max(rtol, options.coarse_rtol),
                    maxiter=maxiter,
                    initial=None if warm is None else restrict(warm),
                    raise_on_failure=False,
                    options=options,
                )

            coarse, coarse_matvecs, coarse_approach = coarse_start(op, heights, solve_coarse, options.coarsen_min_size)
            if coarse is not None and (warm is None or _set_changes(warm, coarse) > _interpolation_changes(warm)):
                initial, initial_approach = coarse, coarse_approach
        sol = _retry_policy(op, heights, maxiter, dict(problem, initial=initial, initial_approach=initial_approach))
    if coarse_matvecs:
        sol = replace(
            sol,
            matvecs=sol.matvecs + int(np.ceil(coarse_matvecs)),
            message=sol.message[:-1] + f" on this grid, plus {coarse_matvecs:.1f} on "
            "coarser grids counted at their share of points)",
        )
    if not sol.success and raise_on_failure:
        raise ConvergenceError(sol.message, sol)
    return sol


def _set_changes(warm, coarse):
    """Contact points (fine-grid count) where the warm start's set differs from the new coarse solution's."""
    return 2**warm.ndim * np.count_nonzero(restrict(warm > 0) != restrict(coarse > 0))


def _interpolation_changes(warm):
    """Contact points the round trip through the coarse grid moves: what the coarse start costs the set."""
    return np.count_nonzero((prolong(restrict(warm)) > 0) != (warm > 0))


def _retry_policy(op, heights, maxiter, problem):
    """The fast attempt, then if needed the careful one.

    Strongly non-symmetric operators go straight to the careful attempt (inner tolerances
    that only tighten); on 2-D periodic grids they first try the line preconditioner, with
    steps guarded by the max-norm residual, and give up on it once its residual stalls or
    its share of ``maxiter`` is spent. Others try the fast attempt (inner tolerances relaxed
    again after full steps) for ``options.fast_share`` of ``maxiter``."""
    o = problem["options"]
    careful = max_phase(op) > o.strong_phase
    if careful and o.lines and o.precondition is None and getattr(op, "factors_along_x", False):
        lines = Attempt(
            maxiter=max(1, int(o.lines_maxiter_share * maxiter)),
            inner_eta=o.lines_eta,
            relax_inner=False,
            precondition="lines",
            residual_stall=o.residual_stall,
            guard=True,
        )
        first = attempt_solve(op, heights, attempt=lines, **problem)
        if first.success or maxiter < 2:
            return first
        log.info("retrying without the line preconditioner: %s", first.message)
        second = Attempt(
            maxiter=max(1, maxiter - first.iterations), inner_eta=o.inner_eta, relax_inner=False, guard=True
        )
        return _after(first, attempt_solve(op, heights, attempt=second, **problem))
    fast = Attempt(
        maxiter=maxiter if careful else math.ceil(o.fast_share * maxiter),
        inner_eta=o.inner_eta,
        relax_inner=not careful,
    )
    first = attempt_solve(op, heights, attempt=fast, **problem)
    if first.success or maxiter < 2 or careful:
        return first
    log.info("retrying with monotone inner tolerances: %s", first.message)
    second = Attempt(maxiter=maxiter - first.iterations, inner_eta=o.inner_eta, relax_inner=False)
    return _after(first, attempt_solve(op, heights, attempt=second, **problem))


def _after(first, second):
    """The second attempt's solution, with the first attempt's work added to its counts."""
    return replace(
        second,
        matvecs=first.matvecs + second.matvecs,
        iterations=first.iterations + second.iterations,
        message=second.message.replace(
            f"active-set iterations ({second.matvecs} operator products)",
            f"active-set iterations after a first attempt of {first.iterations} "
            f"({first.matvecs + second.matvecs} operator products in all)",
        ),
    )
