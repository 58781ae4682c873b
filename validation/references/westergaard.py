"""Westergaard's periodic sinusoid: a rigid wavy surface pressed on an elastic half-space (exact).

Plane strain, SI units. The rigid surface has heights ``h(x) = g0 cos(2 pi x / lam)``
(m), **positive toward the half-space** as everywhere in viscobem, so its crests (first
contact) sit at ``x = 0, ±lam, ...``. The half-space has Young's modulus ``E`` and Poisson
ratio ``nu``; it responds through ``E* = E / (1 - nu**2)``, i.e. through the Fourier
symbol ``u_q = 2 p_q / (E* |q|)`` of :mod:`bem.halfspace.periodic`.

With ``p* = pi E* g0 / lam`` (the mean pressure that just closes the gap) and mean
pressure ``p_mean`` (Pa; load per unit length over ``lam``):

- full contact (``p_mean >= p*``): ``p(x) = p_mean + p* cos(2 pi x / lam)``;
- partial contact: contact half-width ``a`` from ``sin**2(pi a / lam) = p_mean / p*`` and,
  for ``|x| <= a`` (mod ``lam``),
  ``p(x) = 2 p_mean cos(pi x / lam) / sin**2(pi a / lam) * sqrt(sin**2(pi a / lam) - sin**2(pi x / lam))``,
  zero elsewhere.

References: H.M. Westergaard, "Bearing pressures and cracks", J. Appl. Mech. 6 (1939)
A49–A53, doi:10.1115/1.4008919; K.L. Johnson, *Contact Mechanics*, CUP 1985, §13.2
(eqs. 13.3 and 13.9–13.10).
"""

from dataclasses import dataclass

import numpy as np

__all__ = ["WestergaardSolution", "westergaard"]


@dataclass(frozen=True)
class WestergaardSolution:
    """Exact contact of a rigid sinusoid on an elastic half-space (plane strain).

    Attributes
    ----------
    amplitude : float
        ``g0`` (m), half the peak-to-valley height.
    wavelength : float
        ``lam`` (m).
    reduced_modulus : float
        ``E* = E / (1 - nu**2)`` (Pa).
    mean_pressure : float
        ``p_mean`` (Pa); the load per unit length is ``p_mean * lam`` (N/m per period).
    full_contact_pressure : float
        ``p* = pi E* g0 / lam`` (Pa): the mean pressure for full contact, and the amplitude of
        the pressure's cosine in full contact.
    half_width : float
        Contact half-width ``a`` (m); ``lam / 2`` in full contact.
    """

    amplitude: float
    wavelength: float
    reduced_modulus: float
    mean_pressure: float
    full_contact_pressure: float
    half_width: float

    @property
    def full_contact(self):
        """True when ``p_mean >= p*``."""
        return self.mean_pressure >= self.full_contact_pressure

    @property
    def load(self):
        """Load per unit length carried by one period (N/m)."""
        return self.mean_pressure * self.wavelength

    def pressure(self, x):
        """Pressure (Pa) at ``x`` (m, any real values; the solution has period ``lam``)."""
        x = np.asarray(x, dtype=float)
        lam, p_star = self.wavelength, self.full_contact_pressure
        if self.full_contact:
            return self.mean_pressure + p_star * np.cos(2 * np.pi * x / lam)
        xr = x - lam * np.round(x / lam)  # in [-lam/2, lam/2]
        s2a = np.sin(np.pi * self.half_width / lam) ** 2
        root = np.sqrt(np.clip(s2a - np.sin(np.pi * xr / lam) ** 2, 0.0, None))
        p = 2.0 * self.mean_pressure / s2a * np.cos(np.pi * xr / lam) * root
        return np.where(np.abs(xr) < self.half_width, p, 0.0)


def westergaard(amplitude, wavelength, mean_pressure, E, nu=0.5):
    """Exact solution for ``h = amplitude cos(2 pi x / wavelength)`` under ``mean_pressure``.

    Parameters
    ----------
    amplitude : float
        ``g0`` (m), > 0.
    wavelength : float
        ``lam`` (m), > 0.
    mean_pressure : float
        Mean pressure over a period (Pa), > 0.
    E : float
        Young's modulus of the half-space (Pa).
    nu : float
        Poisson ratio.

    Returns
    -------
    WestergaardSolution

    Examples
    --------
    >>> s = westergaard(1e-6, 1e-3, 0.5 * np.pi * 4e6 * 1e-6 / 1e-3, 3e6)
    >>> round(s.half_width / 1e-3, 12)  # p_mean = p*/2: a = lam / 4
    0.25
    """
    e_star = E / (1.0 - nu**2)
    p_star = np.pi * e_star * amplitude / wavelength
    if mean_pressure >= p_star:
        a = 0.5 * wavelength
    else:
        a = wavelength / np.pi * np.arcsin(np.sqrt(mean_pressure / p_star))
    return WestergaardSolution(
        float(amplitude), float(wavelength), float(e_star), float(mean_pressure), float(p_star), float(a)
    )
