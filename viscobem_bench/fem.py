"""Benchmark of the FEM reference: error against run time and memory.

Cases (all SI; R = 10 mm):

- ``rolling``: a standard linear solid (E0 = 1 MPa, E_inf/E0 = 3, nu = 0.5) rolling at
  retardation length ``V lambda = ell a0`` under P = 100 N/m, against Hunter's exact
  solution (validation.hunter): friction and peak-pressure errors over mesh resolution
  (elements per glassy half-width) and domain size (in units of ``V lambda``);
- ``solvers``: the same rolling case factorised with SuperLU and, if installed, PARDISO;
- ``indentation``: creep under a step load (P = 1 N) against Lee & Radok, over mesh
  resolution.

Each case runs in a fresh interpreter (:func:`viscobem_bench._measure.run_in_fresh_process`)
with BLAS/MKL threads pinned to 2, so its peak resident set size is its own.

Run: ``python -m viscobem_bench.fem --quick --out DIR`` (writes ``DIR/fem_benchmark.json``).
"""
from __future__ import annotations

import argparse
import json
import pathlib
import time

import numpy as np

from viscobem_bench._measure import peak_rss, run_in_fresh_process, thread_environment


def _peak_rss_mb():
    return peak_rss() / 2**20


def _sls():
    from bem import Material

    return Material.standard_linear_solid(E0=1e6, E_inf=3e6, relaxation_time=0.01, nu=0.5)


def _rolling_case(material, ell, resolution, domain_factor, solver="auto", grading=1.3):
    from fem_reference import rolling_cylinder
    from validation import hunter
    from validation.hertz import line_contact

    R, P = 0.01, 100.0
    a0 = line_contact(material.E0, material.nu, R, P).a
    V = ell * a0 / material.creep_times[0]
    domain = max(40 * a0, domain_factor * ell * a0)
    t0 = time.perf_counter()
    r = rolling_cylinder(material, radius=R, load=P, speed=V, resolution=resolution, domain=domain,
                         grading=grading, solver=solver)
    wall = time.perf_counter() - t0
    h = hunter.rolling_cylinder(material, radius=R, load=P, speed=V)
    return {
        "ell_r_over_a0": ell, "resolution": resolution, "domain_over_ell_r": domain / (ell * a0),
        "grading": grading, "solver": solver, "unknowns": r.n_unknowns, "elements": r.n_elements,
        "friction": r.friction, "friction_hunter": h.friction,
        "friction_error": r.friction / h.friction - 1, "peak_pressure_error": r.peak_pressure / h.peak_pressure - 1,
        "dissipation_friction_error": r.friction_dissipation / h.friction - 1,
        "leading_edge_error_over_a0": (r.leading_edge - h.leading_edge) / a0,
        "trailing_edge_error_over_a0": (r.trailing_edge - h.trailing_edge) / a0,
        "wall_s": wall, "timings": r.timings, "peak_rss_mb": _peak_rss_mb(),
    }


def _indentation_case(resolution, steps_per_decade):
    from bem import Material
    from fem_reference import indentation

    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, creep_time=1.0, nu=0.5)
    R, P = 0.01, 1.0
    times = np.array([0.0, 0.3, 1.0, 3.0, 10.0, 100.0])
    t0 = time.perf_counter()
    r = indentation(m, radius=R, load=P, times=times, resolution=resolution, steps_per_decade=steps_per_decade)
    wall = time.perf_counter() - t0
    a_lr = (0.75 * R * P * (1 - m.nu**2) * m.creep_compliance(times)) ** (1 / 3)
    return {
        "resolution": resolution, "steps_per_decade": steps_per_decade, "unknowns": r.n_unknowns,
        "steps": r.n_steps, "max_radius_error": float(np.max(np.abs(r.contact_radius / a_lr - 1))),
        "max_approach_error": float(np.max(np.abs(r.approach / (a_lr**2 / R) - 1))),
        "wall_s": wall, "peak_rss_mb": _peak_rss_mb(),
    }


def _table(rows, cols):
    lines = ["  ".join(f"{c:>14s}" for c in cols)]
    for row in rows:
        cells = []
        for c in cols:
            v = row[c]
            cells.append(f"{v:14.4g}" if isinstance(v, float) else f"{v!s:>14s}")
        lines.append("  ".join(cells))
    return "\n".join(lines)


def run(quick: bool = True, out_dir=".") -> dict:
    """Run the benchmark; print tables and write ``out_dir/fem_benchmark.json``."""
    from fem_reference.linsolve import pardiso_available

    env = thread_environment(2)

    def fresh(func, *args):
        return run_in_fresh_process(func, *args, env=env)

    m = _sls()
    resolutions = [2, 3, 4] if quick else [2, 3, 4, 6, 8]
    domains = [3, 10, 30] if quick else [3, 10, 30, 100]
    rolling = [fresh(_rolling_case, m, 1.0, n, 30) for n in resolutions]
    rolling += [fresh(_rolling_case, m, 10.0, 3, d) for d in domains]
    rolling += [fresh(_rolling_case, m, 100.0, n, 30, "auto", 2.0) for n in ([3, 5] if quick else [3, 5, 8])]
    solvers = ["splu"] + (["pardiso"] if pardiso_available() else [])
    solver_rows = [fresh(_rolling_case, m, 1.0, 4 if quick else 6, 30, s) for s in solvers]
    ind = [fresh(_indentation_case, n, 20) for n in ([4, 6] if quick else [4, 6, 8, 12])]

    cols = ["ell_r_over_a0", "resolution", "domain_over_ell_r", "grading", "unknowns", "friction_error",
            "dissipation_friction_error", "peak_pressure_error", "wall_s", "peak_rss_mb"]
    print("rolling cylinder vs Hunter (SLS, E_inf/E0 = 3, nu = 0.5)")
    print(_table(rolling, cols))
    print("\nsparse direct solvers (same case)")
    srows = [dict(r, factor_s=r["timings"]["assemble_factor"], flexibility_s=r["timings"]["flexibility"])
             for r in solver_rows]
    print(_table(srows, ["solver", "unknowns", "factor_s", "flexibility_s", "wall_s", "friction_error"]))
    print("\nindentation vs Lee-Radok (SLS, creep time 1 s)")
    print(_table(ind, ["resolution", "steps_per_decade", "unknowns", "steps", "max_radius_error",
                       "max_approach_error", "wall_s", "peak_rss_mb"]))
    result = {"quick": quick, "rolling": rolling, "solvers": srows, "indentation": ind}
    out = pathlib.Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    (out / "fem_benchmark.json").write_text(json.dumps(result, indent=2, default=float))
    return result


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="fewer, smaller cases")
    p.add_argument("--out", default=".", help="output directory for fem_benchmark.json")
    args = p.parse_args(argv)
    run(quick=args.quick, out_dir=args.out)


if __name__ == "__main__":
    main()
