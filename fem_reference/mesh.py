"""Graded tensor-product meshes of rectangles standing for a half-space.

Every element is an axis-aligned rectangle (``MeshQuad.init_tensor``), so the rows of
quadrature points are horizontal lines: streamlines of the steady rolling flow. The
mesh is uniform (element size ``h``) in a core box around the contact and grows
geometrically by ``ratio`` per element out to the truncated boundaries, so the number of
elements grows only with ``log(L / h)``.

Geometry: ``x`` horizontal (flow axis), ``y`` vertical with the body in ``y <= 0`` and its
free top surface at ``y = 0``; for axisymmetric meshes ``x`` is the radius ``r >= 0``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["graded_axis", "HalfSpaceMesh", "half_space_mesh", "half_space_boundaries"]


def _grow(start, stop, h, ratio):
    """Points from ``start`` (excluded) to ``stop`` (included), first step ``h * ratio``."""
    pts = []
    pos, step, sign = start, h, math.copysign(1.0, stop - start)
    while True:
        step *= ratio
        nxt = pos + sign * step
        if sign * (stop - nxt) <= 0.5 * step:  # close enough: land on stop exactly
            pts.append(stop)
            break
        pts.append(nxt)
        pos = nxt
    return pts


def graded_axis(core_lo, core_hi, h, lo, hi, ratio):
    """Sorted coordinates: uniform (about ``h``) on ``[core_lo, core_hi]``, geometric outside.

    ``lo <= core_lo < core_hi <= hi``; the core spacing is adjusted to divide the core
    exactly; outside it the spacing grows by ``ratio`` per element until ``lo`` / ``hi``.
    """
    n = max(1, int(math.ceil((core_hi - core_lo) / h - 1e-9)))
    core = np.linspace(core_lo, core_hi, n + 1)
    hc = (core_hi - core_lo) / n
    left = _grow(core_lo, lo, hc, ratio)[::-1] if lo < core_lo else []
    right = _grow(core_hi, hi, hc, ratio) if hi > core_hi else []
    return np.concatenate([np.array(left), core, np.array(right)])


def half_space_boundaries(x, y):
    """``MeshQuad.init_tensor(x, y)`` with boundaries ``left``, ``right``, ``bottom``, ``top``
    (the top at ``y = 0``)."""
    from skfem import MeshQuad

    mesh = MeshQuad.init_tensor(x, y)
    x0, x1, y0 = x[0], x[-1], y[0]
    tol = 1e-9 * float(np.min(np.diff(x)).clip(max=np.min(np.diff(y))))

    def near(a, b):
        return np.abs(a - b) <= tol + 1e-12 * abs(b)

    return mesh.with_boundaries(
        {
            "left": lambda p: near(p[0], x0),
            "right": lambda p: near(p[0], x1),
            "bottom": lambda p: near(p[1], y0),
            "top": lambda p: near(p[1], 0.0),
        }
    )


@dataclass(frozen=True)
class HalfSpaceMesh:
    """A graded rectangle mesh and the numbers that define it (all lengths in m).

    Attributes
    ----------
    mesh : skfem.MeshQuad
        The mesh, with boundaries ``left``, ``right``, ``bottom``, ``top``.
    x, y : ndarray
        Element edge coordinates along ``x`` and ``y``.
    element_size : float
        Element size ``h`` in the core box.
    width : tuple of float
        ``(x_min, x_max)`` of the domain.
    depth : float
        Depth ``H`` of the domain (the bottom is at ``y = -H``).
    """

    mesh: object
    x: np.ndarray
    y: np.ndarray
    element_size: float
    width: tuple
    depth: float

    @property
    def n_elements(self):
        return (self.x.size - 1) * (self.y.size - 1)

    @property
    def smallest_element(self):
        """Smallest element width along the flow (m)."""
        return float(np.min(np.diff(self.x)))


def half_space_mesh(core, h, *, x_range, depth, core_depth, ratio=1.2):
    """Build the graded mesh.

    Parameters
    ----------
    core : tuple of float
        ``(x_lo, x_hi)`` of the uniform core (m).
    h : float
        Core element size (m).
    x_range : tuple of float
        ``(x_min, x_max)`` of the domain (m); ``x_min = 0`` for an axisymmetric mesh.
    depth : float
        Depth ``H`` (m).
    core_depth : float
        Depth of the uniform core below the surface (m).
    ratio : float
        Geometric growth factor outside the core.
    """
    x = graded_axis(core[0], core[1], h, x_range[0], x_range[1], ratio)
    y = graded_axis(-core_depth, 0.0, h, -depth, 0.0, ratio)
    mesh = half_space_boundaries(x, y)
    hc = (core[1] - core[0]) / max(1, int(math.ceil((core[1] - core[0]) / h - 1e-9)))
    return HalfSpaceMesh(mesh, x, y, float(hc), (float(x[0]), float(x[-1])), float(-y[0]))
