"""The square patch of a scan that is solved, how its boundary is treated, and the load and speed
that go with it; :func:`from_scan`, the one entry for measured topographies.

**The patch.** Solver cells are square; a scan need not be. The solved patch is a square of
the scan (``patch="centre"``, the largest centred one, by default; or a given origin and side),
and the surface says which: ``metadata["measured"]["patch"]`` (origin, side, points, fraction
of the scan's area), with a warning when the automatic choice is not the whole scan. :func:`cover`
lists squares that together cover the whole scan, to solve each (the scene's ``patch = "cover"``).

**The boundary** (docs/theory.md §5.1). A scan is a patch of a larger surface whose
surroundings carry the same nominal pressure; neither of its edges is special.

- ``boundary="periodic"`` (default): the patch becomes one periodic cell, made periodic first by
  a window (:mod:`.windows`; ``"mirror"`` by default for scans that are not periodic). A mirrored
  cell is twice the patch's side and holds the patch 4 times in 2-D (twice in 1-D):
  ``metadata["measured"]["load_factor"]`` is the factor between the load on the cell and the
  load on the patch (:func:`cell_load` converts).
- ``boundary="isolated"``: the patch is the whole loaded domain of an isolated contact
  (:mod:`bem.halfspace.isolated`; no pressure outside it), right for a scan of a whole finite
  body. For a patch of a larger surface it is a rough flat punch: its edges carry the load the
  surroundings would, and it dissipates at the punch's own scale. Each element gets the mean
  height of the scan over it (:func:`~.windows.element_means`).

A choice measured to misrepresent a patch of a larger surface (``"isolated"``; ``"none"`` on a
scan that is not periodic; ``"hann"``, which flattens most of the patch) is allowed and
warned about, as is a cropped scan: each warning is a sentence in
``surface.metadata["measured"]["warnings"]`` and is also issued as a Python ``UserWarning``.

Line scans give 1-D profiles (the whole line is the patch).
"""

import warnings
from os import PathLike

import numpy as np

from ...checks import check_int, check_positive, check_range
from ...errors import InputError
from ...plausibility import height_checks
from ..surface import Surface
from .cleaning import detrend as detrend_
from .cleaning import find_steps
from .reading import Measurement, from_array, read_topography
from .windows import (
    DEFAULT_WINDOW,
    PERIODIC_MISMATCH,
    WINDOWS,
    edge_mismatch,
    element_means,
    fourier_resample,
    periodic_component,
    periodic_field,
    variance_above,
)

__all__ = [
    "BOUNDARIES",
    "PATCHES",
    "square_patch",
    "cover",
    "to_surface",
    "load_factor",
    "cell_load",
    "speed_limit",
    "speed_limit_warning",
    "from_scan",
    "patch_argument",
]

BOUNDARIES = ("periodic", "isolated")
PATCHES = ("centre",)  # or an origin (x0, y0) or (x0, y0, side) in m


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
    elif record["window"] == "none" and not periodic_scan and mismatch > PERIODIC_MISMATCH:
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
    piece = detrend_(piece, detrend)
    done = piece.source["detrend"]
    found = height_checks(
        piece.heights, max(piece.physical_sizes), name="the scan's heights", advice=_unit_advice(piece)
    )
    found += find_steps(piece.heights, piece.spacing)
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
        heights, factor = element_means(piece.heights, n), 1
        field = periodic_component(piece.heights)  # its spectrum without the edges' leakage
        record.update(window=None, sampling="element means of the cubic spline of the scan")
    else:
        if window is None:
            window = "none" if piece.periodic else DEFAULT_WINDOW
        alpha = check_range("alpha", alpha, 1e-6, 1.0) if window == "tukey" else None
        field, factor = periodic_field(piece.heights, window, alpha)
        heights = fourier_resample(field, factor * n)
        record.update(window=window, alpha=alpha, sampling="Fourier interpolation (band-limited)")
    record["variance_above_grid_nyquist"] = variance_above(field, piece.spacing, np.pi * n / side)
    record["cell_side"] = side * factor
    record["load_factor"] = factor**measurement.heights.ndim
    found += _boundary_warnings(record, mismatch, piece.periodic)
    _warn(found)  # the reader's warnings were issued when it read the scan
    record["warnings"] = list(measurement.source.get("warnings", ())) + found
    label = name if name is not None else str(measurement.source.get("path", "measured"))
    return Surface(
        heights,
        side * factor,
        name=label,
        centered=boundary == "isolated",
        metadata={"kind": "measured", "measured": record},
    )


def load_factor(surface):
    """The load on the cell per load on the measured patch of ``surface`` (4 for a mirrored map, 2
    for a mirrored line, else 1), or None for a surface that is not a measured patch."""
    meta = surface.metadata.get("measured") if hasattr(surface, "metadata") else None
    return None if meta is None else meta["load_factor"]


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


def speed_limit_warning(surface, material, speed):
    """The sentence for a solve of the measured ``surface`` at ``speed`` (m/s) above its
    :func:`speed_limit`, or None."""
    limit = speed_limit(surface, material)
    if not speed > limit:
        return None
    side = surface.metadata["measured"]["patch_side"]
    return (
        f"{speed:.3g} m/s is above {limit:.3g} m/s, where the material's loss peak excites wavelengths longer "
        f"than the scanned patch ({1e3 * side:.3g} mm), which the scan does not hold: friction there is "
        "under-estimated (patches of known surfaces were 9-19 % low on average, "
        "bem.surfaces.measured.speed_limit). Scan a larger area for these speeds"
    )


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
    transpose=False,
):
    """A measured scan on the solver's grid: the one entry for measured topographies.

    Parameters
    ----------
    scan : str, os.PathLike, array_like or Measurement
        A topography file (a plain matrix, ``.npy`` or text; or any format SurfaceTopography
        reads, with the ``topography`` extra), an array of heights ``h[ix, iy]`` (or a line
        ``h[ix]``) in ``unit`` with NaN where a point is missing, or a :class:`Measurement`. Any
        rectangular shape; periodic or not. Axes, units and missing points as
        :mod:`bem.surfaces.measured.reading` states.
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
    transpose : bool
        Swap the axes (and sizes) of the file or array: for rows that run along y.
    detrend, boundary, window, alpha, patch, name
        As :func:`to_surface`; ``detrend="plane"`` by default.

    Returns
    -------
    Surface
        See :func:`to_surface`. :func:`bem.solve` takes the load on the patch and gives the
        mirrored cell its share itself (:func:`cell_load`).

    Examples
    --------
    >>> import numpy as np
    >>> h = np.random.default_rng(0).normal(size=(30, 20))   # micrometres, 300 x 200 um
    >>> s = from_scan(h, 16, physical_sizes=(300, 200), unit="um", patch=(0, 0))
    >>> round(s.metadata["measured"]["patch"]["fraction_of_scan"], 4), round(s.length * 1e6, 9), s.n
    (0.6667, 400.0, 32)
    """
    if isinstance(scan, Measurement):
        if unit is not None or physical_sizes is not None or transpose:
            raise InputError("unit, physical_sizes and transpose come with the Measurement; leave them out")
        measurement = scan
    elif isinstance(scan, (str, PathLike)):
        measurement = read_topography(
            scan, unit=unit, physical_sizes=physical_sizes, channel=channel, transpose=transpose
        )
    else:
        measurement = from_array(scan, physical_sizes, "m" if unit is None else unit, transpose=transpose)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        surface = to_surface(
            measurement, n, boundary=boundary, window=window, alpha=alpha, detrend=detrend, patch=patch, name=name
        )
    _warn(str(w.message) for w in caught)
    return surface


def patch_argument(record):
    """The ``patch`` argument that selected a surface's patch (from its record)."""
    patch = record.get("patch")
    if not patch or patch.get("selection") == "centre" or len(patch.get("origin", ())) < 2:
        return "centre"
    return (*patch["origin"], patch["side"])


def _unit_advice(measurement):
    """Which unit to fix when a scan's heights span more than its patch: heights and sizes are
    read in one unit, so either the heights or the sizes were given in another."""
    source = measurement.source
    unit = source.get("file_unit") or "m"
    sizes = " x ".join(f"{x:.4g}" for x in measurement.physical_sizes)
    if source.get("sizes_from_file", False):
        return f"The file gives the scan's sizes as {sizes} m; are its heights in another unit than it says?"
    return (
        f"Heights and physical_sizes are both read in unit ({unit!r}), which makes the scan {sizes} m: "
        "give both in that unit (sizes in metres with unit='um' make the scan a million times too small), "
        "or heights in micrometres given as metres need unit='um'"
    )
