"""Run a scene and write its outputs: results.json, fields.npz, PNG plots, VTK on request.

Only what the scene asks for is computed (SPEC §5): anisotropy, the contact PSD, Persson's
theory, fields, plots and VTK each run only when requested, and ``results.json`` lists the
stages that ran (``stages_run``) with their times (``stages``, s; per-point work summed over
points). Prony terms that are fully relaxed over the sweep's frequency band (and, on periodic
profiles, glassy over ``[q_L v_min, (pi n / L) v_max]``) are folded into the elastic part first. The sweep itself
is :mod:`viscobem_cli.sweep`: every finished point is on disk at once, and a rerun in the
same folder resumes. ``results.json`` is rewritten (atomically) after every point.

Ensembles: with ``realisations = K`` each number is reported as the mean over the
realisations that converged and its standard error ``std(ddof=1) / sqrt(k)`` (``None`` for
one realisation).

Every file (``results.json``, ``fields.npz``, the plots) is written atomically (a temporary
file, then renamed), so a run that fails never leaves a truncated file, and a scene rejected
as bad input touches nothing in the output folder.
"""
import io
import json
import math
import platform
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from bem import statistics

from . import analysis
from .sweep import execute, load_fields, load_point, point_key, write_atomic

__all__ = ["run_scene", "write_atomic"]

SCALARS = ["friction", "friction_eq6", "contact_fraction", "dissipated_power", "approach"]


def _material_record(m):
    return {"E0": m.E0, "E_inf": m.E_inf, "nu": m.nu, "prony_moduli": m.moduli.tolist(),
            "relaxation_times": m.relaxation_times.tolist(), "creep_compliances": m.compliances.tolist(),
            "creep_times": m.creep_times.tolist()}


def _surface_record(s):
    return {"n": s.n, "dim": s.ndim, "length": s.length, "spacing": s.spacing,
            "rms_height": statistics.rms_height(s), "rms_slope": statistics.rms_slope(s),
            "max_height": float(s.heights.max()), "min_height": float(s.heights.min())}


def fold_material(scene):
    """The scene's material with terms inactive over the sweep's frequency band folded."""
    m = scene.material
    moving = scene.speeds[scene.speeds > 0]
    if m.is_elastic or scene.fold_tol == 0 or moving.size == 0:
        return m
    s = scene.surface
    # Glassy folding is exact only where every mode moves: on a periodic profile the lowest
    # frequency is 2 pi v / L, but the q_x = 0 modes of a 2-D cell are static (they see E0) and
    # an isolated domain has no lowest frequency, so there only relaxed terms are folded.
    w_min = 2 * np.pi / s.length * moving.min() if scene.periodic and s.ndim == 1 else 0.0
    w_max = np.pi * s.n / s.length * moving.max()
    # oblique sliding: |q.d| reaches (|cos| + |sin|) times the Nyquist wavenumber
    w_max *= max(abs(math.cos(t)) + abs(math.sin(t)) for t in scene.directions)
    return m.folded(w_min, w_max, tol=scene.fold_tol)


def mean_se(values):
    """Mean and standard error of the finite values (None where undefined)."""
    v = np.array([x for x in values if x is not None and np.isfinite(x)], dtype=float)
    if v.size == 0:
        return None, None
    se = float(np.std(v, ddof=1) / math.sqrt(v.size)) if v.size > 1 else None
    return float(v.mean()), se


def summarise_curve(scene, recs, l):
    """The friction curve of load ``l``: ensemble means and standard errors per speed."""
    n, k = scene.speeds.size, len(scene.realisations)
    curve = {"load": scene.loads[l], "xi": scene.xi.tolist(), "speed": scene.speeds.tolist(),
             "realisations": k}
    for key in SCALARS:
        curve[key], curve[key + "_se"] = [None] * n, [None] * n
    for key in ("iterations", "operator_products", "residual", "wall_time", "success", "converged"):
        curve[key] = [None] * n
    curve["message"] = [""] * n
    for i in range(n):
        pts = [recs.get((r, l, i)) for r in range(k)]
        done = [p for p in pts if p is not None]
        ok = [p for p in done if p["success"]]
        for key in SCALARS:
            curve[key][i], curve[key + "_se"][i] = mean_se([p[key] for p in ok])
        if ok:
            curve["iterations"][i] = int(max(p["iterations"] for p in ok))
            curve["operator_products"][i] = int(sum(p["operator_products"] for p in ok))
            curve["residual"][i] = float(max(p["residual"] for p in ok))
            curve["wall_time"][i] = float(sum(p["wall_time"] for p in ok))
        curve["converged"][i] = len(ok)
        curve["success"][i] = (len(ok) == k) if len(done) == k else None
        failed = sorted({p["message"] for p in done if not p["success"]})
        curve["message"][i] = "; ".join(failed) if failed else (ok[0]["message"] if ok else "")
    return curve


def _point_list(recs):
    keep = ["r", "l", "i", "seed", "load", "speed", "xi", "success", "message", *SCALARS, "iterations",
            "residual", "wall_time", "times", "moments"]
    return [{k: recs[key].get(k) for k in keep if k in recs[key]} for key in sorted(recs)]


def run_scene(scene, out_dir, *, progress=True, scheduler=None, workers=None):
    """Compute what ``scene`` asks for; write it under ``out_dir``; return the results dict.

    ``scheduler`` and ``workers`` override the scene's ``[solver]`` values (command line).
    A folder holding finished points of the same study is resumed: those points are not
    solved again.
    """
    if len(scene.directions) > 1:  # a sweep over sliding directions: one study per direction
        from .directions import run_sweep

        return run_sweep(run_scene, scene, out_dir, progress=progress, scheduler=scheduler, workers=workers)
    # the solver's own input checks, before anything in out_dir is touched
    from bem.sliding import check_inputs

    for load in scene.loads:
        for speed in (float(np.min(scene.speeds)), float(np.max(scene.speeds))):
            check_inputs(scene.surface, scene.material, speed, load, None, scene.rtol)
    out = Path(out_dir)
    points_dir = out / "points"
    points_dir.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()
    scheduler = scheduler if scheduler is not None else scene.scheduler
    workers = workers if workers is not None else scene.workers
    stages, stages_run = {}, []
    t0 = time.perf_counter()
    material = fold_material(scene)
    stages["fold"] = time.perf_counter() - t0
    outputs = scene.outputs
    keep_fields = outputs["fields"] or outputs["plots"] or outputs["vtk"]
    keep_chi = outputs["contact_psd"]
    settings = {"rtol": scene.rtol, "maxiter": scene.maxiter, "periodic": scene.periodic, "method": scene.method,
                "anisotropy": outputs["anisotropy"],
                "fields": keep_fields, "chi": keep_chi}
    if scene.direction != 0.0:  # sliding direction
        settings["direction"] = scene.direction
    record = {
        "title": scene.title, "scene": scene.source, "viscobem_version": "0.1.0",
        "python": platform.python_version(),
        "units": {"length": "m", "pressure": "Pa", "load": "N (N/m for 1-D profiles)", "speed": "m/s",
                  "power": "W (W/m for 1-D profiles)", "xi": "v * xi_time / length (dimensionless)",
                  "moments": "m20, m02, m11 of the displacement field: m^2/m^2 (dimensionless)"},
        "conventions": "heights positive toward the half-space; the surface slides in +x (axis 0); "
                       "friction = dissipation form, friction_eq6 = -(1/F_N) int p dh/dx dA; ensemble "
                       "values are means over realisations with standard errors in *_se",
        "material": _material_record(scene.material),
        "material_solved": {**_material_record(material), "terms": int(material.moduli.size),
                            "terms_folded": int(scene.material.moduli.size - material.moduli.size)},
        "surface": _surface_record(scene.surface), "realisations": len(scene.realisations),
        "seeds": list(scene.seeds), "loads": list(scene.loads), "load": scene.load, "xi_time": scene.xi_time,
        "solver": {"rtol": scene.rtol, "maxiter": scene.maxiter, "periodic": scene.periodic, "method": scene.method,
                   "workers": workers, "scheduler": scheduler},
        "outputs": dict(outputs), "stages": stages, "stages_run": stages_run, "complete": False,
        "direction_deg": round(math.degrees(scene.direction), 9),
    }
    recs, resumed, todo_keys = {}, 0, {}
    for l, load in enumerate(scene.loads):
        for r, surf in enumerate(scene.realisations):
            for i, speed in enumerate(scene.speeds):
                key = point_key(material, surf, load, speed, settings)
                rec = load_point(points_dir, r, l, i, key)
                if rec is not None:
                    recs[(r, l, i)] = rec
                    resumed += 1
                else:
                    todo_keys[(r, l, i)] = key
    record["resumed_points"] = resumed

    def write_record():
        record["curves"] = [summarise_curve(scene, recs, l) for l in range(len(scene.loads))]
        record["friction_curve"] = record["curves"][0]
        record["points"] = _point_list(recs)
        write_atomic(out / "results.json", json.dumps(record, indent=1))

    from tqdm.auto import tqdm

    bar = tqdm(total=len(todo_keys), disable=not progress, desc="sweep", unit="point")

    def on_point(rec):
        where = (rec["r"], rec["l"], rec["i"])
        if where in todo_keys and where not in recs:
            bar.update(1)
        recs[where] = rec
        write_record()

    def poll():
        for where, key in todo_keys.items():
            if where not in recs:
                rec = load_point(points_dir, *where, key)
                if rec is not None:
                    on_point(rec)

    tasks = _tasks(scene, material, todo_keys, points_dir, workers, scheduler, keep_fields, keep_chi)
    write_record()
    t0 = time.perf_counter()
    try:
        execute(tasks, workers=workers, scheduler=scheduler, on_point=on_point, poll=poll)
    finally:
        bar.close()
    stages["friction_curve"] = time.perf_counter() - t0
    stages_run.append("friction_curve")
    for name in ("solve", "anisotropy"):
        spent = [p["times"][name] for p in recs.values() if name in p.get("times", {})]
        if spent:
            stages["point_" + name] = float(sum(spent))
    if outputs["anisotropy"]:
        stages_run.append("anisotropy")
        record["anisotropy"] = [analysis.anisotropy_summary(scene, recs, l) for l in range(len(scene.loads))]
    extras = {}
    if outputs["contact_psd"]:
        t0 = time.perf_counter()
        record["contact_psd"], extras["psd"] = analysis.contact_psd_summary(scene, recs, points_dir)
        stages["contact_psd"] = time.perf_counter() - t0
        stages_run.append("contact_psd")
    if outputs["persson"]:
        t0 = time.perf_counter()
        record["persson"] = analysis.persson_summary(scene)
        stages["persson"] = time.perf_counter() - t0
        stages_run.append("persson")
    write_record()
    written = ["results.json"]
    fields = _fields_of_first(scene, recs, points_dir) if keep_fields else {}
    if outputs["fields"] and fields:
        t0 = time.perf_counter()
        idx = sorted(fields)
        arrays = {"heights": scene.surface.heights, "speed": scene.speeds[idx], "xi": scene.xi[idx],
                  "pressure": np.stack([fields[i].pressure for i in idx]),
                  "displacement": np.stack([fields[i].displacement for i in idx]),
                  "gap": np.stack([fields[i].gap for i in idx])}
        buffer = io.BytesIO()
        np.savez_compressed(buffer, **arrays)
        write_atomic(out / "fields.npz", buffer.getvalue(), mode="wb")
        stages["fields"] = time.perf_counter() - t0
        stages_run.append("fields")
        written.append("fields.npz")
    if outputs["plots"]:
        t0 = time.perf_counter()
        from . import plots

        written += plots.write_all(scene, record, fields, extras, out)
        stages["plots"] = time.perf_counter() - t0
        stages_run.append("plots")
    if outputs["vtk"] and fields:
        t0 = time.perf_counter()
        from validation import vtk_io

        written += vtk_io.write_sweep(out / "vtk", scene.surface, [fields[i] for i in sorted(fields)],
                                      scene.xi[sorted(fields)])
        stages["vtk"] = time.perf_counter() - t0
        stages_run.append("vtk")
    if scene.surface.metadata.get("kind") == "measured":  # boundary choice and PSD of the measurement
        from .measured_scene import report

        written += report(scene, record, out)
    record["files"] = written
    record["all_converged"] = bool(all(p["success"] for p in recs.values()) and len(recs) == (
        len(scene.realisations) * len(scene.loads) * scene.speeds.size))
    record["complete"] = True
    stages["total"] = time.perf_counter() - t_start
    write_record()
    return record


def _tasks(scene, material, todo, points_dir, workers, scheduler, keep_fields, keep_chi):
    """Chunks of neighbouring speeds per load, covering every point still to solve."""
    tasks = []
    order = np.argsort(scene.speeds, kind="stable")
    parallel = max(int(workers), 1) if scheduler is None else max(int(workers), 2)
    for l, load in enumerate(scene.loads):
        indices = [int(i) for i in order if any((r, l, int(i)) in todo for r in range(len(scene.realisations)))]
        if not indices:
            continue
        size = scene.chunk or max(1, math.ceil(len(indices) / parallel))
        for start in range(0, len(indices), size):
            chunk = indices[start:start + size]
            keys = {(r, i): todo[(r, l, i)] for i in chunk for r in range(len(scene.realisations))
                    if (r, l, i) in todo}
            tasks.append({"material": material, "surfaces": list(scene.realisations), "seeds": list(scene.seeds),
                          "load": load, "l": l, "speeds": scene.speeds, "xi": scene.xi, "indices": chunk,
                          "keys": keys, "rtol": scene.rtol, "maxiter": scene.maxiter,
                          "periodic": scene.periodic, "method": scene.method,
                          "warm_start": scene.warm_start, "anisotropy": scene.outputs["anisotropy"],
                          "keep_fields": keep_fields, "keep_chi": keep_chi, "out": str(points_dir),
                          "single_thread": scheduler is None and workers > 1, "direction": scene.direction})
    return tasks


def _fields_of_first(scene, recs, points_dir):
    """Fields of realisation 0 at the first load, per speed index (namespaces of arrays)."""
    fields = {}
    for i in range(scene.speeds.size):
        rec = recs.get((0, 0, i))
        if rec is None or not rec["success"]:
            continue
        data = load_fields(points_dir, rec, scene.surface)
        if data is not None and "pressure" in data:
            fields[i] = SimpleNamespace(friction=rec["friction"], contact_fraction=rec["contact_fraction"],
                                        **data)
    return fields
