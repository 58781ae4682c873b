"""Sliding in any direction ``d = (cos theta, sin theta)`` in the surface's own frame.

Angles are radians from ``+x`` (axis 0) toward ``+y`` (axis 1); ``theta = 0`` is the
convention of :mod:`bem.periodic` and :mod:`bem.isolated`. Fields always stay on the
surface's own grid; only the direction of motion changes.

Two routes, both exact for the operator they stand for:

- **Quarter turns** (``theta`` a multiple of ``pi/2``, and ``pi`` for 1-D profiles): the
  heights are turned by ``-theta`` about the array centre (``numpy.rot90``, a permutation of
  grid points), the problem is solved along ``+x`` with the solver's fast path (the line
  preconditioner factors the creep along x-lines), and the fields are turned back. Sliding
  along ``d`` over ``h`` is sliding along ``+x`` over ``h`` turned so that ``d`` becomes ``+x``.
- **Oblique** directions on isolated domains: the creep kernels shift along ``d``
  (:mod:`bem.direction_isolated`). On periodic cells the symbol becomes
  ``a_q = 2 (1 - nu**2) / |q| * J(w = -(q.d) v)``. A Nyquist mode (even side) stands for two
  aliased wavevectors ``±q_N`` along that axis; its symbol is the mean of the symbols of its
  aliases along both axes (four at the corner), which makes the operator real and reduces, at
  ``theta = 0``, to the real part at the x-Nyquist mode that the x-operator takes. The
  derivative along ``d`` (for the dissipation) is the same alias mean of ``i q.d``. The creep
  factor then acts along ``d``, not along x-lines, so the operator declares
  ``factors_along_x = False`` and the contact solver uses its general path.

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
from .angles import quarter_turns, unit_vector
from .checks import check_positive
from .errors import ConvergenceError, InputError
from .periodic import PeriodicHalfSpace

__all__ = [
    "DirectedPeriodicHalfSpace",
    "directed_operator",
    "eq6",
    "normalize",
    "operator",
    "plan",
    "quarter_turns",
    "solve_turned",
    "turn_array",
    "turn_back",
    "turn_surface",
    "unit_vector",
]


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


def _alias_mean(f, qx, qy, shape):
    """``f(qx, qy)`` on the half spectrum, averaged over the aliases ``±q_N`` of each Nyquist
    mode (even sides): the x-Nyquist row and the y-Nyquist column (four aliases at the corner)."""
    gx, gy = np.broadcast_arrays(qx, qy)
    out = np.array(f(gx, gy))
    if shape[0] % 2 == 0:
        r = shape[0] // 2
        out[r] = 0.5 * (f(gx[r], gy[r]) + f(-gx[r], gy[r]))
    if shape[1] % 2 == 0:
        cx, cy = gx[:, -1], gy[:, -1]
        col = 0.5 * (f(cx, cy) + f(cx, -cy))
        if shape[0] % 2 == 0:
            r = shape[0] // 2
            col[r] = 0.25 * (f(cx[r], cy[r]) + f(cx[r], -cy[r]) + f(-cx[r], cy[r]) + f(-cx[r], -cy[r]))
        out[:, -1] = col
    return out


class DirectedPeriodicHalfSpace(PeriodicHalfSpace):
    """Periodic steady-sliding operator for motion along ``d = (cos theta, sin theta)`` (2-D).

    Parameters as :class:`bem.periodic.PeriodicHalfSpace`, plus ``direction`` (radians). Every
    method of the x-operator applies; the dissipation integral is ``-∫ p du/ds dA``. The
    operator does not factor along x-lines (``factors_along_x`` is ``False``).
    """

    def __init__(self, shape, length, material, speed, direction):
        if len(shape) != 2:
            raise InputError(f"shape must be 2-D for an oblique sliding direction, got {tuple(shape)}")
        super().__init__(shape, length, material, speed)
        self.direction = float(direction)
        c, s = unit_vector(self.direction)
        qx, qy = fft.wavevectors(self.shape, self.length)
        self._creep = None
        self._qx = np.broadcast_to(_alias_mean(lambda a, b: a * c + b * s, qx, qy, self.shape), self.symbol.shape)
        if material.is_elastic or self.speed == 0.0:
            return
        v = self.speed
        symbol = _alias_mean(lambda a, b: material.complex_compliance(-(a * c + b * s) * v), qx, qy, self.shape)
        # real operator: the alias means make the q_y = 0 and y-Nyquist columns Hermitian in q_x
        # (J(-w) = conj J(w)); the other columns have no partner on the half spectrum
        self.symbol = self._green * symbol
        self.is_symmetric = bool(np.all(self.symbol.imag == 0))
        if self.is_symmetric:
            self.symbol = self.symbol.real

    @property
    def factors_along_x(self):
        """``False``: the creep factor acts along ``d``, so x-line preconditioners do not apply."""
        return False

    def line_preconditioner(self, contact, cache=None):
        """``None``: the operator does not factor along x-lines (the solver's general path)."""
        return

    @property
    def slope_multiplier(self):
        """The multiplier of the derivative along ``d`` divided by ``i`` (rad/m), half spectrum."""
        return self._qx

    def coarsened(self):
        """The same operator on the grid with half the points per axis (even sides only)."""
        if any(n % 2 for n in self.shape):
            raise ValueError(f"coarsening needs even grid sides, got {self.shape}")
        coarse = DirectedPeriodicHalfSpace(
            tuple(n // 2 for n in self.shape), self.length, self.material, self.speed, self.direction
        )
        return coarse.symmetric_part() if self.__dict__.get("_symmetric_part") else coarse

    def _twin(self, *stale):
        twin = super()._twin(*stale)
        twin.__class__ = type(self)
        return twin


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


def operator(operator_for, surface, material, speed, periodic, theta):
    """``operator_for(surface, material, speed, periodic)`` along ``+x`` (``theta == 0``), else
    the cached oblique operator."""
    if theta == 0.0:
        return operator_for(surface, material, speed, periodic)
    return directed_operator(surface, material, speed, theta, periodic)


def solve_turned(solve, surface, material, turns, *, initial=None, **options):
    """``solve`` along ``+x`` on the heights turned by ``-turns`` quarter turns; fields turned back.

    A :class:`bem.errors.ConvergenceError` carries the turned-back result too.
    """
    if options.get("height") is not None:
        raise InputError(
            "direction must be 0 with an exact height function (height=...): the function is "
            "given in the surface's frame; turn the surface instead"
        )
    try:
        result = solve(
            turn_surface(surface, turns), material, initial=turn_array(initial, turns), direction=0.0, **options
        )
    except ConvergenceError as err:
        if err.result is not None:
            err.result = turn_back(err.result, turns)
        raise
    return turn_back(result, turns)


_CACHE = {}


def directed_operator(surface, material, speed, direction, periodic=True):
    """The (cached, up to 4) oblique operator of this grid, material, speed and direction."""
    speed = check_positive("speed", speed, allow_zero=True)
    key = (surface.shape, surface.length, id(material), bool(periodic), float(speed), float(direction))
    op = _CACHE.get(key)
    if op is None or op.material is not material:
        if periodic:
            op = DirectedPeriodicHalfSpace(surface.shape, surface.length, material, speed, direction)
        else:
            from .direction_isolated import DirectedIsolatedHalfSpace

            op = DirectedIsolatedHalfSpace(surface.shape, surface.length, material, speed, direction)
        if len(_CACHE) >= 4:
            _CACHE.pop(next(iter(_CACHE)))
        _CACHE[key] = op
    return op
