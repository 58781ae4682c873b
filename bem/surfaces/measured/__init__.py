"""Measured topographies: read instrument files with their units, clean them, and put a scan of
part of a larger surface on the solver's grid.

The one entry is :func:`from_scan` (a file, an array or a :class:`Measurement` in, a
:class:`~bem.surfaces.Surface` out); the scene kind ``measured`` calls it with the same
defaults. Its steps, one concept per module:

1. read (:mod:`.reading`): :func:`read_topography` for any instrument file, arrays, the unit
   table; :func:`load` for a plain file holding one square periodic cell;
2. clean (:mod:`.cleaning`): :func:`detrend`;
3. cut the square patch and choose its boundary (:mod:`.patch`): :func:`to_surface`,
   :func:`square_patch`, :func:`cover`, and the load (:func:`cell_load`, which :func:`bem.solve`
   applies itself) and speed (:func:`speed_limit`) that go with a patch;
4. make it periodic and put it on the grid (:mod:`.windows`);
5. compare the scan's spectrum with what the grid keeps (:mod:`.spectrum`): :func:`psd`,
   :func:`psd_report`.
"""

from .cleaning import DETREND_MODES, detrend
from .patch import (
    BOUNDARIES,
    cell_load,
    cover,
    from_scan,
    load_factor,
    speed_limit,
    speed_limit_warning,
    square_patch,
    to_surface,
)
from .reading import Measurement, load, read_topography
from .spectrum import psd, psd_report
from .windows import DEFAULT_WINDOW, WINDOWS, edge_mismatch, periodic_component

__all__ = [
    "BOUNDARIES",
    "DEFAULT_WINDOW",
    "DETREND_MODES",
    "WINDOWS",
    "Measurement",
    "cell_load",
    "cover",
    "detrend",
    "edge_mismatch",
    "from_scan",
    "load",
    "load_factor",
    "periodic_component",
    "psd",
    "psd_report",
    "read_topography",
    "speed_limit",
    "speed_limit_warning",
    "square_patch",
    "to_surface",
]
