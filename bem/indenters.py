"""Rigid indenters for isolated contacts: the sphere (2-D map) and the cylinder (1-D profile,
plane strain), on element centres of a domain centred on their axis.
"""

import numpy as np

from .checks import check_int, check_positive, show
from .errors import InputError
from .surface import Surface

__all__ = ["sphere", "cylinder"]


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
