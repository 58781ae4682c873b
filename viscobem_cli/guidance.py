"""What a user should know about a study before and after it runs.

- :func:`hertz_radius`: the relaxed Hertz contact radius ``a0`` of a sphere or cylinder,
  the length in ``xi = v tau / a0`` for indenters (as in Hunter's rolling cylinder, where
  the friction peak sits near ``v tau ~ a0`` whatever the domain).
- :func:`describe_xi`: the time ``tau`` (and where it comes from) and the speeds that the
  sweep's ``xi`` range stands for.
- :func:`resolution_warnings` (before the run) and :func:`peak_warnings` (after): texts that
  say what is doubtful and what to change; the run prints them and stores them in
  ``results.json["warnings"]``, beside every point's own warnings and error estimate, which
  come with its result from :mod:`bem.accuracy` (this module reads them, it does not judge the
  resolution a second time).
"""

import math

import numpy as np

from bem.accuracy.indicators import points_per_wavelength


def hertz_radius(kind, *, modulus, nu, radius, load):
    """Hertz contact radius (m) of a rigid ``"sphere"`` (load in N) or ``"cylinder"`` (load in
    N/m, plane strain, the half-width) on an elastic half-space of Young's ``modulus`` (Pa)."""
    e_star = modulus / (1 - nu**2)
    if kind == "sphere":
        return (3 * load * radius / (4 * e_star)) ** (1 / 3)
    return math.sqrt(4 * load * radius / (math.pi * e_star))


def describe_xi(scene):
    """Lines for the console: tau and its origin, the length in xi, the speed range."""
    v, xi = scene.speeds, scene.xi
    length = "the relaxed Hertz contact radius a0" if scene.xi_length != scene.surface.length else "the cell length L"
    return [
        f"xi = v tau / l with tau = {scene.xi_time:.4g} s ({scene.xi_time_source}) and "
        f"l = {scene.xi_length * 1e3:.4g} mm ({length})",
        f"xi = {xi.min():.3g} .. {xi.max():.3g} is v = {v.min():.3g} .. {v.max():.3g} m/s",
    ]


def resolution_warnings(surface, kind, periodic, minimum):
    """A warning before the run when a periodic surface has fewer than ``minimum`` grid points per
    shortest wavelength (:func:`bem.accuracy.indicators.points_per_wavelength`, measured on the
    heights, whatever made them); isolated domains are judged by their solutions alone."""
    if not periodic:
        return []
    ppw = points_per_wavelength(surface.heights)
    if ppw >= minimum:
        return []
    need = math.ceil(surface.n * minimum / ppw)
    also = " or lower [surface] scales" if kind == "self_affine" else ""
    return [
        f"the grid has {ppw:.3g} points per shortest wavelength of the surface (n = {surface.n}); below "
        f"{minimum}, contact spots are not resolved and friction and contact area are not converged "
        f"(each point's estimated errors follow the run). Raise [surface] n to at least {need}{also}."
    ]


def peak_warnings(curves, xi_time_source):
    """A warning per load whose friction is largest at an end of the sweep: the peak (and the
    physics of the hysteresis maximum) lies outside the xi range."""
    out = []
    for curve in curves:
        mu = np.array([np.nan if x is None else x for x in curve["friction"]], dtype=float)
        xi = np.asarray(curve["xi"], dtype=float)
        ok = np.isfinite(mu) & (xi > 0)
        if np.count_nonzero(ok) < 3:
            continue
        order = np.argsort(xi[ok])
        mu, xi = mu[ok][order], xi[ok][order]
        top = int(np.argmax(mu))
        if 0 < top < mu.size - 1:
            continue
        side, key = ("highest", "stop") if top == mu.size - 1 else ("lowest", "start")
        out.append(
            f"at load {curve['load']:g}, friction is largest at the {side} speed of the sweep (xi = "
            f"{xi[top]:.3g}): the friction peak lies outside the xi range. Extend [loading] xi.{key} "
            f"(tau is {xi_time_source})."
        )
    return out
