"""Measurement helpers shared by the benchmarks: fresh processes, thread settings, memory, timing.

Every measured case runs in a fresh interpreter (``multiprocessing`` with the ``spawn``
context), so its peak resident set size is its own and not the high-water mark of an
earlier case. Thread counts are fixed through the environment before the child imports
numpy (docs/theory.md §12: on 2 shared cores a multi-threaded BLAS on small vector operations can be
1000x slower); FFTs keep using all cores (:func:`bem.parallel.get_threads`).

Memory is read from the kernel: ``getrusage(RUSAGE_SELF).ru_maxrss`` (peak, KiB on Linux,
bytes on macOS) and ``/proc/self/statm`` (current, Linux only).
"""

import contextlib
import hashlib
import multiprocessing
import os
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

__all__ = [
    "THREAD_VARIABLES",
    "thread_environment",
    "run_in_fresh_process",
    "peak_rss",
    "current_rss",
    "median_time",
    "fft_pair_time",
    "load_average",
    "source_snapshot",
    "source_digest",
]

THREAD_VARIABLES = (
    "OMP_NUM_THREADS",
    "OPENBLAS_NUM_THREADS",
    "MKL_NUM_THREADS",
    "BLIS_NUM_THREADS",
    "VECLIB_MAXIMUM_THREADS",
    "NUMEXPR_NUM_THREADS",
)


def thread_environment(blas_threads=1, omp_threads=None):
    """Environment variables that pin BLAS (and OpenMP) thread pools in a child process.

    ``omp_threads`` defaults to ``blas_threads``; pass a different number for a library
    whose own parallel loops use OpenMP (e.g. tamaas).
    """
    env = {name: str(blas_threads) for name in THREAD_VARIABLES}
    env["OMP_NUM_THREADS"] = str(blas_threads if omp_threads is None else omp_threads)
    return env


def run_in_fresh_process(func, *args, env=None, timeout=None):
    """``func(*args)`` in a new interpreter (spawn) with ``env`` added to its environment.

    ``func`` must be importable by name (a module-level function) and return something
    picklable. Raises :class:`multiprocessing.TimeoutError` after ``timeout`` seconds (the
    child is then terminated) and re-raises the child's exception otherwise.
    """
    ctx = multiprocessing.get_context("spawn")
    saved = {k: os.environ.get(k) for k in (env or {})}
    os.environ.update(env or {})
    try:
        with ctx.Pool(1, maxtasksperchild=1) as pool:
            return pool.apply_async(func, args).get(timeout)
    finally:
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value


def peak_rss():
    """Peak resident set size of this process so far (bytes)."""
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return int(peak if sys.platform == "darwin" else peak * 1024)


def current_rss():
    """Current resident set size (bytes), or None where ``/proc`` is unavailable."""
    try:
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return None


def median_time(func, *, min_repeats=5, max_repeats=50, budget=1.0):
    """Median wall time (s) of ``func()`` after one warm-up call.

    Repeats until ``budget`` seconds are spent (within ``[min_repeats, max_repeats]``).
    Returns ``(median, minimum, repeats)``.
    """
    func()
    times = []
    start = time.perf_counter()
    while len(times) < max_repeats and (len(times) < min_repeats or time.perf_counter() - start < budget):
        t0 = time.perf_counter()
        func()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), min(times), len(times)


def fft_pair_time(shape, **kwargs):
    """``median_time`` of one plain FFT pair, ``scipy.fft.irfftn(scipy.fft.rfftn(x))`` on all
    cores (the library's own transforms, no multiply, a fresh output each call), on a random
    real field of ``shape``: the reference cost of one operator application."""
    import numpy as np
    import scipy.fft as sfft

    from bem.parallel import get_threads

    x = np.random.default_rng(0).standard_normal(shape)
    return median_time(
        lambda: sfft.irfftn(sfft.rfftn(x, workers=get_threads()), s=shape, workers=get_threads()), **kwargs
    )


def load_average():
    """1-minute load average of the machine (None where unavailable)."""
    try:
        return round(os.getloadavg()[0], 2)
    except OSError:
        return None


def source_digest(directory):
    """SHA-256 of the ``*.py`` files under ``directory`` (names and contents, sorted)."""
    h = hashlib.sha256()
    for path in sorted(Path(directory).rglob("*.py")):
        h.update(str(path.relative_to(directory)).encode())
        h.update(path.read_bytes())
    return h.hexdigest()


@contextlib.contextmanager
def source_snapshot(package, directory):
    """Run fresh processes on a frozen copy of ``package`` (an imported module).

    Copies the package's sources into ``directory`` and puts that first on ``sys.path``
    (spawned children inherit it), so every case of a benchmark measures the same code even
    while the working tree is being edited. Yields a dict describing the snapshot.
    """
    src = Path(package.__file__).parent
    dst = Path(directory) / src.name
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    info = {"package": src.name, "source": str(src), "sha256": source_digest(dst)}
    try:
        info["git_head"] = (
            subprocess.run(
                ["git", "rev-parse", "HEAD"], cwd=src, capture_output=True, text=True, timeout=10
            ).stdout.strip()
            or None
        )
        info["git_dirty"] = bool(
            subprocess.run(
                ["git", "status", "--porcelain", "--", "."], cwd=src, capture_output=True, text=True, timeout=10
            ).stdout.strip()
        )
    except (OSError, subprocess.SubprocessError):
        info["git_head"] = info["git_dirty"] = None
    sys.path.insert(0, str(directory))
    try:
        yield info
    finally:
        with contextlib.suppress(ValueError):
            sys.path.remove(str(directory))


def write_record(out_dir, name, result):
    """Write ``result`` as indented JSON to ``out_dir/name`` (the folder is created); returns the path."""
    import json

    path = Path(out_dir) / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(result, indent=2, default=float))
    return path


def bench_main(run, description, record, argv=None, quick_help="fewer, smaller cases"):
    """Command line of a benchmark module: ``--quick`` and ``--out`` passed to ``run``."""
    import argparse

    p = argparse.ArgumentParser(description=description)
    p.add_argument("--quick", action="store_true", help=quick_help)
    p.add_argument("--out", default=".", help=f"output directory for {record}")
    args = p.parse_args(argv)
    run(quick=args.quick, out_dir=args.out)
