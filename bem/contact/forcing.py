"""How accurately each Newton point is computed: the forcing term of the inexact Newton steps
(pure functions).

Inexact Newton (Eisenstat & Walker, SIAM J. Sci. Comput. 17 (1996) 16,
doi:10.1137/0917003): while the set changes, a Newton point only has to move the set, and its
inner solve stops at the share ``eta`` of its right-hand side; once the set has settled, the
inner solves are tight (at the outer test's gap tolerance). A damped step tightens ``eta`` a
decade for the rest of the attempt: the Newton point was too loose to be trusted as a step. A loose
GMRES solve takes at most one restart cycle (:mod:`bem.contact.inner`), so a tighter ``eta`` costs
at most one Krylov basis a step, also while the set still moves.
"""

__all__ = ["ETA_MIN", "TIGHTEN", "next_eta"]

TIGHTEN = 0.1
"""Factor on ``eta`` when a damped step tightens it: a decade a step. Ablation row "damped
tighten" (the rule off): 1.17x the products and two cases lost; row "decade tightening" (to
:data:`ETA_MIN` at once instead): 1.04x the products, 1.06x the geometric mean of the cases."""
ETA_MIN = 1e-4
"""Tightest ``eta`` the rule imposes: below it an inexact Newton point is as good as an exact one.
Ablation row "eta floor": off costs 1.30x the products and loses a case. Inner solves that stop
at least this share of their right-hand side use float32 products (:mod:`bem.contact.inner`;
from 1e-3 instead: 1.003x the products, no case changed)."""


def next_eta(eta, *, damped):
    """The forcing term after a step (module docstring): a decade tighter (not below
    :data:`ETA_MIN`) when the step was ``damped`` (shorter than the Newton point), else
    unchanged."""
    return max(TIGHTEN * eta, ETA_MIN) if damped else eta
