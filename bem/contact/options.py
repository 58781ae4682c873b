"""What a user of the contact solver may set (:class:`ContactOptions`), and the solve defaults.

The solve defaults :data:`RTOL` and :data:`MAXITER` are defined here once: :func:`bem.solve`,
:func:`bem.friction_curve`, the scene schema and the documentation read them. Every other
constant of the solver is named in the module that uses it, with its reason.
"""

import math
from dataclasses import dataclass, fields

import numpy as np

from ..errors import InputError

__all__ = ["ContactOptions", "MAXITER", "RTOL"]

RTOL = 1e-8
"""Default tolerance on the complementarity residual of every solve (:func:`bem.solve`,
:func:`bem.friction_curve`, a scene's ``[solver] rtol``): it bounds the relative L2 error of the
pressure by ``10 rtol`` (:mod:`bem.contact.solver`), far below the discretisation error of any
grid a solve can afford."""
MAXITER = 400
"""Default cap on the active-set iterations of one solve: a solve that reaches it has stalled
far beyond what any tested problem needs, and says so."""

# (low, high, low inclusive) of the numeric fields
_RANGES = {"inner_eta": (0.0, 1.0, False), "restart_budget": (1, math.inf, True), "line_budget": (0, math.inf, True)}
_INTEGERS = {"restart_budget", "line_budget"}


@dataclass(frozen=True)
class ContactOptions:
    """What a user of :func:`bem.contact.solve_contact` (and :func:`bem.solve`'s
    ``contact_options``) may set; validated on creation (``InputError``). Variants with
    :func:`dataclasses.replace`."""

    inner_eta: float = 0.1
    """Inexact Newton's forcing term while the contact set changes: looser is cheaper per step and
    may take more steps; tighter the reverse. The default halves the products of exact steps."""
    precondition: bool | None = None
    """Preconditioner from the operator's full-contact inverse restricted to the set: ``None``
    chooses (isolated domains always, periodic cells from 2**17 points; strongly non-symmetric
    periodic cells the line preconditioner first on 2-D cells, else none); ``True`` or ``False`` forces it on or off (no
    line preconditioner). An extra FFT pair per inner iteration against fewer iterations."""
    line_budget: int = 2**30
    """Bytes the line preconditioner's inverses may take (1 GiB); above it the attempt runs
    unpreconditioned, and 0 never tries it: memory against products."""
    restart_budget: int = 2**26
    """Doubles the GMRES basis may take (512 MiB): longer restarts converge in fewer products on
    strongly non-symmetric systems, for memory and orthogonalisation time."""
    single_precision: bool = True
    """Loose inner solves' products in float32: half the memory traffic; the Newton points are
    recomputed in float64, so the answer keeps full accuracy."""
    coarsen: bool = True
    """Start from the same problem on the grid with half the points per axis (nested iteration),
    itself started from the warm start if one is given: a few cheap coarse products against many
    fine Newton steps."""
    symmetric_start: bool = True
    """Start strongly non-symmetric (and non-symmetric 1-D) problems from their symmetric part's
    contact: a robust CG solve places the set, where plain steps from full contact cycle."""

    def __post_init__(self):
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in _RANGES:
                _check_number(f.name, value, *_RANGES[f.name])
            elif f.name == "precondition":
                if value is not None and not isinstance(value, bool):
                    raise InputError(f"options.precondition must be None, True or False, got {value!r}")
            elif not isinstance(value, bool):
                raise InputError(f"options.{f.name} must be True or False, got {value!r}")


def _check_number(name, value, low, high, closed):
    integer = name in _INTEGERS
    kind = "an integer" if integer else "a real number"
    ok = isinstance(value, (int, np.integer) if integer else (int, float, np.integer, np.floating))
    ok = ok and not isinstance(value, bool) and math.isfinite(value)
    ok = ok and (low <= value if closed else low < value) and value <= high
    if not ok:
        bracket = "[" if closed else "("
        raise InputError(f"options.{name} must be {kind} in {bracket}{low}, {high}], got {value!r}")
