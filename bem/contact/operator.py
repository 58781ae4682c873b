"""What the contact solver needs from a response operator, and how it classifies one.

An operator maps a pressure field (Pa, shaped like the heights) to the surface displacement
(m) it causes; :class:`ResponseOperator` states the members every operator provides.
Capabilities that some operators have, and the solver uses where they exist, are the
protocols beside it: an exact full-contact inverse (:class:`ExactInverse`, periodic cells and
dense systems), an approximate one for preconditioning (:class:`ApproximateInverse`),
coarser grids (:class:`Coarsening`), float32 products (:class:`SinglePrecision`), a first
iterate of its own (:class:`OwnStart`) and the factors of the line preconditioner
(:class:`LineFactors`). :mod:`bem.halfspace` implements them; ``isinstance(op, Protocol)``
tells which an operator has.

A non-symmetric operator is *strongly* non-symmetric when its symbol's phase exceeds
:data:`STRONG_PHASE`: the solver then starts from the symmetric part's contact, takes damped
steps and GMRES inner solves from the first step, and (2-D periodic cells) tries the line
preconditioner.
"""

import math
from typing import Protocol, runtime_checkable

import numpy as np

__all__ = [
    "ApproximateInverse",
    "Coarsening",
    "ExactInverse",
    "LineFactors",
    "OwnStart",
    "ResponseOperator",
    "STRONG_PHASE",
    "SinglePrecision",
    "strongly_nonsymmetric",
]

STRONG_PHASE = math.pi / 4
"""Symbol phase (rad) above which an operator is strongly non-symmetric: there its skew part
outweighs its symmetric part, and plain active-set steps from the full-contact start cycle. It
selects the mechanisms of the ablation rows "symmetric-part start" (off: 1.32x the products and a
case lost) and "line preconditioner" (off: 1.34x), and keeps the exact full-contact inverse from
preconditioning them."""


@runtime_checkable
class ResponseOperator(Protocol):
    """Members every operator provides to :func:`bem.contact.solve_contact`."""

    shape: tuple
    """Grid shape, ``(n,)`` or ``(n, n)``; pressures and displacements have it."""
    is_symmetric: bool
    """Whether the operator is symmetric (elastic, or at zero speed): CG instead of GMRES."""

    @property
    def size(self) -> int:
        """Grid points."""

    def displacement(self, pressure: np.ndarray) -> np.ndarray:
        """Displacement (m) under ``pressure`` (Pa); the operator's product."""

    def self_influence(self) -> float:
        """Displacement of a grid cell under a unit pressure on it alone (m/Pa)."""

    def symmetric_part(self) -> "ResponseOperator":
        """The operator ``(A + A^T) / 2``."""

    def max_phase(self) -> float:
        """Largest phase ``|arg a_q|`` (rad) of the symbol; 0 when symmetric."""


@runtime_checkable
class ExactInverse(Protocol):
    """An exact full-contact inverse: the start from the clipped full-contact pressure."""

    def pressure_from_displacement(self, displacement: np.ndarray) -> np.ndarray:
        """Zero-mean pressure (Pa) whose displacement is ``displacement`` up to its mean."""


@runtime_checkable
class ApproximateInverse(Protocol):
    """An approximate inverse of one product's cost: restricted to the contact set, it
    preconditions the inner solves (``R M R^T``)."""

    def approximate_inverse(self, displacement: np.ndarray) -> np.ndarray:
        """Pressure (Pa) whose displacement is about ``displacement`` (m)."""


@runtime_checkable
class Coarsening(Protocol):
    """The same problem on the grid with half the points per axis (nested iteration)."""

    def coarsened(self) -> "ResponseOperator | None":
        """The operator on the coarser grid, or ``None`` where there is none (odd sides)."""

    def restrict(self, field: np.ndarray) -> np.ndarray:
        """``field`` (heights, a pressure) sampled on the coarser grid."""

    def prolong(self, field: np.ndarray) -> np.ndarray:
        """A pressure on the coarser grid interpolated to this one (keeps ``>= 0``)."""


@runtime_checkable
class SinglePrecision(Protocol):
    """Products in float32 for loose inner solves."""

    dtype: np.dtype

    def single_precision(self) -> "ResponseOperator":
        """The same operator with float32 products."""


@runtime_checkable
class OwnStart(Protocol):
    """A first iterate of its own (isolated domains: no exact full-contact inverse)."""

    def initial_pressure(self, ht: np.ndarray, *, mean_pressure=None, approach=None) -> np.ndarray:
        """A pressure (Pa) near the answer for heights ``ht`` (m, maximum 0)."""


@runtime_checkable
class LineFactors(Protocol):
    """The symbol's factors ``a_q = green(|q|) J(-q_x v)``, for the line preconditioner."""

    factors_along_x: bool

    def creep_line_kernel(self, dtype=np.float64) -> np.ndarray:
        """The creep factor's kernel along one x-line."""

    def elastic_inverse(self, field: np.ndarray) -> np.ndarray:
        """The inverse of the elastic factor applied to ``field``."""


def strongly_nonsymmetric(op):
    """Whether ``op``'s symbol phase exceeds :data:`STRONG_PHASE`."""
    return op.max_phase() > STRONG_PHASE
