"""Measured topographies: read instrument files, with their units, and detrend them.

Reading goes through SurfaceTopography (the optional extra ``topography``:
``pip install viscobem[topography]``), imported only when a file is read, so ``import bem``
does not need it. Every format it reads is accepted (AFM, profilometer and interferometer
files: X3P, NetCDF, Gwyddion, Digital Surf SUR, Zygo DATX/MetroPro, Keyence, Sensofar,
Bruker/DI, plain text with a header, ...); its format detection picks the reader.

Units: heights and lateral sizes come back in metres. A file that stores its unit and
physical size is converted with them; a file without them (e.g. a bare matrix of numbers)
needs ``unit`` and ``physical_sizes`` from the caller, and giving a different unit or size
than the file's is an error (the file is the authority).

Arrays are indexed ``h[ix, iy]`` (axis 0 = x), as everywhere in :mod:`bem`. Plain text
matrices are read as SurfaceTopography and the instruments write them, one row per y (as an
image), which is the transpose of :func:`bem.surfaces.load`'s one row per x.
"""

from dataclasses import dataclass, field, replace

import numpy as np

from .checks import check_array
from .errors import InputError

__all__ = ["DETREND_MODES", "Measurement", "detrend", "read_topography"]

_HINT = "reading instrument files needs SurfaceTopography: pip install 'viscobem[topography]'"
DETREND_MODES = ("none", "mean", "plane", "curvature")
_SI = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6, "nm": 1e-9, "pm": 1e-12, "A": 1e-10, "Å": 1e-10}


@dataclass(frozen=True, eq=False)
class Measurement:
    """A measured topography on a uniform grid, in SI units.

    Attributes
    ----------
    heights : ndarray
        ``(nx,)`` line scan or ``(nx, ny)`` map (m), finite.
    physical_sizes : tuple of float
        Extent along each axis (m): ``nx dx`` (and ``ny dy``).
    periodic : bool
        Whether the file declares the data periodic.
    source : dict
        Provenance: path, format, channel, file unit, detrending, filled points.
    """

    heights: np.ndarray
    physical_sizes: tuple
    periodic: bool = False
    source: dict = field(default_factory=dict)

    def __post_init__(self):
        h = check_array("heights", self.heights, ndim=(1, 2))
        if len(self.physical_sizes) != h.ndim or not all(s > 0 for s in self.physical_sizes):
            raise InputError(
                f"physical_sizes must give one positive size (m) per axis of heights {h.shape}, "
                f"got {self.physical_sizes!r}"
            )
        object.__setattr__(self, "heights", h)
        object.__setattr__(self, "physical_sizes", tuple(float(s) for s in self.physical_sizes))

    @property
    def spacing(self):
        """Pixel size along each axis (m)."""
        return tuple(s / n for s, n in zip(self.physical_sizes, self.heights.shape))


def _factor(unit, name):
    if unit not in _SI:
        raise InputError(f"{name} must be one of {', '.join(sorted(_SI))}, got {unit!r}")
    return _SI[unit]


def _read_errors():
    """What a reader raises on a file it cannot read: SurfaceTopography's own errors and the
    plain ones its parsers let through on malformed bytes."""
    from SurfaceTopography import Exceptions as e

    return (
        e.ReadFileError,
        e.UnknownFileFormat,
        e.UnsupportedFormatFeature,
        e.UndefinedDataError,
        ValueError,
        KeyError,
        IndexError,
        TypeError,
        OSError,
        EOFError,
    )


def _open(path):
    try:
        import SurfaceTopography as st
    except ImportError:
        raise ImportError(_HINT) from None
    try:
        return st.open_topography(str(path))
    except FileNotFoundError:
        raise InputError(f"path {str(path)!r}: no such file") from None
    except _read_errors() as err:
        raise InputError(f"path {str(path)!r} could not be read as a topography: {err}") from None


def _fixed(name, given, from_file, same):
    """The file's value, or the caller's where the file has none; a conflict is an error."""
    if from_file is None:
        if given is None:
            raise InputError(f"{name} is required: the file does not store it")
        return given
    if given is not None and not same(given, from_file):
        raise InputError(f"{name} {given!r} contradicts the file's {from_file!r}; leave it out")
    return from_file


def read_topography(path, *, unit=None, physical_sizes=None, channel=0):
    """Read a topography file (any format SurfaceTopography reads) into metres.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    unit : str, optional
        Unit of the heights and lateral sizes when the file has none: ``m``, ``mm``, ``um``
        (``µm``), ``nm``, ``pm``, ``A``.
    physical_sizes : float or tuple of float, optional
        Extent of the scan along each axis, in ``unit``, when the file has none.
    channel : int
        Which height channel of a multi-channel file (index among its height channels).

    Returns
    -------
    Measurement
    """
    reader = _open(path)
    heights_channels = [c for c in reader.channels if getattr(c, "is_height_channel", True)] or reader.channels
    if not (isinstance(channel, int) and 0 <= channel < len(heights_channels)):
        raise InputError(
            f"channel must be an integer in [0, {len(heights_channels) - 1}] (the file's height "
            f"channels: {[c.name for c in heights_channels]}), got {channel!r}"
        )
    info = heights_channels[channel]
    file_unit = info.unit if isinstance(info.unit, str) else None
    unit_used = _fixed("unit", unit, file_unit, lambda a, b: _SI.get(a) == _SI.get(b))
    scale = _factor(unit_used, "unit")
    if physical_sizes is not None:
        physical_sizes = tuple(np.atleast_1d(np.asarray(physical_sizes, dtype=float)))
    file_sizes = None if info.physical_sizes is None else tuple(float(s) for s in info.physical_sizes)
    sizes = _fixed("physical_sizes", physical_sizes, file_sizes, lambda a, b: np.allclose(a, b, rtol=1e-9))
    kwargs = {"channel_index": info.index}
    if file_unit is None:
        kwargs["unit"] = unit_used
    if file_sizes is None:
        kwargs["physical_sizes"] = sizes
    try:
        topo = reader.topography(**kwargs)
    except _read_errors() as err:
        raise InputError(f"path {str(path)!r} could not be read as a topography: {err}") from None
    if not getattr(topo, "is_uniform", True):
        raise InputError(f"path {str(path)!r} holds a non-uniform line scan; resample it to a uniform grid first")
    filled = 0
    if getattr(topo, "has_undefined_data", False):
        filled = int(np.count_nonzero(np.ma.getmaskarray(topo.heights())))
        topo = topo.interpolate_undefined_data()
    heights = np.asarray(np.ma.getdata(topo.heights()), dtype=float) * scale
    sizes = tuple(float(s) * scale for s in topo.physical_sizes)
    source = {
        "path": str(path),
        "format": reader.format(),
        "channel": info.name,
        "file_unit": unit_used,
        "unit_from_file": file_unit is not None,
        "sizes_from_file": file_sizes is not None,
        "filled_points": filled,
        "detrend": "none",
    }
    return Measurement(heights, sizes, periodic=bool(getattr(topo, "is_periodic", False)), source=source)


def _basis(shape, sizes, mode):
    """Polynomial basis (columns) on the pixel centres, coordinates scaled to [-1, 1]."""
    axes = [(np.arange(n) + 0.5) / n * 2 - 1 for n in shape]
    grids = np.meshgrid(*axes, indexing="ij")
    cols = [np.ones(shape)]
    if mode in ("plane", "curvature"):
        cols += list(grids)
    if mode == "curvature":
        cols += [g * g for g in grids]
        if len(grids) == 2:
            cols.append(grids[0] * grids[1])
    return np.stack([c.ravel() for c in cols], axis=1)


def detrend(measurement, mode="plane"):
    """Remove the least-squares fit of a polynomial: ``"mean"`` (a constant), ``"plane"`` (the
    mean plane; a line for a line scan), ``"curvature"`` (a quadratic surface: plane plus
    ``x**2``, ``y**2``, ``x y``) or ``"none"``. Returns a new :class:`Measurement` recording it."""
    if mode not in DETREND_MODES:
        raise InputError(f"detrend must be one of {', '.join(map(repr, DETREND_MODES))}, got {mode!r}")
    h = measurement.heights
    if mode != "none":
        basis = _basis(h.shape, measurement.physical_sizes, mode)
        coef, *_ = np.linalg.lstsq(basis, h.ravel(), rcond=None)
        h = (h.ravel() - basis @ coef).reshape(h.shape)
    return replace(measurement, heights=h, source={**measurement.source, "detrend": mode})
