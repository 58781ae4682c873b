"""Sliding directions as angles: quarter turns and unit vectors.

Angles are radians from ``+x`` (axis 0) toward ``+y`` (axis 1). A direction within 1e-12 rad
of a multiple of ``pi/2`` is that quarter turn exactly, so that the solvers can take their
exact routes along the grid axes.
"""

import math

__all__ = ["quarter_turns", "unit_vector"]

_TOL = 1e-12  # an angle within this of a multiple of pi/2 (radians) counts as a quarter turn


def quarter_turns(theta):
    """``k`` in ``0..3`` if ``theta`` is ``k pi/2`` (mod ``2 pi``, within 1e-12 rad), else ``None``."""
    r = (theta % (2 * math.pi)) / (math.pi / 2)
    k = round(r)
    return k % 4 if abs(r - k) * (math.pi / 2) < _TOL else None


def unit_vector(theta):
    """``(cos theta, sin theta)``, exactly ``0`` and ``±1`` at quarter turns (``cos(pi/2)`` is
    6e-17 in floating point, and a creep time of 1e9 s would see that component)."""
    k = quarter_turns(theta)
    if k is not None:
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[k]
    return math.cos(theta), math.sin(theta)
