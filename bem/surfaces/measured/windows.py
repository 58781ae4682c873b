"""Making a measured patch periodic (the solver's cell is periodic; a scan's opposite edges do not
match), putting it on the solver's grid, and what the grid loses.

Windows (``window``), chosen by measurement (``viscobem bench measured``: patches cut from
periodic surfaces whose friction is known):

* ``"mirror"`` (the default for scans that are not periodic): the patch tiled with its mirror
  images, a cell twice the patch's side with continuous heights (slopes reverse at the seams).
  Nothing is flattened or removed, and the four copies share the cell's load, so the load per
  patch area is unchanged. Sliding along ``x`` over the mirrored copies is sliding along ``-x``
  over the scan, so a scan whose friction differs between the two directions (a sawtooth
  texture) gets their mean.
* ``"periodic_component"``: Moisan's periodic plus smooth decomposition (a harmonic field that
  carries the edge mismatch is removed; the cell is the patch).
* ``"tukey"`` (``alpha`` = tapered fraction) or ``"hann"``: the heights (about their mean)
  multiplied by the separable window, flattening the edges.
* ``"none"``: the jump kept (right only when the scan itself is periodic: the default then).

The periodic field is then resampled by Fourier interpolation (:func:`fourier_resample`), which
keeps exactly the modes the grid can hold; an isolated patch gets element means
(:func:`element_means`).
"""

import numpy as np

__all__ = [
    "WINDOWS",
    "DEFAULT_WINDOW",
    "PERIODIC_MISMATCH",
    "periodic_component",
    "edge_mismatch",
    "periodic_field",
    "fourier_resample",
    "element_means",
    "variance_above",
]

WINDOWS = ("mirror", "periodic_component", "tukey", "hann", "none")
DEFAULT_WINDOW = "mirror"  # for scans that are not periodic: chosen by `viscobem bench measured`
# Relative edge mismatch (rms jump across opposite edges over rms height) below which a scan
# counts as periodic enough for window="none": a self-affine scan that is not periodic has ~1.4.
PERIODIC_MISMATCH = 0.05


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


def periodic_field(patch, kind, alpha):
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


def fourier_resample(field, n):
    import scipy.signal as ssig

    out = field
    for axis in range(field.ndim):
        out = ssig.resample(out, n, axis=axis)
    return out


def element_means(patch, n):
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


def variance_above(field, spacing, q_max):
    """Fraction of the variance of the periodic ``field`` at ``|q| > q_max`` (rad/m)."""
    f = np.abs(np.fft.fftn(field - field.mean())) ** 2
    qs = np.meshgrid(*[2 * np.pi * np.fft.fftfreq(m, d) for m, d in zip(f.shape, spacing)], indexing="ij")
    above = np.sqrt(sum(g**2 for g in qs)) > q_max * (1 + 1e-9)
    return float(f[above].sum() / max(f.sum(), 1e-300))
