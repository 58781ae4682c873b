"""Reading measured topographies: the :class:`Measurement` type, the unit table, instrument files
(through SurfaceTopography) and arrays, all converted to metres.

Reading goes through SurfaceTopography (the optional extra ``topography``:
``pip install 'viscobem[topography]'``), imported only when a file is read, so ``import bem``
does not need it. Every format it reads is accepted (AFM, profilometer and interferometer
files: X3P, NetCDF, Gwyddion, Digital Surf SUR, Zygo DATX/MetroPro, Keyence, Sensofar,
Bruker/DI, NumPy ``.npy``, plain text with a header, ...); its format detection picks the reader.

Units: heights and lateral sizes come back in metres. A file that stores its unit and
physical size is converted with them; a file without them (e.g. a bare matrix of numbers)
needs ``unit`` and ``physical_sizes`` from the caller, and giving a different unit or size
than the file's is an error (the file is the authority).

Arrays are indexed ``h[ix, iy]`` (axis 0 = x, the sliding direction), as everywhere in
:mod:`bem`, and so are ``.npy`` files. Plain text matrices are read as SurfaceTopography and
the instruments write them, one row per y (as an image), which is the transpose of
:func:`load`'s one row per x.

Plain height files (``.npy``, ``.txt``, ``.csv`` in metres or a given unit, one row per x) that
hold one square periodic cell are read without SurfaceTopography by :func:`load`.
"""

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...checks import check_array, check_positive, show
from ...errors import InputError
from ..surface import Surface

__all__ = ["Measurement", "read_topography", "from_array", "load", "unit_factor"]

_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9}
_HINT = "SurfaceTopography is not installed; reading topography files needs it: pip install 'viscobem[topography]'"
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


def unit_factor(unit, name):
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
    except ImportError:  # missing, or installed without a dependency of its own
        raise ModuleNotFoundError(_HINT, name="SurfaceTopography") from None
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
    scale = unit_factor(unit_used, "unit")
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


def from_array(heights, physical_sizes, unit):
    h = check_array("scan", heights, ndim=(1, 2))
    if physical_sizes is None:
        raise InputError("physical_sizes (the scan's extent along each axis, in unit) is required with an array")
    sizes = np.atleast_1d(np.asarray(physical_sizes, dtype=float))
    if sizes.size != h.ndim or not np.all(np.isfinite(sizes)) or np.any(sizes <= 0):
        raise InputError(
            f"physical_sizes must give one size > 0 per axis of the scan {h.shape}, got {show(physical_sizes)}"
        )
    f = unit_factor(unit, "unit")
    return Measurement(h * f, tuple(sizes * f), source={"format": "array", "file_unit": unit, "detrend": "none"})


def load(path, length, *, unit="m", name=None):
    """Measured topography from a ``.npy``, ``.txt`` or ``.csv`` file.

    Text files hold one row per x index (a single row or column is a 1-D profile), values
    separated by commas or whitespace, ``#`` comments allowed.

    Parameters
    ----------
    path : str or os.PathLike
        File with 1-D or square 2-D finite heights, at least 2 per side.
    length : float
        Cell side (m).
    unit : {"m", "mm", "um", "nm"}
        Unit of the stored heights; they are converted to m.
    name : str, optional
        Label (default: the file name without extension).

    Returns
    -------
    Surface
        Periodic surface (the cell is treated as periodic by the solvers and statistics).
    """
    length = check_positive("length", length)
    if unit not in _UNITS:
        raise InputError(f"unit must be one of {sorted(_UNITS)}, got {show(unit)}")
    try:
        p = Path(path)
    except TypeError:
        raise InputError(f"path must be a file path, got {show(path)}") from None
    suffix = p.suffix.lower()
    if suffix not in (".npy", ".txt", ".csv"):
        raise InputError(f"path must end in .npy, .txt or .csv, got {show(str(p))}")
    try:
        if suffix == ".npy":
            data = np.load(p, allow_pickle=False)
        else:
            text = p.read_text()
            if not text.strip():
                raise ValueError("the file is empty")
            lines = text.splitlines()
            comma = any("," in line.split("#")[0] for line in lines)
            data = np.loadtxt(lines, delimiter="," if comma else None, comments="#")
        if np.iscomplexobj(data):
            raise ValueError("heights are complex")
        data = np.asarray(data, dtype=float)
    except (OSError, ValueError, TypeError) as err:
        raise InputError(f"path {show(str(p))} could not be read as heights: {err}") from None
    if data.ndim == 2 and data.shape[0] != data.shape[1]:
        raise InputError(
            f"path {show(str(p))} holds a {data.shape[0]} x {data.shape[1]} map; load() reads one square periodic "
            f"cell. For a scan of any shape (periodic or not) write bem.surfaces.from_scan(np.load(path), "
            f'physical_sizes=(Lx, Ly), unit=...) (scene: [surface] kind = "measured", path, scan_size = [Lx, Ly], '
            f"unit; text matrices are then read as images, one row per y)"
        )
    if data.ndim not in (1, 2):
        raise InputError(f"path {show(str(p))} must hold 1-D or square 2-D heights, got shape {data.shape}")
    if data.shape[0] < 2 or not np.all(np.isfinite(data)):
        raise InputError(
            f"path {show(str(p))} must hold finite heights, at least 2 per side; "
            f"got shape {data.shape}, {np.count_nonzero(~np.isfinite(data))} non-finite"
        )
    meta = {"kind": "file", "path": str(p), "unit": unit}
    return Surface(data * _UNITS[unit], length, name=p.stem if name is None else name, metadata=meta)
