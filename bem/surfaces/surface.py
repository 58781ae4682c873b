"""The :class:`Surface` type: heights of a rigid surface on a square grid, validated.

Conventions (docs/theory.md §4, §5): see :mod:`bem.surfaces`, which also holds every constructor.
"""

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

from .. import fft
from ..checks import check_array, check_positive, show
from ..errors import InputError

__all__ = ["Surface", "from_heights"]


@dataclass(frozen=True, eq=False, repr=False)
class Surface:
    """Heights of a rigid surface on a square cell (validated; heights stored read-only).

    Parameters
    ----------
    heights : array_like
        1-D ``(n,)`` or square 2-D ``(n, n)`` heights (m), finite, ``n >= 2``, positive
        toward the half-space. A read-only copy is stored.
    length : float
        Cell side (m), > 0.
    name : str
        Label for reports.
    centered : bool
        ``False`` (periodic cell, ``x_j = j dx``) or ``True`` (isolated indenter, element
        centres of a domain centred on it).
    metadata : mapping
        How the surface was made, e.g. ``metadata["spectrum"]`` (stored read-only, one
        level of nested mappings included).

    Notes
    -----
    Equality is identity (arrays have no single truth value); make variants with
    :func:`dataclasses.replace`.
    """

    heights: np.ndarray
    length: float
    name: str = ""
    centered: bool = False
    metadata: Mapping = field(default_factory=dict)

    def __post_init__(self):
        h = check_array("heights", self.heights, ndim=(1, 2))
        if h.ndim == 2 and h.shape[0] != h.shape[1]:
            raise InputError(f"heights must be 1-D or square 2-D (n, n), got shape {h.shape}")
        if h.shape[0] < 2:
            raise InputError(f"heights must have at least 2 points per side, got shape {h.shape}")
        h.flags.writeable = False
        object.__setattr__(self, "heights", h)
        object.__setattr__(self, "length", check_positive("length", self.length))
        object.__setattr__(self, "name", str(self.name))
        object.__setattr__(self, "centered", bool(self.centered))
        frozen = {k: MappingProxyType(dict(v)) if isinstance(v, Mapping) else v for k, v in dict(self.metadata).items()}
        object.__setattr__(self, "metadata", MappingProxyType(frozen))

    def __reduce__(self):
        """Pickle and copy through the constructor (mapping proxies do not pickle)."""
        meta = {k: dict(v) if isinstance(v, Mapping) else v for k, v in self.metadata.items()}
        return (Surface, (np.array(self.heights), self.length, self.name, self.centered, meta))

    def __repr__(self):
        kind = "centered" if self.centered else "periodic"
        return f"Surface(name={self.name!r}, shape={self.shape}, length={show(self.length)}, {kind})"

    @property
    def ndim(self):
        """1 for a profile, 2 for a surface."""
        return self.heights.ndim

    @property
    def n(self):
        """Points per side."""
        return self.heights.shape[0]

    @property
    def shape(self):
        """Shape of :attr:`heights`."""
        return self.heights.shape

    @property
    def spacing(self):
        """Grid spacing ``length / n`` (m)."""
        return self.length / self.n

    @property
    def x(self):
        """Coordinates of the grid points along a side (m); see the module docstring."""
        j = np.arange(self.n, dtype=float)
        if self.centered:
            return (j + 0.5) * self.spacing - 0.5 * self.length
        return j * self.spacing

    def coordinates(self):
        """Grid coordinates (m): ``(x,)`` in 1-D, ``(x, y)`` full ``(n, n)`` arrays in 2-D (ij)."""
        if self.ndim == 1:
            return (self.x,)
        return tuple(np.meshgrid(self.x, self.x, indexing="ij"))

    def wavevectors(self):
        """Wavevector components (rad/m) on the half-spectrum grid of :mod:`bem.fft`."""
        return fft.wavevectors(self.shape, self.length)


def from_heights(heights, length, *, name="", centered=False):
    """Surface from any 1-D or square 2-D array of heights (m) on a cell of side ``length`` (m).

    The array is copied and validated; it is never modified.

    Examples
    --------
    >>> from_heights([0.0, 1e-6, 0.0, -1e-6], 1e-3).spacing
    0.00025
    """
    return Surface(heights, length, name=name, centered=centered, metadata={"kind": "array"})
