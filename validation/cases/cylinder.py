"""Rolling cylinder cases: standard linear solid (exact: Hunter) and a multi-term Prony series.

Geometry and load: ``R = 10 mm``, ``P = 1000 N/m``, plane strain, ``nu = 0.5``. Speeds are
given as ``s = V lambda_max / a_0`` (retardation length over the relaxed Hertz half-width),
which spans the friction peak for any modulus ratio.

Solvers (``SOLVERS``): ``bem-periodic`` (1-D periodic BEM on a long cell,
:func:`solvers.bem_periodic_cylinder`), ``bem-isolated-uniform`` and ``bem-isolated-adaptive``
(isolated 1-D BEM, :func:`solvers.bem_isolated_cylinder`), ``fem`` (scikit-fem steady rolling)
and, for one-term materials, ``exact`` (Hunter 1961).
"""

from __future__ import annotations

import numpy as np

from bem import Material
from validation import metrics
from validation.references.hunter import low_speed_friction
from validation.references.hunter import rolling_cylinder as hunter

from .base import Case, CaseOutput, Profile, Sweep
from .cylinder_settings import FULL_HIGH_RATIO, FULL_PRONY, FULL_SLS, QUICK_HIGH_RATIO, QUICK_PRONY, QUICK_SLS
from .fem_checks import fem_self_checks
from .solvers import RTOL, bem_isolated_cylinder, bem_periodic_cylinder, fem_cylinder, hertz_line_half_width
from .vtk_out import write_bem_sweep, write_pvd_for

R, P = 0.01, 1000.0
LAYER = 5  # samples across the leading-edge layer V tau for pointwise pressure checks to be fair


def sls(ratio):
    return Material.standard_linear_solid(E0=1e7 / ratio, E_inf=1e7, creep_time=0.01)


def prony():
    """Three relaxation terms, times 1e-3, 1e-2, 1e-1 s, ``E_inf/E0 = 10`` (the FEM carries one set of
    internal variables per term, so its cost grows with the number of terms)."""
    return Material.from_prony(E0=1e6, moduli=np.full(3, 3e6), times=np.logspace(-3, -1, 3))


def _speed(material, s):
    a0 = hertz_line_half_width(material.E0, material.nu, R, P)
    return s * a0 / float(np.max(material.creep_times))


def _bem(material, V, P, cfg, vtk):
    return bem_periodic_cylinder(material, radius=R, load=P, speed=V, cells=cfg["cells"])


def _fem(material, V, P, cfg, vtk):
    # these cases check the uniform mesh (h = a_inf / resolution: their tolerances count its elements)
    # at the small modulus ratios where it fits; cylinder_fem_high_ratio checks the default mesh
    options = {"mesh": "uniform", **cfg.get("fem_options", {})}
    return fem_cylinder(material, radius=R, load=P, speed=V, resolution=cfg["resolution"], vtk=vtk, **options)


# name -> adapter(material, speed, load, cfg, vtk_path) returning the dict of :mod:`.solvers`; BEM adapters
# (with ``surface`` and ``result``) get .vti files, the FEM writes its own .vtu to ``vtk_path``.
def _isolated(method):
    def adapter(material, V, P, cfg, vtk):
        return bem_isolated_cylinder(material, radius=R, load=P, speed=V, cells=cfg["cells"], method=method)

    return adapter


SOLVERS = {
    "bem-periodic": _bem,
    "bem-isolated-uniform": _isolated("uniform"),
    "bem-isolated-adaptive": _isolated("adaptive"),
    "fem": _fem,
}


def solve_all(
    solvers, material, speeds, values, cfg, vtk_dir, root, out, tamper, load=P, references=(), label_name="s"
):
    """Run every solver at every speed; record costs and VTK; return ``{solver: [outputs]}``.

    ``values`` are the speed parameters (labels ``<label_name>=...``, the .pvd time values). Solvers
    named in ``references`` get the true inputs and are computed once for every
    perturbation (``tamper.reference``); the others get ``tamper.inputs``.
    """
    runs = {name: [] for name in solvers}
    written = {name: [] for name in solvers}
    labels = [f"{label_name}={v:g}" for v in values]
    for k, (V, label) in enumerate(zip(speeds, labels)):
        for name, adapter in solvers.items():
            vtk = None
            if vtk_dir is not None and name == "fem":
                (vtk_dir / name).mkdir(parents=True, exist_ok=True)
                vtk = vtk_dir / name / f"point_{k:03d}.vtm"
                written[name].append((vtk.name, k))
            if name in references:
                sol, cost = tamper.reference(
                    (name, V, load, label), metrics.measure, adapter, material, V, load, cfg, vtk
                )
            else:
                m, v, p = tamper.inputs(name, material, V, load)
                sol, cost = metrics.measure(adapter, m, v, p, cfg, vtk)
            out.cost(name, label, cost, sol["detail"])
            runs[name].append(sol)
    if vtk_dir is not None:
        for name, sols in runs.items():
            if written[name]:
                out.files += write_pvd_for(
                    vtk_dir / name, root, [(f, values[k]) for f, k in written[name]], parameter=label_name
                )
            elif any("surface" in sol for sol in sols):
                done = [(sol, v) for sol, v in zip(sols, values) if sol["success"]]
                if done:
                    out.files += write_bem_sweep(vtk_dir / name, root, *zip(*done), parameter=label_name, rtol=RTOL)
    return runs


def _solve_all(material, s_values, cfg, vtk_dir, root, out, tamper, references=()):
    speeds = [_speed(material, s) for s in s_values]
    return solve_all(SOLVERS, material, speeds, list(s_values), cfg, vtk_dir, root, out, tamper, references=references)


def _edge_checks(out, name, sol, ref_trail, ref_lead, label, tol, why):
    out.check(
        "leading_edge_error_elements",
        name,
        label,
        metrics.edge_error(sol["leading_edge"], ref_lead, sol["spacing"]),
        tol,
        why,
    )
    out.check(
        "trailing_edge_error_elements",
        name,
        label,
        metrics.edge_error(sol["trailing_edge"], ref_trail, sol["spacing"]),
        tol,
        why,
    )


def _self_checks(out, name, label, sol, tol, why):
    """FEM: energy balance, contact and linear residuals; BEM: the dissipation form of the
    friction against eq. 6 (the moment of the pressure on the profile's slope)."""
    if name == "fem":
        fem_self_checks(out, label, sol, tol["balance"], why["balance"], load=P)
    elif "friction_eq6" in tol:
        out.check(
            "friction_forms_rel_diff",
            name,
            label,
            metrics.rel_diff(sol["friction"], sol["result"].friction_eq6),
            tol["friction_eq6"],
            why["friction_eq6"],
        )


def at_speed(settings, s):
    """``settings`` with every per-speed entry (a dict keyed by ``s``) resolved at ``s``."""
    return {k: (v[s] if isinstance(v, dict) and s in v else v) for k, v in settings.items()}


def _band(sol, lo, hi):
    keep = (sol["x"] >= lo) & (sol["x"] <= hi)
    return sol["x"][keep], sol["pressure"][keep]


def run_sls(ratio, *, quick, vtk_dir, root, tamper):
    """SLS at ``E_inf/E0 = ratio``: BEM and FEM against Hunter's exact solution."""
    material = sls(ratio)
    cfg = QUICK_SLS[ratio] if quick else FULL_SLS[ratio]
    s_values = cfg["s"]
    out = CaseOutput()
    runs = _solve_all(material, s_values, cfg, vtk_dir, root, out, tamper)
    tau = float(material.relaxation_times[0])
    for k, s in enumerate(s_values):
        V, label = _speed(material, s), f"s={s:g}"
        ex = hunter(material, radius=R, load=P, speed=V)
        curves, errors = {}, {}
        for name in SOLVERS:
            sol, tol, why = runs[name][k], at_speed(cfg["tol"][name], s), at_speed(cfg["why"][name], s)
            if not out.converged(name, label, sol):
                continue
            p_ex = ex.pressure(sol["x"])
            x_band, p_band = _band(sol, ex.trailing_edge - 0.3 * ex.half_width, ex.leading_edge + 0.3 * ex.half_width)
            e_band = ex.pressure(x_band)
            curves[name], errors[name] = (x_band, p_band), (x_band, p_band - e_band)
            # the leading-edge layer (width V tau) is resolved when it spans LAYER samples
            resolved = V * tau >= LAYER * sol["spacing"]
            layer = f"not judged: the leading-edge layer V tau = {V * tau:.2e} m spans < {LAYER} elements"
            out.check(
                "pressure_rel_l2",
                name,
                label,
                metrics.rel_l2(sol["x"], sol["pressure"], p_ex),
                tol["l2"] if resolved else tol["l2_layer"],
                why["l2"] if resolved else why["l2_layer"],
            )
            out.check(
                "pressure_rel_max",
                name,
                label,
                metrics.rel_max(sol["pressure"], p_ex),
                tol["max"] if resolved else None,
                why["max"]
                if resolved
                else layer + " (a pointwise error at an unresolved jump is bounded only by the jump)",
            )
            out.check(
                "friction_rel_error",
                name,
                label,
                metrics.rel_diff(sol["friction"], ex.friction),
                tol["friction"],
                why["friction"],
            )
            if "friction_moment" in sol:  # the FEM's other form: the moment of its nodal contact forces
                out.check(
                    "friction_moment_rel_error",
                    name,
                    label,
                    metrics.rel_diff(sol["friction_moment"], ex.friction),
                    tol.get("friction_moment"),
                    why.get("friction_moment", "not judged: not measured at these settings"),
                )
            out.check(
                "peak_pressure_rel_error",
                name,
                label,
                metrics.rel_diff(sol["peak_pressure"], ex.peak_pressure),
                tol["peak"] if resolved else None,
                why["peak"] if resolved else layer,
            )
            _edge_checks(out, name, sol, ex.trailing_edge, ex.leading_edge, label, tol["edge"], why["edge"])
            _self_checks(out, name, label, sol, tol, why)
        xf = np.linspace(ex.trailing_edge - 0.3 * ex.half_width, ex.leading_edge + 0.3 * ex.half_width, 801)
        curves["exact"] = (xf, ex.pressure(xf))
        out.profiles.append(Profile(label=f"{label}, V = {V:.3g} m/s", curves=curves, reference="exact", errors=errors))
    s_dense = np.geomspace(min(s_values) / 2, max(s_values) * 2, 41)
    curves = {
        "exact": (
            s_dense,
            np.array([hunter(material, radius=R, load=P, speed=_speed(material, s)).friction for s in s_dense]),
        )
    }
    curves.update({name: (np.array(s_values), np.array([r["friction"] for r in runs[name]])) for name in SOLVERS})
    # a failed solve has friction nan: the plot leaves a gap there
    out.sweeps.append(Sweep("friction against speed", "s = V lambda / a0", "friction coefficient", curves))
    out.numbers["material"] = dict(E0=material.E0, E_inf=material.E_inf, creep_time=float(material.creep_times[0]))
    out.numbers["speeds"] = [_speed(material, s) for s in s_values]
    return out


def _against_fem(out, cfg, name, b, f, label):
    """Bin-averaged pressures, friction and edges of BEM solver ``name`` against the FEM; returns
    the bins' centres and both averages (for the plot)."""
    pair = f"{name} vs fem"
    width = max(b["spacing"], f["spacing"])
    lo = min(b["trailing_edge"], f["trailing_edge"]) - 2 * width
    hi = max(b["leading_edge"], f["leading_edge"]) + 2 * width
    edges = np.arange(lo, hi + width, width)
    pb, pf = metrics.bin_average(b["x"], b["pressure"], edges), metrics.bin_average(f["x"], f["pressure"], edges)
    mid = 0.5 * (edges[1:] + edges[:-1])
    t, why = cfg["tol"], cfg["why"]
    out.check("binned_pressure_rel_l2", pair, label, metrics.rel_l2(mid, pb, pf), t["l2"], why["l2"])
    out.check(
        "friction_rel_diff", pair, label, metrics.rel_diff(b["friction"], f["friction"]), t["friction"], why["friction"]
    )
    out.check(
        "leading_edge_diff_elements",
        pair,
        label,
        abs(b["leading_edge"] - f["leading_edge"]) / width,
        t["edge"],
        why["edge"],
    )
    out.check(
        "trailing_edge_diff_elements",
        pair,
        label,
        abs(b["trailing_edge"] - f["trailing_edge"]) / width,
        t["edge"],
        why["edge"],
    )
    out.check(
        "peak_pressure_rel_diff",
        pair,
        label,
        metrics.rel_diff(b["peak_pressure"], f["peak_pressure"]),
        None,
        "not judged: Prony terms with V tau_k below the element size make leading-edge layers neither grid resolves",
    )
    return mid, pb, pf, width


def run_prony(*, quick, vtk_dir, root, tamper):
    """Three-term Prony series: every BEM solver against the FEM (no exact solution), and the
    low-speed asymptote ``mu ~ (V/R) E0 sum C_k lambda_k`` (exact to first order in V)."""
    material = prony()
    cfg = QUICK_PRONY if quick else FULL_PRONY
    s_values = cfg["s"]
    out = CaseOutput()
    bem_solvers = {n: a for n, a in SOLVERS.items() if n != "fem"}
    runs = solve_all(
        bem_solvers, material, [_speed(material, s) for s in s_values], s_values, cfg, vtk_dir, root, out, tamper
    )
    fem_s = cfg["fem_s"]
    runs.update(
        solve_all(
            {"fem": _fem},
            material,
            [_speed(material, s) for s in fem_s],
            fem_s,
            cfg,
            vtk_dir,
            root,
            out,
            tamper,
            references=("fem",),
        )
    )
    for k, s in enumerate(s_values):
        V, label = _speed(material, s), f"s={s:g}"
        f = runs["fem"][fem_s.index(s)] if s in fem_s else None
        fem_ok = f is not None and out.converged("fem", label, f)
        if fem_ok:
            fem_self_checks(out, label, f, cfg["tol"]["balance"], cfg["why"]["balance"], load=P)
        mu0 = low_speed_friction(material, radius=R, speed=V) if s <= cfg["asymptote_s"] else None
        if fem_ok and mu0 is not None:
            out.check(
                "low_speed_asymptote_rel_error",
                "fem",
                label,
                metrics.rel_diff(f["friction"], mu0),
                cfg["tol"]["asymptote"]["fem"],
                cfg["why"]["asymptote"]["fem"],
            )
        for name in [n for n in SOLVERS if n != "fem"]:
            b = runs[name][k]
            if not out.converged(name, label, b):
                continue
            if mu0 is not None:
                out.check(
                    "low_speed_asymptote_rel_error",
                    name,
                    label,
                    metrics.rel_diff(b["friction"], mu0),
                    cfg["tol"]["asymptote"][name],
                    cfg["why"]["asymptote"][name],
                )
            if fem_ok:
                mid, pb, pf, width = _against_fem(out, cfg, name, b, f, label)
                out.profiles.append(
                    Profile(
                        label=f"{name} vs fem, {label}, V = {V:.3g} m/s (bin averages over {width:.2e} m)",
                        curves={name: (mid, pb), "fem": (mid, pf)},
                        reference="fem",
                        errors={name: (mid, pb - pf)},
                    )
                )
    out.sweeps.append(
        Sweep(
            "friction against speed",
            "s = V lambda_max / a0",
            "friction coefficient",
            {
                name: (np.array(fem_s if name == "fem" else s_values), np.array([r["friction"] for r in runs[name]]))
                for name in SOLVERS
            },
        )
    )
    out.numbers["material"] = dict(
        E0=material.E0, moduli=material.moduli.tolist(), relaxation_times=material.relaxation_times.tolist()
    )
    out.numbers["speeds"] = [_speed(material, s) for s in s_values]
    return out


# High modulus ratio (the FEM under test on the graded mesh): the rubber-like standard solid of
# the FEM benchmark's accuracy table, E0 = 2 MPa, relaxation time 10 ms, R = 20 mm, 500 N/m.
HIGH_R, HIGH_P = 0.02, 500.0


def high_ratio_sls(ratio):
    return Material.standard_linear_solid(E0=2e6, E_inf=2e6 * ratio, relaxation_time=0.01, nu=0.5)


def _fem_graded(material, V, P, cfg, vtk):
    return fem_cylinder(material, radius=HIGH_R, load=P, speed=V, resolution=cfg["resolution"], vtk=vtk)


def run_high_ratio(*, quick, vtk_dir, root, tamper):
    """The FEM on its graded mesh against Hunter at a large modulus ratio: friction in both forms,
    peak pressure, edges (in contact widths) and the FEM's self-checks."""
    cfg = QUICK_HIGH_RATIO if quick else FULL_HIGH_RATIO
    material = high_ratio_sls(cfg["ratio"])
    a0 = hertz_line_half_width(material.E0, material.nu, HIGH_R, HIGH_P)
    lam = float(material.creep_times[0])
    s_values = cfg["s"]
    speeds = [s * a0 / lam for s in s_values]
    out = CaseOutput()
    runs = solve_all({"fem": _fem_graded}, material, speeds, s_values, cfg, vtk_dir, root, out, tamper, load=HIGH_P)
    tol, why = cfg["tol"], cfg["why"]
    for sol, V, s in zip(runs["fem"], speeds, s_values):
        label = f"s={s:g}"
        if not out.converged("fem", label, sol):
            continue
        ex = hunter(material, radius=HIGH_R, load=HIGH_P, speed=V)
        t, w = at_speed(tol, s), at_speed(why, s)
        width = 2 * ex.half_width
        out.check(
            "friction_rel_error",
            "fem",
            label,
            metrics.rel_diff(sol["friction"], ex.friction),
            t["friction"],
            w["friction"],
        )
        out.check(
            "friction_moment_rel_error",
            "fem",
            label,
            metrics.rel_diff(sol["friction_moment"], ex.friction),
            t["friction_moment"],
            w["friction_moment"],
        )
        out.check(
            "peak_pressure_rel_error",
            "fem",
            label,
            metrics.rel_diff(sol["peak_pressure"], ex.peak_pressure),
            t["peak"] if sol["peak_resolved"] else None,
            w["peak"] if sol["peak_resolved"] else "not judged: the leading-edge layer is not resolved",
        )
        for metric, got, ref in (
            ("leading_edge_error_widths", sol["leading_edge"], ex.leading_edge),
            ("trailing_edge_error_widths", sol["trailing_edge"], ex.trailing_edge),
        ):
            out.check(metric, "fem", label, abs(got - ref) / width, t["edge"], w["edge"])
        fem_self_checks(out, label, sol, t["balance"], w["balance"], load=HIGH_P)
        x = np.linspace(ex.trailing_edge - 0.3 * ex.half_width, ex.leading_edge + 0.3 * ex.half_width, 801)
        band = (sol["x"] >= x[0]) & (sol["x"] <= x[-1])
        out.profiles.append(
            Profile(
                label=f"{label}, V = {V:.3g} m/s",
                curves={"fem": (sol["x"][band], sol["pressure"][band]), "exact": (x, ex.pressure(x))},
                reference="exact",
                errors={"fem": (sol["x"][band], sol["pressure"][band] - ex.pressure(sol["x"][band]))},
            )
        )
    out.numbers["material"] = dict(E0=material.E0, E_inf=material.E_inf, relaxation_time=0.01)
    out.numbers["speeds"] = speeds
    return out


CASES = [
    Case(
        "cylinder_sls_r3",
        "Rolling cylinder, standard linear solid, E_inf/E0 = 3",
        "Rigid cylinder (R = 10 mm, 1000 N/m) rolling on the seed paper's SLS (E_inf = 10 MPa, "
        "creep time 10 ms); BEM and FEM against Hunter's exact solution over speeds.",
        ("exact", *SOLVERS),
        "exact",
        lambda **kw: run_sls(3, **kw),
        seconds=270,
    ),
    Case(
        "cylinder_sls_r10",
        "Rolling cylinder, standard linear solid, E_inf/E0 = 10",
        "As cylinder_sls_r3 with E0 = 1 MPa, E_inf = 10 MPa.",
        ("exact", *SOLVERS),
        "exact",
        lambda **kw: run_sls(10, **kw),
        seconds=290,
    ),
    Case(
        "cylinder_prony3",
        "Rolling cylinder, three-term Prony series",
        "Prony series E0 = 1 MPa, three terms of 3 MPa at relaxation times 1e-3, 1e-2, 1e-1 s; BEM against FEM "
        "(no exact solution) and the low-speed asymptote.",
        tuple(SOLVERS),
        "fem",
        run_prony,
        seconds=160,
    ),
    Case(
        "cylinder_fem_high_ratio",
        "Rolling cylinder, FEM against Hunter at a large modulus ratio",
        "Standard linear solid E0 = 2 MPa, relaxation time 10 ms, R = 20 mm, 500 N/m; the FEM on its graded "
        "mesh against Hunter's exact solution at E_inf/E0 = 1000 (full set; 100 in the quick set).",
        ("exact", "fem"),
        "exact",
        run_high_ratio,
        seconds=60,
    ),
]
