"""Scaling of the periodic BEM with problem size, 64² to 2048² (``--quick``: to 512²), on one
self-affine surface (H = 0.8, 16 scales, rms slope 0.1, ~10 % contact, elastic, rtol 1e-8):
wall time, operator products, the FFT-pair time of the same operator in the same process,
and tamaas's PolonskyKeerRey on the identical problem (if installed). The exponent ``k`` of
``t ∝ N**k`` (``N = n²``) is fitted by least squares in log-log, beside the exponent of
``t / (N log N)`` (0 for exact n log n behaviour).
"""

import os

import numpy as np

from viscobem_bench import instruments
from viscobem_bench.cases import E_ELASTIC, L, elastic, rough_heights, rough_load


# ---------------------------------------------------------------- scaling and tamaas
def _scaling_worker(spec):
    import bem
    from bem.sliding import operator_for

    surface = bem.surfaces.from_heights(np.load(spec["heights"]), L)
    m = bem.Material.elastic(E_ELASTIC)
    res = bem.solve(surface, m, speed=0.0, load=rough_load(m), rtol=1e-8)
    peak = instruments.peak_rss()
    np.save(spec["reference"], res.pressure)
    op = operator_for(surface, m, 0.0)
    p = res.pressure.copy()
    pair, _, _ = instruments.median_time(lambda: op.displacement(p), budget=0.5)
    return {
        "n": surface.n,
        "time": res.wall_time,
        "iterations": res.iterations,
        "matvecs": res.matvecs,
        "fft_pair_time": pair,
        "fft_pair_ratio": res.wall_time / (res.matvecs * pair),
        "contact_fraction": res.contact_fraction,
        "peak_rss": peak,
        "success": res.success,
    }


def _fit_exponent(n, t):
    """Least-squares exponents of ``t ∝ N**k`` and of ``t / (N log N) ∝ N**k'``, ``N = n²``."""
    N = np.asarray(n, dtype=float) ** 2
    t = np.asarray(t, dtype=float)
    k = float(np.polyfit(np.log(N), np.log(t), 1)[0])
    k_nlogn = float(np.polyfit(np.log(N), np.log(t / (N * np.log(N))), 1)[0])
    return k, k_nlogn


def run_scaling(quick, tmp, echo=print, max_seconds=600.0):
    from viscobem_bench.periodic.workers import tamaas_worker

    try:
        import tamaas

        tamaas_version = tamaas.__version__
    except ImportError:
        tamaas_version = None
        echo('tamaas not installed (pip install "viscobem[tamaas]"): skipping the tamaas comparison')
    sizes = (64, 128, 256, 512) if quick else (64, 128, 256, 512, 1024, 2048)
    rows, notes = [], []
    cores = os.cpu_count() or 1
    for n in sizes:
        hpath, rpath = str(tmp / f"scaling_h_{n}.npy"), str(tmp / f"scaling_p_{n}.npy")
        np.save(hpath, rough_heights(n))
        try:
            row = instruments.run_in_fresh_process(
                _scaling_worker,
                {"heights": hpath, "reference": rpath},
                env=instruments.thread_environment(1),
                timeout=max_seconds,
            )
        except Exception as err:  # a timeout or crash at one size must not lose the others
            notes.append(f"scaling n = {n}: {type(err).__name__}: {err}")
            echo("  " + notes[-1])
            break
        if tamaas_version:
            spec = {"heights": hpath, "load": rough_load(elastic()), "tol": 1e-9, "reference": rpath}
            try:
                tam = instruments.run_in_fresh_process(
                    tamaas_worker, spec, timeout=max_seconds, env=instruments.thread_environment(1, omp_threads=cores)
                )
                row.update(
                    tamaas_time=tam["wall_time"],
                    tamaas_ratio=tam["wall_time"] / row["time"],
                    tamaas_pressure_difference=tam["pressure_error_l2"],
                    tamaas_iterations=tam["iterations"],
                )
            except Exception as err:
                notes.append(f"tamaas n = {n}: {type(err).__name__}: {err}")
        rows.append(row)
        echo(
            f"  scaling n = {n:5d}: {row['time']:8.3f} s, {row['matvecs']} products, FFT pair "
            f"{1e3 * row['fft_pair_time']:.3f} ms, ratio {row['fft_pair_ratio']:.2f}"
            + (f", tamaas {row['tamaas_time']:.3f} s (x{row['tamaas_ratio']:.2f})" if "tamaas_time" in row else "")
        )
    fit = {}
    if len(rows) >= 3:
        k, k2 = _fit_exponent([r["n"] for r in rows], [r["time"] for r in rows])
        kp, _ = _fit_exponent([r["n"] for r in rows], [r["fft_pair_time"] for r in rows])
        km, _ = _fit_exponent([r["n"] for r in rows], [r["time"] / r["matvecs"] for r in rows])
        fit = {
            "exponent_time": k,
            "exponent_time_over_NlogN": k2,
            "exponent_fft_pair": kp,
            "exponent_time_per_product": km,
        }
        echo(
            f"  fitted t ~ N^{k:.3f} (N = n^2); t/(N log N) ~ N^{k2:.3f}; FFT pair ~ N^{kp:.3f}; "
            f"time per operator product ~ N^{km:.3f}"
        )
    return {
        "sizes": list(sizes),
        "rows": rows,
        "fit": fit,
        "tamaas": tamaas_version,
        "notes": notes,
        "tamaas_threads": cores,
    }
