"""Sweeps a user can leave running: points in chunks, in parallel, resumable.

A *point* is one solve: realisation ``r`` (seed ``seed + r``), load index ``l`` and speed
index ``i``. A *chunk* is one load and a run of neighbouring speeds (ascending) for every
realisation: within it each realisation's solve is warm-started from its solve at the
previous speed, and the operator of a speed (built once, cached by :func:`bem.solve`) serves
every realisation. Chunks run in the calling process (``workers = 1``), in a process pool
(``workers > 1``) or on a Dask cluster (``scheduler``).

Every finished point is written at once, atomically (temporary file + rename), by the
process that solved it: ``points/rRRR_lLLL_sSSS.npz`` (fields, when needed) and then
``points/rRRR_lLLL_sSSS.json`` (numbers; its presence marks the point finished). A point
file carries a key of everything that determines it (material, surface, load, speed,
solver tolerances, requested per-point outputs), so a rerun in the same folder skips the
finished points of the same study and recomputes the others. Dask workers must see the
output folder (a shared filesystem) for fields to be kept; their numbers come back anyway.
"""
import hashlib
import json
import logging
import os
import tempfile
import time
from pathlib import Path

import numpy as np

import bem
from bem import anisotropy
from bem.errors import ConvergenceError

log = logging.getLogger(__name__)


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


def point_name(r, l, i):
    return f"r{r:03d}_l{l:03d}_s{i:03d}"


def point_key(material, surface, load, speed, settings):
    """Hash of everything that determines a point's file (hex string)."""
    h = hashlib.sha256()
    for arr in (material.moduli, material.relaxation_times, surface.heights):
        h.update(np.ascontiguousarray(arr).tobytes())
    h.update(json.dumps([material.E0, material.nu, surface.length, float(load), float(speed),
                         settings], sort_keys=True).encode())
    return h.hexdigest()[:24]


def _save_fields(path, res, keep_fields, keep_chi):
    arrays = {}
    if keep_fields:
        arrays.update(pressure=res.pressure, displacement=res.displacement, approach=res.approach)
    if keep_chi:
        chi = res.pressure > 0
        arrays.update(chi=np.packbits(chi, axis=None), chi_shape=np.array(chi.shape))
    import io

    buf = io.BytesIO()
    np.savez_compressed(buf, **arrays)
    write_atomic(path, buf.getvalue(), mode="wb")


def solve_point(task, r, surface, speed, load, initial):
    """Solve one point and compute its per-point outputs; return (record, result or None)."""
    times = {}
    t0 = time.perf_counter()
    try:
        res = bem.solve(surface, task["material"], speed=speed, load=load, rtol=task["rtol"],
                        maxiter=task["maxiter"], initial=initial, periodic=task.get("periodic", True),
                        method=task.get("method", "auto"), direction=task.get("direction", 0.0))
        message = res.message
    except ConvergenceError as err:
        res, message = None, str(err)
        log.warning("%s", err)
    times["solve"] = time.perf_counter() - t0
    rec = {"success": res is not None, "message": message, "times": times}
    if res is not None:
        for key, attr in [("friction", "friction"), ("friction_eq6", "friction_eq6"),
                          ("contact_fraction", "contact_fraction"), ("approach", "approach"),
                          ("dissipated_power", "dissipated_power"), ("iterations", "iterations"),
                          ("operator_products", "matvecs"), ("residual", "residual"),
                          ("wall_time", "wall_time")]:
            rec[key] = getattr(res, attr)
        if task["anisotropy"] and surface.ndim == 2:
            t0 = time.perf_counter()
            rec["moments"] = anisotropy.spectral_moments(res.displacement, surface.length,
                                                         direction=task.get("direction", 0.0)).as_dict()
            times["anisotropy"] = time.perf_counter() - t0
    return rec, res


def run_chunk(task, callback=None):
    """Solve the points of one chunk; write each at once; return their records.

    ``task`` (a picklable dict): ``material``, ``surfaces`` (one per realisation), ``seeds``,
    ``load``, ``l``, ``speeds`` and ``xi`` (full arrays), ``indices`` (this chunk's speed
    indices, ascending in speed), ``keys`` (``{(r, i): key}`` of the points to solve),
    ``rtol``, ``maxiter``, ``warm_start``, ``anisotropy``, ``keep_fields``, ``keep_chi``,
    ``out`` (folder of the point files) and ``single_thread`` (limit FFT/BLAS threads to 1,
    for pool workers sharing the cores).
    """
    if task.get("single_thread"):
        bem.set_threads(1)
    out = Path(task["out"])
    previous = [None] * len(task["surfaces"])
    records = []
    for i in task["indices"]:
        for r, surface in enumerate(task["surfaces"]):
            key = task["keys"].get((r, i))
            if key is None:  # finished in an earlier run
                continue
            speed = float(task["speeds"][i])
            # the adaptive mesh changes with speed: no warm start across its points
            initial = previous[r] if task["warm_start"] and task.get("method") != "adaptive" else None
            rec, res = solve_point(task, r, surface, speed, task["load"], initial)
            name = point_name(r, task["l"], i)
            rec.update(key=key, r=r, l=task["l"], i=i, seed=task["seeds"][r], load=task["load"],
                       speed=speed, xi=float(task["xi"][i]), fields=None)
            if res is not None:
                previous[r] = res.pressure
            try:
                if res is not None and (task["keep_fields"] or task["keep_chi"]):
                    _save_fields(out / f"{name}.npz", res, task["keep_fields"], task["keep_chi"])
                    rec["fields"] = f"{name}.npz"
                write_atomic(out / f"{name}.json", json.dumps(rec))
            except OSError as err:  # e.g. a Dask worker without the shared folder
                log.warning("point %s not written by the worker: %s", name, err)
            records.append(rec)
            if callback is not None:
                callback(rec)
    return records


def load_point(folder, r, l, i, key):
    """The finished point's record if its file exists with this key, else None."""
    path = Path(folder) / f"{point_name(r, l, i)}.json"
    try:
        rec = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return rec if rec.get("key") == key else None


def load_fields(folder, rec, surface):
    """Arrays stored for a point: dict with pressure, displacement, gap and/or chi."""
    if not rec.get("fields"):
        return None
    path = Path(folder) / rec["fields"]
    if not path.exists():
        return None
    with np.load(path) as z:
        data = {k: z[k] for k in z.files}
    out = {}
    if "pressure" in data:
        h = surface.heights
        out.update(pressure=data["pressure"], displacement=data["displacement"],
                   gap=data["displacement"] - (h - h.max() + float(data["approach"])))
    if "chi" in data:
        shape = tuple(data["chi_shape"])
        out["chi"] = np.unpackbits(data["chi"], count=int(np.prod(shape))).reshape(shape).astype(bool)
    elif "pressure" in out:
        out["chi"] = out["pressure"] > 0
    return out


def _pool_init():
    bem.set_threads(1)
    try:
        from threadpoolctl import threadpool_limits

        threadpool_limits(1)
    except ImportError:  # pragma: no cover - only a speed-up
        pass


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
