"""Persson's theory of rubber (hysteretic) friction on a rough surface.

B. N. J. Persson, J. Chem. Phys. 115 (2001) 3840, doi:10.1063/1.1388626, with the
contact factor ``P(q)`` of partial contact:

    mu(v) = (1/2) ∫_{q0}^{q1} dq q**3 C(q) P(q) ∫_0^{2 pi} dphi cos(phi)
            Im E(q v cos(phi)) / ((1 - nu**2) sigma0),

    P(q) = erf(1 / (2 sqrt(G(q)))),
    G(q) = (1/8) ∫_{q0}^{q} dq' q'**3 C(q') ∫_0^{2 pi} dphi |E(q' v cos(phi)) / ((1 - nu**2) sigma0)|**2,

with ``C(q)`` the isotropic PSD of the rigid surface (normalised as in
:mod:`bem.surfaces.statistics`: ``<h**2> = ∫ C d2q``), ``sigma0`` the nominal pressure (Pa) and
``E(w)`` the complex modulus of :class:`bem.Material` (``Im E(w)`` has the sign of ``w``,
so ``mu >= 0``). ``P(q1)`` is the theory's relative contact area. With
``partial_contact=False``, ``P = 1`` (full contact), where the theory is exact for the
linear problem: it is then the friction of the periodic BEM in full contact.

Two forms:

- :func:`friction_discrete`: the integrals as sums over the wavevectors of a periodic cell
  (``∫ d2q -> sum q_L**2``) with the surface's own Fourier coefficients, and the grid's
  convention at the x-Nyquist mode (no dissipation there, as the BEM operator). In full
  contact it equals the BEM friction to round-off.
- :func:`friction`: the continuous integrals for a PSD given as a function of ``|q|``,
  by composite Simpson rules in ``ln q`` (breakpoints where the PSD has kinks) and the
  trapezoidal rule in ``phi`` (spectrally accurate for the periodic integrand).
"""

import numpy as np
from scipy.integrate import cumulative_simpson, simpson
from scipy.special import erf

from .. import fft
from ..checks import check_array, check_int, check_positive
from ..errors import InputError
from ..materials.material import Material
from ..surfaces.statistics import psd_target

__all__ = ["friction", "friction_discrete", "friction_for_surface"]


def _p_of_g(g):
    with np.errstate(divide="ignore"):
        return np.where(g > 0, erf(0.5 / np.sqrt(np.where(g > 0, g, 1.0))), 1.0)


def _speeds(speeds):
    v = check_array("speeds", np.atleast_1d(speeds), ndim=1)
    if np.any(v < 0):
        raise InputError(f"speeds must be >= 0 m/s, got min {v.min()!r}")
    return v


def _check_common(material, pressure):
    if not isinstance(material, Material):
        raise InputError(f"material must be a bem.Material, got {type(material).__name__}")
    return check_positive("pressure", pressure)


def friction_discrete(surface, material, *, speeds, pressure, partial_contact=True):
    """Persson's friction as sums over the grid wavevectors of a periodic 2-D surface.

    Parameters
    ----------
    surface : bem.surfaces.Surface
        2-D periodic surface; its Fourier coefficients give ``C(q) q_L**2 = |h_q|**2``.
    material : bem.Material
    speeds : array_like
        Sliding speeds (m/s).
    pressure : float
        Nominal pressure ``sigma0 = F_N / L**2`` (Pa).
    partial_contact : bool
        ``True``: ``P(q) = erf(1 / (2 sqrt(G(q))))`` with ``G`` summed over ``|q'| <= |q|``;
        ``False``: ``P = 1``.

    Returns
    -------
    mu : ndarray
        Friction coefficient per speed.
    area : ndarray
        ``P(q_max)`` per speed: the relative contact area (1 with ``partial_contact=False``).
    """
    if getattr(surface, "heights", None) is None or np.ndim(surface.heights) != 2:
        raise InputError("surface must be a 2-D bem.surfaces.Surface")
    sigma0 = _check_common(material, pressure)
    v = _speeds(speeds)
    h = surface.heights
    qx, qy = fft.wavevectors(h.shape, surface.length)
    weight = fft.full_spectrum_weights(h.shape) * np.abs(fft.forward(h)) ** 2  # |h_q|^2, both halves
    qn = np.sqrt(qx**2 + qy**2) * np.ones_like(weight)
    qxb = qx * np.ones_like(weight)
    keep = (qn > 0) & (weight > 0)
    nyq = np.zeros_like(keep)
    if h.shape[0] % 2 == 0:
        nyq[h.shape[0] // 2, :] = True  # the grid's operator dissipates nothing there
    qn, qxk, wk, nyqk = qn[keep], qxb[keep], weight[keep], nyq[keep]
    order = np.argsort(qn, kind="stable")
    qn, qxk, wk, nyqk = qn[order], qxk[order], wk[order], nyqk[order]
    factor = 1.0 / ((1.0 - material.nu**2) * sigma0)
    mu, area = np.empty(v.size), np.empty(v.size)
    for i, speed in enumerate(v):
        e = material.complex_modulus(qxk * speed)
        if partial_contact:
            # G(q) = (1/8) sum_{0 < |q'| <= |q|} |q'|^2 |h_q'|^2 |E / ((1 - nu^2) sigma0)|^2 (ties included)
            cum = np.cumsum(qn**2 * wk * np.abs(e * factor) ** 2 / 8.0)
            last = np.searchsorted(qn, qn, side="right") - 1
            p = _p_of_g(cum[last])
        else:
            p = np.ones_like(qn)
        im = np.where(nyqk, 0.0, e.imag)
        mu[i] = 0.5 * factor * np.sum(wk * qn * qxk * im * p)
        area[i] = p[-1] if partial_contact else 1.0
    return mu, area


def friction(material, *, psd, q0, q1, speeds, pressure, partial_contact=True, breakpoints=(), points=400, angles=256):
    """Persson's friction from the continuous integrals (isotropic PSD).

    Parameters
    ----------
    material : bem.Material
    psd : callable
        ``C(q)`` (m**4) of ``|q|`` (rad/m), vectorised.
    q0, q1 : float
        Integration limits (rad/m), ``0 < q0 < q1``.
    speeds : array_like
        Sliding speeds (m/s).
    pressure : float
        Nominal pressure (Pa).
    partial_contact : bool
        ``P(q)`` of the module docstring, or ``P = 1``.
    breakpoints : sequence of float
        Wavevectors in ``(q0, q1)`` where ``C`` has a kink (e.g. the roll-off); panels end there.
    points : int
        Simpson nodes per panel (odd; in ``ln q``).
    angles : int
        Trapezoidal nodes in ``phi``.

    Returns
    -------
    mu, area : ndarray
        Friction coefficient and ``P(q1)`` per speed.
    """
    sigma0 = _check_common(material, pressure)
    v = _speeds(speeds)
    q0 = check_positive("q0", q0)
    q1 = check_positive("q1", q1)
    if not q1 > q0:
        raise InputError(f"q1 must be > q0 = {q0!r} rad/m, got {q1!r}")
    points = check_int("points", points, 3) | 1
    angles = check_int("angles", angles, 8)
    edges = np.unique(np.concatenate([[q0, q1], [b for b in breakpoints if q0 < b < q1]]))
    s = np.concatenate(
        [
            np.linspace(np.log(a), np.log(b), points)[(1 if k else 0) :]
            for k, (a, b) in enumerate(zip(edges[:-1], edges[1:]))
        ]
    )
    q = np.exp(s)
    bounds = [0] + [k * (points - 1) for k in range(1, edges.size)]
    phi = 2 * np.pi * np.arange(angles) / angles
    cphi = np.cos(phi)
    c = np.asarray(psd(q), dtype=float)
    factor = 1.0 / ((1.0 - material.nu**2) * sigma0)
    mu, area = np.empty(v.size), np.empty(v.size)
    for i, speed in enumerate(v):
        e = material.complex_modulus(np.outer(q, cphi) * speed) * factor
        inner_mu = np.mean(cphi * e.imag, axis=1) * 2 * np.pi
        if partial_contact:
            inner_g = np.mean(np.abs(e) ** 2, axis=1) * 2 * np.pi
            dens = q**4 * c * inner_g / 8.0  # dq = q ds
            g = np.zeros_like(q)
            for a, b in zip(bounds[:-1], bounds[1:]):
                g[a + 1 : b + 1] = g[a] + cumulative_simpson(dens[a : b + 1], x=s[a : b + 1])
            p = _p_of_g(g)
        else:
            p = np.ones_like(q)
        integrand = 0.5 * q**4 * c * p * inner_mu
        mu[i] = sum(simpson(integrand[a : b + 1], x=s[a : b + 1]) for a, b in zip(bounds[:-1], bounds[1:]))
        area[i] = p[-1]
    return mu, area


def friction_for_surface(surface, material, *, speeds, pressure, partial_contact=True, **kw):
    """:func:`friction` with the target PSD of a generated self-affine surface.

    Integrates from ``q0 = q_L / sqrt(pi)`` (the radius of the disc of area ``q_L**2``
    that the ``q = 0`` mode of the grid leaves out) to the cut-off ``q1``.
    """
    spectrum = dict(getattr(surface, "metadata", {}).get("spectrum") or {})
    if not spectrum or spectrum.get("dim") != 2 or spectrum.get("anisotropy", 1.0) != 1.0:
        raise InputError(
            "surface must be an isotropic 2-D bem.surfaces.self_affine surface (its target PSD "
            "is needed); use friction(..., psd=...) or friction_discrete for others"
        )
    q_l = 2 * np.pi / surface.length
    return friction(
        material,
        psd=lambda q: psd_target(q, **spectrum),
        q0=q_l / np.sqrt(np.pi),
        q1=spectrum["cutoff_wavevector"],
        speeds=speeds,
        pressure=pressure,
        partial_contact=partial_contact,
        breakpoints=(spectrum["rolloff_wavevector"],),
        **kw,
    )
