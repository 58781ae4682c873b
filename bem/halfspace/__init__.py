"""Response operators of a viscoelastic half-space in steady sliding: pressure in, displacement out.

Conventions (docs/theory.md §3, SI units) are stated once in :mod:`.periodic`: the indenter
moves with speed ``v`` in ``+x``, pressure is compressive positive, displacement is positive into
the solid. Workflow:

1. a periodic cell (:class:`PeriodicHalfSpace`, FFT symbol) or an isolated domain
   (:class:`IsolatedHalfSpace`, zero-padded FFT of the influence coefficients of
   :mod:`.influence`);
2. sliding along another direction than ``+x``: the operators of :mod:`.directed`;
3. the operators of the last few problems are kept by :mod:`.cache` and reused;
4. the contact solver (:mod:`bem.contact`) uses any of them through ``displacement(p)`` and
   the few methods listed in :func:`bem.contact.solve_contact`.
"""

from .directed import DirectedIsolatedHalfSpace, DirectedPeriodicHalfSpace
from .isolated import IsolatedHalfSpace
from .periodic import PeriodicHalfSpace

__all__ = ["DirectedIsolatedHalfSpace", "DirectedPeriodicHalfSpace", "IsolatedHalfSpace", "PeriodicHalfSpace"]
