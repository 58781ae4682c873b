"""Randomly rough self-affine surfaces and profiles by the spectral method.

The target spectrum and the PSD normalisation are stated in :mod:`bem.surfaces.statistics`; the grid
conventions in :mod:`bem.surfaces`.
"""

import numpy as np

from .. import fft
from ..checks import check_int, check_positive, check_range, show
from ..errors import InputError
from .statistics import psd_moments, psd_target
from .surface import Surface

__all__ = ["self_affine", "profile"]


def _rng(seed):
    if isinstance(seed, np.random.Generator):
        return seed, None
    seed = check_int("seed", seed, 0)
    return np.random.default_rng(seed), seed


def self_affine(
    n,
    length,
    *,
    hurst,
    scales=None,
    cutoff_wavevector=None,
    rolloff=1.0,
    rms_height=None,
    rms_slope=None,
    seed=0,
    dim=2,
    anisotropy=1.0,
    name="self-affine",
):
    """Randomly rough self-affine surface (or profile) by the spectral method.

    Every mode gets the deterministic amplitude ``sqrt(C(q) q_L**dim)`` and a random phase
    (the phase of the FFT of white noise drawn from ``numpy.random.default_rng(seed)``, which
    is Hermitian, so the heights are real and self-conjugate modes get a random sign). The
    realised PSD therefore equals the target :func:`bem.surfaces.statistics.psd_target` exactly on
    the grid; its keywords are stored in ``surface.metadata["spectrum"]``. The mean is zero.

    Target (docs/theory.md §5): ``C(q) ∝ q**-2(1+H)`` (2-D; ``q**-(1+2H)`` for 1-D profiles) for
    ``q_r <= q <= q_1``, flat below ``q_r`` (roll-off), zero above ``q_1`` and at ``q = 0``;
    ``q_L = 2 pi / length``, ``q_r = rolloff q_L``, ``q_1 = scales q_L``.

    Anisotropy ``s``: the ratio of the correlation lengths along x and along y, so that the
    spectral moments obey ``m02 / m20 = <(dh/dy)**2> / <(dh/dx)**2> = s**2`` **exactly**.
    The isotropic shape is evaluated at ``q_e = hypot(min(s, 1) qx, qy / max(s, 1))`` (the
    surface compressed by ``s`` along y for ``s > 1``, by ``1/s`` along x for ``s < 1``, so
    that ``q_L, q_r, q_1`` keep their meaning along the long-correlation direction) and
    multiplied by ``(qx**2 + b qy**2) / |q|**2``, with ``b`` fixed on the grid to make the
    ratio exact; ``b -> 1`` as the grid resolves the spectrum (``b = 1`` when ``s = 1``;
    0.86 <= b <= 1.16 for 1/4 <= s <= 4, H <= 0.95, on 64**2 to 256**2 grids) and is
    stored as ``metadata["spectrum"]["directional_factor"]``.

    Parameters
    ----------
    n : int
        Points per side, >= 2.
    length : float
        Cell side ``L`` (m).
    hurst : float
        Hurst exponent ``H`` in [0, 1].
    scales : int, optional
        Number of scales ``q_1 / q_L`` (default 64), with
        ``scales * max(s, 1/s) <= n / 2`` (the cut-off stays within the grid's Nyquist).
    cutoff_wavevector : float, optional
        ``q_1`` (rad/m) instead of ``scales``; same bound.
    rolloff : float
        ``q_r / q_L`` in ``[1, q_1 / q_L]``; 1 means no plateau.
    rms_height, rms_slope : float
        Exactly one: rms height about the mean (m) or rms gradient magnitude
        ``sqrt(<|grad h|**2>)`` (dimensionless, spectral).
    seed : int or numpy.random.Generator
        Seed (>= 0) of ``numpy.random.default_rng``, or a generator to draw from.
    dim : {1, 2}
        2 for a square surface, 1 for a profile ``h[ix]``.
    anisotropy : float
        ``s > 0`` above (2-D only).
    name : str
        Label.

    Returns
    -------
    Surface
        Periodic surface with ``metadata`` keys ``kind``, ``seed`` and ``spectrum``.

    Examples
    --------
    >>> from bem.surfaces.statistics import rms_height
    >>> s = self_affine(64, 1e-3, hurst=0.8, scales=16, rms_height=1e-6, seed=1)
    >>> s.shape, round(rms_height(s) / 1e-6, 12)
    ((64, 64), 1.0)
    """
    n = check_int("n", n, 2)
    length = check_positive("length", length)
    hurst = check_range("hurst", hurst, 0.0, 1.0)
    dim = check_int("dim", dim, 1, 2)
    s = check_positive("anisotropy", anisotropy)
    if dim == 1 and s != 1.0:
        raise InputError(f"anisotropy must be 1 for a 1-D profile (dim=1), got {show(anisotropy)}")
    stretch = max(s, 1.0 / s)
    q_l = 2.0 * np.pi / length
    if scales is not None and cutoff_wavevector is not None:
        raise InputError(
            f"give scales or cutoff_wavevector, not both; got scales={show(scales)}, "
            f"cutoff_wavevector={show(cutoff_wavevector)}"
        )
    if cutoff_wavevector is None:
        scales = check_int("scales", 64 if scales is None else scales, 1)
        if scales * stretch > n / 2:
            raise InputError(
                f"scales must be in [1, n / 2 / max(anisotropy, 1 / anisotropy)] = "
                f"[1, {n / 2 / stretch:g}] to stay below the grid's Nyquist (n = {n}), "
                f"got {scales}"
            )
        q_1 = scales * q_l
    else:
        q_1 = check_range("cutoff_wavevector", cutoff_wavevector, q_l, np.pi * n / length / stretch)
    rolloff = check_range("rolloff", rolloff, 1.0, q_1 / q_l)
    if (rms_height is None) == (rms_slope is None):
        raise InputError(
            f"give exactly one of rms_height and rms_slope, got rms_height={show(rms_height)}, "
            f"rms_slope={show(rms_slope)}"
        )
    target = check_positive("rms_height", rms_height) if rms_slope is None else None
    slope = check_positive("rms_slope", rms_slope) if rms_height is None else None
    rng, seed_value = _rng(seed)

    shape = (n,) * dim
    q = fft.wavevectors(shape, length)
    spectrum = dict(
        hurst=hurst,
        cutoff_wavevector=q_1,
        rolloff_wavevector=rolloff * q_l,
        dim=dim,
        prefactor=1.0,
        anisotropy=s,
        directional_factor=1.0,
    )
    if s != 1.0:
        spectrum["directional_factor"] = _directional_factor(q, spectrum)
    c = psd_target(q, **spectrum)
    m0, m2 = psd_moments(c, q, shape)
    spectrum["prefactor"] = target**2 / m0 if slope is None else slope**2 / m2
    noise = fft.forward(rng.standard_normal(shape))
    magnitude = np.abs(noise)
    phase = noise / np.where(magnitude > 0, magnitude, 1.0)
    amplitude = np.sqrt(spectrum["prefactor"] * c * q_l**dim)
    heights = fft.inverse(amplitude * phase, shape)
    meta = {"kind": "self_affine", "seed": seed_value, "spectrum": spectrum}
    return Surface(heights, length, name=name, metadata=meta)


def _directional_factor(q, spectrum):
    """``b`` making ``m02 / m20 = s**2`` exactly for the spectrum with ``b = 1`` (see above)."""
    qx, qy = q
    c = psd_target(q, **spectrum)
    mag2 = np.where(qx**2 + qy**2 > 0, qx**2 + qy**2, 1.0)
    w = fft.full_spectrum_weights((qx.shape[0],) * 2)
    # m20 = xx + b xy and m02 = xy + b yy once C is multiplied by (qx**2 + b qy**2) / |q|**2
    xx = np.sum(w * c * qx**4 / mag2)
    xy = np.sum(w * c * qx**2 * qy**2 / mag2)
    yy = np.sum(w * c * qy**4 / mag2)
    s2 = spectrum["anisotropy"] ** 2
    factor = (s2 * xx - xy) / (yy - s2 * xy)
    if not (np.isfinite(factor) and factor > 0):
        raise InputError(
            f"anisotropy {show(spectrum['anisotropy'])} cannot be realised exactly on this grid; "
            "use more scales or a value closer to 1"
        )
    return float(factor)


def profile(
    n,
    length,
    *,
    hurst,
    scales=None,
    cutoff_wavevector=None,
    rolloff=1.0,
    rms_height=None,
    rms_slope=None,
    seed=0,
    name="profile",
):
    """Self-affine 1-D profile: :func:`self_affine` with ``dim=1`` (PSD ∝ q**-(1+2H))."""
    return self_affine(
        n,
        length,
        hurst=hurst,
        scales=scales,
        cutoff_wavevector=cutoff_wavevector,
        rolloff=rolloff,
        rms_height=rms_height,
        rms_slope=rms_slope,
        seed=seed,
        dim=1,
        name=name,
    )
