"""Rigid surfaces: every constructor of the :class:`~bem.surface.Surface` type.

Periodic sinusoids and measured files are made here; self-affine rough surfaces in
:mod:`bem.self_affine`, indenters (sphere, cylinder) in :mod:`bem.indenters`, and all are
reached as ``bem.surfaces.<name>``.

Conventions (docs/theory.md §4, §5). Heights ``h`` (m) are **positive toward the half-space**, so
contact starts at ``max(h)``. A surface is a 1-D profile ``h[ix]`` or a square 2-D map
``h[ix, iy]`` (axis 0 is x, the sliding direction) on a cell of side ``length`` (m) with
``n`` points per side, spacing ``length / n``. Periodic cells put point ``j`` at
``x_j = j * spacing`` (as :mod:`bem.fft`); ``centered`` surfaces (isolated indenters) put
it at the centre of element ``j`` of a domain centred on the indenter,
``x_j = (j + 1/2) * spacing - length / 2``.

PSD normalisation and the target spectrum of :func:`self_affine` are stated in
:mod:`bem.statistics`.
"""

from pathlib import Path

import numpy as np

from .checks import check_int, check_positive, show
from .errors import InputError
from .indenters import cylinder, sphere
from .self_affine import profile, self_affine
from .surface import Surface, from_heights

__all__ = ["Surface", "from_heights", "self_affine", "profile", "sinusoid", "load", "sphere", "cylinder"]

_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9}


def sinusoid(n, length, *, amplitude, wavelength=None, dim=1, direction="x", name="sinusoid"):
    """Periodic sinusoid ``h = amplitude cos(2 pi x / wavelength)``, peak (first contact) at x = 0.

    Parameters
    ----------
    n : int
        Points per side, >= 2, with ``wavelength > 2 length / n``.
    length : float
        Cell side (m).
    amplitude : float
        Peak height (m), > 0; the rms height is ``amplitude / sqrt(2)`` (``/ 2`` for "xy").
    wavelength : float, optional
        Period (m), ``length`` divided by a whole number (default ``length``).
    dim : {1, 2}
        Profile ``h[ix]`` or surface ``h[ix, iy]``.
    direction : {"x", "y", "xy"}
        2-D only: a wave along x (ridges along y), along y, or the egg box
        ``amplitude cos(2 pi x / wavelength) cos(2 pi y / wavelength)``.

    Examples
    --------
    >>> s = sinusoid(8, 1.0, amplitude=2.0)
    >>> float(s.heights[0]), float(s.heights[4])
    (2.0, -2.0)
    """
    n = check_int("n", n, 2)
    length = check_positive("length", length)
    amplitude = check_positive("amplitude", amplitude)
    dim = check_int("dim", dim, 1, 2)
    wavelength = length if wavelength is None else check_positive("wavelength", wavelength)
    periods = round(length / wavelength)
    if periods < 1 or abs(length / wavelength - periods) > 1e-9 * length / wavelength:
        raise InputError(
            f"wavelength must be length / k for a whole number k >= 1 (periodic cell, "
            f"length = {show(length)}), got {show(wavelength)}"
        )
    if 2 * periods >= n:
        raise InputError(
            f"wavelength must be > 2 spacing = {show(2 * length / n)} (resolved on n = {n}), got {show(wavelength)}"
        )
    valid = ("x",) if dim == 1 else ("x", "y", "xy")
    if direction not in valid:
        raise InputError(f"direction must be one of {valid} for dim={dim}, got {show(direction)}")
    wave = np.cos(2 * np.pi * periods * np.arange(n) / n)
    if dim == 1:
        heights = amplitude * wave
    else:
        heights = (
            amplitude
            * {"x": wave[:, None] * np.ones(n), "y": np.ones(n)[:, None] * wave, "xy": np.outer(wave, wave)}[direction]
        )
    meta = {"kind": "sinusoid", "amplitude": amplitude, "wavelength": length / periods, "direction": direction}
    return Surface(heights, length, name=name, metadata=meta)


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
