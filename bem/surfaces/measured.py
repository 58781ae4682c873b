"""Measured topographies: read instrument files with their units, detrend, and put a scan of part
of a larger surface on the solver's grid.

The one entry is :func:`from_scan` (a file, an array or a :class:`Measurement` in, a
:class:`~bem.surfaces.Surface` out); the scene kind ``measured`` calls it with the same
defaults. Its steps are public too: :func:`read_topography`, :func:`detrend`,
:func:`to_surface`; :func:`psd_report` compares the scan's spectrum with what the grid keeps.

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

**Detrending** (:func:`detrend`): the least-squares plane by default, in :func:`from_scan`,
:func:`to_surface` and the scene kind alike, applied to the square patch that is solved and
recorded in ``surface.metadata["measured"]["detrend"]``. A tilt is not roughness: left in, it
adds its slope to every contact and to both friction forms.

**The patch.** Solver cells are square; a scan need not be. The solved patch is a square of
the scan (``patch="centre"``, the largest centred one, by default; or a given origin and side),
and the surface says which: ``metadata["measured"]["patch"]`` (origin, side, points, fraction
of the scan's area), with a warning when the automatic choice is not the whole scan. :func:`cover` lists squares
that together cover the whole scan, to solve each (the scene's ``patch = "cover"``).

**The boundary** (docs/theory.md §5.1). A scan is a patch of a larger surface whose
surroundings carry the same nominal pressure; neither of its edges is special. Chosen by
measurement (``viscobem bench measured``: patches cut from periodic surfaces whose friction is
known):

- ``boundary="periodic"`` (default): the patch becomes one periodic cell. Its opposite edges do
  not match, so it is made periodic first (``window``):

  * ``"mirror"`` (the default for scans that are not periodic): the patch tiled with its mirror
    images, a cell twice the patch's side with continuous heights (slopes reverse at the
    seams). Nothing is flattened or removed, and the four copies share the cell's load, so
    the load per patch area is unchanged: :func:`from_scan` and :func:`to_surface` return
    the cell, and ``metadata["measured"]["load_factor"]`` (= 4 in 2-D, 2 in 1-D) is the
    factor between the load on the cell and the load on the patch
    (:func:`cell_load` converts). Sliding along ``x`` over the mirrored copies is sliding
    along ``-x`` over the scan, so a scan whose friction differs between the two directions
    (a sawtooth texture) gets their mean.
  * ``"periodic_component"``: Moisan's periodic plus smooth decomposition (a harmonic field
    that carries the edge mismatch is removed; the cell is the patch).
  * ``"tukey"`` (``alpha`` = tapered fraction, default 0.25) or ``"hann"``: the heights (about
    their mean) multiplied by the separable window, flattening the edges.
  * ``"none"``: the jump kept (right only when the scan itself is periodic: the default then).

  The periodic field is then resampled to ``n`` points per patch side by Fourier
  interpolation, which keeps exactly the modes the grid can hold.
- ``boundary="isolated"``: the patch is the whole loaded domain of an isolated contact
  (:mod:`bem.halfspace.isolated`; no pressure outside it), right for a scan of a whole finite
  body. For a patch of a larger surface it is a rough flat punch: its edges carry the load the
  surroundings would, and it dissipates at the punch's own scale. Each element gets the mean
  height of the scan over it (the cubic spline of the scan averaged over midpoints, as many
  per axis as there are scan pixels per element).

A choice measured to misrepresent a patch of a larger surface (``"isolated"``; ``"none"`` on a
scan that is not periodic; ``"hann"``, which flattens most of the patch) is allowed and
warned about, as is a cropped scan: each warning is a sentence in
``surface.metadata["measured"]["warnings"]`` and is also issued as a Python ``UserWarning``.

Line scans give 1-D profiles (the whole line is the patch).

Plain height files (``.npy``, ``.txt``, ``.csv`` in metres or a given unit, one row per x) that
hold one square periodic cell are read without SurfaceTopography by :func:`load`.
"""

import warnings
from dataclasses import dataclass, field, replace
from os import PathLike
from pathlib import Path

import numpy as np

from ..checks import check_array, check_int, check_positive, check_range, show
from ..errors import InputError
from .surface import Surface

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
    "periodic_component",
    "psd",
    "psd_report",
    "read_topography",
    "speed_limit",
    "square_patch",
    "to_surface",
]

_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9}
_HINT = "SurfaceTopography is not installed; reading topography files needs it: pip install 'viscobem[topography]'"
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
    return _detrended(measurement, mode)


def _detrended(measurement, mode):
    if mode not in DETREND_MODES:
        raise InputError(f"detrend must be one of {', '.join(map(repr, DETREND_MODES))}, got {mode!r}")
    h = measurement.heights
    if mode != "none":
        basis = _basis(h.shape, measurement.physical_sizes, mode)
        coef, *_ = np.linalg.lstsq(basis, h.ravel(), rcond=None)
        h = (h.ravel() - basis @ coef).reshape(h.shape)
    done = _stronger(measurement.source.get("detrend", "none"), mode)
    return replace(measurement, heights=h, source={**measurement.source, "detrend": done})


BOUNDARIES = ("periodic", "isolated")
WINDOWS = ("mirror", "periodic_component", "tukey", "hann", "none")
DEFAULT_WINDOW = "mirror"  # for scans that are not periodic: chosen by `viscobem bench measured`
PATCHES = ("centre",)  # or an origin (x0, y0) or (x0, y0, side) in m
# Relative edge mismatch (rms jump across opposite edges over rms height) below which a scan
# counts as periodic enough for window="none": a self-affine scan that is not periodic has ~1.4.
_PERIODIC_MISMATCH = 0.05


def _warn(texts):
    for text in texts:
        warnings.warn(text, UserWarning, stacklevel=3)


def _patch_indices(measurement, patch):
    """``(starts, counts, side)`` of the square patch: pixel starts and counts per axis, side (m)."""
    shape, spacing, sizes = measurement.heights.shape, measurement.spacing, measurement.physical_sizes
    if len(shape) == 1:
        if patch != "centre":
            raise InputError(f"patch must be 'centre' for a line scan (the whole line is used), got {patch!r}")
        return (0,), shape, sizes[0]
    if isinstance(patch, str):
        if patch not in PATCHES:
            raise InputError(f"patch must be 'centre' or an origin (x0, y0[, side]) in m, got {patch!r}")
        side = min(sizes)
        counts = [max(2, min(n, round(side / d))) for n, d in zip(shape, spacing)]
        return (
            tuple((n - m) // 2 for n, m in zip(shape, counts)),
            tuple(counts),
            min(m * d for m, d in zip(counts, spacing)),
        )
    try:
        values = [float(v) for v in patch]
    except (TypeError, ValueError):
        raise InputError(f"patch must be 'centre' or an origin (x0, y0[, side]) in m, got {patch!r}") from None
    if len(values) not in (2, 3) or not all(np.isfinite(values)) or min(values[:2]) < 0:
        raise InputError(f"patch must be 'centre' or an origin (x0, y0[, side]) in m with x0, y0 >= 0, got {patch!r}")
    starts = tuple(round(v / d) for v, d in zip(values[:2], spacing))
    room = min((n - s) * d for n, s, d in zip(shape, starts, spacing))
    side = values[2] if len(values) == 3 else room
    if not 0 < side <= room * (1 + 1e-9):
        raise InputError(
            f"patch {patch!r}: the square must lie inside the scan ({sizes[0]:.6g} x {sizes[1]:.6g} m); "
            f"from that origin its side can be at most {room:.6g} m"
        )
    counts = tuple(max(2, min(n - s, round(side / d))) for n, s, d in zip(shape, starts, spacing))
    return starts, counts, min(m * d for m, d in zip(counts, spacing))


def square_patch(measurement, patch="centre"):
    """The square patch that is solved: ``(heights, side)`` (pixels may be rectangular).

    ``patch``: ``"centre"`` (the largest centred square) or an origin ``(x0, y0)`` (m, from the
    scan's first pixel; the largest square from there) or ``(x0, y0, side)``. A line scan is
    its own patch."""
    starts, counts, side = _patch_indices(measurement, patch)
    return measurement.heights[tuple(slice(s, s + m) for s, m in zip(starts, counts))], side


def cover(measurement):
    """Origins ``(x0, y0)`` (m) of squares of the scan's shorter side that together cover it,
    evenly spaced along the longer side (one for a square scan or a line scan): pass each as
    ``patch`` to solve the whole scan."""
    shape, spacing = measurement.heights.shape, measurement.spacing
    if len(shape) == 1:
        return ["centre"]
    _, counts, _ = _patch_indices(measurement, "centre")
    starts = [np.unique(np.rint(np.linspace(0, n - m, int(np.ceil(n / m)))).astype(int)) for n, m in zip(shape, counts)]
    return [(float(i * spacing[0]), float(j * spacing[1])) for i in starts[0] for j in starts[1]]


def periodic_component(heights):
    """Moisan's periodic component of a 1-D or 2-D array (same shape and mean).

    The array is split as ``u = p + s`` with ``s`` the discrete harmonic field whose boundary
    values carry the jumps across opposite edges; ``p`` has no such jumps and keeps the texture
    (L. Moisan, "Periodic plus smooth image decomposition", J. Math. Imaging Vis. 39 (2011)
    161-179, doi:10.1007/s10851-010-0227-1): ``s_q = v_q / sum_axes (2 cos(2 pi k / n) - 2)``
    with ``v`` the boundary image (``v[0] = u[-1] - u[0]``, ``v[-1] = u[0] - u[-1]`` per axis).
    """
    u = np.asarray(heights, dtype=float)
    v = np.zeros_like(u)
    den = np.zeros(u.shape)
    for axis, n in enumerate(u.shape):
        jump = np.take(u, -1, axis=axis) - np.take(u, 0, axis=axis)
        first = [slice(None)] * u.ndim
        first[axis] = 0
        v[tuple(first)] += jump
        first[axis] = -1
        v[tuple(first)] -= jump
        k = np.arange(n).reshape([-1 if a == axis else 1 for a in range(u.ndim)])
        den = den + 2 * np.cos(2 * np.pi * k / n) - 2
    den.flat[0] = 1.0
    s = np.fft.fftn(v) / den
    s.flat[0] = 0.0
    return u - np.real(np.fft.ifftn(s))


def edge_mismatch(heights):
    """The rms jump across opposite edges (both axes) over the rms height about the mean: 0 for
    a periodic scan, about 1.4 for an uncorrelated one."""
    h = np.asarray(heights, dtype=float)
    jumps = [np.take(h, -1, axis=a) - np.take(h, 0, axis=a) for a in range(h.ndim)]
    rms = np.sqrt(np.mean(np.concatenate([np.ravel(j) for j in jumps]) ** 2))
    return float(rms / max(h.std(), 1e-300))


def _window(patch, kind, alpha):
    """The patch made periodic: ``(field, cell factor)`` (the cell side over the patch side)."""
    if kind == "mirror":
        out = patch
        for axis in range(patch.ndim):
            out = np.concatenate([out, np.flip(out, axis=axis)], axis=axis)
        return out, 2
    if kind == "periodic_component":
        return periodic_component(patch), 1
    if kind == "none":
        return patch, 1
    import scipy.signal as ssig  # here, so that importing bem.surfaces stays light

    base = patch.mean()
    w = 1.0
    for axis, n in enumerate(patch.shape):
        shape = [1] * patch.ndim
        shape[axis] = n
        win = ssig.windows.tukey(n, alpha, sym=True) if kind == "tukey" else ssig.windows.hann(n, sym=True)
        w = w * win.reshape(shape)
    return base + (patch - base) * w, 1


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


def _variance_above(field, spacing, q_max):
    """Fraction of the variance of the periodic ``field`` at ``|q| > q_max`` (rad/m)."""
    f = np.abs(np.fft.fftn(field - field.mean())) ** 2
    qs = np.meshgrid(*[2 * np.pi * np.fft.fftfreq(m, d) for m, d in zip(f.shape, spacing)], indexing="ij")
    above = np.sqrt(sum(g**2 for g in qs)) > q_max * (1 + 1e-9)
    return float(f[above].sum() / max(f.sum(), 1e-300))


def _stronger(done, mode):
    """The detrending a measurement has had after ``mode`` is applied over ``done``."""
    order = DETREND_MODES
    return order[max(order.index(done), order.index(mode))] if done in order else mode


def _patch_record(measurement, patch, starts, counts, side):
    shape, spacing, sizes = measurement.heights.shape, measurement.spacing, measurement.physical_sizes
    fraction = float(np.prod([m / n for m, n in zip(counts, shape)]))
    return {
        "selection": patch if isinstance(patch, str) else "given",
        "origin": [float(s * d) for s, d in zip(starts, spacing)],
        "side": float(side),
        "points": [int(m) for m in counts],
        "scan_points": [int(n) for n in shape],
        "scan_sizes": [float(s) for s in sizes],
        "fraction_of_scan": fraction,
    }


def _boundary_warnings(record, mismatch, periodic_scan):
    out = []
    patch = record["patch"]
    if patch["selection"] == "centre" and patch["fraction_of_scan"] < 1 - 1e-9:  # a given square was chosen
        nx, ny = patch["scan_points"]
        lx, ly = (1e3 * s for s in patch["scan_sizes"])
        x0, y0 = (1e3 * s for s in patch["origin"])
        out.append(
            f"the scan is {nx} x {ny} points ({lx:.4g} x {ly:.4g} mm) and solver cells are square: only the "
            f"square of side {1e3 * patch['side']:.4g} mm at ({x0:.4g}, {y0:.4g}) mm ({patch['points'][0]} x "
            f"{patch['points'][1]} points, {100 * patch['fraction_of_scan']:.3g} % of the scan) is solved. To use "
            f'all of it, solve every square of bem.surfaces.measured.cover() (scene: [surface] patch = "cover").'
        )
    if record["boundary"] == "isolated":
        out.append(
            "boundary 'isolated' solves the scan as a finite rigid punch: its edges carry the load that the "
            "surrounding surface would share, and the punch dissipates at its own scale (on patches cut from "
            "known surfaces its friction was 1.3x to 2.3x theirs on average at low speed, up to 3.8x, and its "
            "eq. 6 form took the opposite sign: viscobem bench measured). Keep it for a scan of a whole finite "
            f"body; for a patch of a larger surface use boundary 'periodic' (window {DEFAULT_WINDOW!r}, the default)."
        )
    elif record["window"] == "none" and not periodic_scan and mismatch > _PERIODIC_MISMATCH:
        out.append(
            f"window 'none' keeps the step between the scan's opposite edges (rms jump {mismatch:.2g} times the "
            "rms height; the scan is not periodic): the step's slope enters the friction, eq. 6 most (on patches "
            "cut from known surfaces eq. 6 took the opposite sign of the dissipation form). Use window "
            f"{DEFAULT_WINDOW!r} (the default)."
        )
    elif record["window"] == "hann":
        out.append(
            "window 'hann' flattens the patch toward its edges (only its centre keeps its roughness), which "
            "lowered friction by 45-79 % on average on patches cut from known surfaces (viscobem bench measured). "
            f"Use window {DEFAULT_WINDOW!r} (the default)."
        )
    return out


def to_surface(
    measurement, n=None, *, boundary="periodic", window=None, alpha=0.25, detrend="plane", patch="centre", name=None
):
    """A square patch of the measurement as a :class:`bem.surfaces.Surface`.

    Parameters
    ----------
    measurement : Measurement
        Heights and sizes in m.
    n : int, optional
        Grid points (elements) per side of the patch, >= 4; default: the patch's own pixels
        along its better-resolved axis. A mirrored cell has ``2 n``.
    boundary : {"periodic", "isolated"}
        How the patch is solved (module docstring): a periodic cell (default) or the whole
        domain of an isolated contact.
    window : {"mirror", "periodic_component", "tukey", "hann", "none"}, optional
        Periodic boundary only: how the patch is made periodic. Default ``"none"`` for a scan
        the file declares periodic (solved whole), else ``"mirror"``.
    alpha : float
        Tukey window: fraction of each axis tapered, in (0, 1].
    detrend : {"plane", "none", "mean", "curvature"}
        Polynomial removed from the patch (:func:`detrend`), after any the measurement has had.
    patch : "centre" or tuple
        Which square (:func:`square_patch`).
    name : str, optional
        Label (default: the file's path).

    Returns
    -------
    Surface
        Periodic cell (``length`` = the patch side, twice it when mirrored) or ``centered``
        isolated domain. ``metadata["measured"]``: boundary, window, detrend, the patch
        (origin, side, points, fraction of the scan), ``patch_side`` and ``cell_side`` (m),
        ``load_factor`` (load on the cell per load on the patch), pixel sizes, source, and
        ``warnings`` (sentences; also issued as ``UserWarning``).
    """
    if not isinstance(measurement, Measurement):
        raise InputError(f"measurement must be a bem.surfaces.measured.Measurement, got {type(measurement).__name__}")
    if boundary not in BOUNDARIES:
        raise InputError(f"boundary must be one of {', '.join(map(repr, BOUNDARIES))}, got {boundary!r}")
    if window is not None and window not in WINDOWS:
        raise InputError(f"window must be one of {', '.join(map(repr, WINDOWS))}, got {window!r}")
    starts, counts, side = _patch_indices(measurement, patch)
    n = max(counts) if n is None else check_int("n", n, 4)
    whole = all(m == k for m, k in zip(counts, measurement.heights.shape))
    piece = Measurement(
        measurement.heights[tuple(slice(s, s + m) for s, m in zip(starts, counts))],
        tuple(m * d for m, d in zip(counts, measurement.spacing)),
        periodic=measurement.periodic and whole,
        source=measurement.source,
    )
    piece = _detrended(piece, detrend)
    done = piece.source["detrend"]
    mismatch = edge_mismatch(piece.heights)
    record = {
        "boundary": boundary,
        "detrend": done,
        "patch": _patch_record(measurement, patch, starts, counts, side),
        "patch_side": side,
        "pixel_sizes": list(measurement.spacing),
        "patch_points": list(counts),
        "n": n,
        "edge_mismatch": mismatch,
        "source": dict(piece.source),
    }
    if boundary == "isolated":
        heights, factor = _element_means(piece.heights, n), 1
        field = periodic_component(piece.heights)  # its spectrum without the edges' leakage
        record.update(window=None, sampling="element means of the cubic spline of the scan")
    else:
        if window is None:
            window = "none" if piece.periodic else DEFAULT_WINDOW
        alpha = check_range("alpha", alpha, 1e-6, 1.0) if window == "tukey" else None
        field, factor = _window(piece.heights, window, alpha)
        heights = _fourier_resample(field, factor * n)
        record.update(window=window, alpha=alpha, sampling="Fourier interpolation (band-limited)")
    record["variance_above_grid_nyquist"] = _variance_above(field, piece.spacing, np.pi * n / side)
    record["cell_side"] = side * factor
    record["load_factor"] = factor**measurement.heights.ndim
    record["warnings"] = _boundary_warnings(record, mismatch, piece.periodic)
    _warn(record["warnings"])
    label = name if name is not None else str(measurement.source.get("path", "measured"))
    return Surface(
        heights,
        side * factor,
        name=label,
        centered=boundary == "isolated",
        metadata={"kind": "measured", "measured": record},
    )


def cell_load(surface, patch_load):
    """The load (N; N/m for profiles) to give :func:`bem.solve` for ``patch_load`` on the measured
    patch of ``surface`` (a mirrored cell holds the patch 4 times in 2-D, twice in 1-D, so that the
    load per patch area is unchanged)."""
    meta = surface.metadata.get("measured") if hasattr(surface, "metadata") else None
    if meta is None:
        raise InputError("surface must come from bem.surfaces.from_scan or bem.surfaces.measured.to_surface")
    return check_positive("patch_load", patch_load) * meta["load_factor"]


def speed_limit(surface, material):
    """The sliding speed (m/s) above which a measured patch under-estimates friction, or ``inf``.

    A patch holds wavelengths up to its side ``l``; sliding at ``v`` excites a wavelength ``w``
    at the frequency ``2 pi v / w``. Above ``v* = omega_d l / (2 pi)``, with ``omega_d`` the
    frequency of the material's largest loss tangent, even the patch's longest wavelengths are
    excited beyond that peak, and the longer wavelengths of the real surface, which the scan
    does not hold, dissipate more than any it holds. Measured on patches a quarter of the area
    of known surfaces (``viscobem bench measured``; a 4-term rubber beside it): within 7 % of the
    surface's friction on average below ``v*``, 9-19 % low above it (a sixteenth of the area:
    33-40 % low). ``inf`` for an elastic material.
    """
    meta = surface.metadata.get("measured") if hasattr(surface, "metadata") else None
    if meta is None:
        raise InputError("surface must come from bem.surfaces.from_scan or bem.surfaces.measured.to_surface")
    times = np.concatenate([np.atleast_1d(material.relaxation_times), np.atleast_1d(material.creep_times)])
    if material.is_elastic or times.size == 0:
        return float("inf")
    w = np.logspace(np.log10(0.01 / times.max()), np.log10(100 / times.min()), 2000)
    e = material.complex_modulus(w)
    return float(w[np.argmax(e.imag / e.real)] * meta["patch_side"] / (2 * np.pi))


def from_scan(
    scan,
    n=None,
    *,
    physical_sizes=None,
    unit=None,
    channel=0,
    detrend="plane",
    boundary="periodic",
    window=None,
    alpha=0.25,
    patch="centre",
    name=None,
):
    """A measured scan on the solver's grid: the one entry for measured topographies.

    Parameters
    ----------
    scan : str, os.PathLike, array_like or Measurement
        A topography file (any format SurfaceTopography reads; needs the ``topography`` extra),
        an array of heights ``h[ix, iy]`` (or a line ``h[ix]``) in ``unit``, or a
        :class:`Measurement`. Any rectangular shape; periodic or not.
    n : int, optional
        Grid points per side of the solved patch (default: its own pixels).
    physical_sizes : float or tuple, optional
        Extent along each axis in ``unit``: required for an array, and for a file that does
        not store it.
    unit : str, optional
        Unit of the heights and sizes (``m``, ``mm``, ``um``, ``nm``, ...): for a file only when
        it stores none; for an array default ``"m"``.
    channel : int
        Height channel of a multi-channel file.
    detrend, boundary, window, alpha, patch, name
        As :func:`to_surface`; ``detrend="plane"`` by default.

    Returns
    -------
    Surface
        See :func:`to_surface`. With the default mirrored cell, give :func:`bem.solve` the load
        on the cell, :func:`cell_load` of the load on the patch.

    Examples
    --------
    >>> import numpy as np
    >>> h = np.random.default_rng(0).normal(size=(30, 20))   # micrometres, 300 x 200 um
    >>> s = from_scan(h, 16, physical_sizes=(300, 200), unit="um", patch=(0, 0))
    >>> round(s.metadata["measured"]["patch"]["fraction_of_scan"], 4), round(s.length * 1e6, 9), s.n
    (0.6667, 400.0, 32)
    """
    if isinstance(scan, Measurement):
        if unit is not None or physical_sizes is not None:
            raise InputError("unit and physical_sizes come with the Measurement; leave them out")
        measurement = scan
    elif isinstance(scan, (str, PathLike)):
        measurement = read_topography(scan, unit=unit, physical_sizes=physical_sizes, channel=channel)
    else:
        measurement = _from_array(scan, physical_sizes, "m" if unit is None else unit)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        surface = to_surface(
            measurement, n, boundary=boundary, window=window, alpha=alpha, detrend=detrend, patch=patch, name=name
        )
    _warn(str(w.message) for w in caught)
    return surface


def _from_array(heights, physical_sizes, unit):
    h = check_array("scan", heights, ndim=(1, 2))
    if physical_sizes is None:
        raise InputError("physical_sizes (the scan's extent along each axis, in unit) is required with an array")
    sizes = np.atleast_1d(np.asarray(physical_sizes, dtype=float))
    if sizes.size != h.ndim or not np.all(np.isfinite(sizes)) or np.any(sizes <= 0):
        raise InputError(
            f"physical_sizes must give one size > 0 per axis of the scan {h.shape}, got {show(physical_sizes)}"
        )
    f = _factor(unit, "unit")
    return Measurement(h * f, tuple(sizes * f), source={"format": "array", "file_unit": unit, "detrend": "none"})


def _hann(shape, sizes):
    """The window of the PSD, normalised to ``mean(w**2) = 1``: Hann along a line scan; in 2-D the
    rotationally symmetric Hann ``(1 + cos(pi r / r_max)) / 2`` of radius ``r_max = min(sizes) / 2``
    about grid point ``(nx // 2, ny // 2)``, zero beyond (as SurfaceTopography)."""
    if len(shape) == 1:
        n = shape[0]
        w = 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(n) / n)
    else:
        axes = [s * (np.arange(n) - n // 2) / n for n, s in zip(shape, sizes)]
        r = np.sqrt(axes[0][:, None] ** 2 + axes[1][None, :] ** 2)
        r_max = min(sizes) / 2
        w = np.where(r <= r_max, 0.5 + 0.5 * np.cos(np.pi * np.minimum(r, r_max) / r_max), 0.0)
    return w / np.sqrt(np.mean(w**2))


def psd(measurement, *, per_decade=10):
    """Radially averaged PSD of a scan that need not be periodic: ``(q, C)``.

    The heights about their mean are multiplied by a Hann window (rotationally symmetric in
    2-D) normalised to ``mean(w**2) = 1``, so that the windowed variance equals the scan's
    (dividing by the mean of the squared window: a window that only scaled the variance back
    would count the leaked power of the edges). The periodogram is normalised as
    :mod:`bem.surfaces.statistics` (``C = |h_q|**2 (L / 2 pi)**dim``; SurfaceTopography's ``C`` is
    ``(2 pi)**dim`` times this) and averaged in log-spaced bins of ``|q|``, ``per_decade`` edges
    per decade from the smallest wavevector ``2 pi / max(L)`` to the Nyquist ``pi min(n / L)``
    (each widened by 0.01 decade); ``q`` is the mean ``|q|`` of the modes in each bin (rad/m),
    ``C`` in m**4 (2-D) or m**3 (1-D); a line scan's Nyquist mode is left out. Bins and window follow T. D. B. Jacobs, T. Junge,
    L. Pastewka, Surf. Topogr. Metrol. Prop. 5 (2017) 013001, doi:10.1088/2051-672X/aa51f8.
    """
    per_decade = check_int("per_decade", per_decade, 2)
    h = measurement.heights
    sizes, spacing = measurement.physical_sizes, measurement.spacing
    f = (h - h.mean()) * _hann(h.shape, sizes)
    spec = np.abs(np.fft.fftn(f)) ** 2 * np.prod(spacing) / f.size / (2 * np.pi) ** f.ndim
    qs = np.meshgrid(*[2 * np.pi * np.fft.fftfreq(m, d) for m, d in zip(f.shape, spacing)], indexing="ij")
    q = np.sqrt(sum(c**2 for c in qs)).ravel()
    lo, hi = 2 * np.pi / max(sizes), np.pi * min(m / s for m, s in zip(f.shape, sizes))
    count = int(np.ceil((np.log10(hi) - np.log10(lo) + 1) * per_decade))
    edges = 10 ** np.linspace(np.log10(lo) - 0.01, np.log10(hi) + 0.01, count)
    idx = np.searchsorted(edges, q)
    inside = (idx > 0) & (idx < edges.size)
    if f.ndim == 1:  # a line's Nyquist mode has no partner of opposite sign: left out, as SurfaceTopography does
        inside &= q < hi * (1 - 1e-12)
    bins = np.bincount(idx[inside], minlength=edges.size)[1:]
    sums = np.bincount(idx[inside], spec.ravel()[inside], minlength=edges.size)[1:]
    qsum = np.bincount(idx[inside], q[inside], minlength=edges.size)[1:]
    ok = bins > 0
    return qsum[ok] / bins[ok], sums[ok] / bins[ok]


def _rms_slope(field, spacing):
    grads = np.gradient(field, *spacing) if field.ndim > 1 else [np.gradient(field, spacing[0])]
    return float(np.sqrt(np.mean(sum(g**2 for g in grads))))


def psd_report(measurement, surface, *, per_decade=10):
    """The scan's PSD beside the solver grid's wavevector range (numbers for results).

    ``q`` (rad/m) and ``C``: :func:`psd` of the whole scan; ``q_grid_min = 2 pi / cell side`` and
    ``q_grid_max = pi n / patch side`` (the grid's Nyquist), ``q_measurement_min`` and
    ``q_measurement_max`` (the scan's longest and Nyquist wavevectors); rms height and slope
    (finite differences) of the solved patch and of the solver heights; and the fraction of the
    variance of the periodic field that was put on the grid (isolated: the patch's periodic
    component) at ``|q|`` above the grid's Nyquist, lost to the grid.
    """
    q, c = psd(measurement, per_decade=per_decade)
    rec = surface.metadata["measured"]
    patch, side = square_patch(measurement, _patch_argument(rec))
    spacing = measurement.spacing
    return {
        "q": q.tolist(),
        "C": c.tolist(),
        "q_grid_min": 2 * np.pi / surface.length,
        "q_grid_max": np.pi * rec["n"] / side,
        "q_measurement_min": 2 * np.pi / max(measurement.physical_sizes),
        "q_measurement_max": float(np.pi / max(spacing)),
        "rms_height_measurement": float(patch.std()),
        "rms_height_grid": float(np.std(surface.heights)),
        "rms_slope_measurement": _rms_slope(patch, spacing),
        "rms_slope_grid": _rms_slope(np.asarray(surface.heights), (surface.spacing,) * surface.ndim),
        "variance_above_grid_nyquist": rec["variance_above_grid_nyquist"],
    }


def _patch_argument(record):
    """The ``patch`` argument that selected a surface's patch (from its record)."""
    patch = record.get("patch")
    if not patch or patch.get("selection") == "centre" or len(patch.get("origin", ())) < 2:
        return "centre"
    return (*patch["origin"], patch["side"])


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
