"""The numbers of ``results.json``: material, surface, per-load curves and per-point lists.

Ensembles: with ``realisations = K`` each number is reported as the mean over the
realisations that converged and its standard error ``std(ddof=1) / sqrt(k)`` (``None`` for
one realisation). Indenters (sphere, cylinder) report their contact radius (m) and area
(m², m for a cylinder's profile) per speed, the relaxed and glassy Hertz radii, and no
roughness statistics (an indenter's rms height or slope depends only on the domain size).
"""

import math

import numpy as np

from bem.accuracy import QUANTITIES, gather
from bem.surfaces import statistics

from ..guidance import hertz_radius
from ..scene.temperatures import excited_band

SCALARS = ["friction", "friction_eq6", "contact_fraction", "dissipated_power", "approach", "peak_pressure"]
INDENTER_SCALARS = ["contact_radius", "contact_area"]


def material_record(m):
    """The material's series; for a fitted one also ``fit`` (the fit report: errors, worst points,
    the data's band in this material's frame, plateau flags; for a master curve the shifts and
    the law) and ``data_band`` (rad/s)."""
    rec = {
        "E0": m.E0,
        "E_inf": m.E_inf,
        "nu": m.nu,
        "prony_moduli": m.moduli.tolist(),
        "relaxation_times": m.relaxation_times.tolist(),
        "creep_compliances": m.compliances.tolist(),
        "creep_times": m.creep_times.tolist(),
    }
    if m.fit_report is not None:
        rec["fit"] = m.fit_report.as_dict()
        rec["data_band"] = list(m.data_band)
    return rec


def scene_material_record(scene):
    """:func:`material_record` of the scene's material, with its shift law (``shift``: the law's
    name, constants and reference temperature, K) and the band of frequencies the sliding
    excites (``excited_band``, rad/s; :func:`viscobem_cli.scene.temperatures.excited_band`)."""
    rec = material_record(scene.material)
    if scene.shift is not None:
        rec["shift"] = {"law": type(scene.shift).__name__, **vars(scene.shift)}
    band = excited_band(scene)
    rec["excited_band"] = None if band is None else list(band)
    return rec


def surface_record(scene):
    s = scene.surface
    rec = {
        "kind": scene.kind,
        "n": s.n,
        "dim": s.ndim,
        "length": s.length,
        "spacing": s.spacing,
        "max_height": float(s.heights.max()),
        "min_height": float(s.heights.min()),
    }
    if scene.kind not in ("sphere", "cylinder"):
        return {**rec, "rms_height": statistics.rms_height(s), "rms_slope": statistics.rms_slope(s)}
    radius, m = scene.raw["surface"]["radius"], scene.material
    rec["radius"] = radius
    rec["hertz_radius_relaxed"] = [
        hertz_radius(scene.kind, modulus=m.E0, nu=m.nu, radius=radius, load=f) for f in scene.loads
    ]
    rec["hertz_radius_glassy"] = [
        hertz_radius(scene.kind, modulus=m.E_inf, nu=m.nu, radius=radius, load=f) for f in scene.loads
    ]
    return rec


def mean_se(values):
    """Mean and standard error of the finite values (None where undefined)."""
    v = np.array([x for x in values if x is not None and np.isfinite(x)], dtype=float)
    if v.size == 0:
        return None, None
    se = float(np.std(v, ddof=1) / math.sqrt(v.size)) if v.size > 1 else None
    return float(v.mean()), se


def scalars(scene):
    return SCALARS + (INDENTER_SCALARS if scene.kind in ("sphere", "cylinder") else [])


def summarise_curve(scene, recs, l):
    """The friction curve of load ``l``: ensemble means and standard errors per speed."""
    n, k = scene.speeds.size, len(scene.realisations)
    curve = {"load": scene.loads[l], "xi": scene.xi.tolist(), "speed": scene.speeds.tolist(), "realisations": k}
    names = scalars(scene)
    for key in names:
        curve[key], curve[key + "_se"] = [None] * n, [None] * n
    for key in ("iterations", "operator_products", "residual", "wall_time", "success", "converged"):
        curve[key] = [None] * n
    for q in QUANTITIES:  # the largest estimated relative error over the realisations
        curve[q + "_error"] = [None] * n
    curve["message"] = [""] * n
    for i in range(n):
        done = [p for p in (recs.get((r, l, i)) for r in range(k)) if p is not None]
        ok = [p for p in done if p["success"]]
        for key in names:
            curve[key][i], curve[key + "_se"][i] = mean_se([p.get(key) for p in ok])
        if ok:
            curve["iterations"][i] = int(max(p["iterations"] for p in ok))
            curve["operator_products"][i] = int(sum(p["operator_products"] for p in ok))
            curve["residual"][i] = float(max(p["residual"] for p in ok))
            curve["wall_time"][i] = float(sum(p["wall_time"] for p in ok))
        for q in QUANTITIES:
            known = [p["error_estimate"][q] for p in ok if (p.get("error_estimate") or {}).get(q) is not None]
            curve[q + "_error"][i] = max(known) if known else None
        curve["converged"][i] = len(ok)
        curve["success"][i] = (len(ok) == k) if len(done) == k else None
        failed = sorted({p["message"] for p in done if not p["success"]})
        curve["message"][i] = "; ".join(failed) if failed else (ok[0]["message"] if ok else "")
    return curve


def point_list(scene, recs):
    keep = [
        "r",
        "l",
        "i",
        "seed",
        "load",
        "speed",
        "xi",
        "success",
        "message",
        *scalars(scene),
        "iterations",
        "residual",
        "wall_time",
        "times",
        "moments",
        "error_estimate",
        "warnings",
    ]
    return [{k: recs[key].get(k) for k in keep if k in recs[key]} for key in sorted(recs)]


def _about_material(warning):
    return isinstance(warning, dict) and warning.get("kind") == "material_data"


def point_warnings(scene, recs):
    """Every point's warnings, gathered per load: one sentence per kind of finding, with the points
    it comes from (:func:`bem.accuracy.gather`). The material's data coverage is left out: the
    scene states it once for the band all its speeds load
    (:func:`viscobem_cli.scene.temperatures.material_warnings`)."""
    several = len(scene.realisations) > 1
    out = []
    for l, load in enumerate(scene.loads):
        points = []
        for (r, ll, i), rec in sorted(recs.items(), key=lambda item: (item[0][1], item[0][2], item[0][0])):
            if ll == l:
                label = f"xi = {scene.xi[i]:.3g}" + (f" (realisation {r})" if several else "")
                found = [w for w in rec.get("warnings", []) if not _about_material(w)]
                points.append((label, found))
        found = gather(points, noun="points" if several else "speeds")
        prefix = f"at load {load:g}, " if len(scene.loads) > 1 else ""
        out += [prefix + str(f) for f in found]
    return out
