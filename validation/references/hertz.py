"""Hertz's elastic contact of a rigid parabolic indenter on a half-space (exact).

SI units. ``E`` is Young's modulus of the half-space, ``nu`` its Poisson ratio; the rigid
indenter enters through the reduced modulus ``E* = E / (1 - nu**2)``. Reference:
K.L. Johnson, *Contact Mechanics*, CUP 1985, §4.2 (sphere) and §5.2 (cylinder).
"""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class HertzSolution:
    """Contact half-width (line) or radius (point) ``a`` (m), peak pressure ``p0`` (Pa),
    approach ``delta`` (m; ``nan`` for the line contact, where it is not defined)."""

    a: float
    p0: float
    delta: float
    kind: str

    def pressure(self, r):
        """Pressure (Pa) at distance ``r`` (m) from the centre line / axis."""
        s = np.clip(1.0 - (np.asarray(r, dtype=float) / self.a) ** 2, 0.0, None)
        return self.p0 * np.sqrt(s)


def reduced_modulus(E, nu):
    """``E* = E / (1 - nu**2)`` (Pa)."""
    return E / (1.0 - nu**2)


def line_contact(E, nu, radius, load_per_length):
    """Rigid cylinder of ``radius`` (m) pressed by ``load_per_length`` (N/m), plane strain.

    ``a = sqrt(4 P R / (pi E*))``, ``p0 = 2 P / (pi a)``.
    """
    es = reduced_modulus(E, nu)
    a = np.sqrt(4.0 * load_per_length * radius / (np.pi * es))
    return HertzSolution(float(a), float(2.0 * load_per_length / (np.pi * a)), float("nan"), "line")


def point_contact(E, nu, radius, load):
    """Rigid sphere of ``radius`` (m) pressed by ``load`` (N).

    ``a = (3 P R / (4 E*))**(1/3)``, ``p0 = 3 P / (2 pi a**2)``, ``delta = a**2 / R``.
    """
    es = reduced_modulus(E, nu)
    a = (3.0 * load * radius / (4.0 * es)) ** (1.0 / 3.0)
    return HertzSolution(float(a), float(3.0 * load / (2.0 * np.pi * a**2)), float(a**2 / radius), "point")
