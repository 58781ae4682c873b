"""Rigid surfaces: the :class:`Surface` type, rough-surface generators and measured files.

Conventions (SPEC 2.3, 2.4). Heights ``h`` (m) are **positive toward the half-space**, so
contact starts at ``max(h)``. A surface is a 1-D profile ``h[ix]`` or a square 2-D map
``h[ix, iy]`` (axis 0 is x, the sliding direction) on a cell of side ``length`` (m) with
``n`` points per side, spacing ``length / n``. Periodic cells put point ``j`` at
``x_j = j * spacing`` (as :mod:`bem.fft`); ``centered`` surfaces (isolated indenters) put
it at the centre of element ``j`` of a domain centred on the indenter,
``x_j = (j + 1/2) * spacing - length / 2``.

PSD normalisation and the target spectrum of :func:`self_affine` are stated in
:mod:`bem.statistics`.
"""
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

import numpy as np

from . import fft
from .checks import check_array, check_int, check_positive, check_range, show
from .errors import InputError
from .statistics import _moments, psd_target

__all__ = ["Surface", "from_heights", "self_affine", "profile", "sinusoid", "load", "sphere", "cylinder"]

_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "nm": 1e-9}


@dataclass(frozen=True, eq=False, repr=False)
class Surface:
    """Heights of a rigid surface on a square cell (validated; heights stored read-only).

    Parameters
    ----------
    heights : array_like
        1-D ``(n,)`` or square 2-D ``(n, n)`` heights (m), finite, ``n >= 2``, positive
        toward the half-space. A read-only copy is stored.
    length : float
        Cell side (m), > 0.
    name : str
        Label for reports.
    centered : bool
        ``False`` (periodic cell, ``x_j = j dx``) or ``True`` (isolated indenter, element
        centres of a domain centred on it).
    metadata : mapping
        How the surface was made, e.g. ``metadata["spectrum"]`` (stored read-only, one
        level of nested mappings included).

    Notes
    -----
    Equality is identity (arrays have no single truth value); make variants with
    :func:`dataclasses.replace`.
    """

    heights: np.ndarray
    length: float
    name: str = ""
    centered: bool = False
    metadata: Mapping = field(default_factory=dict)

    def __post_init__(self):
        h = check_array("heights", self.heights, ndim=(1, 2))
        if h.ndim == 2 and h.shape[0] != h.shape[1]:
            raise InputError(f"heights must be 1-D or square 2-D (n, n), got shape {h.shape}")
        if h.shape[0] < 2:
            raise InputError(f"heights must have at least 2 points per side, got shape {h.shape}")
        h.flags.writeable = False
        object.__setattr__(self, "heights", h)
        object.__setattr__(self, "length", check_positive("length", self.length))
        object.__setattr__(self, "name", str(self.name))
        object.__setattr__(self, "centered", bool(self.centered))
        frozen = {k: MappingProxyType(dict(v)) if isinstance(v, Mapping) else v
                  for k, v in dict(self.metadata).items()}
        object.__setattr__(self, "metadata", MappingProxyType(frozen))

    def __reduce__(self):
        """Pickle and copy through the constructor (mapping proxies do not pickle)."""
        meta = {k: dict(v) if isinstance(v, Mapping) else v for k, v in self.metadata.items()}
        return (Surface, (np.array(self.heights), self.length, self.name, self.centered, meta))

    def __repr__(self):
        kind = "centered" if self.centered else "periodic"
        return f"Surface(name={self.name!r}, shape={self.shape}, length={show(self.length)}, {kind})"

    @property
    def ndim(self):
        """1 for a profile, 2 for a surface."""
        return self.heights.ndim

    @property
    def n(self):
        """Points per side."""
        return self.heights.shape[0]

    @property
    def shape(self):
        """Shape of :attr:`heights`."""
        return self.heights.shape

    @property
    def spacing(self):
        """Grid spacing ``length / n`` (m)."""
        return self.length / self.n

    @property
    def x(self):
        """Coordinates of the grid points along a side (m); see the module docstring."""
        j = np.arange(self.n, dtype=float)
        if self.centered:
            return (j + 0.5) * self.spacing - 0.5 * self.length
        return j * self.spacing

    def coordinates(self):
        """Grid coordinates (m): ``(x,)`` in 1-D, ``(x, y)`` full ``(n, n)`` arrays in 2-D (ij)."""
        if self.ndim == 1:
            return (self.x,)
        return tuple(np.meshgrid(self.x, self.x, indexing="ij"))

    def wavevectors(self):
        """Wavevector components (rad/m) on the half-spectrum grid of :mod:`bem.fft`."""
        return fft.wavevectors(self.shape, self.length)


def from_heights(heights, length, *, name="", centered=False):
    """Surface from any 1-D or square 2-D array of heights (m) on a cell of side ``length`` (m).

    The array is copied and validated; it is never modified.

    Examples
    --------
    >>> from_heights([0.0, 1e-6, 0.0, -1e-6], 1e-3).spacing
    0.00025
    """
    return Surface(heights, length, name=name, centered=centered, metadata={"kind": "array"})


def _rng(seed):
    if isinstance(seed, np.random.Generator):
        return seed, None
    seed = check_int("seed", seed, 0)
    return np.random.default_rng(seed), seed


def self_affine(n, length, *, hurst, scales=None, cutoff_wavevector=None, rolloff=1.0,
                rms_height=None, rms_slope=None, seed=0, dim=2, anisotropy=1.0, name="self-affine"):
    """Randomly rough self-affine surface (or profile) by the spectral method.

    Every mode gets the deterministic amplitude ``sqrt(C(q) q_L**dim)`` and a random phase
    (the phase of the FFT of white noise drawn from ``numpy.random.default_rng(seed)``, which
    is Hermitian, so the heights are real and self-conjugate modes get a random sign). The
    realised PSD therefore equals the target :func:`bem.statistics.psd_target` exactly on
    the grid; its keywords are stored in ``surface.metadata["spectrum"]``. The mean is zero.

    Target (SPEC 2.4): ``C(q) ∝ q**-2(1+H)`` (2-D; ``q**-(1+2H)`` for 1-D profiles) for
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
    >>> from bem.statistics import rms_height
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
        raise InputError(f"give scales or cutoff_wavevector, not both; got scales={show(scales)}, "
                         f"cutoff_wavevector={show(cutoff_wavevector)}")
    if cutoff_wavevector is None:
        scales = check_int("scales", 64 if scales is None else scales, 1)
        if scales * stretch > n / 2:
            raise InputError(f"scales must be in [1, n / 2 / max(anisotropy, 1 / anisotropy)] = "
                             f"[1, {n / 2 / stretch:g}] to stay below the grid's Nyquist (n = {n}), "
                             f"got {scales}")
        q_1 = scales * q_l
    else:
        q_1 = check_range("cutoff_wavevector", cutoff_wavevector, q_l, np.pi * n / length / stretch)
    rolloff = check_range("rolloff", rolloff, 1.0, q_1 / q_l)
    if (rms_height is None) == (rms_slope is None):
        raise InputError(f"give exactly one of rms_height and rms_slope, got rms_height={show(rms_height)}, "
                         f"rms_slope={show(rms_slope)}")
    target = check_positive("rms_height", rms_height) if rms_slope is None else None
    slope = check_positive("rms_slope", rms_slope) if rms_height is None else None
    rng, seed_value = _rng(seed)

    shape = (n,) * dim
    q = fft.wavevectors(shape, length)
    spectrum = dict(hurst=hurst, cutoff_wavevector=q_1, rolloff_wavevector=rolloff * q_l, dim=dim,
                    prefactor=1.0, anisotropy=s, directional_factor=1.0)
    if s != 1.0:
        spectrum["directional_factor"] = _directional_factor(q, spectrum)
    c = psd_target(q, **spectrum)
    m0, m2 = _moments(c, q, shape)
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
        raise InputError(f"anisotropy {show(spectrum['anisotropy'])} cannot be realised exactly on this grid; "
                         "use more scales or a value closer to 1")
    return float(factor)


def profile(n, length, *, hurst, scales=None, cutoff_wavevector=None, rolloff=1.0,
            rms_height=None, rms_slope=None, seed=0, name="profile"):
    """Self-affine 1-D profile: :func:`self_affine` with ``dim=1`` (PSD ∝ q**-(1+2H))."""
    return self_affine(n, length, hurst=hurst, scales=scales, cutoff_wavevector=cutoff_wavevector,
                       rolloff=rolloff, rms_height=rms_height, rms_slope=rms_slope, seed=seed,
                       dim=1, name=name)


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
        raise InputError(f"wavelength must be length / k for a whole number k >= 1 (periodic cell, "
                         f"length = {show(length)}), got {show(wavelength)}")
    if 2 * periods >= n:
        raise InputError(f"wavelength must be > 2 spacing = {show(2 * length / n)} (resolved on n = {n}), "
                         f"got {show(wavelength)}")
    valid = ("x",) if dim == 1 else ("x", "y", "xy")
    if direction not in valid:
        raise InputError(f"direction must be one of {valid} for dim={dim}, got {show(direction)}")
    wave = np.cos(2 * np.pi * periods * np.arange(n) / n)
    if dim == 1:
        heights = amplitude * wave
    else:
        heights = amplitude * {"x": wave[:, None] * np.ones(n), "y": np.ones(n)[:, None] * wave,
                               "xy": np.outer(wave, wave)}[direction]
    meta = {"kind": "sinusoid", "amplitude": amplitude, "wavelength": length / periods,
            "direction": direction}
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
        raise InputError(f"path {show(str(p))} must hold finite heights, at least 2 per side; "
                         f"got shape {data.shape}, {np.count_nonzero(~np.isfinite(data))} non-finite")
    meta = {"kind": "file", "path": str(p), "unit": unit}
    return Surface(data * _UNITS[unit], length, name=p.stem if name is None else name, metadata=meta)


def _indenter(radius, n, length, exact, dim, kind):
    """Heights (m) of a sphere (``dim=2``) or cylinder (``dim=1``) at element centres of a
    domain of side ``length`` centred on its axis; maximum (0) at the centre."""
    radius = check_positive("radius", radius)
    n = check_int("n", n, 2)
    length = check_positive("length", length)
    if not isinstance(exact, (bool, np.bool_)):
        raise InputError(f"exact must be True or False, got {show(exact)}")
    reach = np.sqrt(dim) * length / 2  # farthest domain point from the axis
    if exact and not reach < radius:
        limit = "2 radius" if dim == 1 else "sqrt(2) radius"
        raise InputError(f"length must be < {limit} = {show(2 * radius / np.sqrt(dim))} m for the exact "
                         f"{kind} (the domain must lie under the {kind}), got {show(length)}")
    x = (np.arange(n) + 0.5) * (length / n) - length / 2
    r2 = x**2 if dim == 1 else x[:, None] ** 2 + x[None, :] ** 2
    heights = np.sqrt(radius**2 - r2) - radius if exact else -r2 / (2.0 * radius)
    meta = {"kind": kind, "radius": radius, "exact": bool(exact)}
    return Surface(heights, length, name=kind, centered=True, metadata=meta)


def sphere(*, radius, n, length, exact=False):
    """Rigid sphere (2-D map) for isolated contacts: ``h = -(x**2 + y**2) / (2 radius)``.

    Heights (m) are positive toward the half-space, the apex (``h = 0``) at the domain
    centre; grid points are the element centres of a square domain of side ``length`` centred on the
    sphere (``Surface.centered``). The default paraboloid is the shape for which Hertz's
    solution is exact; ``exact=True`` gives the spherical cap ``sqrt(R**2 - r**2) - R``
    (then ``length < sqrt(2) radius``, so that the whole domain lies under the sphere).

    Parameters
    ----------
    radius : float
        Sphere radius (m), > 0.
    n : int
        Elements per side, >= 2.
    length : float
        Domain side (m), > 0; choose it a few contact radii wide.
    exact : bool
        Spherical cap instead of the paraboloid.

    Examples
    --------
    >>> s = sphere(radius=0.01, n=4, length=0.002)
    >>> s.shape, s.centered, round(float(s.heights.max()) / 1e-6, 9)  # apex between elements
    ((4, 4), True, -6.25)
    """
    return _indenter(radius, n, length, exact, 2, "sphere")


def cylinder(*, radius, n, length, exact=False):
    """Rigid cylinder (1-D profile, plane strain) for isolated contacts: ``h = -x**2 / (2 radius)``.

    As :func:`sphere`, for a cylinder whose axis is along ``y`` (rolling or sliding along
    ``x``); ``exact=True`` gives the circle ``sqrt(R**2 - x**2) - R`` (then
    ``length < 2 radius``). The paraboloid default is the shape of Hertz's and Hunter's
    solutions.

    Examples
    --------
    >>> cylinder(radius=1.0, n=4, length=4.0).x.tolist()
    [-1.5, -0.5, 0.5, 1.5]
    """
    return _indenter(radius, n, length, exact, 1, "cylinder")
