"""How accurately each Newton point is computed: the forcing term of the inexact Newton steps,
and the test of whether the contact set is still converging (pure functions).

Inexact Newton (Eisenstat & Walker, SIAM J. Sci. Comput. 17 (1996) 16,
doi:10.1137/0917003): while the set changes, a Newton point only has to move the set, and its
inner solve stops at the share ``eta`` of its right-hand side; once the set has settled, the
inner solves are tight (a decade below the outer test). Two signals tighten ``eta``:

- a damped step on a nearly settled set (:func:`settled`): the Newton point was too loose to be
  trusted as a step, so the next is a decade tighter;
- a set that stops converging (:func:`set_converging`): loose Newton points flip points at the
  margin of the contact back and forth (broad-band roughness has many), so ``eta`` drops a
  decade for the rest of the attempt.

Otherwise the fast attempt loosens ``eta`` again, up to its ceiling.
"""

from dataclasses import dataclass, replace

__all__ = [
    "ETA_MIN",
    "Forcing",
    "OSCILLATION_DECREASE",
    "RELAX",
    "SETTLING_CHANGES",
    "SETTLING_SHARE",
    "TIGHTEN",
    "next_forcing",
    "set_converging",
    "settled",
]

OSCILLATION_DECREASE = 0.7
"""A converging set at least halves its changes per step; one whose changes fall by less than
this factor while growing, or mostly undoing the last step's, has stopped converging."""
SETTLING_CHANGES = 100
"""Set changes a settling set may make without counting as oscillating or diverging: a few
points at the margin of the contact flip while the Newton points tighten."""
SETTLING_SHARE = 0.01
"""... or this share of the contact set, on large contacts."""
TIGHTEN = 0.1
"""Factor on ``eta`` when it tightens: a decade a step, the Krylov solves' natural unit."""
RELAX = 3.0
"""Factor on ``eta`` after a full step of the fast attempt: loose, cheap solves again once on track."""
ETA_MIN = 1e-4
"""Tightest ``eta`` the rules impose: below it an inexact Newton point is as good as an exact one."""


def set_converging(changed, before, undone, *, decrease, settling):
    """Whether a contact set is still converging after a step that changed ``changed`` points,
    ``undone`` of them reversing the last step's ``before`` changes.

    Not converging: more than ``settling`` changes, more than ``decrease`` times the last step's,
    and either more than the last step's (the set diverges) or mostly undoing it (it
    oscillates). A first step (``before`` 0) and a settling set always pass. The solver passes
    :data:`OSCILLATION_DECREASE` and :data:`SETTLING_CHANGES`.
    """
    slow = before > 0 and changed > decrease * before and changed > settling
    return not (slow and (changed > before or 2 * undone > changed))


def settled(changed, contact_size, *, changes, share):
    """Whether a step's ``changed`` points on a set of ``contact_size`` points leave it nearly
    settled: at most ``changes``, or at most the share ``share`` of the set (the solver passes
    :data:`SETTLING_CHANGES` and :data:`SETTLING_SHARE`)."""
    return changed <= max(changes, share * contact_size)


@dataclass(frozen=True)
class Forcing:
    """The forcing term ``eta`` of the next Newton point and its ceiling ``top`` (which drops once
    the set stops converging); ``start`` is the attempt's own value."""

    eta: float
    top: float
    start: float

    @classmethod
    def at(cls, eta):
        return cls(eta, eta, eta)


def next_forcing(forcing, *, damped, settled, converging, relax, oscillation=True, damping=True):
    """The forcing after a step (module docstring): ``damped`` the step was shorter than the
    Newton point; ``settled`` the set nearly settled (:func:`settled`); ``converging`` the set
    still converging (:func:`set_converging`). Which rules apply is the attempt's: ``oscillation``
    (the ceiling drops once the set stops converging), ``damping`` (a damped step on a settled set
    tightens) and ``relax`` (otherwise ``eta`` loosens toward the ceiling: the fast attempt)."""
    if oscillation and not converging and forcing.top == forcing.start:
        top = max(TIGHTEN * forcing.top, ETA_MIN)
        return replace(forcing, eta=top, top=top)
    if damping and damped and settled:
        return replace(forcing, eta=max(TIGHTEN * forcing.eta, ETA_MIN))
    if relax:
        return replace(forcing, eta=min(forcing.top, RELAX * forcing.eta))
    return forcing
