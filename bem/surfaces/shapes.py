"""Analytic rigid shapes: the periodic sinusoid (1-D or 2-D cell) and the indenters of isolated
contacts, the sphere (2-D map) and the cylinder (1-D profile, plane strain), on element centres
of a domain centred on their axis.
"""

import numpy as np

from ..checks import check_int, check_positive, show
from ..errors import InputError
from .surface import Surface

__all__ = ["sinusoid", "sphere", "cylinder"]


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
        raise InputError(
            f"length must be < {limit} = {show(2 * radius / np.sqrt(dim))} m for the exact "
            f"{kind} (the domain must lie under the {kind}), got {show(length)}"
        )
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
