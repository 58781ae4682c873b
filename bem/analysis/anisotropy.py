"""Anisotropy measures of fields on a periodic cell (docs/theory.md §6; the seed's section 3).

Conventions: fields are 2-D arrays ``f[ix, iy]`` on a square periodic cell of side
``length`` (m), axis 0 = x; Fourier coefficients as in :mod:`bem.fft`. Every measure is
reported in the frame of the sliding direction ``direction`` (radians from ``+x`` toward
``+y``, default 0, as in :func:`bem.solve`): its first axis ``s`` is the sliding direction,
its second ``t`` is ``s`` turned by ``+pi/2``, and angles ``theta`` are measured from the
sliding direction toward ``t``. With ``direction = 0`` these are x, y and angles from ``+x``.

Spectral moments. ``m20 = <(df/dx)**2>``, ``m02 = <(df/dy)**2>``, ``m11 = <df/dx df/dy>``
with spectral derivatives (``i q`` multipliers; the Nyquist row and column, whose ``i q``
is not a real operator, are dropped, so the derivative of a real field is real). Then the
second spectral moment of the profiles along ``theta``,
``m2(theta) = m20 cos**2 + 2 m11 sin cos + m02 sin**2``, is exactly the mean square slope
along ``theta``. ``gamma = min m2 / max m2 <= 1`` (the eigenvalues of the moment tensor)
and ``theta_max`` (in ``[0, pi)``) is the direction of the maximum.

Contact PSD. ``C_chi(q) = |chi_q|**2 (L / 2 pi)**2`` of the *fluctuation* ``chi - <chi>``
of the contact indicator (the mean only puts a delta at ``q = 0``), averaged over the
maps given (an ensemble) and smoothed by a normalised Gaussian convolution over
neighbouring modes (a periodogram has 100 % scatter per mode). ``C_chi(0)`` is the
smoothed limit ``q -> 0`` (the ``q = 0`` mode itself is excluded from the average), so
``C_chi(q) / C_chi(0)`` starts at 1 and its iso-contour at level ``c`` (seed: 0.476)
marks the size and shape of the contact spots: spots elongated along y give a contour
stretched along ``q_x``.
"""

import dataclasses
from dataclasses import dataclass

import numpy as np
import scipy.fft as sfft
from scipy import ndimage

from .. import fft
from ..checks import check_array, check_int, check_positive, check_range
from ..errors import InputError
from ..parallel import get_threads

__all__ = [
    "ContactPSD",
    "Ellipse",
    "SpectralMoments",
    "contact_psd",
    "moments_from_tensor",
    "psd_contour",
    "relative_moments",
    "spectral_moments",
]

SEED_LEVEL = 0.476


@dataclass(frozen=True)
class SpectralMoments:
    """Second spectral moments of a 2-D field (units: field unit squared per m squared).

    Attributes
    ----------
    m20, m02, m11 : float
        ``<fs**2>``, ``<ft**2>``, ``<fs ft>`` (spectral derivatives along the sliding direction
        ``s`` and across it, ``t``; x and y for ``direction = 0``).
    gamma : float
        ``min m2 / max m2`` in ``[0, 1]`` (1 for an isotropic field).
    theta_max : float
        Direction of the maximum of ``m2`` (radians from the sliding direction, in ``[0, pi)``).
    direction : float
        The sliding direction (radians from ``+x``) the moments are measured from.
    """

    m20: float
    m02: float
    m11: float
    gamma: float
    theta_max: float
    direction: float = 0.0

    def m2(self, theta):
        """Mean square slope along ``theta`` (radians from the sliding direction, array_like)."""
        t = np.asarray(theta, dtype=float)
        c, s = np.cos(t), np.sin(t)
        return self.m20 * c**2 + 2 * self.m11 * s * c + self.m02 * s**2

    @property
    def m2_max(self):
        return float(self.m2(self.theta_max))

    @property
    def m2_min(self):
        return float(self.m2(self.theta_max + np.pi / 2))

    def as_dict(self):
        return {
            "m20": self.m20,
            "m02": self.m02,
            "m11": self.m11,
            "gamma": self.gamma,
            "theta_max": self.theta_max,
            "direction": self.direction,
        }


def _in_sliding_frame(m20, m02, m11, direction):
    """The moment tensor in the frame ``(s, t)`` of the sliding direction (radians from +x)."""
    c, s = np.cos(direction), np.sin(direction)
    return (
        m20 * c * c + 2 * m11 * c * s + m02 * s * s,
        m20 * s * s - 2 * m11 * c * s + m02 * c * c,
        (m02 - m20) * c * s + m11 * (c * c - s * s),
    )


def moments_from_tensor(m20, m02, m11):
    """:class:`SpectralMoments` of the second-moment tensor ``[[m20, m11], [m11, m02]]``: its
    eigenvalue ratio ``gamma = min/max`` and the direction of its largest eigenvalue."""
    half_sum, half_diff = 0.5 * (m20 + m02), 0.5 * (m20 - m02)
    radius = np.hypot(half_diff, m11)
    lo, hi = half_sum - radius, half_sum + radius
    gamma = lo / hi if hi > 0 else 1.0
    theta = 0.5 * np.arctan2(2 * m11, m20 - m02) % np.pi
    return SpectralMoments(float(m20), float(m02), float(m11), float(gamma), float(theta))


def _check_field(name, field, length):
    f = check_array(name, field, ndim=2)
    if f.shape[0] != f.shape[1] or f.shape[0] < 4:
        raise InputError(f"{name} must be a square 2-D array (n, n) with n >= 4, got shape {f.shape}")
    return f, check_positive("length", length)


def spectral_moments(field, length, *, direction=0.0):
    """Second spectral moments ``m20, m02, m11``, ``gamma`` and ``theta_max`` of a 2-D field.

    Parameters
    ----------
    field : array_like
        Square 2-D field ``f[ix, iy]`` (e.g. the deformed surface, m), periodic.
    length : float
        Cell side (m).
    direction : float
        Sliding direction (radians from ``+x``): the moments and angles are measured from it.

    Returns
    -------
    SpectralMoments
        With ``.m2(theta)``.

    Examples
    --------
    >>> x = np.arange(16) / 16
    >>> f = np.cos(2 * np.pi * x)[:, None] + 0 * x    # ridges along y: slopes along x only
    >>> sm = spectral_moments(f, 1.0)
    >>> [round(v, 12) for v in (sm.m20 / (2 * np.pi**2), sm.m02, sm.gamma, sm.theta_max)]
    [1.0, 0.0, 0.0, 0.0]
    """
    f, length = _check_field("field", field, length)
    fq = fft.forward(f)
    qx, qy = fft.wavevectors(f.shape, length)
    n = f.shape[0]
    qx = np.where(np.arange(n)[:, None] == n // 2, 0.0, qx) if n % 2 == 0 else qx
    qy = np.where(np.arange(qy.shape[1])[None, :] == n // 2, 0.0, qy) if n % 2 == 0 else qy
    w = fft.full_spectrum_weights(f.shape) * np.abs(fq) ** 2
    direction = _check_direction(direction)
    tensor = _in_sliding_frame(np.sum(w * qx**2), np.sum(w * qy**2), np.sum(w * qx * qy), direction)
    return dataclasses.replace(moments_from_tensor(*tensor), direction=direction)


def _check_direction(direction):
    try:
        theta = float(direction)
    except (TypeError, ValueError):
        raise InputError(f"direction must be an angle in radians, got {direction!r}") from None
    if not np.isfinite(theta):
        raise InputError(f"direction must be a finite angle in radians, got {direction!r}")
    return theta


def relative_moments(moments, reference):
    """Anisotropy of ``moments`` relative to ``reference`` (both :class:`SpectralMoments`).

    The moment tensor ``M`` is whitened by the reference tensor ``M0``:
    ``M0**-1/2 M M0**-1/2``, so a field whose slopes grew equally in every direction with
    respect to the reference has ``gamma = 1``; ``theta_max`` is the direction (in the
    original coordinates) along which ``m2`` grew most relative to the reference. Used to
    separate speed-induced anisotropy from a realisation's own. Both must be measured from
    the same sliding direction; the result is too.
    """
    if moments.direction != reference.direction:
        raise InputError(
            f"reference must be measured from the same sliding direction as moments "
            f"({moments.direction!r} rad), got {reference.direction!r} rad"
        )
    m0 = np.array([[reference.m20, reference.m11], [reference.m11, reference.m02]])
    m = np.array([[moments.m20, moments.m11], [moments.m11, moments.m02]])
    vals, vecs = np.linalg.eigh(m0)
    if not vals.min() > 0:
        raise InputError("reference moments must be positive definite (a field with slopes in two directions)")
    root = vecs @ np.diag(vals**-0.5) @ vecs.T
    r = root @ m @ root
    rel = moments_from_tensor(r[0, 0], r[1, 1], r[0, 1])
    # direction in the original frame: ratio m2(theta) / m2_0(theta) is largest along it
    theta = np.linspace(0, np.pi, 721)[:-1]
    ratio = moments.m2(theta) / reference.m2(theta)
    return SpectralMoments(rel.m20, rel.m02, rel.m11, rel.gamma, float(theta[np.argmax(ratio)]), moments.direction)


@dataclass(frozen=True, eq=False)
class ContactPSD:
    """Smoothed contact-indicator PSD on the full, centred spectrum grid.

    Attributes
    ----------
    q : ndarray
        Wavevector axis (rad/m), ``(n,)``, centred (``q[n // 2] == 0``), same along x and y.
    C : ndarray
        ``C_chi[iqx, iqy]`` (m**4), smoothed, ``C[n//2, n//2] = C_chi(0)`` (the limit).
    level_map : ndarray
        ``C / C_chi(0)``.
    contact_fraction : float
        Mean of the indicator (over the maps).
    smoothing : float
        Gaussian width of the smoothing (in grid modes, ``q_L``).
    """

    q: np.ndarray
    C: np.ndarray
    contact_fraction: float
    smoothing: float

    @property
    def c0(self):
        n = self.q.size
        return float(self.C[n // 2, n // 2])

    @property
    def level_map(self):
        return self.C / self.c0


def periodogram_full(chi, length):
    """Full centred periodogram of the fluctuation of one indicator map (m**4)."""
    c = np.asarray(chi, dtype=float)
    cq = sfft.fftn(c - c.mean(), norm="forward", workers=get_threads())
    return sfft.fftshift(np.abs(cq) ** 2) * (length / (2 * np.pi)) ** 2


def contact_psd(chi, length, *, smoothing=1.0):
    """PSD of the contact indicator ``chi`` (one map or a stack ``(K, n, n)``, averaged).

    Parameters
    ----------
    chi : array_like
        Indicator(s): booleans or 0/1, ``(n, n)`` or ``(K, n, n)``.
    length : float
        Cell side (m).
    smoothing : float
        Width (standard deviation, in grid modes ``q_L``) of the normalised Gaussian
        smoothing, in ``[0.25, n / 4]``. At ``q = 0`` the average runs over the other modes
        only, which defines ``C_chi(0)`` as the limit ``q -> 0``.

    Returns
    -------
    ContactPSD
    """
    a = check_array("chi", np.asarray(chi, dtype=float), ndim=(2, 3))
    maps = a if a.ndim == 3 else a[None]
    n = maps.shape[1]
    if maps.shape[2] != n or n < 4:
        raise InputError(f"chi must be square maps (n, n) or (K, n, n) with n >= 4, got shape {a.shape}")
    if np.any((maps != 0) & (maps != 1)):
        raise InputError("chi must be a contact indicator (0/1 or booleans)")
    length = check_positive("length", length)
    sigma = check_range("smoothing", smoothing, 0.25, n / 4)
    raw = np.mean([periodogram_full(m, length) for m in maps], axis=0)
    weight = np.ones_like(raw)
    weight[n // 2, n // 2] = 0.0
    raw[n // 2, n // 2] = 0.0
    num = ndimage.gaussian_filter(raw, sigma, mode="wrap", truncate=4.0)
    den = ndimage.gaussian_filter(weight, sigma, mode="wrap", truncate=4.0)
    q = 2 * np.pi / length * (np.arange(n) - n // 2)
    return ContactPSD(q=q, C=num / den, contact_fraction=float(maps.mean()), smoothing=sigma)


@dataclass(frozen=True, eq=False)
class Ellipse:
    """Ellipse fitted to an iso-contour of a centred spectrum.

    In the frame of the sliding direction ``direction`` (radians from ``+q_x``):
    ``A qs**2 + 2 B qs qt + D qt**2 = 1`` with ``qs`` along the sliding direction and ``qt``
    across it (``qx, qy`` for ``direction = 0``); ``semi_axes = (major, minor)`` (rad/m);
    ``aspect_ratio = major / minor >= 1``; ``orientation`` = direction of the major axis
    (radians from the sliding direction, in ``[0, pi)``); ``stretch_x`` = extent along the
    sliding direction over extent across it (> 1: stretched along the sliding direction).
    ``points`` are the contour points ``(qs, qt)`` (rad/m) found along rays; ``residual``
    the rms relative misfit of the fit.
    """

    A: float
    B: float
    D: float
    points: np.ndarray
    level: float
    residual: float
    direction: float = 0.0

    @property
    def _eig(self):
        return np.linalg.eigh(np.array([[self.A, self.B], [self.B, self.D]]))

    @property
    def semi_axes(self):
        vals = self._eig[0]
        return float(vals[0] ** -0.5), float(vals[1] ** -0.5)

    @property
    def aspect_ratio(self):
        major, minor = self.semi_axes
        return major / minor

    @property
    def orientation(self):
        vec = self._eig[1][:, 0]
        return float(np.arctan2(vec[1], vec[0]) % np.pi)

    @property
    def stretch_x(self):
        return float(np.sqrt(self.D / self.A))

    def as_dict(self):
        major, minor = self.semi_axes
        return {
            "level": self.level,
            "semi_major": major,
            "semi_minor": minor,
            "aspect_ratio": self.aspect_ratio,
            "orientation": self.orientation,
            "stretch_x": self.stretch_x,
            "fit_residual": self.residual,
            "direction": self.direction,
        }


def psd_contour(cpsd, level=SEED_LEVEL, *, rays=180, step=0.02, direction=0.0):
    """Iso-contour ``C_chi(q) / C_chi(0) = level`` and the centred ellipse fitted to it.

    Along each of ``rays`` directions the normalised map is interpolated (cubic splines
    between grid modes) outward from ``q = 0`` in steps of ``step`` grid modes; the first
    crossing below ``level`` is located by linear interpolation between steps. A centred
    ellipse is fitted to the points by linear least squares (the PSD of a real field is
    even in ``q``), in the frame of the sliding direction ``direction`` (radians from ``+q_x``).

    Returns
    -------
    Ellipse
    """
    level = check_range("level", level, 1e-6, 1 - 1e-6)
    rays = check_int("rays", rays, 8)
    step = check_range("step", step, 1e-3, 0.5)
    n = cpsd.q.size
    dq = float(cpsd.q[1] - cpsd.q[0])
    ratio = cpsd.level_map
    coeffs = ndimage.spline_filter(ratio, order=3, mode="grid-wrap")
    r = np.arange(0, n / 2 - 1, step)
    phi = np.pi * np.arange(rays) / rays  # half circle suffices (even), mirrored below
    ix = n // 2 + np.outer(np.cos(phi), r)
    iy = n // 2 + np.outer(np.sin(phi), r)
    vals = ndimage.map_coordinates(
        coeffs, [ix.ravel(), iy.ravel()], order=3, mode="grid-wrap", prefilter=False
    ).reshape(ix.shape)
    pts = []
    for k in range(rays):
        below = np.nonzero(vals[k] < level)[0]
        if below.size == 0 or below[0] == 0:
            continue
        j = below[0]
        f0, f1 = vals[k, j - 1], vals[k, j]
        rc = r[j - 1] + step * (f0 - level) / (f0 - f1)
        pts.append((rc * np.cos(phi[k]), rc * np.sin(phi[k])))
    if len(pts) < 8:
        raise InputError(
            f"level {level!r}: the contour C/C0 = level was found along only {len(pts)} of "
            f"{rays} rays; choose a level between the map's values"
        )
    p = np.array(pts) * dq
    theta = _check_direction(direction)
    c, sn = np.cos(theta), np.sin(theta)
    p = np.column_stack([p[:, 0] * c + p[:, 1] * sn, -p[:, 0] * sn + p[:, 1] * c])  # (qs, qt)
    p = np.vstack([p, -p])
    design = np.column_stack([p[:, 0] ** 2, 2 * p[:, 0] * p[:, 1], p[:, 1] ** 2])
    coef, *_ = np.linalg.lstsq(design, np.ones(len(p)), rcond=None)
    resid = float(np.sqrt(np.mean((design @ coef - 1) ** 2)))
    if not (coef[0] > 0 and coef[2] > 0 and coef[0] * coef[2] > coef[1] ** 2):
        raise InputError(f"level {level!r}: the contour is not an ellipse (fit is indefinite)")
    return Ellipse(
        A=float(coef[0]), B=float(coef[1]), D=float(coef[2]), points=p, level=level, residual=resid, direction=theta
    )
