"""The mesh of creep indentation: as fine relative to the contact wherever its edge can be.

Under a held load the contact radius grows from the glassy Hertz radius ``a_inf`` at ``t = 0+``
to the relaxed ``a0 = a_inf (E_inf/E0)^(1/3)``. The contact radius is read at the edge, and the
edge's error is a share of the element there, so the element size at radius ``r`` is

    h(r) = max(r, a_inf) / resolution           for r <= band * a0,

uniform over the glassy contact and growing geometrically, by ``1 + 1/resolution`` per element,
over the whole range the edge sweeps: every contact radius between ``a_inf`` and ``a0`` sees
``resolution`` elements per radius, the same relative mesh. Beyond ``band * a0`` the elements grow
by ``grading`` per element out to the block's side. The depth axis is graded the same way from the
surface, so that the elements under each contact edge are as deep as they are wide there. Per
axis the count is about ``resolution (1 + ln(band a0 / a_inf)) + log(L / a0) / log(grading)``:
it grows with the logarithm of the modulus ratio, where a uniform core of ``a_inf / resolution``
over ``band * a0`` grows like its cube root.
"""

from __future__ import annotations

import math

import numpy as np

from .mesh import HalfSpaceMesh, half_space_boundaries

__all__ = ["creep_axis", "indentation_mesh"]


def _geometric(start, stop, first, ratio):
    """Points after ``start`` up to ``stop`` (included): steps growing by ``ratio`` from about
    ``first``, all scaled by one factor so that the last lands on ``stop``."""
    n = max(1, round(math.log(1.0 + (stop - start) * (ratio - 1.0) / first) / math.log(ratio)))
    steps = ratio ** np.arange(n)
    return start + np.cumsum(steps) * (stop - start) / steps.sum()


def creep_axis(a_glassy, sweep_end, resolution, length, grading, phase=0.0):
    """Coordinates (m) from 0 to ``length``: ``resolution`` uniform elements over ``[0, a_glassy]``,
    elements of ``r / resolution`` over ``[a_glassy, sweep_end]``, then growing by ``grading``.

    Parameters
    ----------
    a_glassy : float
        Glassy contact radius (m), the smallest the contact has.
    sweep_end : float
        End of the range the contact edge can reach (m), ``>= a_glassy``.
    resolution : int
        Elements per local contact radius.
    length : float
        End of the axis (m), ``> sweep_end``.
    grading : float
        Element growth ratio beyond ``sweep_end``, > 1.
    phase : float
        Shift of the nodes in the sweep, in elements: the uniform part ends at ``a_glassy
        rho^phase``, with ``rho`` (about ``1 + 1/resolution``) the sweep's step ratio at phase 0,
        and the sweep keeps that ratio; 0.5 puts the vertices halfway between those of phase 0
        over the whole sweep.
    """
    growth = 1.0 + 1.0 / resolution
    # the nearest whole number of elements of ratio ``growth`` from a_glassy: none where the sweep
    # is shorter than half an element (a nearly elastic solid); every phase keeps phase 0's ratio,
    # so that its nodes stay the same share of a step away from phase 0's through the sweep
    n_sweep = round(math.log(sweep_end / a_glassy) / math.log(growth))
    rho = (sweep_end / a_glassy) ** (1.0 / n_sweep) if n_sweep else growth
    core_end = a_glassy * rho**phase
    core = np.linspace(0.0, core_end, resolution + 1)
    sweep = core_end * rho ** np.arange(1, n_sweep + 1)
    edges = np.concatenate([core, sweep])
    outer = _geometric(edges[-1], length, (edges[-1] - edges[-2]) * grading, grading)
    return np.concatenate([edges, outer])


def indentation_mesh(a_glassy, a_relaxed, resolution, *, band, length, grading, phase=0.0):
    """The axisymmetric block (radius = depth = ``length``, m) for creep indentation, graded as the
    module docstring says (``phase``: see :func:`creep_axis`); ``element_size`` is the glassy
    contact's ``a_glassy / resolution``."""
    x = creep_axis(a_glassy, band * a_relaxed, resolution, length, grading, phase)
    y = -x[::-1]
    return HalfSpaceMesh(half_space_boundaries(x, y), x, y, a_glassy / resolution, (0.0, float(x[-1])), float(length))
