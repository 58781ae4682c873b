"""What a user should know about a study before and after it runs.

- :func:`hertz_radius`: the relaxed Hertz contact radius ``a0`` of a sphere or cylinder,
  the length in ``xi = v tau / a0`` for indenters (as in Hunter's rolling cylinder, where
  the friction peak sits near ``v tau ~ a0`` whatever the domain).
- :func:`describe_xi`: the time ``tau`` (and where it comes from) and the speeds that the
  sweep's ``xi`` range stands for.
- :func:`resolution_warnings` (before the run), :func:`friction_form_warnings` and
  :func:`peak_warnings` (after):
  texts that say what is doubtful and what to change; the run prints them and stores them
  in ``results.json["warnings"]``.
"""

import math

import numpy as np

FORM_TOLERANCE = 0.05  # the dissipation and eq. 6 friction forms agree to 5 % on a resolved grid
NEGLIGIBLE = 0.01  # friction below 1 % of the curve's peak is not compared (both forms ~ 0 there)


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


def points_per_wavelength(raw_surface, n):
    """Grid points per shortest wavelength of a generated surface, or None if not defined."""
    kind = raw_surface.get("kind")
    if kind == "self_affine":
        s = float(raw_surface.get("anisotropy", 1.0))
        return n / (raw_surface.get("scales", 64) * max(s, 1 / s))
    if kind == "sinusoid":
        wavelength = raw_surface.get("wavelength", raw_surface["length"])
        return wavelength / raw_surface["length"] * n
    return None


def resolution_warnings(raw_surface, n, minimum):
    """A warning when the grid has fewer than ``minimum`` points per shortest wavelength."""
    ppw = points_per_wavelength(raw_surface, n)
    if ppw is None or ppw >= minimum:
        return []
    need = math.ceil(n * minimum / ppw)
    return [
        f"the grid has {ppw:.3g} points per shortest wavelength of the surface (n = {n}); below "
        f"{minimum}, contact spots are not resolved and friction and contact area are not converged "
        f"(the dissipation and eq. 6 friction forms drift apart). Raise [surface] n to at least {need} "
        f"or lower [surface] scales."
    ]


def form_advice(kind):
    """What to change when the two friction forms differ, for a surface of scene ``kind``: only
    generated rough surfaces have ``scales``."""
    if kind == "self_affine":
        return "Raise [surface] n (or lower [surface] scales) until they agree."
    if kind == "measured":
        return (
            "Raise [surface] n (at most the scan's own pixels per side), and keep the default boundary "
            "(boundary = 'isolated' and window = 'none' load the patch's edges)."
        )
    return "Raise [surface] n until they agree."


def friction_form_warnings(
    curves, tolerance=FORM_TOLERANCE, advice="Raise [surface] n (or lower [surface] scales) until they agree."
):
    """A warning per load whose two friction forms differ by more than ``tolerance`` (relative)."""
    out = []
    for curve in curves:
        mu = np.array([np.nan if x is None else x for x in curve["friction"]], dtype=float)
        mu6 = np.array([np.nan if x is None else x for x in curve["friction_eq6"]], dtype=float)
        if not np.any(np.isfinite(mu)):
            continue
        peak = np.nanmax(np.abs(mu))
        with np.errstate(invalid="ignore", divide="ignore"):
            rel = np.abs(mu - mu6) / np.maximum(np.abs(mu), np.abs(mu6))
        bad = np.flatnonzero((rel > tolerance) & (np.abs(mu) > NEGLIGIBLE * peak))
        if bad.size == 0:
            continue
        worst = int(bad[np.argmax(rel[bad])])
        out.append(
            f"at load {curve['load']:g}, the two friction forms (dissipation and eq. 6) differ by more "
            f"than {100 * tolerance:g} % at {bad.size} of {mu.size} speeds (worst {100 * rel[worst]:.3g} % "
            f"at xi = {curve['xi'][worst]:.3g}): the grid does not resolve the contact. {advice}"
        )
    return out


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
