"""How accurately each Newton point is computed: the forcing term of the inexact Newton steps
(pure functions).

Inexact Newton (Eisenstat & Walker, SIAM J. Sci. Comput. 17 (1996) 16,
doi:10.1137/0917003): while the set changes, a Newton point only has to move the set, and its
inner solve stops at the share ``eta`` of its right-hand side; once the set has settled, the
inner solves are tight (at the outer test's gap tolerance). A damped step on a nearly settled set
(:func:`settled`) tightens ``eta`` a decade for the rest of the attempt: the Newton point was too
loose to be trusted as a step. While many points still change, the damping is the moving set's
(contact edges that creep a cell per step), not the inner solve's, and tight solves on a set that is
still wrong are wasted.
"""

__all__ = ["ETA_MIN", "SETTLING_CHANGES", "TIGHTEN", "next_eta", "settled"]

SETTLING_CHANGES = 100
"""Set changes a nearly settled set may make in a step: a few points at the margin of the contact
flip while the Newton points tighten, where a moving set changes whole edges. Measured on the 128²
cell at E_inf/E0 = 1e4, xi = 1 of ``tests/bem/test_robustness.py`` (slow), whose unpreconditioned
attempt creeps: with the bound, 93 active-set steps and 468,233 products; without it (any damped
step tightens) ``eta`` tightens from the first damped step, while 1632 points change, and nearly
every later step is a GMRES solve of the system's full length (16,386 products): 125 steps and
1,294,961 products. Ablation row "damped-settled tighten" (the bound off): the same products on
the quick set (20,480), the same cases and errors; what it saves is on attempts that creep. The
value is not tuned beyond lying between the two: margin flips of a few points, and on that cell
set moves of 122 to 2339 points a step over its first 26 steps."""

TIGHTEN = 0.1
"""Factor on ``eta`` when a damped step tightens it: a decade a step. Ablation row "damped
tighten" (the rule off): 1.17x the products and two cases lost; row "decade tightening" (to
:data:`ETA_MIN` at once instead): 1.04x the products, 1.06x the geometric mean of the cases."""
ETA_MIN = 1e-4
"""Tightest ``eta`` the rule imposes: below it an inexact Newton point is as good as an exact one.
Ablation row "eta floor": off costs 1.30x the products and loses a case. Inner solves that stop
at least this share of their right-hand side use float32 products (:mod:`bem.contact.inner`;
from 1e-3 instead: 1.003x the products, no case changed)."""


def settled(changed, *, changes=None):
    """Whether a step that changed ``changed`` points leaves the set nearly settled: at most
    ``changes`` (by default :data:`SETTLING_CHANGES`)."""
    return changed <= (SETTLING_CHANGES if changes is None else changes)


def next_eta(eta, *, damped, settled):
    """The forcing term after a step (module docstring): a decade tighter (not below
    :data:`ETA_MIN`) when the step was ``damped`` (shorter than the Newton point) on a nearly
    ``settled`` set, else unchanged."""
    return max(TIGHTEN * eta, ETA_MIN) if damped and settled else eta
