"""Run validation cases and collect one record (a plain dict, JSON-ready) of every number.

The record: ``cases[name]`` with the case's ``checks`` (metric, solver, label, value,
tolerance, passed, why), ``runs`` (seconds, peak MiB per solver call), ``files`` (VTK),
``profiles`` and ``sweeps`` (the plotted data), ``numbers``, ``status`` (``passed`` /
``failed`` / ``error``) and ``seconds``; ``summary`` counts them; ``environment`` says
where and from which commit the numbers came.
"""

from __future__ import annotations

import datetime
import logging
import platform
import subprocess
import time
import traceback
from pathlib import Path

import numpy as np

from .cases import CASES

__all__ = ["run_cases", "run_case", "environment", "select"]
log = logging.getLogger(__name__)


def environment():
    """Commit, date (UTC), machine and library versions of this run."""
    import scipy

    try:
        root = Path(__file__).resolve().parent.parent
        commit = (
            subprocess.run(
                ["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True, timeout=10
            ).stdout.strip()
            or "unknown"
        )
        dirty = (
            subprocess.run(
                ["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
                capture_output=True,
                text=True,
                timeout=10,
            ).stdout.strip()
            != ""
        )
    except (OSError, subprocess.SubprocessError):
        commit, dirty = "unknown", False
    return dict(
        commit=commit,
        dirty=dirty,
        date=datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        machine=f"{platform.node()} {platform.machine()} {platform.processor() or ''}".strip(),
        python=platform.python_version(),
        numpy=np.__version__,
        scipy=scipy.__version__,
    )


def select(names):
    """The cases to run, in registry order; unknown names raise :class:`bem.errors.InputError`."""
    from bem.errors import InputError

    if not names:
        return list(CASES)
    unknown = [n for n in names if n not in CASES]
    if unknown:
        raise InputError(f"case must be one of {', '.join(CASES)}; got {', '.join(unknown)}")
    return [n for n in CASES if n in names]


def _arrays(obj):
    """numpy -> lists, recursively (JSON)."""
    if isinstance(obj, dict):
        return {str(k): _arrays(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_arrays(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    return obj


def _case_record(case, out, seconds):
    checks = [c.as_dict() for c in out.checks]
    failed = [c for c in checks if not c["passed"]]
    return dict(
        title=case.title,
        description=case.description,
        solvers=list(case.solvers),
        reference=case.reference,
        status="failed" if failed else "passed",
        seconds=seconds,
        checks=checks,
        runs=[
            dict(solver=r.solver, label=r.label, seconds=r.seconds, peak_mib=r.peak_mib, detail=r.detail)
            for r in out.runs
        ],
        files=list(out.files),
        notes=list(out.notes),
        numbers=_arrays(out.numbers),
        profiles=[
            dict(
                label=p.label,
                reference=p.reference,
                xlabel=p.xlabel,
                curves=_arrays(p.curves),
                errors=_arrays(p.errors),
            )
            for p in out.profiles
        ],
        sweeps=[
            dict(title=s.title, xlabel=s.xlabel, ylabel=s.ylabel, logx=s.logx, logy=s.logy, curves=_arrays(s.curves))
            for s in out.sweeps
        ],
    )


def run_case(name, *, quick, out_dir, vtk=True):
    """Run one case; its record (a crashing case is a record of status ``error``: the others still run)."""
    out_dir = Path(out_dir)
    case = CASES[name]
    t0 = time.perf_counter()
    try:
        out = case(quick=quick, vtk_dir=(out_dir / "vtk" / name) if vtk else None, root=out_dir)
    except Exception as err:
        log.error("case %s raised %s", name, err)
        return dict(
            title=case.title,
            description=case.description,
            solvers=list(case.solvers),
            reference=case.reference,
            status="error",
            seconds=time.perf_counter() - t0,
            error=f"{type(err).__name__}: {err}",
            traceback=traceback.format_exc(),
            checks=[],
            runs=[],
            files=[],
            notes=[],
            numbers={},
            profiles=[],
            sweeps=[],
        )
    return _case_record(case, out, time.perf_counter() - t0)


# one thread per library in each process of a parallel run: the processes already keep the cores
# busy, and threaded factorisations beside them would only compete for the same cores
ONE_THREAD = ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS")


def in_processes(fn, names, jobs, bar, **kw):
    """``{name: fn(name, **kw)}`` for the case ``names``, computed in ``jobs`` processes, the costliest
    case (:attr:`Case.seconds`) started first; ``bar`` (tqdm) counts them. The processes are started
    fresh (``spawn``: ``fn`` is a module-level function), with one thread each."""
    import concurrent.futures
    import multiprocessing
    import os

    saved = {k: os.environ.get(k) for k in ONE_THREAD}
    os.environ.update(dict.fromkeys(ONE_THREAD, "1"))  # read by the numerical libraries as they load
    records = {}
    try:
        with concurrent.futures.ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context("spawn")) as pool:
            order = sorted(names, key=lambda n: -CASES[n].seconds)
            futures = {pool.submit(fn, n, **kw): n for n in order}
            for done in concurrent.futures.as_completed(futures):
                records[futures[done]] = done.result()
                bar.set_postfix_str(futures[done])
                bar.update()
    finally:
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
    return {n: records[n] for n in names}


def check_jobs(jobs):
    from bem.errors import InputError

    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise InputError(f"jobs must be an integer >= 1; got {jobs!r}")


def run_cases(names, *, quick, out_dir, vtk=True, progress=True, jobs=1):
    """Run the named cases (all if empty), ``jobs`` at a time in separate processes (one: in this
    one); return the record (see module docstring)."""
    from tqdm.auto import tqdm

    check_jobs(jobs)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    record = dict(quick=bool(quick), environment=environment(), cases={})
    t_all = time.perf_counter()
    names = select(names)
    kw = dict(quick=quick, out_dir=out_dir, vtk=vtk)
    if jobs > 1 and len(names) > 1:
        with tqdm(total=len(names), desc="validation", unit="case", disable=not progress) as bar:
            record["cases"] = in_processes(run_case, names, min(jobs, len(names)), bar, **kw)
    else:
        bar = tqdm(names, desc="validation", unit="case", disable=not progress)
        for name in bar:
            bar.set_postfix_str(name)
            record["cases"][name] = run_case(name, **kw)
    record["seconds"] = time.perf_counter() - t_all
    cases = record["cases"].values()
    record["summary"] = dict(
        cases=len(record["cases"]),
        passed=sum(c["status"] == "passed" for c in cases),
        failed=[n for n, c in record["cases"].items() if c["status"] != "passed"],
        checks=sum(len(c["checks"]) for c in cases),
        failed_checks=[dict(case=n, **k) for n, c in record["cases"].items() for k in c["checks"] if not k["passed"]],
    )
    return record
