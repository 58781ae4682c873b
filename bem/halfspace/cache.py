"""The response operators of the last few problems, built once and reused.

Building an operator costs more than a product (the symbol of a periodic cell; the influence
coefficients and their FFT for an isolated domain, a quadrature for oblique directions), and
a sweep solves many points on the same grid, material and speed (several surfaces, loads or
temperatures). :func:`operator_for` keeps the last :data:`SIZE` operators, keyed by what
defines them: the kind of domain, the grid, the cell side, the material's values (not its
identity: a material rebuilt with the same numbers reuses the operator), the speed and the
sliding direction.

The tables of influence coefficients that other operators are built from (the adaptive mesh's
lattice tables, :mod:`bem.adaptive.square`) are kept here too, by :func:`table_for`, so that one
module decides what operators and their parts stay in memory.
"""

from .directed import DirectedIsolatedHalfSpace, DirectedPeriodicHalfSpace
from .isolated import IsolatedHalfSpace
from .periodic import PeriodicHalfSpace

__all__ = ["SIZE", "TABLES", "clear_operator_cache", "operator_for", "table_for"]

SIZE = 4
"""Operators kept: a sweep over several loads or realisations reuses the speed's operator, and
a few grids' worth of symbols and kernels stay well under the memory of their solves."""

TABLES = 8
"""Tables kept: the elastic and slope tables and one creep table per Prony term of a few lattices,
reused across the refinement levels of a solve and across its speeds."""

_operators = {}
_tables = {}


def _material_key(material):
    return (material.E0, material.nu, material.moduli.tobytes(), material.relaxation_times.tobytes())


def operator_for(surface, material, speed, periodic=True, direction=0.0):
    """The operator of ``surface``'s grid for ``material`` sliding at ``speed`` (m/s) along
    ``direction`` (radians from +x): a periodic cell or, with ``periodic=False``, an isolated
    domain; oblique directions take the operators of :mod:`bem.halfspace.directed`."""
    key = (bool(periodic), surface.shape, surface.length, _material_key(material), float(speed), float(direction))
    op = _operators.get(key)
    if op is None:
        args = (surface.shape, surface.length, material, float(speed))
        if direction == 0.0:
            op = PeriodicHalfSpace(*args) if periodic else IsolatedHalfSpace(*args)
        else:
            kind = DirectedPeriodicHalfSpace if periodic else DirectedIsolatedHalfSpace
            op = kind(*args, float(direction))
        if len(_operators) >= SIZE:
            _operators.pop(next(iter(_operators)))
        _operators[key] = op
    return op


def table_for(key, build):
    """The table ``build()`` made for ``key`` (a hashable description of what defines it), built
    once and kept among the last :data:`TABLES`."""
    if key not in _tables:
        if len(_tables) >= TABLES:
            _tables.pop(next(iter(_tables)))
        _tables[key] = build()
    return _tables[key]


def clear_operator_cache():
    """Forget the operators :func:`operator_for` keeps and the tables of :func:`table_for`, e.g.
    to time an operator's construction or to free its memory."""
    _operators.clear()
    _tables.clear()
