"""Rough periodic profile sliding over a rubber: several contact spots, below, at and above the friction peak.

The profile is self-affine over a few scales: 64 samples over ``L = 1 mm``, wavelengths ``L`` to
``L / 16`` with amplitudes ``k^-(1 + H)`` (``H = 0.8``), random phases
(``numpy.random.default_rng(SEED)``), scaled to 20 um peak to valley; heights positive toward the
solid, sampled at ``x_j = j L / 64``, continued between the samples by their trigonometric
interpolant (:func:`fem_reference.profile.profile_nodes`). The rubber is a 4-term Prony series
(``E0 = 1 MPa``, ``E_k = 50, 30, 20, 10 MPa``, ``tau_k = 1e-6..1e-3 s``, ``nu = 0.5``); the load is
40 N/m per period.

There is no exact solution. The reference (``bem-reference``) is the BEM converged on the profile's
interpolant on 4096 points. Under test: ``bem-periodic``, the BEM on the interpolant on 256 points
(as a user would run it on a resampled profile), and in the full set ``fem-profile``
(:func:`fem_reference.sliding_profile`, its default call). Compared: the friction in both forms
(dissipation, the BEM's ``friction``; moment, ``friction_eq6``), the contact fraction and, for the
FEM, the pressure on its contact nodes and the positions of the spot edges.
"""

from __future__ import annotations

import numpy as np

import bem
from bem import surfaces
from fem_reference.profile import profile_nodes, spot_edges
from validation import metrics

from .base import Case, CaseOutput, Profile, Sweep
from .fem_checks import force_balance_check
from .vtk_out import write_bem_sweep, write_pvd_for

L = 1e-3  # period (m)
SAMPLES = 64  # samples of the profile over one period
MODES = 16  # wavelengths L, L/2, ..., L/16
HURST = 0.8
PEAK_TO_VALLEY = 20e-6  # m
# the first seed of 0..39 giving 10-15 % contact on 4 spots at 0.1 m/s (BEM, 4096 points): 11.2 %,
# spots of 69, 180, 69 and 136 of the 4096 points
SEED = 22
LOAD = 40.0  # N/m per period
REF_POINTS = 4096  # the converged BEM reference
RTOL = 1e-10  # the BEM solves' complementarity tolerance


def rubber():
    """The case's 4-term Prony rubber: E0 = 1 MPa, E_inf = 111 MPa."""
    return bem.Material.from_prony(E0=1e6, moduli=[5e7, 3e7, 2e7, 1e7], times=[1e-6, 1e-5, 1e-4, 1e-3], nu=0.5)


def profile_heights(seed=SEED):
    """The 64 samples of the profile (m), positive toward the solid, zero mean."""
    rng = np.random.default_rng(seed)
    x = np.arange(SAMPLES) * L / SAMPLES
    k = np.arange(1, MODES + 1)
    phases = rng.uniform(0.0, 2 * np.pi, k.size)
    h = np.sum(k[:, None] ** -(1 + HURST) * np.cos(2 * np.pi * k[:, None] * x / L + phases[:, None]), axis=0)
    h -= h.mean()
    return h * PEAK_TO_VALLEY / np.ptp(h)


def _resampled(heights, n):
    """The profile's trigonometric interpolant on ``n`` points as a BEM surface."""
    fine, _ = profile_nodes(heights, L, np.arange(n) * L / n)
    return surfaces.Surface(fine, L)


def _bem(surface, material, V, load):
    return bem.solve(surface, material, speed=V, load=load, rtol=RTOL)


def _fem(material, heights, V, load, vtk):
    from fem_reference import sliding_profile

    return sliding_profile(material, heights=heights, length=L, load=load, speed=V, vtk=vtk)


def _interp_periodic(x, xp, fp):
    return np.interp(x, np.r_[xp, L], np.r_[fp, fp[0]])


def _edge_distance(spots, ref_spots):
    """The largest distance (m) of an edge of ``spots`` from the nearest edge of ``ref_spots``, either
    way round (a spot missing on one side counts through its edges' distance to the other's), on the
    periodic cell."""

    def one_way(a, b):
        ea, eb = np.asarray(a, float).ravel() % L, np.asarray(b, float).ravel() % L
        if ea.size == 0 or eb.size == 0:
            return L if ea.size != eb.size else 0.0
        d = np.abs(ea[:, None] - eb[None, :])
        return float(np.max(np.min(np.minimum(d, L - d), axis=1)))

    return max(one_way(spots, ref_spots), one_way(ref_spots, spots))


def run_rough_profile(*, quick, vtk_dir, root, tamper):
    cfg = QUICK if quick else FULL
    material = rubber()
    heights = profile_heights()
    out = CaseOutput()
    reference_surface = _resampled(heights, REF_POINTS)
    xb = np.arange(REF_POINTS) * L / REF_POINTS
    refs, bems, fems, sols = [], [], [], []
    for V in SPEEDS:
        label = f"V={V:g}"
        ref, cost = tamper.reference(("bem-reference", V), metrics.measure, _bem, reference_surface, material, V, LOAD)
        if tamper.perturbation.name == "none":
            out.cost("bem-reference", label, cost, f"{REF_POINTS} points")
        refs.append(ref)
        profile_curves = {"bem-reference": (xb, ref.pressure)}
        errors = {}
        for n in cfg["bem_points"]:
            solver = "bem-periodic"
            m, v, load = tamper.inputs(solver, material, V, LOAD)
            surface = _resampled(heights, n)
            res, cost = metrics.measure(_bem, surface, m, v, load)
            out.cost(solver, f"{label} n={n}", cost, f"{n} points, {res.iterations} iterations")
            pair, tol, why = f"{solver} vs bem-reference", TOL_BEM[n][V], WHY_BEM[n][V]
            at = f"{label} n={n}"
            out.check(
                "friction_rel_diff",
                pair,
                at,
                metrics.rel_diff(res.friction, ref.friction),
                *tol_why(tol, why, "friction"),
            )
            out.check(
                "friction_eq6_rel_diff",
                pair,
                at,
                metrics.rel_diff(res.friction_eq6, ref.friction_eq6),
                *tol_why(tol, why, "friction_eq6"),
            )
            out.check(
                "contact_fraction_rel_diff",
                pair,
                at,
                metrics.rel_diff(res.contact_fraction, ref.contact_fraction),
                *tol_why(tol, why, "contact_fraction"),
            )
            x = np.arange(n) * L / n
            profile_curves[f"{solver} n={n}"] = (x, res.pressure)
            errors[f"{solver} n={n}"] = (x, res.pressure - _interp_periodic(x, xb, ref.pressure))
            bems.append((n, V, res))
            sols.append(dict(surface=surface, result=res, material=m, detail=f"bem.solve, {n} points"))
        if cfg["fem"]:
            f = _run_fem(out, material, heights, V, label, ref, xb, vtk_dir, tamper)
            if f is not None:
                fems.append((V, f))
                profile_curves["fem-profile"] = (f.x, f.pressure)
                errors["fem-profile"] = (f.x, f.pressure - _interp_periodic(f.x, xb, ref.pressure))
        out.profiles.append(Profile(f"{label} m/s", profile_curves, reference="bem-reference", errors=errors))
    speeds = np.array(SPEEDS)
    curves = {
        "bem-reference (dissipation)": (speeds, np.array([r.friction for r in refs])),
        "bem-reference (moment)": (speeds, np.array([r.friction_eq6 for r in refs])),
    }
    for n in cfg["bem_points"]:
        curves[f"bem-periodic n={n}"] = (speeds, np.array([r.friction for k, _, r in bems if k == n]))
    if fems:
        curves["fem-profile (dissipation)"] = (
            np.array([V for V, _ in fems]),
            np.array([f.friction_dissipation for _, f in fems]),
        )
        curves["fem-profile (moment)"] = (np.array([V for V, _ in fems]), np.array([f.friction for _, f in fems]))
    out.sweeps.append(Sweep("friction against speed", "V (m/s)", "friction coefficient", curves))
    out.sweeps.append(
        Sweep(
            "contact fraction against speed",
            "V (m/s)",
            "contact fraction",
            {"bem-reference": (speeds, np.array([r.contact_fraction for r in refs]))}
            | {
                f"bem-periodic n={n}": (speeds, np.array([r.contact_fraction for k, _, r in bems if k == n]))
                for n in cfg["bem_points"]
            }
            | (
                {"fem-profile": (np.array([V for V, _ in fems]), np.array([f.contact_fraction for _, f in fems]))}
                if fems
                else {}
            ),
        )
    )
    if vtk_dir is not None:
        for n in cfg["bem_points"]:
            picked = [(s, V) for s, (k, V, _) in zip(sols, bems) if k == n]
            out.files += write_bem_sweep(vtk_dir / f"bem_n{n}", root, *zip(*picked), parameter="V", rtol=RTOL)
        if fems:
            out.files += write_pvd_for(
                vtk_dir / "fem-profile",
                root,
                [(f"point_{k:03d}.vtm", V) for k, (V, _) in enumerate(fems)],
                parameter="V",
            )
    out.numbers["profile"] = dict(
        samples=SAMPLES, modes=MODES, hurst=HURST, seed=SEED, peak_to_valley=PEAK_TO_VALLEY, length=L, load=LOAD
    )
    out.numbers["reference"] = {
        f"V={V:g}": dict(
            friction=r.friction,
            friction_eq6=r.friction_eq6,
            contact_fraction=r.contact_fraction,
            spots=int(len(spot_edges(xb, r.pressure, r.pressure > 0, L))),
        )
        for V, r in zip(SPEEDS, refs)
    }
    return out


def tol_why(tol, why, key, speed=None):
    """``(tolerance, reason)`` of ``key``; entries given per speed (dicts keyed by the speed) at ``speed``."""
    t, w = tol[key], why[key]
    return (t[speed], w[speed]) if isinstance(t, dict) else (t, w)


def _run_fem(out, material, heights, V, label, ref, xb, vtk_dir, tamper):
    """The FEM's default call against the converged BEM; returns its result (None when it failed)."""
    solver = "fem-profile"
    m, v, load = tamper.inputs(solver, material, V, LOAD)
    vtk = None
    if vtk_dir is not None:
        (vtk_dir / solver).mkdir(parents=True, exist_ok=True)
        vtk = vtk_dir / solver / f"point_{SPEEDS.index(V):03d}.vtm"
    f, cost = metrics.measure(_fem, m, heights, v, load, vtk)
    out.cost(solver, label, cost, f"{f.n_unknowns} unknowns, {f.passes} meshes, {f.elements} surface squares")
    if not out.converged(solver, label, dict(success=f.success, message=f.message, residual=f.residual)):
        return None
    pair = f"{solver} vs bem-reference"
    force_balance_check(out, label, float(np.sum(f.forces)), LOAD, pair)
    out.check(
        "friction_moment_rel_diff",
        pair,
        label,
        metrics.rel_diff(f.friction, ref.friction_eq6),
        *tol_why(TOL_FEM, WHY_FEM, "moment"),
    )
    out.check(
        "friction_rel_diff",
        pair,
        label,
        metrics.rel_diff(f.friction_dissipation, ref.friction),
        *tol_why(TOL_FEM, WHY_FEM, "dissipation"),
    )
    out.check(
        "contact_fraction_rel_diff",
        pair,
        label,
        metrics.rel_diff(f.contact_fraction, ref.contact_fraction),
        *tol_why(TOL_FEM, WHY_FEM, "contact_fraction"),
    )
    on = np.asarray(f.contact, bool)
    p_ref = _interp_periodic(f.x[on], xb, ref.pressure)
    out.check(
        "spot_pressure_rel_l2",
        pair,
        label,
        float(np.sqrt(np.sum((f.pressure[on] - p_ref) ** 2) / np.sum(p_ref**2))),
        *tol_why(TOL_FEM, WHY_FEM, "pressure", V),
    )
    ref_spots = spot_edges(xb, ref.pressure, ref.pressure > 0, L)
    out.check(
        "spot_edge_distance_per_L",
        pair,
        label,
        _edge_distance(f.spots, ref_spots) / L,
        *tol_why(TOL_FEM, WHY_FEM, "edge"),
    )
    out.numbers[f"fem {label}"] = dict(
        friction=f.friction,
        friction_dissipation=f.friction_dissipation,
        contact_fraction=f.contact_fraction,
        error_estimate=dict(f.error_estimate) if f.error_estimate else None,
        warnings=list(f.warnings),
        n_unknowns=int(f.n_unknowns),
    )
    return f


from .rough_profile_settings import FULL, QUICK, SPEEDS, TOL_BEM, TOL_FEM, WHY_BEM, WHY_FEM  # noqa: E402

CASES = [
    Case(
        "rough_profile",
        "Rough periodic profile sliding over a rubber (several spots, around the friction peak)",
        "Self-affine profile (64 samples, wavelengths L..L/16, 20 um peak to valley, L = 1 mm) at 40 N/m on a "
        "4-term Prony rubber, a decade below, at and a decade above the friction peak: the BEM on 256 points "
        "(and in the full set the FEM's default call) against the BEM converged on 4096 points.",
        ("bem-periodic", "fem-profile", "bem-reference"),
        "bem-reference",
        run_rough_profile,
        seconds=400,
    )
]
