"""Sweeps a user can leave running: points in chunks, in parallel, resumable.

A *point* is one solve: realisation ``r`` (seed ``seed + r``), load index ``l`` and speed
index ``i``. A *chunk* is one load and a run of neighbouring speeds for every realisation,
solved by :func:`bem.sweep.sweep` (the same warm-started loop as :func:`bem.friction_curve`).
Chunks run in the calling process (``workers = 1``), in a process pool
(``workers > 1``) or on a Dask cluster (``scheduler``).

Every finished point is written at once, atomically (temporary file + rename), by the
process that solved it, once: ``points/rRRR_lLLL_sSSS.npz`` (fields of realisation 0 at the
first load, contact maps when the contact PSD is asked for) and then
``points/rRRR_lLLL_sSSS.json`` (numbers; its presence marks the point finished). A process
killed at any moment (``kill -9``) leaves only whole files and temporaries that the next run
removes. When the study's ``fields.npz`` is written, the point field files it holds are
removed; :func:`load_fields` then reads the point from it. A point
file carries a key of everything that determines it (material, surface, load, speed,
solver tolerances, requested per-point outputs), so a rerun in the same folder skips the
finished points of the same study and recomputes the others. Dask workers must see the
output folder (a shared filesystem) for fields to be kept; their numbers come back anyway.
"""

import hashlib
import io
import json
import logging
import time
from pathlib import Path

import numpy as np

import bem
from bem.accuracy import Finding
from bem.analysis import anisotropy
from bem.sweep import sweep

from ..files import write_atomic

log = logging.getLogger(__name__)


def point_name(r, l, i):
    return f"r{r:03d}_l{l:03d}_s{i:03d}"


def point_key(material, surface, load, speed, settings):
    """Hash of everything that determines a point's file (hex string)."""
    h = hashlib.sha256()
    for arr in (material.moduli, material.relaxation_times, surface.heights):
        h.update(np.ascontiguousarray(arr).tobytes())
    h.update(
        json.dumps(
            [material.E0, material.nu, surface.length, float(load), float(speed), settings], sort_keys=True
        ).encode()
    )
    return h.hexdigest()[:24]


def _save_fields(path, res, keep_fields, keep_chi, dtype):
    arrays = {}
    if keep_fields:
        arrays.update(
            pressure=res.pressure.astype(dtype), displacement=res.displacement.astype(dtype), approach=res.approach
        )
    if keep_chi:
        chi = res.pressure > 0
        arrays.update(chi=np.packbits(chi, axis=None), chi_shape=np.array(chi.shape))
    buf = io.BytesIO()
    np.savez_compressed(buf, **arrays)
    write_atomic(path, buf.getvalue(), mode="wb")


NUMBERS = [
    ("friction", "friction"),
    ("friction_eq6", "friction_eq6"),
    ("contact_fraction", "contact_fraction"),
    ("approach", "approach"),
    ("dissipated_power", "dissipated_power"),
    ("iterations", "iterations"),
    ("operator_products", "matvecs"),
    ("residual", "residual"),
    ("wall_time", "wall_time"),
]


def point_record(task, r, i, res, message):
    """The numbers of one solved point (``res`` None: it failed), with its per-point outputs."""
    speed = float(task["speeds"][i])
    rec = {
        "success": res is not None,
        "message": message,
        "times": {},
        "key": task["keys"][(r, i)],
        "r": r,
        "l": task["l"],
        "i": i,
        "seed": task["seeds"][r],
        "load": task["load"],
        "speed": speed,
        "xi": float(task["xi"][i]),
        "fields": None,
    }
    if res is None:
        rec["warnings"] = [Finding(f"the solve failed: {message}", "not_converged").as_dict()]
        return rec
    rec["times"]["solve"] = res.wall_time
    for key, attr in NUMBERS:
        rec[key] = getattr(res, attr)
    rec["peak_pressure"] = res.peak_pressure
    rec["error_estimate"] = res.error_estimate.as_dict()
    rec["warnings"] = [Finding.from_dict(w).as_dict() for w in res.warnings]
    if task.get("indenter"):
        rec.update(indenter_contact(task["indenter"], res.pressure, task["surfaces"][r].spacing))
    if task["anisotropy"] and res.pressure.ndim == 2:
        t0 = time.perf_counter()
        rec["moments"] = anisotropy.spectral_moments(
            res.displacement, task["surfaces"][r].length, direction=task.get("direction", 0.0)
        ).as_dict()
        rec["times"]["anisotropy"] = time.perf_counter() - t0
    return rec


def indenter_contact(kind, pressure, spacing):
    """Contact area (m²; m for a cylinder's profile) and contact radius (m): of the circle of equal
    area for a sphere, half the contact width for a cylinder."""
    count = int(np.count_nonzero(pressure > 0))
    if kind == "sphere":
        area = count * spacing**2
        return {"contact_area": area, "contact_radius": float(np.sqrt(area / np.pi))}
    return {"contact_area": count * spacing, "contact_radius": count * spacing / 2}


def run_chunk(task, callback=None):
    """Solve the points of one chunk with :func:`bem.sweep.sweep`; write each at once; return
    their records.

    ``task`` (a picklable dict): ``material``, ``surfaces`` (one per realisation), ``seeds``,
    ``load``, ``l``, ``speeds`` and ``xi`` (full arrays), ``indices`` (this chunk's speed
    indices), ``keys`` (``{(r, i): key}`` of the points to solve), ``rtol``, ``maxiter``,
    ``warm_start``, ``periodic``, ``method``, ``anisotropy``, ``keep_fields`` (fields of
    realisation 0 at load 0 are stored), ``keep_chi`` (contact maps of every point),
    ``precision`` ("float32" | "float64"), ``indenter`` ("sphere" | "cylinder" | None: contact
    radius and area per point), ``error_estimate`` (as in :func:`bem.solve`; each point's record
    carries its ``error_estimate`` and ``warnings``), ``out`` (folder of the point files) and
    ``single_thread`` (limit FFT threads to 1, for pool workers sharing the cores).
    """
    if task.get("single_thread"):
        bem.set_threads(1)
    out = Path(task["out"])
    indices = list(task["indices"])
    records = []

    def on_point(j, r, res, message):
        i = indices[j]
        rec = point_record(task, r, i, res, message)
        name = point_name(r, task["l"], i)
        keep_fields = task["keep_fields"] and r == 0 and task["l"] == 0
        try:
            if res is not None and (keep_fields or task["keep_chi"]):
                _save_fields(out / f"{name}.npz", res, keep_fields, task["keep_chi"], task.get("precision", "float32"))
                rec["fields"] = f"{name}.npz"
            write_atomic(out / f"{name}.json", json.dumps(rec))
        except OSError as err:  # e.g. a Dask worker without the shared folder
            log.warning("point %s not written by the worker: %s", name, err)
        records.append(rec)
        if callback is not None:
            callback(rec)

    sweep(
        task["surfaces"],
        task["material"],
        speeds=np.asarray(task["speeds"])[indices],
        load=task["load"],
        rtol=task["rtol"],
        maxiter=task["maxiter"],
        warm_start=task["warm_start"],
        periodic=task.get("periodic", True),
        method=task.get("method", "auto"),
        skip=lambda j, r: (r, indices[j]) not in task["keys"],
        on_point=on_point,
        keep=False,
        direction=task.get("direction", 0.0),
        error_estimate=task.get("error_estimate", "indicators"),
    )
    return records


def load_point(folder, r, l, i, key):
    """The finished point's record if its file exists with this key, else None."""
    path = Path(folder) / f"{point_name(r, l, i)}.json"
    try:
        rec = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return rec if rec.get("key") == key else None


STUDY_FIELDS = "fields.npz"  # in the folder above points/: fields of realisation 0 at load 0


_study_cache = {}  # fields.npz path -> (modification time, arrays), read once per run


def _study_fields(folder, key):
    """The arrays of the point ``key`` from the study's fields.npz (its point files are removed
    once it is written), or None."""
    path = Path(folder).parent / STUDY_FIELDS
    try:
        stamp = path.stat().st_mtime_ns
        if _study_cache.get(path, (None,))[0] != stamp:
            with np.load(path) as z:
                _study_cache.clear()
                _study_cache[path] = (stamp, {k: z[k] for k in ("point_keys", "pressure", "displacement", "approach")})
        data = _study_cache[path][1]
    except (OSError, ValueError, KeyError):
        return None
    keys = [str(k) for k in data["point_keys"]]
    if key not in keys:
        return None
    j = keys.index(key)
    return {"pressure": data["pressure"][j], "displacement": data["displacement"][j], "approach": data["approach"][j]}


def load_fields(folder, rec, surface):
    """Arrays stored for a point: dict with pressure, displacement, gap and/or chi (None if none)."""
    data = None
    if rec.get("fields") and (Path(folder) / rec["fields"]).exists():
        with np.load(Path(folder) / rec["fields"]) as z:
            data = {k: z[k] for k in z.files}
    elif rec.get("fields"):
        data = _study_fields(folder, rec["key"])
    if data is None:
        return None
    out = {}
    if "pressure" in data:
        h = surface.heights
        out.update(
            pressure=data["pressure"],
            displacement=data["displacement"],
            gap=data["displacement"] - (h - h.max() + float(data["approach"])),
        )
    if "chi" in data:
        shape = tuple(data["chi_shape"])
        out["chi"] = np.unpackbits(data["chi"], count=int(np.prod(shape))).reshape(shape).astype(bool)
    elif "pressure" in out:
        out["chi"] = out["pressure"] > 0
    return out


def _pool_init():
    """One thread per worker process for the FFTs and BLAS alike: the workers share the cores."""
    bem.set_threads(1)
    bem.set_blas_threads(1)


def execute(tasks, *, workers=1, scheduler=None, on_point, poll):
    """Run ``tasks`` (chunks); call ``on_point(record)`` for every finished point.

    In-process: after every point. Pool or Dask: ``poll()`` every 0.5 s (it reads the point
    files the workers wrote), and each chunk's returned records on completion.
    """
    if not tasks:
        return
    if scheduler is None and workers == 1:
        for task in tasks:
            run_chunk(task, callback=on_point)
        return
    if scheduler is not None:
        from dask.distributed import Client, wait

        with Client(scheduler, timeout="30s") as client:
            futures = [client.submit(run_chunk, t, pure=False) for t in tasks]
            pending = set(futures)
            while pending:
                try:
                    done = wait(list(pending), timeout=0.5, return_when="FIRST_COMPLETED").done
                except TimeoutError:
                    done = set()
                poll()
                for f in done:
                    for rec in f.result():
                        on_point(rec)
                pending -= set(done)
        return
    import multiprocessing as mp
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor
    from concurrent.futures import wait as cf_wait

    ctx = mp.get_context("spawn")
    with ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_pool_init) as pool:
        pending = {pool.submit(run_chunk, t) for t in tasks}
        try:
            while pending:
                done, pending = cf_wait(pending, timeout=0.5, return_when=FIRST_COMPLETED)
                poll()
                for f in done:
                    for rec in f.result():
                        on_point(rec)
        except BaseException:  # Ctrl-C or a failing chunk: drop queued chunks, keep what is on disk
            pool.shutdown(wait=False, cancel_futures=True)
            raise
