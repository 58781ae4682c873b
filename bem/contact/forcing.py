"""How accurately each Newton point is computed: the forcing term of the inexact Newton steps
(pure functions).

Inexact Newton (Eisenstat & Walker, SIAM J. Sci. Comput. 17 (1996) 16,
doi:10.1137/0917003): while the set changes, a Newton point only has to move the set, and its
inner solve stops at the share ``eta`` of its right-hand side; once the set has settled, the
inner solves are tight (at the outer test's gap tolerance). A damped step on a nearly settled set
(:func:`settled`) tightens ``eta`` a decade for the rest of the attempt: the Newton point was too
loose to be trusted as a step.
"""

__all__ = ["ETA_MIN", "SETTLING_CHANGES", "TIGHTEN", "next_eta", "settled"]

SETTLING_CHANGES = 100
"""Set changes a settling set may make: a few points at the margin of the contact flip while the
Newton points tighten. Ablation row "damped-settled tighten" (the rule it gates): off costs 1.23x
the products and loses two cases; row "settling changes" (10 instead of 100): 0.82x the products,
no case lost, so the value is not tuned beyond keeping the rule."""
TIGHTEN = 0.1
"""Factor on ``eta`` when it tightens: a decade a step, the Krylov solves' natural unit (the step
of the rule of ablation row "damped-settled tighten")."""
ETA_MIN = 1e-4
"""Tightest ``eta`` the rule imposes: below it an inexact Newton point is as good as an exact one.
Ablation row "eta floor": off costs 1.31x the products and loses a case."""


def settled(changed, *, changes=None):
    """Whether a step that changed ``changed`` points leaves the set nearly settled: at most
    ``changes`` (by default :data:`SETTLING_CHANGES`)."""
    return changed <= (SETTLING_CHANGES if changes is None else changes)


def next_eta(eta, *, damped, settled):
    """The forcing term after a step (module docstring): a decade tighter (not below
    :data:`ETA_MIN`) when the step was ``damped`` (shorter than the Newton point) on a ``settled``
    set, else unchanged."""
    return max(TIGHTEN * eta, ETA_MIN) if damped and settled else eta
