"""Unilateral frictionless contact of a rigid indenter on a half-space: the complementarity solver.

The problem and the algorithm are stated in :mod:`.solver`; every tunable is a field of
:class:`ContactOptions`. Workflow:

1. the caller builds a response operator (:mod:`bem.halfspace`) and gives heights and a load
   (or an approach) to :func:`solve_contact` (:mod:`.solver`), which also owns the retries;
2. a first iterate is chosen (:mod:`.start`: the same problem on a coarser grid, a warm start,
   or the symmetric part's solution);
3. each attempt is an active-set (semismooth Newton) iteration (:mod:`.newton`) whose Newton
   points are linear solves on the contact set (:mod:`.inner`) by CG or GMRES (:mod:`.krylov`),
   preconditioned by the full-contact inverse or, for strongly non-symmetric 2-D operators, by
   :mod:`.line_preconditioner`;
4. the answer is a :class:`ContactSolution` with its complementarity residual, or a
   :class:`~bem.errors.ConvergenceError`.
"""

from .newton import ContactSolution, complementarity_residual
from .options import ContactOptions
from .solver import solve_contact

__all__ = ["ContactOptions", "ContactSolution", "complementarity_residual", "solve_contact"]
