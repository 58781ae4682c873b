"""Lee & Radok's creep indentation of a viscoelastic half-space by a rigid sphere (exact).

A step load ``P`` (N) applied at ``t = 0`` and held; sphere radius ``R`` (m), heights
``h(r) = -r^2 / (2R)``. While the contact grows (always, under a held load on a solid whose
creep compliance increases), E.H. Lee and J.R.M. Radok (J. Appl. Mech. 27 (1960) 438-444,
doi:10.1115/1.3644020) give

    a(t)^3 = (3 R / 4) P (1 - nu^2) J(t),          delta(t) = a(t)^2 / R,
    p(r, t) = 2 / (pi R (1 - nu^2)) * int_{0-}^{t} E(t - s) d/ds sqrt(a(s)^2 - r^2)_+ ds,

with ``J`` the creep compliance and ``E`` the relaxation modulus (Pa); at ``t = 0+`` and
``t -> inf`` the pressure is Hertz's with ``E_inf`` and ``E0``. SI units throughout.
"""

from __future__ import annotations

import numpy as np

__all__ = ["contact_radius", "approach", "pressure"]


def contact_radius(material, radius, load, t):
    """``a(t)`` (m) at times ``t`` (s, >= 0; 0 means 0+)."""
    return (0.75 * radius * load * (1 - material.nu**2) * material.creep_compliance(np.asarray(t, float))) ** (1 / 3)


def approach(material, radius, load, t):
    """``delta(t) = a(t)^2 / R`` (m)."""
    return contact_radius(material, radius, load, t) ** 2 / radius


def pressure(material, radius, load, t, r, samples=4000):
    """``p(r, t)`` (Pa) at radii ``r`` (m, array) and one time ``t`` (s).

    The hereditary integral is a Stieltjes sum over ``samples`` geometric time steps from
    ``1e-6 min(lambda_k)`` (a pressure increment ``dF`` weighted by ``E`` at the step's
    midpoint): second-order accurate, ~1e-6 relative at the default count.
    """
    r = np.atleast_1d(np.asarray(r, float))
    t = float(t)
    if t > 0 and material.creep_times.size:
        t0 = min(1e-6 * float(np.min(material.creep_times)), 1e-3 * t)
        s = np.concatenate([[0.0], np.geomspace(t0, t, samples)])
    else:
        s = np.array([0.0])
    a = contact_radius(material, radius, load, s)
    F = np.sqrt(np.clip(a[:, None] ** 2 - r[None, :] ** 2, 0.0, None))  # (time, r)
    mid = 0.5 * (s[1:] + s[:-1])
    p = material.relaxation_modulus(np.array([t]))[0] * F[0]
    if s.size > 1:
        p = p + np.sum(material.relaxation_modulus(t - mid)[:, None] * np.diff(F, axis=0), axis=0)
    return 2.0 / (np.pi * radius * (1 - material.nu**2)) * p
