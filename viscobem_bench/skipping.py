"""What skipping saves: folding inactive Prony terms (:meth:`bem.Material.folded`), reusing
operators across a sweep (the LRU cache of :mod:`bem.sliding`, and warm starts), and not
computing the outputs a scene does not request.

The last one times a study of the command line; the study runner is passed in by the caller
(``viscobem bench`` gives :func:`viscobem_cli.main.run_scene_text`), so the benchmarks do not
depend on the command line package that runs them.
"""

import re
import time
from pathlib import Path

import numpy as np

from viscobem_bench import instruments
from viscobem_bench.cases import L, rough_heights, rough_load, seed_material, timed


def _skip_worker(spec):
    import bem
    from bem import sliding
    from bem.halfspace.periodic import PeriodicHalfSpace

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
        build, _, _ = instruments.median_time(
            lambda m=m: PeriodicHalfSpace(surface.shape, L, m, speed), min_repeats=3, max_repeats=10, budget=1.0
        )
        sliding.clear_operator_cache()
        res, t = timed(lambda m=m: bem.solve(surface, m, speed=speed, load=load))
        out[f"fold_{name}"] = {
            "terms": int(m.moduli.size),
            "operator_build_time": build,
            "solve_time": t,
            "friction": res.friction,
            "matvecs": res.matvecs,
        }
    out["fold_friction_change"] = abs(out["fold_folded"]["friction"] / out["fold_full"]["friction"] - 1)
    # 2. reuse across a sweep: a load sweep at one speed with and without the operator cache,
    # and a speed sweep with and without warm starts
    m = seed_material()
    v = 1e-2 * L / m.creep_times[0]
    loads = rough_load(rubber) * np.array([0.5, 1.0, 2.0, 4.0])

    def load_sweep(cached):
        sliding.clear_operator_cache()
        for f in loads:
            if not cached:
                sliding.clear_operator_cache()
            bem.solve(surface, rubber, speed=speed, load=f)

    load_sweep(True)  # warm-up, untimed
    times = {True: [], False: []}
    for _ in range(2):  # interleaved repeats: the machine's load drifts
        for cached in (False, True):
            times[cached].append(timed(lambda cached=cached: load_sweep(cached))[1])
    build, _, _ = instruments.median_time(
        lambda: PeriodicHalfSpace(surface.shape, L, rubber, speed), min_repeats=3, max_repeats=10, budget=0.5
    )
    out["reuse_operator"] = {
        "solves": len(loads),
        "time_cached": min(times[True]),
        "time_rebuilt": min(times[False]),
        "operator_build_time": build,
        "material": "40-term rubber (unfolded)",
    }
    speeds = v * np.logspace(-2, 2, 9)
    bem.friction_curve(surface, m, speeds=speeds[:2], load=rough_load(m))  # warm-up, untimed
    sliding.clear_operator_cache()
    _, t_warm = timed(lambda: bem.friction_curve(surface, m, speeds=speeds, load=rough_load(m), warm_start=True))
    sliding.clear_operator_cache()
    _, t_coldstart = timed(lambda: bem.friction_curve(surface, m, speeds=speeds, load=rough_load(m), warm_start=False))
    out["warm_start"] = {"speeds": len(speeds), "time_warm": t_warm, "time_cold": t_coldstart}
    return out


def _outputs_worker(spec):
    """Stage timings of one small study with every output against only the friction curve;
    ``spec["study"](scene_text, out_dir)`` runs the study, ``spec["template"]`` is its scene."""
    text = spec["template"]
    text = re.sub(r"^n = \d+", f"n = {spec['n']}", text, flags=re.M)
    text = re.sub(r"xi = \{[^}]*\}", "xi = { start = 1e-3, stop = 1e-1, num = 5 }", text)
    text = re.sub(r"^scales = \d+", f"scales = {spec['n'] // 4}", text, flags=re.M)
    out = {}
    for name, outputs in (
        ("all", "friction_curve = true\nfields = true\nplots = true\nvtk = true"),
        ("needed", "friction_curve = true\nfields = false\nplots = false\nvtk = false"),
    ):
        body = re.sub(r"\[outputs\][^\[]*", "", text) + f"\n[outputs]\n{outputs}\n"
        t0 = time.perf_counter()
        rec = spec["study"](body, Path(spec["tmp"]) / name)
        out[name] = {"total": time.perf_counter() - t0, "stages": rec["stages"], "files": rec["files"]}
    return out


def run_skip(quick, tmp, echo=print, study=None):
    """Folding, operator reuse and warm starts; with ``study = (run, template)`` (a module-level
    ``run(scene_text, out_dir) -> record`` and a scene's text) also the outputs' stages."""
    n = 128 if quick else 256
    env = instruments.thread_environment(1)
    res = instruments.run_in_fresh_process(_skip_worker, {"n": n}, env=env)
    if study is not None:
        spec = {"n": n, "tmp": str(tmp), "study": study[0], "template": study[1]}
        res["outputs"] = instruments.run_in_fresh_process(_outputs_worker, spec, env=env)
    res["n"] = n
    f, r, w = res["fold_full"], res["reuse_operator"], res["warm_start"]
    echo(
        f"  folding: {f['terms']} -> {res['fold_folded']['terms']} terms, operator build "
        f"{1e3 * f['operator_build_time']:.2f} -> {1e3 * res['fold_folded']['operator_build_time']:.2f} ms, "
        f"friction change {res['fold_friction_change']:.1e}"
    )
    echo(
        f"  operator cache over {r['solves']} loads: {r['time_rebuilt']:.3f} s rebuilt -> {r['time_cached']:.3f} s "
        f"(one build {1e3 * r['operator_build_time']:.1f} ms)"
    )
    echo(f"  warm starts over {w['speeds']} speeds: {w['time_cold']:.3f} s -> {w['time_warm']:.3f} s")
    if "outputs" in res:
        o = res["outputs"]
        echo(f"  outputs: everything {o['all']['total']:.3f} s -> friction curve only {o['needed']['total']:.3f} s")
    return res
