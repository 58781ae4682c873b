"""Sphere cases: Hertz limits and the low-speed friction asymptote; creep indentation.

Sphere ``R = 10 mm``, load ``P = 1 N``, the seed paper's standard linear solid
(``E_inf = 10 MPa``, ``E_inf/E0 = 3``, creep time 10 ms, ``nu = 0.5``).

Solvers: ``fem`` (axisymmetric scikit-fem indentation under a step load: the glassy limit
at ``t = 0+`` and the relaxed one at ``t = 1000 lambda``), ``bem-periodic`` (2-D periodic BEM
with one sphere cap per cell, :func:`solvers.bem_periodic_sphere`) at rest and at low speed;
``bem-isolated-uniform`` and ``bem-isolated-adaptive`` (isolated 2-D BEM,
:func:`solvers.bem_isolated_sphere`) at rest, at the glassy limit (``s = 1e4``) and at low
speed. The periodic cell cannot show the glassy limit: its ``q_x = 0`` modes are not excited
by sliding and respond relaxed at any speed.
"""

from __future__ import annotations

import numpy as np

from validation import metrics
from validation.references import lee_radok
from validation.references.hertz import point_contact
from validation.references.hunter import low_speed_friction

from .base import Case, CaseOutput, Profile, Sweep
from .cylinder import sls
from .fem_checks import force_balance_check
from .solvers import bem_isolated_sphere, bem_periodic_sphere
from .sphere_settings import FULL_CREEP, FULL_SPHERE, QUICK_CREEP, QUICK_SPHERE, WHY, WHY_FEM
from .vtk_out import write_bem_sweep

R, P = 0.01, 1.0
HIGH_SPEED = 1e4  # s = V lambda / a0 standing for the glassy limit (creep terms shifted by 1e4 a0)


def _isolated(method):
    def adapter(material, *, radius, load, speed, cells):
        return bem_isolated_sphere(material, radius=radius, load=load, speed=speed, cells=cells, method=method)

    return adapter


SPHERE_BEM = {
    "bem-periodic": bem_periodic_sphere,
    "bem-isolated-uniform": _isolated("uniform"),
    "bem-isolated-adaptive": _isolated("adaptive"),
}


def _fem_indentation(material, times, load=P, vtk=None):
    import fem_reference

    return fem_reference.indentation(material, radius=R, load=load, times=np.asarray(times, float), vtk=vtk)


def _a0(material):
    return point_contact(material.E0, material.nu, R, P).a


def run_sphere(*, quick, vtk_dir, root, tamper):
    material = sls(3)
    cfg = QUICK_SPHERE if quick else FULL_SPHERE
    lam = float(material.creep_times[0])
    out = CaseOutput()
    # --- FEM: both elastic limits from one step-load run
    # the two elastic limits depend on the moduli and the load only
    m_fem, _, p_fem = tamper.inputs("fem", material, 0.0, P, insensitive=("times", "speed"))
    fem, cost = metrics.measure(_fem_indentation, m_fem, [0.0, 1000 * lam], p_fem)
    out.cost("fem", "t=0+, 1000 lambda", cost, f"{fem.n_unknowns} unknowns, h = {fem.element_size:.3e} m")
    t = cfg["tol"]["fem"]
    for i, (label, modulus) in enumerate((("glassy (t=0+)", material.E_inf), ("relaxed (t=1000 lambda)", material.E0))):
        force_balance_check(out, label, fem.contact_force[i], P)
        hz = point_contact(modulus, material.nu, R, P)
        out.check(
            "contact_radius_error_elements",
            "fem",
            label,
            metrics.edge_error(fem.contact_radius[i], hz.a, fem.element_size),
            t["edge"],
            WHY_FEM["edge"],
        )
        out.check(
            "approach_rel_error",
            "fem",
            label,
            metrics.rel_diff(fem.approach[i], hz.delta),
            t["approach"],
            WHY_FEM["approach"],
        )
        out.check(
            "peak_pressure_rel_error",
            "fem",
            label,
            metrics.rel_diff(fem.peak_pressure[i], hz.p0),
            t["peak"],
            WHY_FEM["peak"],
        )
    hz0 = point_contact(material.E0, material.nu, R, P)
    out.check(
        "pressure_rel_l2",
        "fem",
        "relaxed (t=1000 lambda)",
        metrics.rel_l2(fem.r, fem.pressure, hz0.pressure(fem.r), weight=fem.r),
        t["l2"],
        WHY_FEM["l2"],
    )
    # --- BEM: at rest (Hertz with E0), glassy limit (isolated only), low speeds (friction asymptote)
    a0 = _a0(material)
    curves = {
        "asymptote (V/R) E0 C lambda": (
            np.array(cfg["s"]),
            np.array([low_speed_friction(material, radius=R, speed=s * a0 / lam) for s in cfg["s"]]),
        )
    }
    xf = np.linspace(-1.3 * hz0.a, 1.3 * hz0.a, 401)
    keep_f = fem.r <= 1.3 * hz0.a
    rest = Profile(
        "at rest / relaxed: Hertz with E0 (BEM: row next to y = 0; FEM: radius)",
        {"exact": (xf, hz0.pressure(xf)), "fem": (fem.r[keep_f], fem.pressure[keep_f])},
        reference="exact",
        errors={"fem": (fem.r[keep_f], fem.pressure[keep_f] - hz0.pressure(fem.r[keep_f]))},
    )
    hzi = point_contact(material.E_inf, material.nu, R, P)
    for name, adapter in SPHERE_BEM.items():
        tb, why = cfg["tol"][name], WHY[name]
        points = [0.0] + ([HIGH_SPEED] if name != "bem-periodic" else []) + cfg["s"]
        sols, labels = [], []
        for s in points:
            V = s * a0 / lam
            label = "rest" if s == 0 else ("glassy" if s == HIGH_SPEED else f"s={s:g}")
            m, v, p = tamper.inputs(name, material, V, P)
            b, cost = metrics.measure(adapter, m, radius=R, load=p, speed=v, cells=cfg["cells"])
            out.cost(name, label, cost, b["detail"])
            if not out.converged(name, label, b):
                continue
            sols.append(b)
            labels.append(s)
            if s in (0.0, HIGH_SPEED):
                hz = hz0 if s == 0 else hzi
                y = b.get("line_y", 0.0)
                out.check(
                    "pressure_rel_l2",
                    name,
                    label,
                    metrics.rel_l2(None, b["field"].ravel(), hz.pressure(np.hypot(b["X"], b["Y"]).ravel())),
                    tb["l2"],
                    why["l2"],
                )
                out.check(
                    "peak_pressure_rel_error",
                    name,
                    label,
                    metrics.rel_diff(b["peak_pressure"], hz.p0),
                    tb["peak"],
                    why["peak"],
                )
                out.check(
                    "contact_radius_error_elements",
                    name,
                    label,
                    metrics.edge_error(b["leading_edge"], np.sqrt(hz.a**2 - y**2), b["spacing"]),
                    tb["edge"],
                    why["edge"],
                )
                if s == 0:
                    keep = np.abs(b["x"]) <= 1.3 * hz0.a
                    p_ex = hz0.pressure(np.hypot(b["x"][keep], y))
                    rest.curves[name] = (b["x"][keep], b["pressure"][keep])
                    rest.errors[name] = (b["x"][keep], b["pressure"][keep] - p_ex)
            else:
                mu0 = low_speed_friction(material, radius=R, speed=V)
                out.check(
                    "low_speed_asymptote_rel_error",
                    name,
                    label,
                    metrics.rel_diff(b["friction"], mu0),
                    tb["asymptote"],
                    why["asymptote"],
                )
                if "excess" in tb:
                    out.check(
                        "low_speed_asymptote_excess",
                        name,
                        label,
                        (b["friction"] - mu0) / mu0,
                        tb["excess"],
                        why["excess"],
                    )
        low = [(s, b["friction"]) for s, b in zip(labels, sols) if s in cfg["s"]]
        if low:
            curves[name] = tuple(np.array(v) for v in zip(*low))
        if vtk_dir is not None and sols:
            out.files += write_bem_sweep(vtk_dir / name, root, sols, labels, parameter="s")
    out.profiles.append(rest)
    out.sweeps.append(Sweep("low-speed friction", "s = V lambda / a0", "friction coefficient", curves, logy=True))
    out.numbers["fem"] = dict(
        contact_radius=fem.contact_radius.tolist(),
        approach=fem.approach.tolist(),
        peak_pressure=fem.peak_pressure.tolist(),
    )
    out.numbers["hertz"] = dict(a0=hz0.a, p0=hz0.p0, delta0=hz0.delta)
    return out


def run_creep(*, quick, vtk_dir, root, tamper):
    """Step load on the sphere: contact radius, approach, peak pressure and the final pressure
    profile against Lee & Radok (:mod:`validation.references.lee_radok`)."""
    material = sls(3)
    cfg = QUICK_CREEP if quick else FULL_CREEP
    lam = float(material.creep_times[0])
    times = np.array(cfg["t"]) * lam
    out = CaseOutput()
    m_fem, _, p_fem = tamper.inputs("fem", material, 0.0, P)
    pvd = None if vtk_dir is None else vtk_dir / "fem" / "creep.pvd"
    fem, cost = metrics.measure(_fem_indentation, m_fem, times, p_fem, pvd)
    if pvd is not None:
        out.files += [str(f.relative_to(root)) for f in sorted(pvd.parent.glob("creep_*.vtm"))]
        out.files.append(str(pvd.relative_to(root)))
    out.cost("fem", "all times", cost, f"{fem.n_unknowns} unknowns, {fem.n_steps} steps, h = {fem.element_size:.3e} m")
    a_ex = lee_radok.contact_radius(material, R, P, times)
    d_ex = lee_radok.approach(material, R, P, times)
    # the exact maximum over r: an off-axis ring once the contact has crept (r/a ~ 0.9 at higher ratios)
    p_ex = np.array(
        [lee_radok.pressure(material, R, P, tt, np.linspace(0.0, a, 801)).max() for tt, a in zip(times, a_ex)]
    )
    t = cfg["tol"]
    for i, tt in enumerate(cfg["t"]):
        label = f"t={tt:g} lambda"
        force_balance_check(out, label, fem.contact_force[i], P)
        out.check(
            "contact_radius_error_elements",
            "fem",
            label,
            metrics.edge_error(fem.contact_radius[i], a_ex[i], fem.element_size),
            t["edge"],
            WHY_FEM["edge"],
        )
        out.check(
            "approach_rel_error",
            "fem",
            label,
            metrics.rel_diff(fem.approach[i], d_ex[i]),
            t["approach"],
            WHY_FEM["approach"],
        )
        out.check(
            "peak_pressure_rel_error",
            "fem",
            label,
            metrics.rel_diff(fem.peak_pressure[i], p_ex[i]),
            t["peak"],
            WHY_FEM["peak_creep"],
        )
    td = np.geomspace(1e-2, max(cfg["t"]) * 2, 60) * lam
    a_d = lee_radok.contact_radius(material, R, P, td)
    pos = times > 0
    out.sweeps.append(
        Sweep(
            "contact radius against time",
            "t (s)",
            "a (m)",
            {"Lee-Radok": (td, a_d), "fem": (times[pos], fem.contact_radius[pos])},
        )
    )
    out.sweeps.append(
        Sweep(
            "approach against time",
            "t (s)",
            "delta (m)",
            {"Lee-Radok": (td, a_d**2 / R), "fem": (times[pos], fem.approach[pos])},
        )
    )
    a_end = float(a_ex[-1])
    xf = np.linspace(0, 1.3 * a_end, 300)
    keep = fem.r <= 1.3 * a_end
    p_end = lee_radok.pressure(material, R, P, times[-1], fem.r)
    out.check(
        "pressure_rel_l2",
        "fem",
        f"t={cfg['t'][-1]:g} lambda",
        metrics.rel_l2(fem.r, fem.pressure, p_end, weight=fem.r),
        t["l2"],
        WHY_FEM["l2"],
    )
    out.check(
        "axis_pressure_rel_error",
        "fem",
        f"t={cfg['t'][-1]:g} lambda",
        metrics.rel_diff(fem.pressure[0], p_end[0]),
        t["axis"],
        WHY_FEM["axis"],
    )
    out.profiles.append(
        Profile(
            f"t = {cfg['t'][-1]:g} lambda",
            {
                "Lee-Radok": (xf, lee_radok.pressure(material, R, P, times[-1], xf)),
                "fem": (fem.r[keep], fem.pressure[keep]),
            },
            reference="Lee-Radok",
            errors={"fem": (fem.r[keep], fem.pressure[keep] - p_end[keep])},
            xlabel="r (m)",
        )
    )
    out.numbers["times"] = times.tolist()
    out.numbers["fem"] = dict(
        contact_radius=fem.contact_radius.tolist(),
        approach=fem.approach.tolist(),
        error_estimate={k: np.asarray(v).tolist() for k, v in fem.error_estimate.items()},
        warnings=list(fem.warnings),
    )
    out.numbers["exact"] = dict(contact_radius=a_ex.tolist(), approach=d_ex.tolist())
    return out


CASES = [
    Case(
        "sphere_hertz",
        "Sphere: Hertz limits and low-speed friction",
        "Rigid sphere (R = 10 mm, 1 N) on the seed SLS: FEM indentation at t = 0+ (Hertz, E_inf) and "
        "t = 1000 lambda (Hertz, E0); periodic 2-D BEM at rest (Hertz, E0) and at low speed against "
        "mu ~ (V/R) E0 sum C_k lambda_k; isolated 2-D BEM (uniform, adaptive) also at the glassy limit.",
        ("exact", *SPHERE_BEM, "fem"),
        "exact",
        run_sphere,
        seconds=30,
    ),
    Case(
        "creep_indentation",
        "Sphere: creep under a step load (Lee-Radok)",
        "Step load 1 N on a rigid sphere (R = 10 mm), seed SLS: FEM contact radius, approach and peak "
        "pressure against Lee & Radok over time.",
        ("exact", "fem"),
        "exact",
        run_creep,
        seconds=20,
    ),
]
