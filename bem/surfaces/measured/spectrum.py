"""The spectrum of a measured scan (which need not be periodic) and a report of what the solver's
grid keeps of it.
"""

import numpy as np

from ...checks import check_int
from .patch import patch_argument, square_patch

__all__ = ["psd", "psd_report"]


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
    patch, side = square_patch(measurement, patch_argument(rec))
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
