"""Run a scene and write its outputs: results.json, fields.npz, PNG plots, VTK on request.

Only what the scene asks for is computed: anisotropy, the contact PSD, Persson's theory,
fields, plots and VTK each run only when requested, and ``results.json`` lists the stages
that ran (``stages_run``) with their times (``stages``, s; per-point work summed over
points). Prony terms that are fully relaxed over the sweep's frequency band (and, on periodic
profiles, glassy over ``[q_L v_min, (pi n / L) v_max]``) are folded into the elastic part first.

The sweep itself is :mod:`viscobem_cli.run.points`: every finished point is written once, as
its own file, and a rerun in the same folder resumes from them. ``results.json`` is written
when the run starts (``complete: false``), when it is interrupted, and when it ends; a run
killed outright is rebuilt from the point files by the next run. ``results.json["warnings"]``
lists what is doubtful about the study and what to change: the scene's own (before the run),
every point's warnings (:mod:`bem.accuracy`: estimated errors above 5 %, friction forms that
disagree, ...) gathered one sentence per kind with the points they come from, and a friction peak
outside the sweep.

``fields.npz`` (realisation 0 at the first load, one row per converged speed): ``heights``
(m), ``speed`` (m/s), ``xi``, ``approach`` (m), ``pressure`` (Pa) and ``displacement`` (m)
in ``[outputs] fields_precision`` (float32 by default), compressed. The gap is
``displacement - (heights - max(heights) + approach)``.

Every file is written atomically (a temporary file, then renamed) with the permissions of
a plain new file, so a run that fails never leaves a truncated file, and a scene rejected
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

from bem.sweep import check_sweep

from .. import guidance
from ..files import remove_stale_temporaries, write_atomic
from . import analysis, directions, records, temperatures
from .points import STUDY_FIELDS, execute, load_fields, load_point, point_key, point_name

__all__ = ["run_scene", "fold_material"]


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


def _version():
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("viscobem")
    except PackageNotFoundError:
        return "unknown"


def _base_record(scene, material, workers, scheduler):
    return {
        "title": scene.title,
        "scene": scene.source,
        "viscobem_version": _version(),
        "python": platform.python_version(),
        "units": {
            "length": "m",
            "pressure": "Pa",
            "load": "N (N/m for 1-D profiles)",
            "speed": "m/s",
            "power": "W (W/m for 1-D profiles)",
            "xi": "v * xi_time / xi_length (dimensionless)",
            "contact_radius": "m",
            "contact_area": "m^2 (m for 1-D profiles)",
            "moments": "m20, m02, m11 of the displacement field: m^2/m^2 (dimensionless)",
        },
        "conventions": "heights positive toward the half-space; the surface slides in +x (axis 0); "
        "friction = dissipation form, friction_eq6 = -(1/F_N) int p dh/dx dA; ensemble "
        "values are means over realisations with standard errors in *_se",
        "material": records.scene_material_record(scene),
        "material_solved": {
            **records.material_record(material),
            "terms": int(material.moduli.size),
            "terms_folded": int(scene.material.moduli.size - material.moduli.size),
        },
        "surface": records.surface_record(scene),
        "realisations": len(scene.realisations),
        "seeds": list(scene.seeds),
        "loads": list(scene.loads),
        "load": scene.load,
        "xi_time": scene.xi_time,
        "xi_time_source": scene.xi_time_source,
        "xi_length": scene.xi_length,
        "solver": {
            "rtol": scene.rtol,
            "maxiter": scene.maxiter,
            "periodic": scene.periodic,
            "method": scene.method,
            "error_estimate": scene.error_estimate,
            "workers": workers,
            "scheduler": scheduler,
        },
        "outputs": {**scene.outputs, "fields_precision": scene.fields_precision},
        "warnings": list(scene.warnings),
        "stages": {},
        "stages_run": [],
        "complete": False,
        "direction_deg": round(math.degrees(scene.direction), 9),
    }


def _finished_points(scene, material, settings, points_dir):
    """Points on disk from an earlier run of the same study, and the keys of those to solve."""
    recs, todo = {}, {}
    for l, load in enumerate(scene.loads):
        for r, surf in enumerate(scene.realisations):
            for i, speed in enumerate(scene.speeds):
                key = point_key(material, surf, load, speed, settings)
                rec = load_point(points_dir, r, l, i, key)
                if rec is None:
                    todo[(r, l, i)] = key
                else:
                    recs[(r, l, i)] = rec
    return recs, todo


def _write_record(out, scene, record, recs):
    record["curves"] = [records.summarise_curve(scene, recs, l) for l in range(len(scene.loads))]
    record["friction_curve"] = record["curves"][0]
    record["points"] = records.point_list(scene, recs)
    write_atomic(out / "results.json", json.dumps(record, indent=1))


def _sweep(scene, material, todo, recs, points_dir, workers, scheduler, progress, keep):
    """Solve the points in ``todo``; every finished one is added to ``recs``."""
    from tqdm.auto import tqdm

    bar = tqdm(total=len(todo), disable=not progress, desc="sweep", unit="point")

    def on_point(rec):
        where = (rec["r"], rec["l"], rec["i"])
        if where in todo and where not in recs:
            bar.update(1)
        recs[where] = rec

    def poll():
        for where, key in todo.items():
            if where not in recs:
                rec = load_point(points_dir, *where, key)
                if rec is not None:
                    on_point(rec)

    try:
        execute(
            _tasks(scene, material, todo, points_dir, workers, scheduler, keep),
            workers=workers,
            scheduler=scheduler,
            on_point=on_point,
            poll=poll,
        )
    finally:
        bar.close()


def _analyses(scene, record, recs, points_dir, stages):
    """Anisotropy, contact PSD and Persson's theory, as requested; returns plot extras."""
    extras = {}
    if scene.outputs["anisotropy"]:
        record["anisotropy"] = [analysis.anisotropy_summary(scene, recs, l) for l in range(len(scene.loads))]
        record["stages_run"].append("anisotropy")
    if scene.outputs["contact_psd"]:
        t0 = time.perf_counter()
        record["contact_psd"], extras["psd"] = analysis.contact_psd_summary(scene, recs, points_dir)
        stages["contact_psd"] = time.perf_counter() - t0
        record["stages_run"].append("contact_psd")
    if scene.outputs["persson"]:
        t0 = time.perf_counter()
        record["persson"] = analysis.persson_summary(scene)
        stages["persson"] = time.perf_counter() - t0
        record["stages_run"].append("persson")
    return extras


def _write_fields(scene, fields, out, points_dir, recs):
    """fields.npz of realisation 0 at the first load; its points' field files are then removed."""
    idx = sorted(fields)
    dtype = np.dtype(scene.fields_precision)
    keys = [recs[(0, 0, i)]["key"] for i in idx]
    arrays = {
        "heights": scene.surface.heights.astype(dtype),
        "speed": scene.speeds[idx],
        "xi": scene.xi[idx],
        "approach": np.array([fields[i].approach for i in idx]),
        "point_keys": np.array(keys),
        "pressure": np.stack([fields[i].pressure for i in idx]).astype(dtype),
        "displacement": np.stack([fields[i].displacement for i in idx]).astype(dtype),
    }
    buffer = io.BytesIO()
    np.savez_compressed(buffer, **arrays)
    write_atomic(out / STUDY_FIELDS, buffer.getvalue(), mode="wb")
    if not scene.outputs["contact_psd"]:  # the point files hold nothing else
        for i in idx:
            (points_dir / f"{point_name(0, 0, i)}.npz").unlink(missing_ok=True)
    return [STUDY_FIELDS]


def _outputs(scene, record, recs, points_dir, out, extras, stages):
    """fields.npz, plots and VTK as requested; returns the file names written."""
    outputs, written = scene.outputs, ["results.json"]
    fields = (
        _fields_of_first(scene, recs, points_dir) if outputs["fields"] or outputs["plots"] or outputs["vtk"] else {}
    )
    steps = [
        ("fields", outputs["fields"] and fields, lambda: _write_fields(scene, fields, out, points_dir, recs)),
        ("plots", outputs["plots"], lambda: _plots(scene, record, fields, extras, out)),
        ("vtk", outputs["vtk"] and fields, lambda: _vtk(scene, fields, out)),
    ]
    for name, wanted, step in steps:
        if wanted:
            t0 = time.perf_counter()
            written += step()
            stages[name] = time.perf_counter() - t0
            record["stages_run"].append(name)
    return written


def _plots(scene, record, fields, extras, out):
    from .. import plots

    return plots.write_all(scene, record, fields, extras, out) + temperatures.write_master_curve(scene, out)


def _vtk(scene, fields, out):
    from validation import vtk_io

    idx = sorted(fields)
    settings = {
        "rtol": scene.rtol,
        "maxiter": scene.maxiter,
        "periodic": scene.periodic,
        "method": scene.method,
        "direction_deg": math.degrees(scene.direction),
        "grid": list(scene.surface.shape),
        "xi_time_s": scene.xi_time,
        "xi_length_m": scene.xi_length,
    }
    extra = vtk_io.provenance(
        solver=f"bem.solve ({'periodic' if scene.periodic else 'isolated'} BEM, method={scene.method!r}), "
        f"realisation 0 at load {scene.loads[0]:g}",
        settings=settings,
        material_given=scene.raw.get("material"),
    )
    return vtk_io.write_sweep(
        out / "vtk", scene.surface, [fields[i] for i in idx], scene.xi[idx], material=scene.material, extra=extra
    )


def run_scene(scene, out_dir, *, progress=True, scheduler=None, workers=None):
    """Compute what ``scene`` asks for; write it under ``out_dir``; return the results dict.

    ``scheduler`` and ``workers`` override the scene's ``[solver]`` values (command line).
    A folder holding finished points of the same study is resumed: those points are not
    solved again.
    """
    options = dict(progress=progress, scheduler=scheduler, workers=workers)
    if len(scene.directions) > 1:  # a sweep over sliding directions: one study per direction
        return _per_direction(scene, out_dir, options)
    check_sweep(scene.surface, scene.material, speeds=scene.speeds, loads=scene.loads, rtol=scene.rtol)
    if scene.temperatures and scene.superposition:  # one curve over the reduced speeds
        return temperatures.superposed(scene, out_dir)
    if scene.temperatures:  # one sweep per temperature (viscobem_cli.scene.temperatures)
        return _per_temperature(scene, out_dir, options)
    out = Path(out_dir)
    points_dir = out / "points"
    points_dir.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(points_dir)
    remove_stale_temporaries(out)
    t_start = time.perf_counter()
    scheduler = scheduler if scheduler is not None else scene.scheduler
    workers = workers if workers is not None else scene.workers
    material = fold_material(scene)
    record = _base_record(scene, material, workers, scheduler)
    stages = record["stages"]
    stages["fold"] = time.perf_counter() - t_start
    outputs = scene.outputs
    keep = {
        "fields": outputs["fields"] or outputs["plots"] or outputs["vtk"],
        "chi": outputs["contact_psd"],
        "precision": scene.fields_precision,
    }
    settings = {
        "rtol": scene.rtol,
        "maxiter": scene.maxiter,
        "periodic": scene.periodic,
        "method": scene.method,
        "error_estimate": scene.error_estimate,
        "anisotropy": outputs["anisotropy"],
        **keep,
    }
    if scene.direction != 0.0:  # sliding direction
        settings["direction"] = scene.direction
    recs, todo = _finished_points(scene, material, settings, points_dir)
    record["resumed_points"] = len(recs)
    _write_record(out, scene, record, recs)
    t0 = time.perf_counter()
    try:
        _sweep(scene, material, todo, recs, points_dir, workers, scheduler, progress, keep)
    except BaseException:  # Ctrl-C or a failing chunk: results.json lists the finished points
        _write_record(out, scene, record, recs)
        raise
    stages["friction_curve"] = time.perf_counter() - t0
    record["stages_run"].append("friction_curve")
    for name in ("solve", "anisotropy"):
        spent = [p["times"][name] for p in recs.values() if name in p.get("times", {})]
        if spent:
            stages["point_" + name] = float(sum(spent))
    extras = _analyses(scene, record, recs, points_dir, stages)
    _write_record(out, scene, record, recs)  # the curves, for the plots
    record["warnings"] += records.point_warnings(scene, recs)
    record["warnings"] += guidance.peak_warnings(record["curves"], scene.xi_time_source)
    record["files"] = _outputs(scene, record, recs, points_dir, out, extras, stages)
    if scene.surface.metadata.get("kind") == "measured":  # boundary choice and PSD of the measurement
        from .measured import report

        record["files"] += report(scene, record, out)
    expected = len(scene.realisations) * len(scene.loads) * scene.speeds.size
    record["all_converged"] = bool(all(p["success"] for p in recs.values()) and len(recs) == expected)
    record["complete"] = True
    stages["total"] = time.perf_counter() - t_start
    _write_record(out, scene, record, recs)
    return record


def _per_direction(scene, out_dir, options):
    """One study per sliding direction (:mod:`viscobem_cli.run.directions`), each in its folder."""
    out, started, records = Path(out_dir), time.perf_counter(), []
    out.mkdir(parents=True, exist_ok=True)
    for one, folder in directions.studies(scene):
        records.append(run_scene(one, out / folder, **options))
        directions.write_progress(scene, records, out)
    return directions.finish(scene, records, out, started)


def _per_temperature(scene, out_dir, options):
    """One speed sweep per temperature (:mod:`viscobem_cli.run.temperatures`), each in its folder."""
    out, started = Path(out_dir), time.perf_counter()
    out.mkdir(parents=True, exist_ok=True)
    records = [run_scene(sub, out / folder, **options) for sub, folder in temperatures.studies(scene)]
    return temperatures.combine(scene, records, out, started)


def _tasks(scene, material, todo, points_dir, workers, scheduler, keep):
    """Chunks of neighbouring speeds per load, covering every point still to solve."""
    tasks = []
    order = np.argsort(scene.speeds, kind="stable")
    parallel = max(int(workers), 1) if scheduler is None else max(int(workers), 2)
    indenter = scene.kind if scene.kind in ("sphere", "cylinder") else None
    for l, load in enumerate(scene.loads):
        indices = [int(i) for i in order if any((r, l, int(i)) in todo for r in range(len(scene.realisations)))]
        if not indices:
            continue
        size = scene.chunk or max(1, math.ceil(len(indices) / parallel))
        for start in range(0, len(indices), size):
            chunk = indices[start : start + size]
            keys = {(r, i): todo[(r, l, i)] for i in chunk for r in range(len(scene.realisations)) if (r, l, i) in todo}
            tasks.append(
                {
                    "material": material,
                    "surfaces": list(scene.realisations),
                    "seeds": list(scene.seeds),
                    "load": load,
                    "l": l,
                    "speeds": scene.speeds,
                    "xi": scene.xi,
                    "indices": chunk,
                    "keys": keys,
                    "rtol": scene.rtol,
                    "maxiter": scene.maxiter,
                    "periodic": scene.periodic,
                    "method": scene.method,
                    "error_estimate": scene.error_estimate,
                    "warm_start": scene.warm_start,
                    "anisotropy": scene.outputs["anisotropy"],
                    "keep_fields": keep["fields"],
                    "keep_chi": keep["chi"],
                    "precision": keep["precision"],
                    "indenter": indenter,
                    "out": str(points_dir),
                    "single_thread": scheduler is None and workers > 1,
                    "direction": scene.direction,
                }
            )
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
            fields[i] = SimpleNamespace(
                friction=rec["friction"],
                friction_eq6=rec["friction_eq6"],
                residual=rec["residual"],
                iterations=rec["iterations"],
                success=rec["success"],
                contact_fraction=rec["contact_fraction"],
                speed=rec["speed"],
                load=rec["load"],
                approach=rec["approach"],
                **data,
            )
    return fields
