"""Rolling cylinder on a rubber: many Prony terms, a large modulus ratio, at the friction peak.

The material is a Prony series with equal moduli and log-spaced relaxation times,
``E0 = 1 MPa``; the cylinder ``R = 20 mm`` carries ``P = 1500 N/m`` (plane strain). The full
case is the rubber of the FEM benchmark (8 terms, ``E_inf/E0 = 300``, times 1e-5..1e-1 s); the
quick one has 4 terms, ``E_inf/E0 = 30``, times 1e-4..1e-1 s. Speeds: the BEM's friction peak
and a decade below it (the peak is checked to be a maximum of the friction over speed).

There is no exact solution. The reference (``bem-reference``) is the isolated BEM on twice as
many cells as the solvers under test (``bem-periodic``, ``bem-isolated-uniform``,
``bem-isolated-adaptive``); ``fem`` (scikit-fem steady rolling, on the mesh graded toward the
contact edges and the leading-edge layers) is compared with the BEM reference solved on the FEM's
material: the case's rubber, or a smaller one where ``FULL["fem"]["material"]`` names it (said in
the report's notes). The quick set runs the FEM at one speed.
Pressures are compared as bin averages over the coarser spacing (:mod:`validation.metrics`).
"""

from __future__ import annotations

import numpy as np

from bem import Material
from validation import metrics

from .base import Case, CaseOutput, Profile, Sweep
from .cylinder import at_speed, solve_all
from .fem_checks import fem_self_checks
from .solvers import bem_isolated_cylinder, bem_periodic_cylinder, fem_cylinder

R, P = 0.02, 1500.0


def rubber(ratio, terms, tmin, tmax=1e-1, E0=1e6):
    """Prony series: ``terms`` equal moduli summing to ``(ratio - 1) E0``, times log-spaced in
    ``[tmin, tmax]`` (s)."""
    return Material.from_prony(
        E0=E0, moduli=np.full(terms, E0 * (ratio - 1) / terms), times=np.geomspace(tmin, tmax, terms)
    )


def _isolated(method, key="cells"):
    def adapter(material, V, load, cfg, vtk):
        return bem_isolated_cylinder(material, radius=R, load=load, speed=V, cells=cfg[key], method=method)

    return adapter


def _periodic(material, V, load, cfg, vtk):
    return bem_periodic_cylinder(material, radius=R, load=load, speed=V, cells=cfg["cells"])


def _fem(material, V, load, cfg, vtk):
    fem = cfg["fem"]
    return fem_cylinder(
        material, radius=R, load=load, speed=V, resolution=fem["resolution"], vtk=vtk, **fem.get("options", {})
    )


UNDER_TEST = {
    "bem-periodic": _periodic,
    "bem-isolated-uniform": _isolated("uniform"),
    "bem-isolated-adaptive": _isolated("adaptive"),
}
REFERENCE = {"bem-reference": _isolated("uniform", "ref_cells")}


def compare(out, tol, why, name, b, ref, label, solver=None):
    """Binned pressure, friction, edges and peak of ``b`` against ``ref``; returns the plot data."""
    pair = f"{solver or name} vs bem-reference"
    width = max(b["spacing"], ref["spacing"])
    lo = min(b["trailing_edge"], ref["trailing_edge"]) - 2 * width
    hi = max(b["leading_edge"], ref["leading_edge"]) + 2 * width
    edges = np.arange(lo, hi + width, width)
    pb, pr = metrics.bin_average(b["x"], b["pressure"], edges), metrics.bin_average(ref["x"], ref["pressure"], edges)
    mid = 0.5 * (edges[1:] + edges[:-1])
    out.check("binned_pressure_rel_l2", pair, label, metrics.rel_l2(mid, pb, pr), tol["l2"], why["l2"])
    out.check(
        "friction_rel_diff",
        pair,
        label,
        metrics.rel_diff(b["friction"], ref["friction"]),
        tol["friction"],
        why["friction"],
    )
    if "friction_moment" in b:  # the FEM's other form: the moment of its nodal contact forces
        out.check(
            "friction_moment_rel_diff",
            pair,
            label,
            metrics.rel_diff(b["friction_moment"], ref["friction"]),
            tol.get("friction_moment"),
            why.get("friction_moment", "not judged: not measured at these settings"),
        )
    for side in ("leading", "trailing"):
        out.check(
            f"{side}_edge_diff_elements",
            pair,
            label,
            abs(b[f"{side}_edge"] - ref[f"{side}_edge"]) / width,
            tol["edge"],
            why["edge"],
        )
    judged = tol["peak_speeds"] is None or label.split("=")[-1] in {f"{v:g}" for v in tol["peak_speeds"]}
    peak_tol, peak_why = tol["peak"], why["peak"]
    if isinstance(peak_tol, dict):  # per solver under test
        peak_tol, peak_why = peak_tol[name], peak_why[name]
    reason = peak_why if judged else why["peak_unjudged"]
    unresolved = [(n, s) for n, s in ((solver or name, b), ("bem-reference", ref)) if not s.get("peak_resolved", True)]
    if unresolved and not judged:  # why the peak is not judged, with the numbers, in the report
        reason += "; thinnest leading-edge layer V tau_k below " + "; ".join(
            f"{n}'s cell or element ({s['layer']:.2e} m < {s['layer_cell']:.2e} m)" for n, s in unresolved
        )
    out.check(
        "peak_pressure_rel_diff",
        pair,
        label,
        metrics.rel_diff(b["peak_pressure"], ref["peak_pressure"]),
        peak_tol if judged else None,
        reason,
    )
    return mid, pb, pr


def _peak_check(out, material, cfg, tamper):
    """The higher speed is the friction peak: the friction there exceeds that at 10^(+-1/4) of it."""
    V = cfg["speeds"][-1]
    ad = UNDER_TEST["bem-isolated-uniform"]
    mu = [
        tamper.reference(("peak", f), ad, material, V * f, P, cfg, None)["friction"] for f in (10**-0.25, 1.0, 10**0.25)
    ]
    out.check(
        "peak_speed_friction_excess",
        "bem-reference",
        f"V={V:g}",
        max(mu[0], mu[2]) / mu[1] - 1,
        0.0,
        "the friction at the peak speed exceeds that at 10^(+-1/4) of it (a maximum): value < 0",
    )
    return mu


def run_rubber(*, quick, vtk_dir, root, tamper):
    cfg = QUICK if quick else FULL
    material = rubber(**cfg["material"])
    speeds = cfg["speeds"]
    out = CaseOutput()
    runs = solve_all(UNDER_TEST, material, speeds, speeds, cfg, vtk_dir, root, out, tamper, load=P, label_name="V")
    runs.update(
        solve_all(
            REFERENCE,
            material,
            speeds,
            speeds,
            cfg,
            None,
            root,
            out,
            tamper,
            load=P,
            references=tuple(REFERENCE),
            label_name="V",
        )
    )
    mu_peak = _peak_check(out, material, cfg, tamper)
    for k, V in enumerate(speeds):
        label = f"V={V:g}"
        ref = runs["bem-reference"][k]
        if not out.converged("bem-reference", label, ref):
            continue
        curves, errors = {"bem-reference": (ref["x"], ref["pressure"])}, {}
        for name in UNDER_TEST:
            b = runs[name][k]
            if out.converged(name, label, b):
                mid, pb, pr = compare(out, cfg["tol"]["bem"], cfg["why"]["bem"], name, b, ref, label)
                curves[name], errors[name] = (b["x"], b["pressure"]), (mid, pb - pr)
        out.profiles.append(
            Profile(f"{label} m/s (errors: bin averages)", curves, reference="bem-reference", errors=errors)
        )
    _run_fem(out, material, cfg, vtk_dir, root, tamper)
    out.sweeps.append(
        Sweep(
            "friction against speed",
            "V (m/s)",
            "friction coefficient",
            {
                name: (np.array(speeds), np.array([r["friction"] for r in runs[name]]))
                for name in (*UNDER_TEST, *REFERENCE)
            }
            | {"peak bracket": (speeds[-1] * np.array([10**-0.25, 1.0, 10**0.25]), np.array(mu_peak))},
        )
    )
    out.numbers["material"] = dict(
        E0=material.E0,
        E_inf=material.E_inf,
        moduli=material.moduli.tolist(),
        relaxation_times=material.relaxation_times.tolist(),
    )
    out.numbers["speeds"] = list(speeds)
    return out


def _run_fem(out, material, cfg, vtk_dir, root, tamper):
    """The FEM on its material (the case's, or the largest it affords) against the BEM reference
    solved on the same material."""
    fem = cfg["fem"]
    m_fem = rubber(**fem["material"]) if fem.get("material") else material
    if fem.get("material") and fem["speeds"]:
        out.notes.append(fem["note"])
    speeds = fem["speeds"]
    if not speeds:
        out.notes.append(fem["note"])
        return
    # the FEM is under test here (wrong inputs under --sensitivity), the BEM reference is computed once
    f_runs = solve_all(
        {"fem": _fem}, m_fem, speeds, speeds, cfg, vtk_dir, root, out, tamper, load=P, label_name="fem V"
    )
    r_runs = solve_all(
        {"bem-reference": REFERENCE["bem-reference"]},
        m_fem,
        speeds,
        speeds,
        cfg,
        None,
        root,
        out,
        tamper,
        load=P,
        references=("bem-reference",),
        label_name="fem V",
    )
    for k, V in enumerate(speeds):
        label = f"fem V={V:g}"
        f, ref = f_runs["fem"][k], r_runs["bem-reference"][k]
        if not (out.converged("fem", label, f) and out.converged("bem-reference", label, ref)):
            continue
        tol, why = at_speed(cfg["tol"]["fem"], V), at_speed(cfg["why"]["fem"], V)
        fem_self_checks(out, label, f, tol["balance"], why["balance"], load=P)
        mid, pf, pr = compare(out, tol, why, "fem", f, ref, label)
        out.profiles.append(
            Profile(
                f"{label} m/s, FEM material E_inf/E0 = {m_fem.E_inf / m_fem.E0:.3g}, "
                f"{m_fem.moduli.size} terms (bin averages)",
                {"fem": (mid, pf), "bem-reference": (mid, pr)},
                reference="bem-reference",
                errors={"fem": (mid, pf - pr)},
            )
        )


from .rubber_settings import FULL, QUICK  # noqa: E402  (the settings name this module's solvers)

CASES = [
    Case(
        "rubber",
        "Rolling cylinder on a rubber (many Prony terms, large modulus ratio)",
        "Rigid cylinder (R = 20 mm, 1500 N/m) on a Prony rubber with equal moduli (full: 8 terms, E_inf/E0 = 300, "
        "times 1e-5..1e-1 s; quick: 4 terms, E_inf/E0 = 30), at the BEM's friction peak and a decade below: "
        "every BEM solver against the isolated BEM on twice the cells, and the FEM against that reference.",
        (*UNDER_TEST, *REFERENCE, "fem"),
        "bem-reference",
        run_rubber,
        seconds=210,
    )
]
