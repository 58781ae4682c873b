"""Run a scene and write its outputs: results.json, fields.npz, PNG plots, VTK on request.

Every finished point of a sweep is written to ``results.json`` at once (atomically:
written to a temporary file, then renamed), so an interrupted sweep keeps what it did.
"""
import json
import os
import platform
import tempfile
import time
from pathlib import Path

import numpy as np

import bem
from bem import statistics


def write_atomic(path, data, mode="w"):
    """Write ``data`` to ``path`` through a temporary file in the same folder + rename."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, mode) as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _material_record(m):
    return {"E0": m.E0, "E_inf": m.E_inf, "nu": m.nu, "prony_moduli": m.moduli.tolist(),
            "relaxation_times": m.relaxation_times.tolist(), "creep_compliances": m.compliances.tolist(),
            "creep_times": m.creep_times.tolist()}


def _surface_record(s):
    return {"n": s.n, "dim": s.ndim, "length": s.length, "spacing": s.spacing,
            "rms_height": statistics.rms_height(s), "rms_slope": statistics.rms_slope(s),
            "max_height": float(s.heights.max()), "min_height": float(s.heights.min())}


def run_scene(scene, out_dir, *, progress=True):
    """Compute what ``scene`` asks for; write it under ``out_dir``; return the results dict."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()
    record = {
        "title": scene.title, "scene": scene.source, "viscobem_version": "0.1.0",
        "python": platform.python_version(),
        "units": {"length": "m", "pressure": "Pa", "load": "N (N/m for 1-D profiles)", "speed": "m/s",
                  "power": "W (W/m for 1-D profiles)", "xi": "v * xi_time / length (dimensionless)"},
        "conventions": "heights positive toward the half-space; the surface slides in +x (axis 0); "
                       "friction = dissipation form, friction_eq6 = -(1/F_N) int p dh/dx dA",
        "material": _material_record(scene.material), "surface": _surface_record(scene.surface),
        "load": scene.load, "xi_time": scene.xi_time,
        "solver": {"rtol": scene.rtol, "maxiter": scene.maxiter, "periodic": scene.periodic,
                   "method": scene.method},
        "stages": {}, "complete": False,
    }
    n = scene.speeds.size
    curve = {"xi": scene.xi.tolist(), "speed": scene.speeds.tolist(),
             "friction": [None] * n, "friction_eq6": [None] * n, "contact_fraction": [None] * n,
             "dissipated_power": [None] * n, "approach": [None] * n, "iterations": [None] * n,
             "operator_products": [None] * n, "residual": [None] * n, "wall_time": [None] * n,
             "success": [None] * n, "message": [""] * n}
    record["friction_curve"] = curve
    fields = {}

    def save_point(i, speed, res, message):
        curve["message"][i] = message
        curve["success"][i] = res is not None
        if res is not None:
            for key, attr in [("friction", "friction"), ("friction_eq6", "friction_eq6"),
                              ("contact_fraction", "contact_fraction"), ("approach", "approach"),
                              ("dissipated_power", "dissipated_power"), ("iterations", "iterations"),
                              ("operator_products", "matvecs"), ("residual", "residual"),
                              ("wall_time", "wall_time")]:
                curve[key][i] = getattr(res, attr)
            if scene.outputs["fields"] or scene.outputs["plots"] or scene.outputs["vtk"]:
                fields[i] = res
        write_atomic(out / "results.json", json.dumps(record, indent=1))

    t0 = time.perf_counter()
    fc = bem.friction_curve(scene.surface, scene.material, speeds=scene.speeds, load=scene.load,
                            rtol=scene.rtol, maxiter=scene.maxiter, warm_start=scene.warm_start,
                            progress=progress, callback=save_point, periodic=scene.periodic,
                            method=scene.method)
    record["stages"]["friction_curve"] = time.perf_counter() - t0
    written = ["results.json"]
    if scene.outputs["fields"] and fields:
        t0 = time.perf_counter()
        idx = sorted(fields)
        arrays = {"heights": scene.surface.heights, "speed": scene.speeds[idx], "xi": scene.xi[idx],
                  "pressure": np.stack([fields[i].pressure for i in idx]),
                  "displacement": np.stack([fields[i].displacement for i in idx]),
                  "gap": np.stack([fields[i].gap for i in idx])}
        with open(out / "fields.npz", "wb") as f:
            np.savez_compressed(f, **arrays)
        record["stages"]["fields"] = time.perf_counter() - t0
        written.append("fields.npz")
    if scene.outputs["plots"]:
        t0 = time.perf_counter()
        from . import plots

        written += plots.write_all(scene, fc, fields, out)
        record["stages"]["plots"] = time.perf_counter() - t0
    if scene.outputs["vtk"] and fields:
        t0 = time.perf_counter()
        from validation import vtk_io

        written += vtk_io.write_sweep(out / "vtk", scene.surface, [fields[i] for i in sorted(fields)],
                                      scene.xi[sorted(fields)])
        record["stages"]["vtk"] = time.perf_counter() - t0
    record["files"] = written
    record["all_converged"] = fc.all_converged
    record["complete"] = True
    record["stages"]["total"] = time.perf_counter() - t_start
    write_atomic(out / "results.json", json.dumps(record, indent=1))
    return record
