"""Measured topographies: read instrument files with their units, detrend, and put them on the
solver's grid.

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

On the solver's grid (:func:`to_surface`). A measurement is a finite patch, rarely periodic. How
it is solved is an explicit choice, recorded in ``surface.metadata["measured"]``:

- ``boundary="isolated"``: the patch is the loaded domain of an isolated contact
  (:mod:`bem.halfspace.isolated`; pressure outside it is zero). Each element gets the mean height of
  the scan over it (the cubic spline of the scan averaged over midpoints, as many per axis
  as there are scan pixels per element), so a finer scan does not alias onto the grid.
- ``boundary="periodic"``: the patch becomes one periodic cell. Its edges do not match, so a
  ``window`` is applied first: ``"tukey"`` (``alpha`` = tapered fraction, default 0.25) or
  ``"hann"`` multiply the heights (about their mean) by the separable window, which brings
  them to the mean at the edges; ``"mirror"`` tiles the patch with its mirror images (cell
  side twice the patch, continuous heights, slopes reversed at the seams); ``"none"`` keeps
  the jump (only sensible when the file says the data are periodic). The periodic field is
  then resampled to ``n`` points per side by Fourier interpolation, which keeps exactly the
  modes the grid can hold (an ideal low-pass at the grid's Nyquist when coarser).

The square patch is the largest centred square of the scan (physical sizes). Line scans
give 1-D profiles. The PSD report compares the measurement with what the grid keeps.

Plain height files (``.npy``, ``.txt``, ``.csv`` in metres or a given unit, one row per x) are
read without SurfaceTopography by :func:`load`.
"""

from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..checks import check_array, check_int, check_positive, check_range, show
from ..errors import InputError
from .surface import Surface

__all__ = [
    "BOUNDARIES",
    "DETREND_MODES",
    "WINDOWS",
    "Measurement",
    "detrend",
    "load",
    "psd_report",
    "read_topography",
    "square_patch",
    "to_surface",
]

_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9}
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


BOUNDARIES = ("isolated", "periodic")
WINDOWS = ("tukey", "hann", "mirror", "none")


def square_patch(measurement):
    """The largest centred square of the scan: ``(heights, side)`` (pixels may be rectangular)."""
    h = measurement.heights
    side = min(measurement.physical_sizes)
    keep = []
    for n, d in zip(h.shape, measurement.spacing):
        m = max(2, min(n, round(side / d)))
        start = (n - m) // 2
        keep.append(slice(start, start + m))
    patch = h[tuple(keep)]
    return patch, min(m * d for m, d in zip(patch.shape, measurement.spacing))


def _window(patch, kind, alpha):
    base = patch.mean()
    if kind == "mirror":
        out = patch
        for axis in range(patch.ndim):
            out = np.concatenate([out, np.flip(out, axis=axis)], axis=axis)
        return out
    if kind == "none":
        return patch
    import scipy.signal as ssig  # here, so that importing bem.surfaces stays light

    w = 1.0
    for axis, n in enumerate(patch.shape):
        shape = [1] * patch.ndim
        shape[axis] = n
        win = ssig.windows.tukey(n, alpha, sym=True) if kind == "tukey" else ssig.windows.hann(n, sym=True)
        w = w * win.reshape(shape)
    return base + (patch - base) * w


def _fourier_resample(field, n):
    import scipy.signal as ssig

    out = field
    for axis in range(field.ndim):
        out = ssig.resample(out, n, axis=axis)
    return out


def _element_means(patch, n):
    """Mean heights of ``n`` equal elements per axis: the cubic spline of ``patch`` averaged over
    ``k`` midpoints per axis and element (``k`` = measured pixels per element, rounded up), a box
    filter that keeps the grid free of aliases of the finer scan."""
    from scipy import ndimage

    ratio = [m / n for m in patch.shape]
    k = [max(1, int(np.ceil(r))) for r in ratio]
    coords = [((np.arange(n * kk) + 0.5) / kk) * r - 0.5 for kk, r in zip(k, ratio)]
    grids = np.meshgrid(*coords, indexing="ij")
    fine = ndimage.map_coordinates(patch, grids, order=3, mode="nearest")
    shape = [v for nk in zip([n] * patch.ndim, k) for v in nk]
    return fine.reshape(shape).mean(axis=tuple(range(1, 2 * patch.ndim, 2)))


def to_surface(measurement, n, *, boundary="isolated", window="tukey", alpha=0.25, name=None):
    """The measurement as a :class:`bem.surfaces.Surface` of ``n`` points per side.

    Parameters
    ----------
    measurement : Measurement
        Heights in m (detrend it first, :func:`bem.surfaces.measured.detrend`).
    n : int
        Points (elements) per side of the solver grid, >= 4.
    boundary : {"isolated", "periodic"}
        How the non-periodic patch is solved (module docstring).
    window : {"tukey", "hann", "mirror", "none"}
        Periodic boundary only: how the patch is made periodic.
    alpha : float
        Tukey window: fraction of each axis tapered, in (0, 1].

    Returns
    -------
    Surface
        ``centered`` for ``isolated``; ``metadata["measured"]`` records the boundary, window,
        patch and cell sides (m), the measurement's pixel sizes and the source.
    """
    if not isinstance(measurement, Measurement):
        raise InputError(f"measurement must be a bem.surfaces.measured.Measurement, got {type(measurement).__name__}")
    n = check_int("n", n, 4)
    if boundary not in BOUNDARIES:
        raise InputError(f"boundary must be one of {', '.join(map(repr, BOUNDARIES))}, got {boundary!r}")
    if window not in WINDOWS:
        raise InputError(f"window must be one of {', '.join(map(repr, WINDOWS))}, got {window!r}")
    patch, side = square_patch(measurement)
    record = {
        "boundary": boundary,
        "patch_side": side,
        "pixel_sizes": list(measurement.spacing),
        "patch_points": list(patch.shape),
        "n": n,
        "source": dict(measurement.source),
    }
    if boundary == "isolated":
        heights, length = _element_means(patch, n), side
        record["sampling"] = "element means of the cubic spline of the scan"
    else:
        alpha = check_range("alpha", alpha, 1e-6, 1.0) if window == "tukey" else None
        field = _window(patch, window, alpha)
        length = side * (2 if window == "mirror" else 1)
        heights = _fourier_resample(field, n)
        record.update(window=window, alpha=alpha, sampling="Fourier interpolation (band-limited)")
    record["cell_side"] = length
    label = name if name is not None else str(measurement.source.get("path", "measured"))
    return Surface(
        heights, length, name=label, centered=boundary == "isolated", metadata={"kind": "measured", "measured": record}
    )


def _radial_psd(field, spacing, bins):
    """Radially averaged periodogram (m**4 in 2-D, m**3 in 1-D) on log-spaced bins of |q|."""
    f = field - field.mean()
    spec = np.abs(np.fft.fftn(f)) ** 2 * np.prod(spacing) / f.size / (2 * np.pi) ** f.ndim
    qs = np.meshgrid(*[2 * np.pi * np.fft.fftfreq(m, d) for m, d in zip(f.shape, spacing)], indexing="ij")
    q = np.sqrt(sum(c**2 for c in qs)).ravel()
    spec = spec.ravel()
    keep = q > 0
    edges = np.geomspace(q[keep].min(), q.max() * 1.0001, bins + 1)
    idx = np.digitize(q[keep], edges) - 1
    sums = np.bincount(idx, spec[keep], minlength=bins)[:bins]
    counts = np.bincount(idx, minlength=bins)[:bins]
    centres = np.sqrt(edges[:-1] * edges[1:])
    ok = counts > 0
    return centres[ok], sums[ok] / counts[ok]


def _rms_slope(field, spacing):
    grads = np.gradient(field, *spacing) if field.ndim > 1 else [np.gradient(field, spacing[0])]
    return float(np.sqrt(np.mean(sum(g**2 for g in grads))))


def psd_report(measurement, surface, *, bins=40):
    """The measurement's PSD beside the solver grid's wavevector range (numbers for results).

    ``q`` (rad/m) and ``C`` (radially averaged periodogram of the centred square patch, Hann
    windowed against leakage, normalised so that ``sum C (2 pi / L)**dim`` is the variance);
    ``q_grid_min = 2 pi / cell side`` and ``q_grid_max = pi n / cell side`` (the grid's
    Nyquist); ``q_measurement_max`` (the scan's Nyquist); rms height and slope (finite
    differences) of the patch and of the solver heights, and the fraction of the patch's
    height variance at ``|q|`` above the grid's Nyquist.
    """
    patch, side = square_patch(measurement)
    spacing = measurement.spacing
    win = _window(patch - patch.mean(), "hann", None)
    win = win * np.sqrt(patch.var() / max(win.var(), 1e-300))
    q, c = _radial_psd(win, spacing, check_int("bins", bins, 4))
    cell = surface.length
    q_max = np.pi * surface.shape[0] / cell
    f = patch - patch.mean()
    full = np.abs(np.fft.fftn(f)) ** 2
    qs = np.meshgrid(*[2 * np.pi * np.fft.fftfreq(m, d) for m, d in zip(f.shape, spacing)], indexing="ij")
    above = np.sqrt(sum(g**2 for g in qs)) > q_max
    return {
        "q": q.tolist(),
        "C": c.tolist(),
        "q_grid_min": 2 * np.pi / cell,
        "q_grid_max": q_max,
        "q_measurement_min": 2 * np.pi / side,
        "q_measurement_max": float(np.pi / max(spacing)),
        "rms_height_measurement": float(f.std()),
        "rms_height_grid": float(np.std(surface.heights)),
        "rms_slope_measurement": _rms_slope(patch, spacing),
        "rms_slope_grid": _rms_slope(np.asarray(surface.heights), (surface.spacing,) * surface.ndim),
        "variance_above_grid_nyquist": float(full[above].sum() / max(full.sum(), 1e-300)),
    }


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
    if data.ndim not in (1, 2) or (data.ndim == 2 and data.shape[0] != data.shape[1]):
        raise InputError(f"path {show(str(p))} must hold 1-D or square 2-D heights, got shape {data.shape}")
    if data.shape[0] < 2 or not np.all(np.isfinite(data)):
        raise InputError(
            f"path {show(str(p))} must hold finite heights, at least 2 per side; "
            f"got shape {data.shape}, {np.count_nonzero(~np.isfinite(data))} non-finite"
        )
    meta = {"kind": "file", "path": str(p), "unit": unit}
    return Surface(data * _UNITS[unit], length, name=p.stem if name is None else name, metadata=meta)
