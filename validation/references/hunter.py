"""Hunter's exact solution: a rigid cylinder rolling on a standard-linear-solid half-space.

Frictionless, steady, plane strain (S.C. Hunter, J. Appl. Mech. 28 (1961) 611-617,
doi:10.1115/1.3641792). SI units: m, N/m, Pa, s.

Conventions (docs/theory.md §3), stated once here: the cylinder moves with speed ``V`` in ``+x``
(material flows in ``-x`` in its frame); ``x`` is measured from the cylinder's axis, whose
profile is ``h(x) = -x**2 / (2 R)``; the contact is ``[trailing_edge, leading_edge]`` with
the leading edge at ``+x``; displacement ``u`` is positive into the solid and
``mu = (1/P) integral p x / R dx > 0``. Material: ``J(w) = 1/E_inf + C / (1 + i w lam)``,
``C = 1/E0 - 1/E_inf``, creep time ``lam``, relaxation time ``tau = lam r``, ``r = E0/E_inf``.

Derivation (checked against the brute-force BEM of ``validation/references/bruteforce_line.py``).
Let ``s = dw/dx`` be the surface slope that ``p`` would give on a half-space of unit
modulus, ``s(x) = (2 (1-nu^2) / pi) PV integral p(t) / (t - x) dt``. With ``L = V lam``,
``l = V tau`` and ``d/dt = -V d/dx`` the SLS law reads ``E0 (u' - L u'') = s - l s'``.
In contact ``u' = -x/R``, so there ``s - l s' = E0 (L - x) / R``, whose solution is
``s = E0 (c - x) / R + A exp(x / l)``, ``c = L - l``: the exponential is the memory of the
material that entered at the leading edge. Put ``x = m + h t`` (``|t| <= 1``; centre ``m``,
half-width ``h``), ``kappa = h / l``, ``sigma = h / L = r kappa``, ``E0* = E0 / (1-nu^2)``.
Expanding ``exp(kappa t) = I0 + 2 sum I_n T_n(t)`` (modified Bessel ``I_n(kappa)``), the
finite Hilbert transform is inverted term by term; the pressure is bounded at both edges iff
the ``T_0`` coefficient vanishes, the load is the ``T_1`` coefficient and the first moment
(friction) the ``T_2`` one. One more condition fixes ``A``: ``u'`` at the leading edge must
equal ``-a/R`` when built from the slope ahead of the contact,
``E0 u'(a) = r s(a) + (1 - r) integral_0^inf exp(-z) s(a + L z) dz``; the Laplace integral
of the outer field gives ``K_0(sigma)``, ``K_1(sigma)`` and one smooth double integral ``N``.
Scaled by ``exp(-kappa)`` (``ive``, ``kve``) the result is, with ``k1 = kve(1, sigma)``,
``om = 1 - ive(0, kappa)`` and ``km = (sigma k1 - 1) / sigma``::

    D = ive0 + r om + (1-r) (ive0 sigma km + sigma (ive1 kve0 - N))
    m = (1-r) h [r (om/sigma - ive0 km) + (1-r) (ive1 kve0 - N)] / D
    P = (pi E0* h^2 / (4 R)) (1 + 2 (1-r) k1 ive1 / D)                 (solved for h)
    mu = m / R + (pi E0* h^2 / (4 R^2 P)) (1-r) h k1 ive2 / D
    p(t) = (E0* h / (2 R)) sqrt(1 - t^2) (1 + (1-r) (k1 / D) Z(t)),
    Z(t) = (1/pi) integral_0^pi (exp(kappa (cos f - 1)) - exp(kappa (t - 1))) / (cos f - t) df
    N = (1/pi) integral_0^pi sin(f)^2 exp(-kappa (1-cos f)) integral_0^inf
            exp(-sigma (cosh v - 1)) / (cosh v - cos f) dv df.

Limits: ``V -> 0`` gives Hertz with ``E0`` and ``mu -> (V lam / R)(1 - r)`` (``lam`` the
creep time); ``V -> inf`` gives Hertz with ``E_inf``. ``N`` and ``Z`` are evaluated by
Gauss-Legendre quadrature in variables that resolve their corners and decay scales (``N``
agrees with nested adaptive quadrature to 1e-14 for ``kappa`` in [1e-3, 1e6]).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from scipy import optimize, special

from bem.checks import check_positive
from bem.errors import InputError
from bem.materials.material import Material
from validation.references.hertz import line_contact

__all__ = ["HunterSolution", "rolling_cylinder", "low_speed_friction"]

_X64, _W64 = np.polynomial.legendre.leggauss(64)
_X12, _W12 = np.polynomial.legendre.leggauss(12)
_CUT = 40.0  # exp(-40) ~ 4e-18: weights beyond this exponent are dropped


def _n_integral(kap, sig):
    """The double integral ``N(kappa, sigma)`` of the module docstring (64 x 64 GL)."""
    fmax = 2 * np.arcsin(min(1.0, np.sqrt(_CUT / (2 * kap))))  # kap (1 - cos f) <= _CUT
    f = 0.5 * fmax * (_X64 + 1)
    wf = 0.5 * fmax * _W64
    vmax = min(_CUT, 2 * np.arcsinh(np.sqrt(_CUT / (2 * sig))))  # sig (cosh v - 1) <= _CUT
    wmax = np.arcsinh(vmax / f)[:, None]  # v = f sinh(w) resolves the corner v ~ f ~ 0
    w = 0.5 * wmax * (_X64 + 1)
    v = f[:, None] * np.sinh(w)
    dv = f[:, None] * np.cosh(w) * 0.5 * wmax * _W64
    den = 2 * (np.sinh(v / 2) ** 2 + np.sin(f[:, None] / 2) ** 2)  # cosh v - cos f
    inner = np.sum(np.exp(-2 * sig * np.sinh(v / 2) ** 2) / den * dv, axis=1)
    return np.sum(wf * np.sin(f) ** 2 * np.exp(-2 * kap * np.sin(f / 2) ** 2) * inner) / np.pi


def _hankel(n, z, sign):
    """``sqrt(2 pi z) ive(n, z)`` (sign -1) or ``sqrt(2 z / pi) kve(n, z)`` (+1) for large ``z``
    (four terms of the Hankel expansion: exact to round-off for ``z > 1e8``)."""
    mu, term, total = 4.0 * n * n, 1.0, 1.0
    for k in range(1, 5):
        term *= sign * (mu - (2 * k - 1) ** 2) / (k * 8.0 * z)
        total += term
    return total


def _ive(n, z):  # exp(-z) I_n(z); scipy (AMOS) returns nan beyond z ~ 2**31
    return special.ive(n, z) if z < 1e8 else _hankel(n, z, -1) / np.sqrt(2 * np.pi * z)


def _kve(n, z):  # exp(z) K_n(z), likewise
    return special.kve(n, z) if z < 1e8 else _hankel(n, z, 1) * np.sqrt(np.pi / (2 * z))


def _kve1m(s):
    """``(s kve(1, s) - 1) / s`` without cancellation (series of ``K_1`` for ``s < 1/2``)."""
    if s > 0.5:
        return (s * _kve(1, s) - 1) / s
    k = np.arange(12)
    q = (s * s / 4) ** k / (special.factorial(k) * special.factorial(k + 1))
    sk1m1 = np.log(s / 2) * (s / 2) * q.sum() - (s / 4) * np.sum((special.digamma(k + 1) + special.digamma(k + 2)) * q)
    return np.expm1(s) / s + np.exp(s) * sk1m1


def _one_minus_ive0(k):
    """``1 - exp(-k) I0(k)`` without cancellation for small ``k``."""
    if k > 1:
        return 1 - _ive(0, k)
    j = np.arange(1, 14)
    return -np.expm1(-k) - np.exp(-k) * np.sum((k * k / 4) ** j / special.factorial(j) ** 2)


def _state(h, e0s, r, lc, radius):
    """Centre ``m``, load ``P``, friction term and pressure scale at half-width ``h``."""
    sig = h / lc
    kap = sig / r
    nn = _n_integral(kap, sig)
    i0, i1, i2 = _ive(0, kap), _ive(1, kap), _ive(2, kap)
    k0, k1 = _kve(0, sig), _kve(1, sig)
    km, om = _kve1m(sig), _one_minus_ive0(kap)
    d = i0 + r * om + (1 - r) * (i0 * sig * km + sig * (i1 * k0 - nn))
    m = (1 - r) * h * (r * (om / sig - i0 * km) + (1 - r) * (i1 * k0 - nn)) / d
    load = np.pi * e0s * h**2 / (4 * radius) * (1 + 2 * (1 - r) * k1 * i1 / d)
    mu_extra = np.pi * e0s * h**2 / (4 * radius**2) * (1 - r) * h * k1 * i2 / d  # times 1/P
    return m, load, mu_extra, (1 - r) * k1 / d, kap


def _z(t, kap):
    """``Z(t)`` of the module docstring, by composite Gauss-Legendre graded at ``arccos t``
    (width ``1/kappa``) and at ``f = 0`` (width ``1/sqrt(kappa)``); ``t`` is a 1-D array."""
    f0 = np.arccos(t)[:, None]
    steps = 2.0 ** np.arange(60) / (4 * (kap + 1))
    steps = steps[steps < np.pi]
    near0 = 2.0 ** np.arange(30) / (4 * np.sqrt(kap + 1))
    near0 = near0[near0 < np.pi]
    edges = np.concatenate(
        [np.broadcast_to(np.r_[0.0, np.pi, near0], (t.size, near0.size + 2)), f0 - steps, f0 + steps], axis=1
    )
    edges = np.sort(np.clip(edges, 0.0, np.pi), axis=1)
    lo, hi = edges[:, :-1, None], edges[:, 1:, None]
    f = 0.5 * (hi - lo) * (_X12 + 1) + lo
    tt = t[:, None, None]
    y = np.cos(f) - tt
    small = np.abs(kap * y) < 1  # divided difference of exp: expm1 form near the diagonal
    ys = np.where(small & (y != 0), y, 1.0)
    near = np.where(y == 0, kap, special.expm1(kap * np.where(small, y, 0.0)) / ys)
    far = (np.exp(kap * (np.cos(f) - 1)) - np.exp(kap * (tt - 1))) / np.where(small, 1.0, y)
    dd = np.where(small, np.exp(kap * (tt - 1)) * near, far)
    val = dd * 0.5 * (hi - lo) * _W12
    return val.sum(axis=(1, 2)) / np.pi


@dataclass(frozen=True)
class HunterSolution:
    """Steady rolling contact of a rigid cylinder on a standard linear solid (plane strain).

    Attributes
    ----------
    leading_edge, trailing_edge : float
        Contact edges (m) measured from the cylinder's axis; leading at ``+x``.
    half_width, centre : float
        ``(lead - trail) / 2`` and ``(lead + trail) / 2`` (m).
    friction : float
        Rolling friction coefficient ``mu = (1/P) integral p x / R dx`` (> 0).
    peak_pressure, peak_position : float
        Maximum pressure (Pa) and its position (m).
    load, radius, speed : float
        The inputs: N/m, m, m/s.
    """

    leading_edge: float
    trailing_edge: float
    half_width: float
    centre: float
    friction: float
    peak_pressure: float
    peak_position: float
    load: float
    radius: float
    speed: float
    _p_scale: float = field(repr=False)  # E0* h / (2 R), Pa
    _z_scale: float = field(repr=False)  # (1 - r) kve1 / D
    _kappa: float = field(repr=False)

    def pressure(self, x):
        """Pressure (Pa) at ``x`` (m, any shape); zero outside the contact."""
        x = np.asarray(x, dtype=float)
        t = ((x - self.centre) / self.half_width).ravel()
        inside = np.abs(t) < 1
        p = np.zeros(t.shape)
        ti = t[inside]
        corr = self._z_scale * _z(ti, self._kappa) if self._z_scale else 0.0
        p[inside] = self._p_scale * np.sqrt((1 - ti) * (1 + ti)) * (1 + corr)
        return p.reshape(x.shape)


def _peak(sol):
    """Locate the pressure maximum: dense scan in ``t = cos(theta)`` then bounded Brent."""
    t = np.cos(np.linspace(np.pi, 0, 101)[1:-1])
    t = np.concatenate([t, 1 - np.geomspace(1e-10, 1e-3, 20)])
    x = sol.centre + sol.half_width * np.sort(t)
    p = sol.pressure(x)
    i = int(np.argmax(p))
    lo, hi = x[max(i - 1, 0)], x[min(i + 1, x.size - 1)]
    res = optimize.minimize_scalar(
        lambda s: -sol.pressure(np.array([s]))[0],
        bounds=(lo, hi),
        method="bounded",
        options={"xatol": 1e-12 * sol.half_width},
    )
    return (-res.fun, res.x) if -res.fun >= p[i] else (p[i], x[i])


def rolling_cylinder(material, *, radius, load, speed):
    """Hunter's exact steady rolling contact of a rigid cylinder on a standard linear solid.

    Parameters
    ----------
    material : bem.Material
        One-term (standard linear solid) or elastic material.
    radius : float
        Cylinder radius ``R`` (m), > 0.
    load : float
        Normal load per unit length ``P`` (N/m), > 0.
    speed : float
        Rolling speed ``V`` (m/s), >= 0; ``0`` (and an elastic material) gives Hertz with
        the relaxed modulus ``E0`` exactly.

    Returns
    -------
    HunterSolution
        Edges, friction, peak and ``pressure(x)``.

    Notes
    -----
    S.C. Hunter, J. Appl. Mech. 28 (1961) 611-617, doi:10.1115/1.3641792; the formulas are
    in the module docstring. Accuracy, for ``V lam / a`` from 1e-6 to 1e6 and ``E_inf/E0``
    up to 1e4: edges to ~1e-15 and friction to ~1e-13 relative, the latter degrading like
    ``1e-16 V lam / a`` at high speed (1e-10 at 1e6, where ``mu -> 0``); pressure to ~1e-12
    (1e-9 when ``V tau / a < 1e-9``); the peak position to ~1e-8 of the half-width (flat
    maximum). Agrees with the brute-force BEM to 2.5e-10 in friction (its own error at 1600
    cells). 5-45 ms a call.

    Raises
    ------
    InputError
        For a multi-term material or a non-positive radius or load, or a negative speed.

    Examples
    --------
    >>> from bem import Material
    >>> sls = Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)
    >>> round(rolling_cylinder(sls, radius=0.01, load=1000.0, speed=0.2).friction, 6)
    0.049242
    """
    if not isinstance(material, Material):
        raise InputError(f"material must be a bem.Material, got {type(material).__name__}")
    if material.moduli.size > 1:
        raise InputError(
            f"material must be elastic or a one-term standard linear solid, got {material.moduli.size} Prony terms"
        )
    radius = check_positive("radius", radius)
    load = check_positive("load", load)
    speed = check_positive("speed", speed, allow_zero=True)
    e0s = material.E0 / material.plane_strain_factor
    if material.is_elastic or speed == 0:
        hz = line_contact(material.E0, material.nu, radius, load)
        return HunterSolution(
            hz.a, -hz.a, hz.a, 0.0, 0.0, hz.p0, 0.0, load, radius, speed, e0s * hz.a / (2 * radius), 0.0, 0.0
        )
    r = material.E0 / material.E_inf
    lc = speed * material.creep_times[0]
    a0 = line_contact(material.E0, material.nu, radius, load).a
    # P(h) rises from <= load at the glassy Hertz width to >= load at the relaxed one
    lh = optimize.brentq(
        lambda q: np.log(_state(np.exp(q), e0s, r, lc, radius)[1] / load),
        np.log(a0 * np.sqrt(r)) - 1e-9,
        np.log(a0) + 1e-9,
        xtol=1e-15,
        rtol=1e-15,
    )
    h = float(np.exp(lh))
    m, _, mu_extra, z_scale, kap = (float(v) for v in _state(h, e0s, r, lc, radius))
    sol = HunterSolution(
        m + h,
        m - h,
        h,
        m,
        m / radius + mu_extra / load,
        np.nan,
        np.nan,
        load,
        radius,
        speed,
        e0s * h / (2 * radius),
        z_scale,
        kap,
    )
    pk, xk = _peak(sol)
    return replace(sol, peak_pressure=float(pk), peak_position=float(xk))


def low_speed_friction(material, *, radius, speed):
    """Leading-order rolling friction of a cylinder at low speed, any creep series.

    ``mu ~ (V / R) E0 sum_k C_k lam_k`` (for one term ``(V lam / R)(1 - E0/E_inf)``, with
    ``lam`` the creep time): to first order in ``V``, ``J(w) ~ 1/E0 - i w sum C_k lam_k``
    makes the pressure the Hertz (``E0``) one shifted ahead by ``c = V E0 sum_k C_k lam_k``
    (outside a leading-edge layer of width ``V tau`` that keeps the leading edge at the
    Hertz one while the trailing edge advances by ``c``). Independent of load.

    ``material`` is any :class:`bem.Material`, ``radius`` in m (> 0), ``speed`` in m/s
    (>= 0); returns the (dimensionless) friction coefficient.
    """
    radius = check_positive("radius", radius)
    speed = check_positive("speed", speed, allow_zero=True)
    return speed / radius * material.E0 * float(np.sum(material.compliances * material.creep_times))
