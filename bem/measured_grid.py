"""A measured topography on the solver's grid: square patch, boundary choice, resampling, PSD.

A measurement is a finite patch, rarely periodic. How it is solved is an explicit choice,
recorded in ``surface.metadata["measured"]``:

- ``boundary="isolated"``: the patch is the loaded domain of an isolated contact
  (:mod:`bem.isolated`; pressure outside it is zero). Each element gets the mean height of
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
"""

import numpy as np
import scipy.signal as ssig
from scipy import ndimage

from .checks import check_int, check_range
from .errors import InputError
from .measured import Measurement
from .surfaces import Surface

__all__ = ["BOUNDARIES", "WINDOWS", "psd_report", "square_patch", "to_surface"]

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
    w = 1.0
    for axis, n in enumerate(patch.shape):
        shape = [1] * patch.ndim
        shape[axis] = n
        win = ssig.windows.tukey(n, alpha, sym=True) if kind == "tukey" else ssig.windows.hann(n, sym=True)
        w = w * win.reshape(shape)
    return base + (patch - base) * w


def _fourier_resample(field, n):
    out = field
    for axis in range(field.ndim):
        out = ssig.resample(out, n, axis=axis)
    return out


def _element_means(patch, n):
    """Mean heights of ``n`` equal elements per axis: the cubic spline of ``patch`` averaged over
    ``k`` midpoints per axis and element (``k`` = measured pixels per element, rounded up), a box
    filter that keeps the grid free of aliases of the finer scan."""
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
        Heights in m (detrend it first, :func:`bem.measured.detrend`).
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
        raise InputError(f"measurement must be a bem.measured.Measurement, got {type(measurement).__name__}")
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
