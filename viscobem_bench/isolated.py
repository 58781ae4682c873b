"""Benchmark of the isolated-contact solvers: uniform DC-FFT grid against the adaptive mesh.

Problems (SI; seed material: standard linear solid, E_inf = 10 MPa, E_inf/E0 = 3, creep time
lambda = 0.01 s, nu = 0.5; R = 10 mm), at speeds ``V lambda = f a0`` with ``f = 0.3, 1, 5``
and ``a0`` the relaxed (E0) Hertz half-width / radius:

- ``cylinder``: rolling cylinder, P = 1000 N/m, domain 3 a0 wide; reference: Hunter's exact
  solution (:func:`validation.references.hunter.rolling_cylinder`).
- ``sphere``: sliding sphere, P = 1 N, domain (3 a0)^2; reference: Richardson extrapolation
  of the uniform solver's friction and peak pressure from its three finest grids (ratio 2;
  the observed order is fitted from the three and recorded; if it falls outside [0.5, 4]
  or the three are not monotone, the finest grid's value is used instead). No exact
  solution exists.
- ``sphere-wide``, ``sphere-xwide``: the same sphere at ``f = 1`` on domains (12 a0)^2 and
  (24 a0)^2, the case a user who does not know the contact size meets, and the one that
  favours coarse far elements.

Solvers: ``bem.solve(..., periodic=False, method="uniform")`` over a range of grids, and
``bem.adaptive.solve_adaptive`` over fine grids and refinement levels (coarse mesh of 32
strips, or 8 x 8 squares). Error = max(|friction/ref - 1|, |peak pressure/ref - 1|), with
``friction`` the dissipation form of each solver. Each case runs in a fresh interpreter with
BLAS threads pinned to 1 (:mod:`viscobem_bench.instruments`); wall time is that of the solve call
(kernel construction included, imports excluded); memory is the child's peak RSS.

Outputs: ``DIR/isolated_benchmark.json`` (all cases, Pareto fronts, the fastest method per
requested tolerance), ``DIR/isolated_pareto.png`` (error against time, log-log, per problem).

Run: ``python -m viscobem_bench.isolated [--quick] --out DIR`` or ``viscobem bench isolated``.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import platform
import re
import time

import numpy as np

from viscobem_bench.instruments import load_average, peak_rss, run_in_fresh_process, source_snapshot, thread_environment

RADIUS = 0.01
LOADS = {"cylinder": 1000.0, "sphere": 1.0, "sphere-wide": 1.0, "sphere-xwide": 1.0}
SPEEDS = {"cylinder": (0.3, 1.0, 5.0), "sphere": (0.3, 1.0, 5.0), "sphere-wide": (1.0,), "sphere-xwide": (1.0,)}
# domain side in relaxed Hertz half-widths (cylinder) / radii (sphere)
DOMAIN = {"cylinder": 3.0, "sphere": 3.0, "sphere-wide": 12.0, "sphere-xwide": 24.0}
TOLERANCES = (1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5)


def seed_material():
    from bem import Material

    return Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)


def contact_half_width(problem, material):
    from validation.references.hertz import line_contact, point_contact

    contact = line_contact if problem == "cylinder" else point_contact
    return contact(material.E0, material.nu, RADIUS, LOADS[problem]).a


def run_case(problem, factor, method, n, levels):
    """One solve in this (fresh) process; returns its numbers."""
    import bem
    from bem import surfaces
    from bem.adaptive import solve_adaptive

    m = seed_material()
    a0 = contact_half_width(problem, m)
    make = surfaces.cylinder if problem == "cylinder" else surfaces.sphere
    s = make(radius=RADIUS, n=n, length=DOMAIN[problem] * a0)
    speed = factor * a0 / m.creep_times[0]
    load = LOADS[problem]
    t0 = time.perf_counter()
    if method == "uniform":
        r = bem.solve(s, m, speed=speed, load=load, periodic=False, method="uniform")
    else:
        r = solve_adaptive(s, m, speed=speed, load=load, levels=levels)
    wall = time.perf_counter() - t0
    row = {
        "problem": problem,
        "speed_factor": factor,
        "method": method,
        "n": n,
        "levels": levels,
        "friction": r.friction,
        "friction_eq6": r.friction_eq6,
        "peak_pressure": float(r.pressure.max()),
        "contact_fraction": r.contact_fraction,
        "iterations": r.iterations,
        "success": bool(r.success),
        "wall_s": wall,
        "peak_rss_mb": peak_rss() / 2**20,
    }
    # the adaptive message starts "<levels> refinement levels, <N_e> elements; ..."
    row["elements"] = int(re.search(r"(\d+) elements", r.message).group(1)) if method == "adaptive" else n**s.ndim
    return row


def _sizes(problem, quick):
    """(uniform grids, adaptive (n, levels)) per problem."""
    if problem == "cylinder":
        uni = [128, 256, 512, 1024, 2048] if quick else [128, 256, 512, 1024, 2048, 4096, 8192, 16384]
        ada = [128, 256, 512, 1024] if quick else [128, 256, 512, 1024, 2048, 4096, 8192]
        return uni, [(n, int(np.log2(n // 32))) for n in ada]
    if problem == "sphere-wide":  # contact ~1/6 of the domain side: room for coarse elements
        uni = [64, 128, 256] if quick else [64, 128, 192, 256, 384, 512]
        ada = [(64, 3), (128, 4)] if quick else [(64, 3), (128, 4), (192, 4), (256, 5)]
        return uni, ada
    if problem == "sphere-xwide":  # contact ~1/12 of the domain side
        uni = [128, 256, 512] if quick else [128, 256, 384, 512, 768]
        ada = [(128, 4), (256, 5)] if quick else [(128, 4), (256, 5), (384, 5), (512, 6)]
        return uni, ada
    uni = [32, 64, 128] if quick else [32, 48, 64, 96, 128, 192, 256, 512]
    ada = [(32, 2), (64, 3)] if quick else [(32, 2), (48, 2), (64, 3), (96, 3)]
    return uni, ada


def _richardson(rows, key):
    """Extrapolate ``key`` from the three finest uniform grids in ratio 2."""
    by_n = {r["n"]: r[key] for r in rows}
    ns = sorted(by_n)
    trip = [n for n in ns if n * 2 in by_n and n * 4 in by_n]
    if not trip:
        return by_n[ns[-1]], None, [ns[-1]]
    n = trip[-1]
    f1, f2, f3 = by_n[n], by_n[2 * n], by_n[4 * n]
    if (f1 - f2) * (f2 - f3) <= 0 or f2 == f3:
        return f3, None, [n, 2 * n, 4 * n]
    p = float(np.log2((f1 - f2) / (f2 - f3)))
    if not 0.5 <= p <= 4:
        return f3, p, [n, 2 * n, 4 * n]
    return f3 - (f2 - f3) / (2**p - 1), p, [n, 2 * n, 4 * n]


def _pareto(points):
    """Non-dominated (time, error) points, sorted by time."""
    front, best = [], np.inf
    for t, e, tag in sorted(points):
        if e < best:
            front.append((t, e, tag))
            best = e
    return front


def _fastest(rows, tol):
    """Least wall time of a case with error <= tol (None if none reaches it)."""
    ok = [r["wall_s"] for r in rows if r["error"] <= tol]
    return min(ok) if ok else None


def _plot(groups, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    fig, axes = plt.subplots(3, 3, figsize=(13, 11))
    for ax, (key, rows) in zip(axes.ravel(), groups.items()):
        for method, style in (("uniform", "o-"), ("adaptive", "s--")):
            pts = [(r["wall_s"], r["error"], r["n"]) for r in rows if r["method"] == method and r["error"] > 0]
            if not pts:
                continue
            t, e, _ = zip(*sorted(pts))
            ax.loglog(t, e, style[0], alpha=0.35, color="C0" if method == "uniform" else "C1")
            front = _pareto(pts)
            ax.loglog(
                [f[0] for f in front],
                [f[1] for f in front],
                style,
                color="C0" if method == "uniform" else "C1",
                label=f"{method} (Pareto front)",
            )
            for ft, fe, fn in front:
                ax.annotate(str(fn), (ft, fe), fontsize=7, textcoords="offset points", xytext=(3, 3))
        ax.set_title(key, fontsize=10)
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
        ax.set_xlabel("wall time (s)")
        ax.set_ylabel("error max(friction, peak pressure)")
        ax.legend(fontsize=8)
    for ax in axes.ravel()[len(groups) :]:
        ax.set_visible(False)
    fig.suptitle("Isolated contacts: uniform DC-FFT grid vs adaptive mesh (labels: fine cells per side)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _measure_all(problems, quick, env):
    """Every (problem, speed, method, grid) case in a fresh process; ``(rows, bem snapshot)``."""
    import tempfile

    import bem

    rows = []
    # every case measures the same frozen copy of bem/, even if the tree is edited meanwhile
    with tempfile.TemporaryDirectory() as tmp, source_snapshot(bem, tmp) as snapshot:
        for problem in problems:
            uni, ada = _sizes(problem, quick)
            for factor in SPEEDS[problem]:
                for n in uni:
                    rows.append(run_in_fresh_process(run_case, problem, factor, "uniform", n, 0, env=env))
                for n, levels in ada:
                    rows.append(run_in_fresh_process(run_case, problem, factor, "adaptive", n, levels, env=env))
                print(f"  {problem} f={factor}: {len(uni) + len(ada)} cases done", flush=True)
    return rows, snapshot


def _reference(problem, factor, sel, m):
    """Hunter's exact solution for the cylinder, else Richardson extrapolation of the uniform grids."""
    from validation.references.hunter import rolling_cylinder

    if problem == "cylinder":
        a0 = contact_half_width(problem, m)
        ex = rolling_cylinder(m, radius=RADIUS, load=LOADS[problem], speed=factor * a0 / m.creep_times[0])
        return {"kind": "Hunter (exact)", "friction": ex.friction, "peak_pressure": ex.peak_pressure}
    uni = [r for r in sel if r["method"] == "uniform"]
    mu, p_mu, grids = _richardson(uni, "friction")
    pk, p_pk, _ = _richardson(uni, "peak_pressure")
    # order None: not monotone, the finest grid's value is the reference
    return {
        "kind": "Richardson extrapolation of the uniform grids",
        "friction": mu,
        "peak_pressure": pk,
        "order_friction": p_mu,
        "order_peak": p_pk,
        "grids": grids,
    }


def _errors(problems, rows, m):
    """``(references, groups)``: each row's errors against its problem's reference."""
    references, groups = {}, {}
    for problem in problems:
        for factor in SPEEDS[problem]:
            key = f"{problem} V lambda/a0 = {factor:g}"
            sel = [r for r in rows if r["problem"] == problem and r["speed_factor"] == factor]
            ref = _reference(problem, factor, sel, m)
            for r in sel:
                r["friction_error"] = abs(r["friction"] / ref["friction"] - 1)
                r["peak_error"] = abs(r["peak_pressure"] / ref["peak_pressure"] - 1)
                r["error"] = max(r["friction_error"], r["peak_error"])
            references[key] = ref
            groups[key] = sel
    return references, groups


def _compare(groups):
    """Which method is faster at each tolerance, per problem; and both at the same fine grid."""
    choice = []
    for key, sel in groups.items():
        for tol in TOLERANCES:
            tu = _fastest([r for r in sel if r["method"] == "uniform"], tol)
            ta = _fastest([r for r in sel if r["method"] == "adaptive"], tol)
            winner = (
                None
                if tu is None and ta is None
                else ("uniform" if ta is None or (tu is not None and tu <= ta) else "adaptive")
            )
            choice.append({"problem": key, "tolerance": tol, "uniform_s": tu, "adaptive_s": ta, "faster": winner})
    same_grid = []
    for key, sel in groups.items():
        for r in sel:
            u = [q for q in sel if q["method"] == "uniform" and q["n"] == r["n"]]
            if r["method"] == "adaptive" and u:
                same_grid.append(
                    {
                        "problem": key,
                        "n": r["n"],
                        "levels": r["levels"],
                        "elements": r["elements"],
                        "uniform_s": u[0]["wall_s"],
                        "adaptive_s": r["wall_s"],
                        "uniform_error": u[0]["error"],
                        "adaptive_error": r["error"],
                        "uniform_rss_mb": u[0]["peak_rss_mb"],
                        "adaptive_rss_mb": r["peak_rss_mb"],
                    }
                )
    return choice, same_grid


def _print_tables(groups, choice):
    print(
        f"\n{'problem':32s} {'method':9s} {'n':>6s} {'lev':>3s} {'elem':>8s} {'mu err':>9s} {'peak err':>9s} "
        f"{'wall s':>8s} {'RSS MB':>7s}"
    )
    for key, sel in groups.items():
        for r in sorted(sel, key=lambda r: (r["method"], r["n"])):
            print(
                f"{key:32s} {r['method']:9s} {r['n']:6d} {r['levels']:3d} {r['elements']:8d} "
                f"{r['friction_error']:9.2e} {r['peak_error']:9.2e} {r['wall_s']:8.3f} {r['peak_rss_mb']:7.0f}"
            )
    print(f"\n{'problem':32s} {'tol':>7s} {'uniform s':>10s} {'adaptive s':>10s}  faster")
    for c in choice:
        fmt = lambda v: f"{v:10.3f}" if v is not None else f"{'-':>10s}"
        print(f"{c['problem']:32s} {c['tolerance']:7.0e} {fmt(c['uniform_s'])} {fmt(c['adaptive_s'])}  {c['faster']}")


def run(quick: bool = True, out_dir=".", only=None) -> dict:
    """Run the benchmark; print tables and write JSON + PNG into ``out_dir``.

    ``only``: a list of problem names (keys of ``SPEEDS``) to run instead of all."""
    import subprocess

    problems = list(SPEEDS) if not only else [p for p in SPEEDS if p in only]
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    m = seed_material()
    rows, snapshot = _measure_all(problems, quick, thread_environment(1))
    references, groups = _errors(problems, rows, m)
    choice, same_grid = _compare(groups)
    _print_tables(groups, choice)
    fronts = {
        key: {
            method: _pareto([(r["wall_s"], r["error"], r["n"]) for r in sel if r["method"] == method])
            for method in ("uniform", "adaptive")
        }
        for key, sel in groups.items()
    }
    _plot(groups, out / "isolated_pareto.png")
    head = (
        subprocess.run(
            ["git", "rev-parse", "HEAD"], capture_output=True, text=True, cwd=pathlib.Path(__file__).parent
        ).stdout.strip()
        or None
    )
    result = {
        "quick": quick,
        "created_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        "git_head": head,
        "bem_snapshot": snapshot,
        "machine": {"platform": platform.platform(), "cpus": os.cpu_count(), "load_average_1min": load_average()},
        "material": {"E0": m.E0, "E_inf": m.E_inf, "creep_time": float(m.creep_times[0]), "nu": m.nu},
        "radius": RADIUS,
        "loads": LOADS,
        "domain_over_a0": DOMAIN,
        "speed_factors": SPEEDS,
        "references": references,
        "cases": rows,
        "pareto": fronts,
        "fastest_at_tolerance": choice,
        "same_grid": same_grid,
    }
    (out / "isolated_benchmark.json").write_text(json.dumps(result, indent=1))
    print(f"\nwrote {out / 'isolated_benchmark.json'} and {out / 'isolated_pareto.png'}")
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="small sizes (smoke test)")
    parser.add_argument("--out", default="bench-out", help="output folder")
    parser.add_argument("--only", nargs="+", choices=list(SPEEDS), help="run only these problems")
    args = parser.parse_args(argv)
    run(quick=args.quick, out_dir=args.out, only=args.only)


if __name__ == "__main__":
    main()
