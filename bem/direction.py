"""Sliding in any direction ``d = (cos theta, sin theta)`` in the surface's own frame.

Angles are radians from ``+x`` (axis 0) toward ``+y`` (axis 1); ``theta = 0`` is the
convention of :mod:`bem.halfspace.periodic` and :mod:`bem.halfspace.isolated`. Fields always stay on the
surface's own grid; only the direction of motion changes.

Two routes, both exact for the operator they stand for:

- **Quarter turns** (``theta`` a multiple of ``pi/2``, and ``pi`` for 1-D profiles): the
  heights are turned by ``-theta`` about the array centre (``numpy.rot90``, a permutation of
  grid points), the problem is solved along ``+x`` with the solver's fast path (the line
  preconditioner factors the creep along x-lines), and the fields are turned back. Sliding
  along ``d`` over ``h`` is sliding along ``+x`` over ``h`` turned so that ``d`` becomes ``+x``.
- **Oblique** directions: the operators of :mod:`bem.halfspace.directed`, whose creep acts
  along ``d``.

Lattice directions on periodic cells. Along a lattice direction of the cell (x, y, or any
``(i, j)`` with whole numbers) the modes with ``q.d = 0`` are static and respond with the relaxed
modulus; at an oblique angle no mode but the mean is static, the slowest being excited at
``w ~ 2 pi v |sin(theta - theta_lattice)| / L``. Friction and contact are continuous in
``theta`` while ``v lambda_max |sin(theta - theta_lattice)| / L << 1`` (the seed's solid at
``xi = 0.3``: a relative change of 2e-7 at 1e-6 rad from +x, linear in the angle); a material
with retardation times far beyond the time to cross the cell (``v lambda / L`` of 1e10) changes
its steady state discontinuously there, as the model of an infinitely long steady slide says.

Friction along ``d``: ``mu = -(1/F_N) ∫ p du/ds dA`` (dissipation form, the force opposing the
motion over the load) and ``mu_eq6 = -(1/F_N) ∫ p dh/ds dA``, with ``s`` the arc length along ``d``.
"""

import dataclasses
import math

import numpy as np

from . import fft
from .errors import InputError
from .halfspace.directed import DirectedPeriodicHalfSpace, quarter_turns, unit_vector

__all__ = ["eq6", "normalize", "plan", "turn_array", "turn_back", "turn_surface"]


def normalize(direction, ndim):
    """``direction`` (radians) reduced to ``[0, 2 pi)``; profiles accept only ``0`` and ``pi``."""
    try:
        theta = float(direction)
    except (TypeError, ValueError):
        raise InputError(f"direction must be an angle in radians (a real number), got {direction!r}") from None
    if not math.isfinite(theta):
        raise InputError(f"direction must be a finite angle in radians, got {direction!r}")
    theta = theta % (2 * math.pi)
    k = quarter_turns(theta)
    if ndim == 1 and k not in (0, 2):
        raise InputError(
            f"direction must be 0 or pi (radians) for a 1-D profile (it slides along its own axis), got {direction!r}"
        )
    return 0.0 if k == 0 else (k * math.pi / 2 if k is not None else theta)


def _turn(field, k):
    """``field`` turned by ``k`` quarter turns (counter-clockwise from +x toward +y)."""
    if field.ndim == 1:
        return np.ascontiguousarray(field[::-1]) if k % 4 == 2 else field
    return np.ascontiguousarray(np.rot90(field, k))


def turn_surface(surface, k):
    """The surface turned by ``-k`` quarter turns, so that the direction ``k pi/2`` becomes ``+x``."""
    return dataclasses.replace(surface, heights=_turn(np.asarray(surface.heights), -k))


def turn_array(field, k):
    """An array on the surface's grid in the turned frame of :func:`turn_surface`."""
    return None if field is None else _turn(np.asarray(field), -k)


def turn_back(result, k):
    """A solver result in the turned frame with its fields turned back onto the original grid."""
    fields = {name: _turn(getattr(result, name), k) for name in ("pressure", "displacement", "gap")}
    return dataclasses.replace(result, **fields)


def eq6(op, heights, pressure, total, along_x):
    """Eq. 6 along the operator's direction, ``-(1/F_N) ∫ p dh/ds dA``: ``along_x`` (the value
    along x) unless ``op`` is oblique, then by the spectral derivative along ``d`` on periodic
    cells (the alias mean of ``i q.d``) and central differences on isolated domains."""
    direction = getattr(op, "direction", None)
    if direction is None:
        return along_x
    if not isinstance(op, DirectedPeriodicHalfSpace):
        gx, gy = np.gradient(heights, op.spacing)
        c, s = unit_vector(direction)
        dhds = c * gx + s * gy
        return float(-np.sum(pressure * dhds) * op.spacing**2 / total)
    dhds = fft.inverse(1j * op.slope_multiplier * fft.forward(heights), heights.shape)
    return float(-np.mean(pressure * dhds) * op.area / total)


def plan(direction, ndim, periodic=True, method="auto"):
    """``(theta, turns)``: the direction in ``[0, 2 pi)`` and its quarter turns (``None`` when
    oblique). Refuses the combinations that have no oblique operator (the adaptive mesh)."""
    theta = normalize(direction, ndim)
    turns = quarter_turns(theta)
    if turns is None and not periodic and method == "adaptive":
        raise InputError(
            f"direction must be a multiple of pi/2 (radians) with method='adaptive' (its mesh "
            f"kernels shift along x only; use method='uniform' for oblique directions), got {direction!r}"
        )
    return theta, turns
