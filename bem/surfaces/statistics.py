"""Statistics of rough surfaces: rms height, rms slope and power spectral density (PSD).

Everything is computed spectrally on the periodic cell, with the coefficients ``h_q`` of
:mod:`bem.fft` (``h(x) = sum_q h_q exp(i q.x)``, ``q_L = 2 pi / L`` the grid step in q).

PSD normalisation (the one used throughout viscobem)::

    2-D:  C(q) = |h_q|**2 (L / 2 pi)**2    so  <h**2> = sum_q C(q) q_L**2  ~ integral C(q) d2q
    1-D:  C(q) = |h_q|**2 (L / 2 pi)       so  <h**2> = sum_q C(q) q_L     ~ integral C(q) dq

where the sums run over the full spectrum (both signs of each component) and the 1-D
integral over ``-inf < q < inf``. Units: m**4 in 2-D, m**3 in 1-D; wavevectors in rad/m.
The mean (``q = 0``) is excluded from every statistic: rms height is about the mean plane.

Inputs are a :class:`bem.surfaces.Surface` (anything with ``heights`` and ``length``) or
an array with the cell side ``length`` (m) beside it. Derivatives are spectral: the cell
is treated as periodic, as the solvers treat it.
"""

import numpy as np

from .. import fft
from ..checks import check_array, check_int, check_positive, check_range, show
from ..errors import InputError

__all__ = ["periodogram", "rms_height", "rms_slope", "psd", "psd_target"]


def _field(surface, length, *, need_length=True):
    """Heights (float array, a copy) and cell side of a surface or of an array."""
    if hasattr(surface, "heights") and hasattr(surface, "length"):
        if length is not None:
            raise InputError(f"length is taken from the surface; pass None, got {show(length)}")
        return np.asarray(surface.heights, dtype=float), float(surface.length)
    h = check_array("heights", surface, ndim=(1, 2))
    if h.ndim == 2 and h.shape[0] != h.shape[1]:
        raise InputError(f"heights must be 1-D or square 2-D, got shape {h.shape}")
    if h.shape[0] < 2:
        raise InputError(f"heights must have at least 2 points per side, got shape {h.shape}")
    if length is None:
        if need_length:
            raise InputError("length (cell side, m) must be given with an array of heights, got None")
        return h, None
    return h, check_positive("length", length)


def psd_moments(c, q, shape):
    """Full-spectrum sums ``sum C q_L**d`` and ``sum |q|**2 C q_L**d`` of a half-spectrum PSD.

    ``q`` are the wavevector components of :func:`bem.fft.wavevectors` for ``shape``;
    with ``C`` normalised as in the module docstring these are ``<h**2>`` and
    ``<|grad h|**2>``.
    """
    w = fft.full_spectrum_weights(shape)
    dq = float(np.ravel(q[0])[1]) ** len(shape)
    q2 = sum(qi**2 for qi in q)
    return float(np.sum(w * c) * dq), float(np.sum(w * q2 * c) * dq)


def periodogram(surface, length=None):
    """PSD ``C(q)`` of every grid mode, on the half-spectrum grid of :func:`bem.fft.forward`.

    Parameters
    ----------
    surface : Surface or array_like
        Heights (m), 1-D ``(n,)`` or square 2-D ``(n, n)``.
    length : float, optional
        Cell side (m); required for an array, omitted for a surface.

    Returns
    -------
    ndarray
        ``C`` (m**4 in 2-D, m**3 in 1-D) at the wavevectors ``bem.fft.wavevectors``; the
        ``q = 0`` entry is the squared mean times the same factor. Sum over the full
        spectrum with :func:`bem.fft.full_spectrum_weights`.
    """
    h, L = _field(surface, length)
    return np.abs(fft.forward(h)) ** 2 * (L / (2 * np.pi)) ** h.ndim


def rms_height(surface, length=None):
    """Root mean square height about the mean plane (m), ``sqrt(sum_{q != 0} |h_q|**2)``.

    Parameters
    ----------
    surface : Surface or array_like
        Heights (m); ``length`` is not needed (nor allowed with a surface).
    length : float, optional
        Cell side (m), accepted for symmetry with :func:`rms_slope`.

    Examples
    --------
    >>> round(rms_height([1.0, -1.0, 1.0, -1.0]), 12)
    1.0
    """
    h, _ = _field(surface, length, need_length=False)
    hq = fft.forward(h)
    w = fft.full_spectrum_weights(h.shape)
    hq.flat[0] = 0.0
    return float(np.sqrt(np.sum(w * np.abs(hq) ** 2)))


def rms_slope(surface, length=None):
    """Root mean square slope (dimensionless), ``sqrt(sum_q |q|**2 |h_q|**2)``.

    In 2-D this is the rms of the gradient magnitude, ``sqrt(<|grad h|**2>)``. The derivative
    is spectral (exact for band-limited periodic heights, such as the generated ones).

    Parameters
    ----------
    surface : Surface or array_like
        Heights (m).
    length : float, optional
        Cell side (m); required for an array.
    """
    h, L = _field(surface, length)
    q = fft.wavevectors(h.shape, L)
    c = np.abs(fft.forward(h)) ** 2
    w = fft.full_spectrum_weights(h.shape)
    return float(np.sqrt(np.sum(w * sum(qi**2 for qi in q) * c)))


def psd(surface, length=None, *, bins=None):
    """Radially averaged PSD ``(q, C(q))`` of a 1-D profile or 2-D surface.

    Parameters
    ----------
    surface : Surface or array_like
        Heights (m).
    length : float, optional
        Cell side (m); required for an array.
    bins : None, int or array_like, optional
        ``None`` (default): no binning -- one entry per distinct ``|q|`` on the grid, the
        average over the modes sharing it (exact: for an isotropic generated surface it is
        the target PSD itself). An int: that many log-spaced bins from ``q_L`` to the largest
        ``|q|`` on the grid. An array: increasing bin edges (rad/m). Empty bins are dropped.

    Returns
    -------
    q : ndarray
        Wavevector magnitudes (rad/m): the exact ``|q|`` (unbinned) or the mean ``|q|`` of
        the modes in each bin.
    C : ndarray
        Mean PSD of those modes (m**4 in 2-D, m**3 in 1-D), normalised as in the module
        docstring; the ``q = 0`` mode is excluded.
    """
    h, L = _field(surface, length)
    c = periodogram(h, L)
    q = fft.wavevectors(h.shape, L)
    mag = np.sqrt(sum(qi**2 for qi in q))
    w = fft.full_spectrum_weights(h.shape) * np.ones_like(c)
    keep = mag > 0
    mag, c, w = mag[keep], c[keep], w[keep]
    q_l = 2 * np.pi / L
    if bins is None:
        levels, index = np.unique(np.rint((mag / q_l) ** 2).astype(np.int64), return_inverse=True)
        q_out = q_l * np.sqrt(levels)
    else:
        if np.ndim(bins) == 0:
            edges = np.geomspace(q_l, mag.max(), check_int("bins", bins, 1) + 1)
            edges[0], edges[-1] = 0.999 * q_l, 1.001 * mag.max()
        else:
            edges = check_array("bins", bins, ndim=1, min_size=2)
            if np.any(np.diff(edges) <= 0):
                raise InputError(f"bins must be strictly increasing edges (rad/m), got {show(edges)}")
        index = np.searchsorted(edges, mag, side="right") - 1
        inside = (index >= 0) & (index < edges.size - 1)
        mag, c, w, index = mag[inside], c[inside], w[inside], index[inside]
        q_out = None
    total = np.bincount(index, weights=w)
    used = total > 0
    c_out = np.bincount(index, weights=w * c)[used] / total[used]
    if q_out is None:
        q_out = np.bincount(index, weights=w * mag)[used] / total[used]
    return q_out, c_out


def psd_target(
    q, *, hurst, cutoff_wavevector, rolloff_wavevector, dim=2, prefactor=1.0, anisotropy=1.0, directional_factor=1.0
):
    """Target PSD of the self-affine generator (:func:`bem.surfaces.self_affine`).

    Isotropic shape ``S(q) = max(q, q_r)**e`` for ``0 < q <= q_1``, zero at ``q = 0`` and
    above ``q_1``, with ``e = -2 (1 + H)`` in 2-D and ``e = -(1 + 2 H)`` in 1-D; on a grid
    of cell side ``L`` the smallest nonzero ``q`` is ``q_L``, so the plateau covers
    ``q_L <= q < q_r``. ``C = prefactor * S``. Anisotropic 2-D spectra need components
    ``q = (qx, qy)`` and read ``C = prefactor * S(q_e) * (qx**2 + b qy**2) / |q|**2`` with
    ``q_e = hypot(min(s, 1) qx, qy / max(s, 1))``, ``s = anisotropy`` and
    ``b = directional_factor`` (see the generator).

    The generator stores these keywords as ``surface.metadata["spectrum"]``, so
    ``psd_target(surface.wavevectors(), **surface.metadata["spectrum"])`` equals
    :func:`periodogram` of the surface (to round-off).

    Parameters
    ----------
    q : array_like or tuple of array_like
        Magnitudes ``|q|`` (rad/m, isotropic only), or components ``(qx,)`` / ``(qx, qy)``
        as returned by :func:`bem.fft.wavevectors`.
    hurst : float
        Hurst exponent ``H`` in [0, 1].
    cutoff_wavevector, rolloff_wavevector : float
        ``q_1`` and ``q_r`` (rad/m), ``q_r <= q_1``.
    dim : {1, 2}
        Dimension of the PSD (sets the exponent ``e``).
    prefactor : float
        ``C(q_r)`` divided by ``q_r**e`` (m**4 or m**3 times (rad/m)**-e).
    anisotropy, directional_factor : float
        ``s`` and ``b`` above (1 for isotropic spectra).

    Returns
    -------
    ndarray
        ``C`` broadcast over ``q`` (m**4 in 2-D, m**3 in 1-D).
    """
    hurst = check_range("hurst", hurst, 0.0, 1.0)
    dim = check_int("dim", dim, 1, 2)
    q_1 = check_positive("cutoff_wavevector", cutoff_wavevector)
    q_r = check_positive("rolloff_wavevector", rolloff_wavevector)
    if q_r > q_1:
        raise InputError(
            f"rolloff_wavevector must be in (0, cutoff_wavevector = {q_1}], got {show(rolloff_wavevector)}"
        )
    prefactor = check_positive("prefactor", prefactor, allow_zero=True)
    s = check_positive("anisotropy", anisotropy)
    b = check_positive("directional_factor", directional_factor)
    exponent = -2.0 * (1.0 + hurst) if dim == 2 else -(1.0 + 2.0 * hurst)
    factor = 1.0
    if isinstance(q, tuple) and len(q) == 2:
        qx, qy = (np.asarray(qi, dtype=float) for qi in q)
        mag2 = qx**2 + qy**2
        q_eff = np.hypot(min(s, 1.0) * qx, qy / max(s, 1.0))
        factor = (qx**2 + b * qy**2) / np.where(mag2 > 0, mag2, 1.0)
    elif s != 1.0 or b != 1.0:
        raise InputError(
            f"q must be components (qx, qy) for anisotropy != 1 or directional_factor != 1, "
            f"got anisotropy={show(s)}, directional_factor={show(b)}"
        )
    else:
        q_eff = np.abs(np.asarray(q[0] if isinstance(q, tuple) else q, dtype=float))
    shape = np.maximum(q_eff, q_r) ** exponent
    support = (q_eff > 0) & (q_eff <= q_1 * (1 + 1e-9))
    return np.where(support, prefactor * shape * factor, 0.0)
