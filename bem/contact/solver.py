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
  the set changes, tightly once it has settled; ``eta`` tightens when a step is damped.
- Preconditioners: ``R A^-1 R^T`` (full-contact inverse restricted to ``C``) on large grids;
  for strongly non-symmetric 2-D operators :mod:`bem.contact.line_preconditioner`.
- Nested iteration [4]: grids start from the grid with half the points per axis,
  which takes any warm start (kept where nearer the answer, :mod:`bem.contact.start`).
- Retry (:func:`solve_contact`): strongly non-symmetric 2-D operators first try the line
  preconditioner, then an unpreconditioned attempt; others make one attempt.
What a user may set is a field of :class:`ContactOptions`; every other constant is named in
the module that uses it, with its reason (``docs/theory.md`` §4.2 lists them all).

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
from dataclasses import replace

import numpy as np

from ..errors import ConvergenceError, InputError
from ..parallel import blas_limit
from .newton import Attempt, ContactSolution, attempt_solve, complementarity_residual
from .operator import LineFactors, strongly_nonsymmetric
from .options import MAXITER, RTOL, ContactOptions
from .start import coarse_start, nearer, start_rtol, wants_coarse_start

__all__ = ["ContactOptions", "ContactSolution", "complementarity_residual", "solve_contact"]

log = logging.getLogger(__name__)
DEFAULT_OPTIONS = ContactOptions()

LINES_MAXITER_SHARE = 0.5
"""Share of ``maxiter`` the line-preconditioned attempt may take, leaving the rest to the
unpreconditioned one: it ends a line attempt that creeps. Ablation row "lines maxiter share": no
effect on the case set; it keeps steps for the second attempt (``tests/bem/test_robustness.py``)."""
LINES_RESIDUAL_STALL = 30
"""Steps without a new low in the residual that end the line-preconditioned attempt (it cycles
on some near-full contacts and creeps on stiff ones). Measured: no effect on the quick ablation
set; without it the path-sensitive 32² case takes 1.075x the products, and the 128² cell at
E_inf/E0 = 1e4 of ``tests/bem/test_robustness.py`` spends 200 line steps instead of 44 before the
unpreconditioned attempt (``docs/theory.md`` §4.2)."""


def solve_contact(
    op,
    heights,
    *,
    mean_pressure=None,
    approach=None,
    rtol=RTOL,
    maxiter=MAXITER,
    initial=None,
    raise_on_failure=True,
    options=DEFAULT_OPTIONS,
):
    """Solve the contact problem for operator ``op`` (see the module docstring).

    Parameters
    ----------
    op : bem.contact.operator.ResponseOperator
        The response operator (:mod:`bem.halfspace`); its optional capabilities
        (:mod:`bem.contact.operator`) choose the start and the preconditioner.
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
        What a user may set (:class:`ContactOptions`).

    Returns
    -------
    ContactSolution
        ``matvecs`` counts operator products (one FFT pair each, preconditioner
        applications included), coarser grids' at their share of grid points. A solve
        stopped at its round-off floor gives the residual it attained (``attainable``).
    """
    if (mean_pressure is None) == (approach is None):
        raise InputError(f"give exactly one of mean_pressure and approach, got {mean_pressure!r} and {approach!r}")
    if not isinstance(options, ContactOptions):
        raise InputError(f"options must be a bem.contact.ContactOptions, got {type(options).__name__}")
    problem = {"mean_pressure": mean_pressure, "approach": approach, "rtol": rtol, "options": options}
    with blas_limit():  # small dense calls (bem.parallel)
        coarse_matvecs, initial_approach = 0.0, None
        if wants_coarse_start(op, heights, mean_pressure, options):
            coarse, coarse_matvecs, coarse_approach = _coarse(op, heights, maxiter, initial, problem)
            if coarse is not None and (initial is None or not nearer(op, np.asarray(initial, dtype=float), coarse)):
                initial, initial_approach = coarse, coarse_approach
        sol = _retry_policy(op, heights, maxiter, dict(problem, initial=initial, initial_approach=initial_approach))
    if coarse_matvecs:
        sol = replace(
            sol,
            matvecs=sol.matvecs + int(np.ceil(coarse_matvecs)),
            message=sol.message.replace(
                " operator products)",
                f" operator products on this grid, plus {coarse_matvecs:.1f} on coarser grids counted at their "
                "share of points)",
                1,
            ),
        )
    if not sol.success and raise_on_failure:
        raise ConvergenceError(sol.message, sol)
    return sol


def _coarse(op, heights, maxiter, initial, problem):
    """:func:`~bem.contact.start.coarse_start`: the same problem on the coarser grid, from the warm
    start sampled there, to the start's tolerance."""
    warm = None if initial is None else op.restrict(np.asarray(initial, dtype=float))

    def solve_coarse(coarse_op, coarse_heights):
        return solve_contact(
            coarse_op,
            coarse_heights,
            mean_pressure=problem["mean_pressure"],
            approach=problem["approach"],
            rtol=start_rtol(problem["rtol"]),
            maxiter=maxiter,
            initial=warm,
            raise_on_failure=False,
            options=problem["options"],
        )

    return coarse_start(op, heights, solve_coarse)


def _retry_policy(op, heights, maxiter, problem):
    """One attempt; strongly non-symmetric operators on 2-D periodic grids first try the line
    preconditioner, and give up on it once its residual stalls or its share of ``maxiter`` is
    spent."""
    o = problem["options"]
    lines = o.precondition is None and o.line_budget > 0 and isinstance(op, LineFactors) and op.factors_along_x
    if lines and strongly_nonsymmetric(op):
        lines = Attempt(
            maxiter=max(1, int(LINES_MAXITER_SHARE * maxiter)),
            eta=o.inner_eta,
            precondition="lines",
            own_forcing=True,
            residual_stall=LINES_RESIDUAL_STALL,
        )
        first = attempt_solve(op, heights, attempt=lines, **problem)
        if first.success or first.attainable is not None or maxiter < 2:
            return first
        log.info("retrying without the line preconditioner: %s", first.message)
        second = Attempt(maxiter=max(1, maxiter - first.iterations), eta=o.inner_eta)
        return _after(first, attempt_solve(op, heights, attempt=second, **problem))
    return attempt_solve(op, heights, attempt=Attempt(maxiter=maxiter, eta=o.inner_eta), **problem)


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
