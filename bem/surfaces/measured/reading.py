"""Reading measured topographies into metres: the :class:`Measurement` type, the one unit table,
plain matrices (``.npy`` and text) and instrument files (through SurfaceTopography).

**Axes (one convention for every reader).** Heights are ``h[ix, iy]``: array axis 0 is x, the
sliding direction, as everywhere in :mod:`bem`. A bare matrix in a file is that array as
written: ``.npy`` holds it as it is, and a text file holds one row per x (row ``i`` is
``h[i, 0], h[i, 1], ...``), which is what ``numpy.save(path, h)`` and ``numpy.savetxt(path, h)``
write. Text cells are separated by commas, semicolons, tabs or spaces (a semicolon-separated
file may use decimal commas); ``#`` starts a comment. Instrument formats (X3P, NetCDF, Gwyddion,
SUR, DATX, ... and text exports whose header names the sizes and units, which store one row per y
as an image) know their own axes: SurfaceTopography reads them, and they come out as
``h[ix, iy]`` too. A file whose rows run the other way is read with ``transpose=True``, which
swaps its axes (and its sizes) before anything else. Pixels that the sizes and shape make
non-square by more than :data:`SQUARE_PIXELS` are warned about, saying how to transpose: a map
read with its axes crossed shows up that way.

**Units** (:data:`UNITS`): every reader takes the same spellings (``m``, ``mm``, ``um``, ``µm``
with either micro sign, ``micron``, ``nm``, ``pm``, ``A``, ``Å``). A file that stores its unit
and size is converted with them (the file is the authority: a different ``unit`` or
``physical_sizes`` is an error); a bare matrix needs both from the caller.

**Missing points** (``NaN`` in an array, empty or ``nan`` cells in text, undefined data in an
instrument file) follow one policy, :func:`bem.surfaces.measured.cleaning.fill_missing`.

SurfaceTopography is the optional extra ``topography`` (``pip install 'viscobem[topography]'``),
imported only when an instrument file is read, so ``import bem`` and plain matrices do not need
it.
"""

import re
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...checks import check_array, check_positive, show
from ...errors import InputError
from ..surface import Surface
from .cleaning import fill_missing

__all__ = [
    "UNITS",
    "SQUARE_PIXELS",
    "MATRIX_SUFFIXES",
    "Measurement",
    "read_topography",
    "read_matrix",
    "from_array",
    "load",
    "unit_factor",
    "pixel_warnings",
]

# the one unit table of lengths (m per unit); both micro signs (U+00B5, U+03BC) are written
UNITS = {
    "m": 1.0,
    "mm": 1e-3,
    "um": 1e-6,
    "\u00b5m": 1e-6,
    "\u03bcm": 1e-6,
    "micron": 1e-6,
    "nm": 1e-9,
    "pm": 1e-12,
    "A": 1e-10,
    "\u00c5": 1e-10,
}
# pixel aspect ratio beyond which the axes are suspected crossed: instruments write square
# pixels to well within a percent, and a transposed 160 x 240 map has pixels 2.25 : 1
SQUARE_PIXELS = 0.03
MATRIX_SUFFIXES = (".npy", ".txt", ".csv", ".tsv", ".dat", ".asc")
_HINT = "SurfaceTopography is not installed; reading topography files needs it: pip install 'viscobem[topography]'"
# header lines of instrument text exports (SurfaceTopography's text reader parses them)
_INSTRUMENT_HEADER = re.compile(
    r"^\s*#?\s*(width|height|x-length|y-length|x-pixels|y-pixels|value units|channel|x-unit|z-unit|"
    r"lateral units|data units)\b\s*[:=]",
    re.IGNORECASE,
)
_MISSING_CELLS = {"", "nan", "na", "n/a", "-", "--", "none", "null"}


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
        Provenance: path, format, channel, file unit, detrending, ``transposed``, the filled
        points (``filled_points``, ``filled_fraction``) and the reader's ``warnings``.
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


def unit_factor(unit, name="unit"):
    """Metres per ``unit`` (a key of :data:`UNITS`); anything else is an InputError naming ``name``."""
    if not isinstance(unit, str) or unit.strip() not in UNITS:
        raise InputError(f"{name} must be one of {', '.join(UNITS)}, got {show(unit)}")
    return UNITS[unit.strip()]


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


def _cells(line, delimiter):
    return [c.strip() for c in (line.split(delimiter) if delimiter else line.split())]


def _number(cell):
    """A text cell as a float: NaN for a missing point, None for text that is not a number."""
    if cell.strip('"').lower() in _MISSING_CELLS:
        return np.nan
    try:
        return float(cell.strip('"'))
    except ValueError:
        return None


def _text_rows(lines, where):
    """The rows of numbers of a text matrix (``#`` comments dropped; NaN for a missing cell)."""
    body = [ln.split("#", 1)[0].rstrip() for ln in lines]
    body = [(k + 1, ln) for k, ln in enumerate(body) if ln.strip()]
    if not body:
        raise InputError(f"path {where} holds no rows of numbers")
    text = "\n".join(ln for _, ln in body)
    delimiter = next((d for d in (";", ",", "\t") if d in text), None)
    decimal_comma = delimiter == ";" and "," in text and "." not in text
    rows = []
    for number, line in body:
        cells = _cells(line.replace(",", ".") if decimal_comma else line, delimiter)
        values = [_number(c) for c in cells]
        if any(v is None for v in values):
            raise InputError(
                f"path {where}: line {number} ({line.strip()[:60]!r}) is not a row of numbers; a plain height "
                "matrix holds numbers separated by commas, semicolons, tabs or spaces, with # comments"
            )
        rows.append(values)
    widths = {len(r) for r in rows}
    if len(widths) > 1:
        raise InputError(
            f"path {where}: rows hold different numbers of values ({', '.join(map(str, sorted(widths)))}); "
            "write a missing point as an empty cell or nan, not by leaving it out"
        )
    data = np.array(rows, dtype=float)
    return data[0] if data.shape[0] == 1 else (data[:, 0] if data.shape[1] == 1 else data)


def is_instrument_text(path):
    """Whether a text file carries an instrument header (sizes, units) that SurfaceTopography
    reads; such files store one row per y, as an image."""
    try:
        with open(path, encoding="utf-8-sig", errors="replace") as f:
            head = [next(f, "") for _ in range(60)]
    except OSError:
        return False
    return any(_INSTRUMENT_HEADER.match(line) for line in head)


def read_matrix(path):
    """The array a plain height file holds, ``h[ix, iy]`` in the file's own unit (NaN where a
    point is missing): ``.npy`` as saved, text one row per x (module docstring)."""
    try:
        p = Path(path)
    except TypeError:
        raise InputError(f"path must be a file path, got {show(path)}") from None
    where = show(str(p))
    try:
        if p.suffix.lower() == ".npy":
            data = np.load(p, allow_pickle=False)
        else:
            data = _text_rows(p.read_text(encoding="utf-8-sig").splitlines(), where)
        if np.iscomplexobj(data):
            raise ValueError("heights are complex")
        data = np.asarray(data, dtype=float)
    except (OSError, ValueError, TypeError, UnicodeDecodeError) as err:
        raise InputError(f"path {where} could not be read as heights: {err}") from None
    if data.ndim not in (1, 2) or min(data.shape) < 2:
        raise InputError(f"path {where} must hold a line or a map of heights, at least 2 per side; got {data.shape}")
    return data


def pixel_warnings(shape, sizes, given_by):
    """A sentence when the sizes and the array's shape make pixels that are not square."""
    if len(shape) != 2:
        return []
    dx, dy = (s / n for s, n in zip(sizes, shape))
    ratio = max(dx, dy) / min(dx, dy)
    if ratio <= 1 + SQUARE_PIXELS:
        return []
    return [
        f"pixels are {dx:.4g} x {dy:.4g} m ({ratio:.3g} : 1) for a {shape[0]} x {shape[1]} map of "
        f"{sizes[0]:.4g} x {sizes[1]:.4g} m ({given_by}): axis 0 of the heights is x. If the rows of the "
        "file run along y (an image), or the array is h[iy, ix], read it with transpose=True (scene: "
        "[surface] transpose = true), which swaps its axes and sizes"
    ]


def _finish(heights, sizes, *, transpose, periodic, source, given_by):
    """The Measurement of heights ``h`` (m, NaN where missing) and sizes (m), transposed on
    request, missing points filled, with the reader's warnings in ``source["warnings"]``."""
    if transpose and heights.ndim == 2:
        heights, sizes = heights.T, tuple(reversed(sizes))
    elif transpose:
        raise InputError("transpose=True applies to a map, not a line scan")
    filled, fill_record, notes = fill_missing(heights)
    notes = notes + pixel_warnings(filled.shape, sizes, given_by)
    for text in notes:
        warnings.warn(text, UserWarning, stacklevel=4)
    source = {**source, **fill_record, "transposed": bool(transpose), "detrend": "none", "warnings": notes}
    return Measurement(filled, sizes, periodic=periodic, source=source)


def _sizes(physical_sizes, ndim, shape):
    sizes = np.atleast_1d(np.asarray(physical_sizes, dtype=float))
    if sizes.size != ndim or not np.all(np.isfinite(sizes)) or np.any(sizes <= 0):
        raise InputError(
            f"physical_sizes must give one size > 0 per axis of the scan {shape}, got {show(physical_sizes)}"
        )
    return tuple(float(v) for v in sizes)


def read_topography(path, *, unit=None, physical_sizes=None, channel=0, transpose=False):
    """Read a topography file into metres: a plain matrix (``.npy``, text) or any format
    SurfaceTopography reads.

    Parameters
    ----------
    path : str or os.PathLike
        The file. Axes as the module docstring states: a bare matrix is ``h[ix, iy]`` (text: one
        row per x); instrument formats carry their own.
    unit : str, optional
        Unit of the heights and lateral sizes when the file has none (a key of :data:`UNITS`).
    physical_sizes : float or tuple of float, optional
        Extent of the scan along each axis of the file, in ``unit``, when the file has none.
    channel : int
        Which height channel of a multi-channel instrument file (index among its height channels).
    transpose : bool
        Swap the file's axes (and sizes): for a file whose rows run the other way.

    Returns
    -------
    Measurement
        ``source`` records the format, units, the filled points and the reader's warnings.
    """
    p = Path(path)
    if p.suffix.lower() in MATRIX_SUFFIXES and not (p.suffix.lower() != ".npy" and is_instrument_text(p)):
        data = read_matrix(p)
        if unit is None:
            raise InputError(f"unit is required: the file {show(str(p))} does not store it (one of {', '.join(UNITS)})")
        if physical_sizes is None:
            raise InputError(
                f"physical_sizes is required: the file {show(str(p))} does not store it (the extent along each "
                f"axis of its {' x '.join(map(str, data.shape))} points, in unit)"
            )
        source = {"path": str(p), "format": "matrix", "channel": None, "file_unit": unit}
        source.update(unit_from_file=False, sizes_from_file=False)
        return _given(data, physical_sizes, unit, transpose, source)
    reader = _open(path)
    heights_channels = [c for c in reader.channels if getattr(c, "is_height_channel", True)] or reader.channels
    if not (isinstance(channel, int) and 0 <= channel < len(heights_channels)):
        raise InputError(
            f"channel must be an integer in [0, {len(heights_channels) - 1}] (the file's height "
            f"channels: {[c.name for c in heights_channels]}), got {channel!r}"
        )
    info = heights_channels[channel]
    file_unit = info.unit if isinstance(info.unit, str) else None
    unit_used = _fixed("unit", unit, file_unit, lambda a, b: UNITS.get(a) == UNITS.get(b))
    scale = unit_factor(unit_used)
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
    raw = np.ma.asarray(topo.heights(), dtype=float)
    heights = np.where(np.ma.getmaskarray(raw), np.nan, np.ma.getdata(raw)) * scale
    source = {"path": str(path), "format": reader.format(), "channel": info.name, "file_unit": unit_used}
    source.update(unit_from_file=file_unit is not None, sizes_from_file=file_sizes is not None)
    given = "from the file" if file_sizes is not None else "physical_sizes as given"
    return _finish(
        heights,
        tuple(float(s) * scale for s in topo.physical_sizes),
        transpose=transpose,
        periodic=bool(getattr(topo, "is_periodic", False)),
        source=source,
        given_by=given,
    )


def from_array(heights, physical_sizes, unit="m", *, transpose=False):
    """A :class:`Measurement` of an array ``h[ix, iy]`` (or a line ``h[ix]``) in ``unit``, extent
    ``physical_sizes`` per axis in ``unit``; NaN marks a missing point (filled by the one policy)."""
    try:
        h = np.array(heights, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"scan must be an array of real numbers, got {type(heights).__name__}") from None
    if h.ndim not in (1, 2) or min(h.shape, default=0) < 2:
        raise InputError(f"scan must be a line or a map of heights, at least 2 per side; got shape {h.shape}")
    if np.any(np.isinf(h)):
        raise InputError(
            f"scan must hold finite heights or NaN for missing points; {np.count_nonzero(np.isinf(h))} inf"
        )
    if physical_sizes is None:
        raise InputError("physical_sizes (the scan's extent along each axis, in unit) is required with an array")
    return _given(h, physical_sizes, unit, transpose, {"format": "array", "file_unit": unit})


def _given(h, physical_sizes, unit, transpose, source):
    """The Measurement of an array ``h`` in ``unit`` whose sizes the caller gives (in ``unit``)."""
    f = unit_factor(unit)
    sizes = tuple(v * f for v in _sizes(physical_sizes, h.ndim, h.shape))
    return _finish(h * f, sizes, transpose=transpose, periodic=False, source=source, given_by="physical_sizes as given")


def load(path, length, *, unit="m", name=None):
    """A plain height file that holds one square periodic cell, as a :class:`~bem.surfaces.Surface`.

    The file is read as every bare matrix is (:func:`read_matrix`: ``.npy`` as saved, text one
    row per x; a single row or column is a 1-D profile). Missing points are refused here: a
    periodic cell is taken as it is (use :func:`~bem.surfaces.measured.from_scan` for a scan).

    Parameters
    ----------
    path : str or os.PathLike
        File with 1-D or square 2-D finite heights, at least 2 per side.
    length : float
        Cell side (m).
    unit : str
        Unit of the stored heights (a key of :data:`UNITS`); they are converted to m.
    name : str, optional
        Label (default: the file name without extension).

    Returns
    -------
    Surface
        Periodic surface (the cell is treated as periodic by the solvers and statistics).
    """
    length = check_positive("length", length)
    scale = unit_factor(unit)
    try:
        p = Path(path)
    except TypeError:
        raise InputError(f"path must be a file path, got {show(path)}") from None
    if p.suffix.lower() not in (".npy", ".txt", ".csv"):
        raise InputError(f"path must end in .npy, .txt or .csv, got {show(str(p))}")
    data = read_matrix(p)
    if data.ndim == 2 and data.shape[0] != data.shape[1]:
        raise InputError(
            f"path {show(str(p))} holds a {data.shape[0]} x {data.shape[1]} map; load() reads one square periodic "
            f"cell. For a scan of any shape (periodic or not) write bem.surfaces.from_scan(path, "
            f'physical_sizes=(Lx, Ly), unit=...) (scene: [surface] kind = "measured", path, scan_size = [Lx, Ly], '
            f"unit)"
        )
    if not np.all(np.isfinite(data)):
        raise InputError(
            f"path {show(str(p))} must hold finite heights; got {np.count_nonzero(~np.isfinite(data))} missing "
            "(a scan with missing points is read by bem.surfaces.from_scan, which fills them)"
        )
    meta = {"kind": "file", "path": str(p), "unit": unit}
    return Surface(data * scale, length, name=p.stem if name is None else name, metadata=meta)
