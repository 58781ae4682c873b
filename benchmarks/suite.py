"""``viscobem bench``: run time against error for every solver, scaling, and what skipping saves.

Run it with ``viscobem bench [--quick] --out DIR`` (or ``python -m benchmarks.suite``). It
writes ``DIR/bench.json``, one Pareto plot per solver (``DIR/pareto_<name>.png``: error
against wall time, log-log, the Pareto front joined), ``DIR/scaling.png`` and ``DIR/bench.md``,
and regenerates the table between ``<!-- bench:begin -->`` and ``<!-- bench:end -->`` in
``README.md`` (``--readme PATH``; ``--no-readme`` to leave it alone).

What is measured (SI units; every group of points runs in a fresh interpreter with BLAS
pinned to one thread and FFTs on all cores, see :mod:`benchmarks._measure`):

1. **Solvers** (the :data:`REGISTRY`): each entry sweeps its resolution and tolerance
   knobs and reports, per point, the error against an exact or converged reference, the
   wall time and the peak resident memory of its process (``ru_maxrss``).
2. **Scaling** of the periodic BEM with problem size, 64² to 2048² (``--quick``: to 512²),
   on one self-affine surface (H = 0.8, 16 scales, rms slope 0.1, ~10 % contact, elastic,
   rtol 1e-8): wall time, operator products, the FFT-pair time of the same operator in the
   same process, and tamaas's PolonskyKeerRey on the identical problem (if installed).
   The exponent ``k`` of ``t ∝ N**k`` (``N = n²``) is fitted by least squares in log-log,
   beside the exponent of ``t / (N log N)`` (0 for exact n log n behaviour).
3. **Skipping** what a scene does not need: folding inactive Prony terms
   (:meth:`bem.Material.folded`), reusing operators across a sweep (the LRU cache of
   :mod:`bem.sliding`, and warm starts), and not computing unrequested outputs.

Adding a solver takes one function and a decorator (the isolated uniform and adaptive BEM
entries, against Hunter's exact rolling cylinder, are written this way)::

    def _isolated_group(group, quick):  # runs in a fresh process; returns a list of points
        ...  # build the sphere on group["n"]², solve per rtol, compare with validation.hertz
        return [{"n": n, "rtol": rtol, "error": err, "time": t, "peak_rss": _measure.peak_rss()}]

    @register("isolated-hertz", solver="isolated BEM", measure=_isolated_group, knobs=("n", "rtol"),
              problem="rigid sphere on an SLS", reference="Hertz (exact, both limits)",
              error="rel. L2 pressure error")
    def _isolated(quick):  # one group = one fresh process
        for n in (64, 128) if quick else (64, 128, 256, 512):
            yield {"n": n}
"""
import argparse
import json
import os
import platform
import re
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from benchmarks import _measure

MiB = 2.0**20
L = 0.01  # m: the cell of every periodic case (tamaas worker of benchmarks.periodic uses it too)
E_ELASTIC = 1e7  # Pa
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10)
RTOL_REF = 1e-12
README_BEGIN, README_END = "<!-- bench:begin -->", "<!-- bench:end -->"


# ---------------------------------------------------------------- registry
@dataclass(frozen=True)
class SolverBenchmark:
    """One solver's error-against-time benchmark.

    ``groups(quick)`` yields picklable dicts; ``measure(group, quick)`` runs one group in a
    fresh process and returns a list of points, each with at least ``error`` (dimensionless),
    ``time`` (s) and ``peak_rss`` (bytes) and the knob values named in ``knobs``.
    """

    name: str
    solver: str
    problem: str
    reference: str
    error: str
    knobs: tuple
    groups: Callable
    measure: Callable
    env: dict = field(default_factory=lambda: _measure.thread_environment(1))


REGISTRY = {}


def register(name, *, solver, problem, reference, error, knobs, measure, env=None):
    """Decorator adding a :class:`SolverBenchmark` whose group generator it decorates."""
    def wrap(groups):
        REGISTRY[name] = SolverBenchmark(name, solver, problem, reference, error, tuple(knobs), groups,
                                         measure, env or _measure.thread_environment(1))
        return groups
    return wrap


def _timed(func):
    t0 = time.perf_counter()
    out = func()
    return out, time.perf_counter() - t0


# ---------------------------------------------------------------- periodic BEM, Westergaard
def _westergaard_group(group, quick):
    import bem
    from validation.westergaard import westergaard

    n, amplitude = group["n"], 1e-6
    m = bem.Material.elastic(E_ELASTIC)
    surface = bem.surfaces.sinusoid(n, L, amplitude=amplitude, dim=2, direction="x")
    exact = westergaard(amplitude, L, 0.5 * np.pi * m.E0 / (1 - m.nu**2) * amplitude / L, m.E0, m.nu)
    p_exact = np.broadcast_to(exact.pressure(surface.x)[:, None], surface.shape)
    # rtol 1e-12 on the same grid (the tolerance's share of the error); also warms up FFT plans
    tight = bem.solve(surface, m, speed=0.0, load=exact.mean_pressure * L**2, rtol=RTOL_REF).pressure
    points = []
    for rtol in RTOLS:
        res, t = _timed(lambda: bem.solve(surface, m, speed=0.0, load=exact.mean_pressure * L**2, rtol=rtol))
        err = float(np.linalg.norm(res.pressure - p_exact) / np.linalg.norm(p_exact))
        points.append({"n": n, "rtol": rtol, "error": err, "time": t, "peak_rss": _measure.peak_rss(),
                       "iterations": res.iterations, "matvecs": res.matvecs,
                       "contact_fraction": res.contact_fraction,
                       "tolerance_error": float(np.linalg.norm(res.pressure - tight) / np.linalg.norm(tight))})
    return points


@register("periodic-westergaard", solver="periodic BEM", measure=_westergaard_group,
          problem="2-D cell, rigid sinusoid (ridges along y) on an elastic half-space, p = p*/2",
          reference="Westergaard (exact)", error="rel. L2 pressure error at the nodes", knobs=("n", "rtol"))
def _westergaard(quick):
    for n in (64, 128, 256, 512) if quick else (64, 128, 256, 512, 1024):
        yield {"n": n}


# ---------------------------------------------------------------- periodic BEM, rough viscoelastic
BASE_N = 64
ROUGH = dict(hurst=0.8, scales=16, rms_slope=0.1, seed=1)


def rough_heights(n):
    """The benchmark surface (generated on 64², 16 scales) on an ``n x n`` grid, n >= 64: the
    spectrum is zero-padded, so every size sees exactly the same band-limited surface."""
    import bem
    from bem import fft

    h = bem.surfaces.self_affine(BASE_N, L, **ROUGH).heights
    if n == BASE_N:
        return np.array(h)
    hq, half = fft.forward(h), BASE_N // 2  # Nyquist row and column are zero (16 < 32 scales)
    big = np.zeros((n, n // 2 + 1), dtype=complex)
    big[:half, : half + 1] = hq[:half, : half + 1]
    big[n - half:, : half + 1] = hq[half:, : half + 1]
    return fft.inverse(big, (n, n))


def rough_load(material):
    """Load (N) for ~10 % contact: Persson's A/A0 ~ sqrt(8/pi) p / (E* slope), with E0."""
    e_star = material.E0 / (1 - material.nu**2)
    return 0.1 * e_star * ROUGH["rms_slope"] / np.sqrt(8 / np.pi) * L**2


def seed_material():
    import bem

    return bem.Material.standard_linear_solid(E0=E_ELASTIC / 3, E_inf=E_ELASTIC, creep_time=0.01)


def _rough_group(group, quick):
    import bem

    m = seed_material()
    speed = 1e-2 * L / m.creep_times[0]  # xi = 1e-2
    surface = bem.surfaces.from_heights(rough_heights(group["n"]), L)
    bem.solve(surface, m, speed=speed, load=rough_load(m), rtol=1e-4)  # warm-up (FFT plans), untimed
    points = []
    for rtol in group["rtols"]:
        res, t = _timed(lambda: bem.solve(surface, m, speed=speed, load=rough_load(m), rtol=rtol))
        points.append({"n": group["n"], "rtol": rtol, "friction": res.friction, "time": t,
                       "peak_rss": _measure.peak_rss(), "iterations": res.iterations, "matvecs": res.matvecs,
                       "contact_fraction": res.contact_fraction, "pressure": res.pressure})
    # the tolerance's own share of the error: pressure against the same grid at rtol 1e-12
    tight = points[-1]["pressure"] if group["rtols"][-1] == RTOL_REF else \
        bem.solve(surface, m, speed=speed, load=rough_load(m), rtol=RTOL_REF).pressure
    for p in points:
        p["tolerance_error"] = float(np.linalg.norm(p.pop("pressure") - tight) / np.linalg.norm(tight))
    return points


@register("periodic-rough-viscoelastic", solver="periodic BEM", measure=_rough_group,
          problem="self-affine surface (H 0.8, 16 scales, rms slope 0.1), seed SLS at xi = 1e-2, ~10 % contact",
          reference="converged: finest grid at rtol 1e-12", error="rel. friction error", knobs=("n", "rtol"))
# (each point also carries ``tolerance_error``: rel. L2 pressure error against rtol 1e-12 on its own grid)
def _rough(quick):
    sizes = (64, 128, 256) if quick else (64, 128, 256, 512)
    for n in sizes:
        yield {"n": n, "rtols": RTOLS}
    yield {"n": 2 * sizes[-1], "rtols": (RTOL_REF,), "reference": True}


def _rough_finish(points):
    """Errors of every point against the reference point (finest grid, tightest rtol)."""
    ref = [p for p in points if p["rtol"] == RTOL_REF]
    if not ref:
        return points
    mu = ref[0]["friction"]
    for p in points:
        p["error"] = abs(p["friction"] / mu - 1) if p is not ref[0] else None
        p["reference"] = p is ref[0]
    return points


# ---------------------------------------------------------------- FEM, Hunter
def _fem_group(group, quick):
    from benchmarks.fem import _rolling_case, _sls

    r = _rolling_case(_sls(), 1.0, group["resolution"], group["domain"])
    return [{"resolution": group["resolution"], "domain": group["domain"], "error": abs(r["friction_error"]),
             "peak_pressure_error": abs(r["peak_pressure_error"]), "time": r["wall_s"],
             "peak_rss": _measure.peak_rss(), "unknowns": r["unknowns"]}]


@register("fem-hunter", solver="FEM (scikit-fem)", measure=_fem_group, env=_measure.thread_environment(2),
          problem="rigid cylinder rolling on an SLS (E_inf/E0 = 3), V lambda = a0, P = 100 N/m, R = 10 mm",
          reference="Hunter (exact)", error="rel. friction error", knobs=("resolution", "domain"))
def _fem(quick):
    for res in (2, 3, 4) if quick else (2, 3, 4, 6, 8):
        yield {"resolution": res, "domain": 30}
    for dom in (3, 10) if quick else (3, 10, 100):
        yield {"resolution": 3, "domain": dom}


# ---------------------------------------------------------------- isolated BEM (uniform, adaptive), Hunter
def _hunter_reference(factor):
    """Hunter's exact friction and peak pressure for benchmarks.isolated's cylinder problem."""
    from benchmarks.isolated import LOADS, RADIUS, _a0, _material
    from validation.hunter import rolling_cylinder

    m = _material()
    exact = rolling_cylinder(m, radius=RADIUS, load=LOADS["cylinder"], speed=factor * _a0("cylinder", m) / m.creep_times[0])
    return exact.friction, exact.peak_pressure


def _isolated_group(group, quick):
    from benchmarks.isolated import _case

    mu, peak = _hunter_reference(group["factor"])
    row = _case("cylinder", group["factor"], group["method"], group["n"], group.get("levels", 0))
    error = max(abs(row["friction"] / mu - 1), abs(row["peak_pressure"] / peak - 1))
    return [{"n": group["n"], "levels": group.get("levels", 0), "error": error, "time": row["wall_s"],
             "peak_rss": _measure.peak_rss(), "friction_error": abs(row["friction"] / mu - 1),
             "peak_pressure_error": abs(row["peak_pressure"] / peak - 1), "iterations": row["iterations"],
             "elements": row["elements"]}]


_HUNTER_PROBLEM = ("rigid cylinder rolling on an SLS (E_inf/E0 = 3), V lambda = a0, P = 1000 N/m, R = 10 mm, "
                   "domain 3 a0")


@register("isolated-uniform-hunter", solver="isolated BEM (uniform DC-FFT)", measure=_isolated_group,
          problem=_HUNTER_PROBLEM, reference="Hunter (exact)",
          error="max(rel. friction error, rel. peak-pressure error)", knobs=("n",))
def _isolated_uniform(quick):
    for n in (128, 256, 512, 1024) if quick else (128, 256, 512, 1024, 2048, 4096, 8192):
        yield {"method": "uniform", "n": n, "factor": 1.0}


@register("isolated-adaptive-hunter", solver="isolated BEM (adaptive mesh)", measure=_isolated_group,
          problem=_HUNTER_PROBLEM, reference="Hunter (exact)",
          error="max(rel. friction error, rel. peak-pressure error)", knobs=("n", "levels"))
def _isolated_adaptive(quick):
    for n in (128, 256, 512) if quick else (128, 256, 512, 1024, 2048):
        yield {"method": "adaptive", "n": n, "levels": int(np.log2(n // 32)), "factor": 1.0}


FINISH = {"periodic-rough-viscoelastic": _rough_finish}


# ---------------------------------------------------------------- scaling and tamaas
def _scaling_worker(spec):
    import bem
    from bem.sliding import operator_for

    surface = bem.surfaces.from_heights(np.load(spec["heights"]), L)
    m = bem.Material.elastic(E_ELASTIC)
    res = bem.solve(surface, m, speed=0.0, load=rough_load(m), rtol=1e-8)
    peak = _measure.peak_rss()
    np.save(spec["reference"], res.pressure)
    op = operator_for(surface, m, 0.0)
    p = res.pressure.copy()
    pair, _, _ = _measure.median_time(lambda: op.displacement(p), budget=0.5)
    return {"n": surface.n, "time": res.wall_time, "iterations": res.iterations, "matvecs": res.matvecs,
            "fft_pair_time": pair, "fft_pair_ratio": res.wall_time / (res.matvecs * pair),
            "contact_fraction": res.contact_fraction, "peak_rss": peak, "success": res.success}


def _fit_exponent(n, t):
    """Least-squares exponents of ``t ∝ N**k`` and of ``t / (N log N) ∝ N**k'``, ``N = n²``."""
    N = np.asarray(n, dtype=float) ** 2
    t = np.asarray(t, dtype=float)
    k = float(np.polyfit(np.log(N), np.log(t), 1)[0])
    k_nlogn = float(np.polyfit(np.log(N), np.log(t / (N * np.log(N))), 1)[0])
    return k, k_nlogn


def run_scaling(quick, tmp, echo=print, max_seconds=600.0):
    from benchmarks.periodic import _tamaas_worker

    try:
        import tamaas
        tamaas_version = tamaas.__version__
    except ImportError:
        tamaas_version = None
        echo("tamaas not installed (optional: pip install tamaas): skipping the tamaas comparison")
    sizes = (64, 128, 256, 512) if quick else (64, 128, 256, 512, 1024, 2048)
    rows, notes = [], []
    cores = os.cpu_count() or 1
    for n in sizes:
        hpath, rpath = str(tmp / f"scaling_h_{n}.npy"), str(tmp / f"scaling_p_{n}.npy")
        np.save(hpath, rough_heights(n))
        try:
            row = _measure.run_in_fresh_process(_scaling_worker, {"heights": hpath, "reference": rpath},
                                                env=_measure.thread_environment(1), timeout=max_seconds)
        except Exception as err:  # a timeout or crash at one size must not lose the others
            notes.append(f"scaling n = {n}: {type(err).__name__}: {err}")
            echo("  " + notes[-1])
            break
        if tamaas_version:
            spec = {"heights": hpath, "load": rough_load(_elastic()), "tol": 1e-9, "reference": rpath}
            try:
                tam = _measure.run_in_fresh_process(_tamaas_worker, spec, timeout=max_seconds,
                                                    env=_measure.thread_environment(1, omp_threads=cores))
                row.update(tamaas_time=tam["wall_time"], tamaas_ratio=tam["wall_time"] / row["time"],
                           tamaas_pressure_difference=tam["pressure_error_l2"],
                           tamaas_iterations=tam["iterations"])
            except Exception as err:
                notes.append(f"tamaas n = {n}: {type(err).__name__}: {err}")
        rows.append(row)
        echo(f"  scaling n = {n:5d}: {row['time']:8.3f} s, {row['matvecs']} products, FFT pair "
             f"{1e3 * row['fft_pair_time']:.3f} ms, ratio {row['fft_pair_ratio']:.2f}"
             + (f", tamaas {row['tamaas_time']:.3f} s (x{row['tamaas_ratio']:.2f})" if "tamaas_time" in row else ""))
    fit = {}
    if len(rows) >= 3:
        k, k2 = _fit_exponent([r["n"] for r in rows], [r["time"] for r in rows])
        kp, _ = _fit_exponent([r["n"] for r in rows], [r["fft_pair_time"] for r in rows])
        km, _ = _fit_exponent([r["n"] for r in rows], [r["time"] / r["matvecs"] for r in rows])
        fit = {"exponent_time": k, "exponent_time_over_NlogN": k2, "exponent_fft_pair": kp,
               "exponent_time_per_product": km}
        echo(f"  fitted t ~ N^{k:.3f} (N = n^2); t/(N log N) ~ N^{k2:.3f}; FFT pair ~ N^{kp:.3f}; "
             f"time per operator product ~ N^{km:.3f}")
    return {"sizes": list(sizes), "rows": rows, "fit": fit, "tamaas": tamaas_version, "notes": notes,
            "tamaas_threads": cores}


def _elastic():
    import bem

    return bem.Material.elastic(E_ELASTIC)


# ---------------------------------------------------------------- skipping what is not needed
def _skip_worker(spec):
    import bem
    from bem import sliding
    from bem.periodic import PeriodicHalfSpace

    n = spec["n"]
    out = {}
    surface = bem.surfaces.from_heights(rough_heights(n), L)
    # 1. folding: a 40-term rubber over 20 decades, sliding band [q_L v, q_max v]
    rubber = bem.Material.from_prony(E0=1e6, moduli=np.full(40, (1e9 - 1e6) / 40), times=np.logspace(-12, 8, 40))
    speed = 1e-4  # m/s
    # The band of w = -q_x v on a 2-D cell starts at 0, not at q_L v: the modes constant along x
    # (q_x = 0) are static. Folding "glassy" terms with w_min = q_L v stiffens those modes
    # (here E0 1e6 -> 5e7 Pa) and changed the friction by 130 % in a trial run; only
    # fully relaxed terms may be folded on a 2-D cell.
    w_min, w_max = 0.0, np.pi * n / L * np.sqrt(2) * speed
    folded = rubber.folded(w_min, w_max)
    load = rough_load(rubber) * 3
    for name, m in (("full", rubber), ("folded", folded)):
        build, _, _ = _measure.median_time(lambda: PeriodicHalfSpace(surface.shape, L, m, speed), min_repeats=3,
                                           max_repeats=10, budget=1.0)
        sliding._operators.clear()
        res, t = _timed(lambda: bem.solve(surface, m, speed=speed, load=load))
        out[f"fold_{name}"] = {"terms": int(m.moduli.size), "operator_build_time": build, "solve_time": t,
                               "friction": res.friction, "matvecs": res.matvecs}
    out["fold_friction_change"] = abs(out["fold_folded"]["friction"] / out["fold_full"]["friction"] - 1)
    # 2. reuse across a sweep: a load sweep at one speed with and without the operator cache,
    # and a speed sweep with and without warm starts
    m = seed_material()
    v = 1e-2 * L / m.creep_times[0]
    loads = rough_load(rubber) * np.array([0.5, 1.0, 2.0, 4.0])

    def load_sweep(cached):
        sliding._operators.clear()
        for f in loads:
            if not cached:
                sliding._operators.clear()
            bem.solve(surface, rubber, speed=speed, load=f)
    load_sweep(True)  # warm-up, untimed
    times = {True: [], False: []}
    for _ in range(2):  # interleaved repeats: the machine's load drifts
        for cached in (False, True):
            times[cached].append(_timed(lambda: load_sweep(cached))[1])
    build, _, _ = _measure.median_time(lambda: PeriodicHalfSpace(surface.shape, L, rubber, speed), min_repeats=3,
                                       max_repeats=10, budget=0.5)
    out["reuse_operator"] = {"solves": len(loads), "time_cached": min(times[True]),
                             "time_rebuilt": min(times[False]), "operator_build_time": build,
                             "material": "40-term rubber (unfolded)"}
    speeds = v * np.logspace(-2, 2, 9)
    bem.friction_curve(surface, m, speeds=speeds[:2], load=rough_load(m))  # warm-up, untimed
    sliding._operators.clear()
    _, t_warm = _timed(lambda: bem.friction_curve(surface, m, speeds=speeds, load=rough_load(m), warm_start=True))
    sliding._operators.clear()
    _, t_coldstart = _timed(lambda: bem.friction_curve(surface, m, speeds=speeds, load=rough_load(m),
                                                       warm_start=False))
    out["warm_start"] = {"speeds": len(speeds), "time_warm": t_warm, "time_cold": t_coldstart}
    return out


def _outputs_worker(spec):
    """Stage timings of one small study with every output against only the friction curve."""
    from viscobem_cli import scene as scenes
    from viscobem_cli.study import run_scene

    text = scenes.DEFAULT_SCENE.read_text()
    text = re.sub(r"^n = \d+", f"n = {spec['n']}", text, flags=re.M)
    text = re.sub(r"xi = \{[^}]*\}", "xi = { start = 1e-3, stop = 1e-1, num = 5 }", text)
    text = re.sub(r"^scales = \d+", f"scales = {spec['n'] // 4}", text, flags=re.M)
    out = {}
    for name, outputs in (("all", "friction_curve = true\nfields = true\nplots = true\nvtk = true"),
                          ("needed", "friction_curve = true\nfields = false\nplots = false\nvtk = false")):
        body = re.sub(r"\[outputs\][^\[]*", "", text) + f"\n[outputs]\n{outputs}\n"
        scene = scenes.parse(body)
        t0 = time.perf_counter()
        rec = run_scene(scene, Path(spec["tmp"]) / name, progress=False)
        out[name] = {"total": time.perf_counter() - t0, "stages": rec["stages"], "files": rec["files"]}
    return out


def run_skip(quick, tmp, echo=print):
    n = 128 if quick else 256
    env = _measure.thread_environment(1)
    res = _measure.run_in_fresh_process(_skip_worker, {"n": n}, env=env)
    res["outputs"] = _measure.run_in_fresh_process(_outputs_worker, {"n": n, "tmp": str(tmp)}, env=env)
    res["n"] = n
    f, r, w, o = res["fold_full"], res["reuse_operator"], res["warm_start"], res["outputs"]
    echo(f"  folding: {f['terms']} -> {res['fold_folded']['terms']} terms, operator build "
         f"{1e3 * f['operator_build_time']:.2f} -> {1e3 * res['fold_folded']['operator_build_time']:.2f} ms, "
         f"friction change {res['fold_friction_change']:.1e}")
    echo(f"  operator cache over {r['solves']} loads: {r['time_rebuilt']:.3f} s rebuilt -> {r['time_cached']:.3f} s "
         f"(one build {1e3 * r['operator_build_time']:.1f} ms)")
    echo(f"  warm starts over {w['speeds']} speeds: {w['time_cold']:.3f} s -> {w['time_warm']:.3f} s")
    echo(f"  outputs: everything {o['all']['total']:.3f} s -> friction curve only {o['needed']['total']:.3f} s")
    return res


# ---------------------------------------------------------------- reports
def pareto_front(points):
    """Indices of the points not dominated in (time, error), sorted by time."""
    pts = sorted((p["time"], p["error"], i) for i, p in enumerate(points) if p.get("error") is not None)
    front, best = [], np.inf
    for t, e, i in pts:
        if e < best:
            front.append(i)
            best = e
    return front


def _plots(result, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    files = []
    for name, entry in result["solvers"].items():
        pts = [p for p in entry["points"] if p.get("error") is not None and p["error"] > 0]
        if not pts:
            continue
        fig, ax = plt.subplots(figsize=(5.5, 4))
        knob = entry["knobs"][0]
        values = sorted({p[knob] for p in pts})
        cmap = plt.get_cmap("viridis", max(len(values), 2))
        for j, v in enumerate(values):
            sel = [p for p in pts if p[knob] == v]
            ax.scatter([p["time"] for p in sel], [p["error"] for p in sel], color=cmap(j), label=f"{knob} = {v}")
        front = [entry["points"][i] for i in entry["pareto"] if entry["points"][i]["error"] > 0]
        ax.plot([p["time"] for p in front], [p["error"] for p in front], "k--", lw=1, label="Pareto front")
        ax.set(xscale="log", yscale="log", xlabel="wall time (s)", ylabel=entry["error"],
               title=f"{entry['solver']}: {name}\nreference: {entry['reference']}")
        ax.title.set_fontsize(9)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(out / f"pareto_{name}.png", dpi=110)
        plt.close(fig)
        files.append(f"pareto_{name}.png")
    rows = result["scaling"]["rows"]
    if rows:
        fig, ax = plt.subplots(figsize=(5.5, 4))
        N = np.array([r["n"] ** 2 for r in rows], dtype=float)
        ax.loglog(N, [r["time"] for r in rows], "o-", label="viscobem periodic BEM")
        ax.loglog(N, [r["fft_pair_time"] * r["matvecs"] for r in rows], "s:", label="products x FFT-pair time")
        if any("tamaas_time" in r for r in rows):
            ax.loglog([n for n, r in zip(N, rows) if "tamaas_time" in r],
                      [r["tamaas_time"] for r in rows if "tamaas_time" in r], "^-", label="tamaas PolonskyKeerRey")
        ref = N * np.log(N)
        ax.loglog(N, ref / ref[-1] * rows[-1]["time"], "k--", lw=1, label="N log N")
        ax.set(xlabel="N = n²", ylabel="wall time (s)", title="elastic rough contact, ~10 % contact, rtol 1e-8")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(out / "scaling.png", dpi=110)
        plt.close(fig)
        files.append("scaling.png")
    return files


def _g(x, spec=".3g"):
    return "" if x is None else format(x, spec)


def markdown(result):
    """The README table (and bench.md): Pareto fronts, scaling, skipping."""
    lines = ["'rtol's share': rel. L2 pressure error against rtol 1e-12 on the same grid (where measured).", "",
             f"Measured by `viscobem bench{' --quick' if result['quick'] else ''}` on {result['date']} "
             f"({result['machine']['cpu_count']} cores, load average {result['machine']['load_average']}); "
             "regenerate with that command.", "",
             "| solver | problem | reference | knobs on the Pareto front | error | rtol's share | time (s) "
             "| peak RSS (MiB) |", "|---|---|---|---|---|---|---|---|"]
    for name, e in result["solvers"].items():
        for i in e["pareto"]:
            p = e["points"][i]
            knobs = ", ".join(f"{k} {p[k]:g}" for k in e["knobs"] if k in p)
            lines.append(f"| {e['solver']} | {name} | {e['reference']} | {knobs} | {_g(p['error'], '.2e')} "
                         f"| {_g(p.get('tolerance_error'), '.1e')} | {_g(p['time'])} | {p['peak_rss'] / MiB:.0f} |")
    sc = result["scaling"]
    if sc["rows"]:
        lines += ["", "| n² | time (s) | products | FFT pair (ms) | time / (products x pair) | tamaas (s) "
                  "| tamaas / ours |", "|---|---|---|---|---|---|---|"]
        for r in sc["rows"]:
            lines.append(f"| {r['n']}² | {_g(r['time'])} | {r['matvecs']} | {_g(1e3 * r['fft_pair_time'])} "
                         f"| {_g(r['fft_pair_ratio'])} | {_g(r.get('tamaas_time'))} | {_g(r.get('tamaas_ratio'))} |")
        if sc["fit"]:
            lines += ["", f"Scaling: t ∝ N^{sc['fit']['exponent_time']:.2f} (N = n²); t / (N log N) ∝ "
                      f"N^{sc['fit']['exponent_time_over_NlogN']:.2f}; time per operator product ∝ "
                      f"N^{sc['fit']['exponent_time_per_product']:.2f}. tamaas {sc['tamaas'] or 'not installed'}"
                      f" ({sc['tamaas_threads']} OpenMP threads)."]
    s = result.get("skip")
    if s:
        f0, f1, r, w, o = s["fold_full"], s["fold_folded"], s["reuse_operator"], s["warm_start"], s["outputs"]
        sweep = r["time_cached"]
        saved_builds = (r["solves"] - 1) * r["operator_build_time"]
        lines += ["", f"Skipping what a scene does not need ({s['n']}²; 'saved' is the share of that run's time):",
                  "", "| what | without | with | saved |", "|---|---|---|---|",
                  f"| fold inactive Prony terms ({f0['terms']} -> {f1['terms']}): operator build | "
                  f"{1e3 * f0['operator_build_time']:.2f} ms | {1e3 * f1['operator_build_time']:.2f} ms | "
                  f"{(f0['operator_build_time'] - f1['operator_build_time']) / f1['solve_time']:.1e} of a solve "
                  f"(friction changes {s['fold_friction_change']:.1e}) |",
                  f"| reuse the operator over a sweep of {r['solves']} loads: builds | {r['solves']} x "
                  f"{1e3 * r['operator_build_time']:.2f} ms | 1 | {saved_builds / sweep:.1e} of the sweep "
                  f"(sweeps measured {r['time_rebuilt']:.3f} s / {r['time_cached']:.3f} s: noise) |",
                  f"| warm starts over {w['speeds']} speeds | {w['time_cold']:.3f} s | {w['time_warm']:.3f} s "
                  f"| {1 - w['time_warm'] / w['time_cold']:.0%} |",
                  f"| unrequested outputs (fields, plots, VTK) | {o['all']['total']:.3f} s | "
                  f"{o['needed']['total']:.3f} s | {1 - o['needed']['total'] / o['all']['total']:.0%} |"]
    return "\n".join(lines)


def update_readme(path, table):
    """Replace the text between the bench markers of ``path`` (append a section if absent)."""
    path = Path(path)
    text = path.read_text()
    block = f"{README_BEGIN}\n{table}\n{README_END}"
    if README_BEGIN in text and README_END in text:
        head, rest = text.split(README_BEGIN, 1)
        text = head + block + rest.split(README_END, 1)[1]
    else:
        text = text.rstrip("\n") + "\n\n## Run time against error\n\n" + block + "\n"
    from viscobem_cli.study import write_atomic

    write_atomic(path, text)


# ---------------------------------------------------------------- driver
def run(quick=False, out_dir="bench-out", *, readme="README.md", solvers=None, scaling=True, skip=True,
        echo=print):
    """Run the benchmark suite; write JSON, plots, ``bench.md`` and the README table."""
    import bem
    import scipy

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()
    result = {"benchmark": "suite", "issue": 7, "quick": quick,
              "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
              "machine": {"cpu_count": os.cpu_count(), "platform": platform.platform(),
                          "python": platform.python_version(), "numpy": np.__version__,
                          "scipy": scipy.__version__, "load_average": _measure.load_average()},
              "solvers": {}, "scaling": {"rows": []}, "notes": []}
    with tempfile.TemporaryDirectory(prefix="viscobem-bench-") as tmp, \
            _measure.source_snapshot(bem, Path(tmp) / "src") as code:
        result["code"] = code
        tmp = Path(tmp)
        for name, entry in REGISTRY.items():
            if solvers and name not in solvers:
                continue
            echo(f"{name}: {entry.problem}")
            points = []
            for group in entry.groups(quick):
                try:
                    got = _measure.run_in_fresh_process(entry.measure, group, quick, env=entry.env, timeout=1800)
                except Exception as err:  # one failing group must not lose the others
                    result["notes"].append(f"{name} {group}: {type(err).__name__}: {err}")
                    echo("  " + result["notes"][-1])
                    continue
                points += got
                for p in got:
                    echo("  " + ", ".join(f"{k} {p[k]:g}" for k in entry.knobs if k in p)
                         + f": time {p['time']:.3f} s" + (f", error {p['error']:.2e}" if p.get("error") else ""))
            points = FINISH.get(name, lambda x: x)(points)
            result["solvers"][name] = {"solver": entry.solver, "problem": entry.problem,
                                       "reference": entry.reference, "error": entry.error,
                                       "knobs": list(entry.knobs), "points": points,
                                       "pareto": pareto_front(points)}
        if scaling:
            echo("scaling with problem size (elastic, periodic BEM)")
            result["scaling"] = run_scaling(quick, tmp, echo)
        if skip:
            echo("skipping what a scene does not need")
            result["skip"] = run_skip(quick, tmp, echo)
    result["total_time"] = time.perf_counter() - started
    result["files"] = ["bench.json", "bench.md"] + _plots(result, out)
    table = markdown(result)
    (out / "bench.json").write_text(json.dumps(result, indent=1, default=float) + "\n")
    (out / "bench.md").write_text("# viscobem bench\n\n" + table + "\n")
    if readme:
        update_readme(readme, table)
        result["files"].append(str(readme))
    echo("\n" + table)
    echo(f"\nwrote {', '.join(result['files'])} in {out}; total {result['total_time']:.0f} s")
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m benchmarks.suite", description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="smaller sizes (scaling to 512²)")
    parser.add_argument("--out", default="bench-out")
    parser.add_argument("--readme", default="README.md")
    parser.add_argument("--no-readme", action="store_true")
    parser.add_argument("--solvers", nargs="+", choices=sorted(REGISTRY))
    parser.add_argument("--no-scaling", action="store_true")
    parser.add_argument("--no-skip", action="store_true")
    args = parser.parse_args(argv)
    run(args.quick, args.out, readme=None if args.no_readme else args.readme, solvers=args.solvers,
        scaling=not args.no_scaling, skip=not args.no_skip)
    return 0


if __name__ == "__main__":
    sys.exit(main())
