"""Work the periodic benchmark does in fresh processes: one case at one size, tamaas on the
identical elastic problem, and a profile of one solve."""

import contextlib
import os
import re
import sys
import tempfile
import time

import numpy as np

import bem
from viscobem_bench import instruments
from viscobem_bench.periodic.problem import (
    E_ELASTIC,
    LENGTH,
    MAXITER,
    REPEAT_BUDGET,
    REPEATS,
    RTOL,
    RTOL_REF,
    TAMAAS_MAX_ITER,
    materials,
)


def case_worker(spec):
    """One material at one size: default solve (timed, peak RSS), FFT pair, tight solve."""
    from bem.halfspace.periodic import PeriodicHalfSpace
    from bem.sliding import operator_for

    rss_base, rss_base_now = instruments.peak_rss(), instruments.current_rss()
    surface = bem.surfaces.from_heights(np.load(spec["heights"]), LENGTH)
    material, speed = materials()[spec["case"]]
    rss_inputs = instruments.current_rss()
    load_avg = instruments.load_average()
    maxiter = spec.get("maxiter") or MAXITER[spec["case"]]

    def default_solve():  # each building its operator afresh
        bem.sliding.clear_operator_cache()
        return bem.solve(
            surface, material, speed=speed, load=spec["load"], rtol=RTOL, maxiter=maxiter, raise_on_failure=False
        )

    if spec.get("timing_only"):  # a later round (ROUNDS): the repeated solves and the FFT pair only
        return {
            "wall_times": [default_solve().wall_time for _ in range(REPEATS)],
            "fft_pair_time_min": instruments.fft_pair_time(surface.shape)[1],
        }
    res = default_solve()
    peak = instruments.peak_rss()
    walls = [res.wall_time]  # the fastest of REPEATS solves
    while len(walls) < REPEATS and res.wall_time <= REPEAT_BUDGET:
        walls.append(default_solve().wall_time)
    wall = min(walls)
    op = operator_for(surface, material, speed)
    p = res.pressure.copy()
    product, product_min, product_repeats = instruments.median_time(lambda: op.displacement(p))
    pair, pair_min, repeats = instruments.fft_pair_time(surface.shape)
    t0 = time.perf_counter()
    PeriodicHalfSpace(surface.shape, surface.length, material, speed)
    setup = time.perf_counter() - t0
    ref = None
    if res.wall_time <= spec.get("tight_budget", np.inf):
        ref = bem.solve(
            surface,
            material,
            speed=speed,
            load=spec["load"],
            rtol=RTOL_REF,
            maxiter=MAXITER[spec["case"]],
            raise_on_failure=False,
        )
        if spec.get("save_reference"):
            np.save(spec["save_reference"], ref.pressure)
        err_p = float(np.linalg.norm(res.pressure - ref.pressure) / np.linalg.norm(ref.pressure))
        err_mu = abs(res.friction - ref.friction) / ref.friction if ref.friction > 0 else None
    else:
        err_p = err_mu = None
    return {
        "n": surface.n,
        "case": spec["case"],
        "speed": speed,
        "load": spec["load"],
        "bem_imported_from": os.path.dirname(bem.__file__),
        "maxiter": maxiter,
        "memory_probe": bool(spec.get("maxiter")),
        "success": res.success,
        "message": res.message,
        "residual": res.residual,
        "iterations": res.iterations,
        "matvecs": res.matvecs,
        "wall_time": wall,
        "wall_times": walls,
        "operator_setup_time": setup,
        "fft_pair_time": pair,
        "fft_pair_time_min": pair_min,
        "fft_pair_repeats": repeats,
        "fft_pair_ratio": wall / (res.matvecs * pair_min),
        "product_time": product,
        "product_time_min": product_min,
        "product_repeats": product_repeats,
        "product_ratio": wall / (res.matvecs * product_min),
        "contact_fraction": res.contact_fraction,
        "friction": res.friction,
        "friction_eq6": res.friction_eq6,
        "peak_rss": peak,
        "rss_after_imports": rss_base,
        "rss_after_imports_current": rss_base_now,
        "rss_with_inputs": rss_inputs,
        "rss_increment": peak - (rss_base_now or rss_base),
        "load_average_1min": load_avg,
        "reference": ref
        and {
            "rtol": RTOL_REF,
            "success": ref.success,
            "residual": ref.residual,
            "iterations": ref.iterations,
            "matvecs": ref.matvecs,
            "wall_time": ref.wall_time,
            "contact_fraction": ref.contact_fraction,
            "friction": ref.friction,
        },
        "pressure_error_l2": err_p,
        "friction_error": err_mu,
    }


@contextlib.contextmanager
def _captured_fds():
    """Redirect the C-level stdout/stderr to a temporary file (tamaas prints from C++)."""
    import ctypes

    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    with tempfile.TemporaryFile() as tmp:
        os.dup2(tmp.fileno(), 1)
        os.dup2(tmp.fileno(), 2)
        text = []
        try:
            yield text
        finally:
            with contextlib.suppress(Exception):
                ctypes.CDLL(None).fflush(None)
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            for fd in saved:
                os.close(fd)
            tmp.seek(0)
            text.append(tmp.read().decode(errors="replace"))


def tamaas_worker(spec):
    """tamaas PolonskyKeerRey on the identical elastic problem; compared to our tight solve."""
    try:
        import tamaas
    except ImportError:
        return None
    rss_base = instruments.current_rss() or instruments.peak_rss()
    heights = np.load(spec["heights"])
    n = heights.shape[0]
    mean_pressure = spec["load"] / LENGTH**2
    with _captured_fds() as log:
        t0 = time.perf_counter()
        model = tamaas.ModelFactory.createModel(tamaas.model_type.basic_2d, [LENGTH, LENGTH], [n, n])
        model.E, model.nu = E_ELASTIC, 0.5  # tamaas uses E* = E / (1 - nu^2), as we do
        solver = tamaas.PolonskyKeerRey(model, heights, spec["tol"])
        solver.max_iter = TAMAAS_MAX_ITER
        solver.dump_freq = 10**9  # print only the first and the last iteration
        t1 = time.perf_counter()
        error = solver.solve(mean_pressure)
        t2 = time.perf_counter()
    peak = instruments.peak_rss()
    p = np.array(model.traction, dtype=float).reshape(n, n)
    ref = np.load(spec["reference"])
    iters = [int(m.group(1)) for m in re.finditer(r"^\s*(\d+)\s+\S+\s+\S+\s*$", log[0], re.M)]
    return {
        "n": n,
        "version": tamaas.__version__,
        "tol": spec["tol"],
        "max_iter": TAMAAS_MAX_ITER,
        "iterations": max(iters) if iters else None,
        "error_measure": float(error),
        "wall_time": t2 - t0,
        "solve_time": t2 - t1,
        "E_star": float(model.E_star),
        "contact_fraction": float(np.count_nonzero(p > 0) / p.size),
        "pressure_error_l2": float(np.linalg.norm(p - ref) / np.linalg.norm(ref)),
        "max_pressure_difference_over_mean": float(np.abs(p - ref).max() / ref.mean()),
        "peak_rss": peak,
        "rss_increment": peak - rss_base,
        "load_average_1min": instruments.load_average(),
        "warnings": [line for line in log[0].splitlines() if re.search(r"warn|converge|fail", line, re.I)][:5],
    }


def profile_worker(spec, top=30):
    """cProfile of one default solve; returns the report text."""
    import cProfile
    import io
    import pstats

    surface = bem.surfaces.from_heights(np.load(spec["heights"]), LENGTH)
    material, speed = materials()[spec["case"]]
    prof = cProfile.Profile()
    t0 = time.perf_counter()
    prof.enable()
    res = bem.solve(
        surface,
        material,
        speed=speed,
        load=spec["load"],
        rtol=RTOL,
        maxiter=MAXITER[spec["case"]],
        raise_on_failure=False,
    )
    prof.disable()
    wall = time.perf_counter() - t0
    buf = io.StringIO()
    buf.write(
        f"profile of {spec['case']} at n = {surface.n}: {wall:.2f} s under cProfile, "
        f"{res.matvecs} operator products, {res.iterations} active-set iterations\n"
    )
    stats = pstats.Stats(prof, stream=buf).strip_dirs()
    stats.sort_stats("tottime").print_stats(top)
    stats.sort_stats("cumulative").print_stats(top)
    return buf.getvalue()
