"""``viscobem bench``: run time against error for every solver, scaling, and what skipping saves.

Run it with ``viscobem bench [--quick] --out DIR`` (or ``python -m viscobem_bench.suite``). It
writes ``DIR/bench.json``, one Pareto plot per solver (``DIR/pareto_<name>.png``: error
against wall time, log-log, the Pareto front joined), ``DIR/scaling.png`` and ``DIR/bench.md``,
and nothing outside ``DIR`` (the documentation's benchmark page is generated from
``bench.json``).

What is measured (SI units; every group of points runs in a fresh interpreter with BLAS
pinned to one thread and FFTs on all cores, see :mod:`viscobem_bench.instruments`):

1. **Solvers** (the registry of :mod:`viscobem_bench.cases`; adding a solver takes one
   function and a decorator): each entry sweeps its resolution and tolerance knobs and
   reports, per point, the error against an exact or converged reference, the wall time
   and the peak resident memory of its process (``ru_maxrss``).
2. **Scaling** of the periodic BEM with problem size (:mod:`viscobem_bench.scaling`).
3. **Skipping** what a scene does not need (:mod:`viscobem_bench.skipping`).

Tables and plots: :mod:`viscobem_bench.report`.
"""

import argparse
import json
import os
import platform
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from viscobem_bench import instruments
from viscobem_bench.cases import FINISH, REGISTRY
from viscobem_bench.report import markdown, pareto_front, plots
from viscobem_bench.scaling import run_scaling
from viscobem_bench.skipping import run_skip


# ---------------------------------------------------------------- driver
def run(quick=False, out_dir="bench-out", *, solvers=None, scaling=True, skip=True, study=None, echo=print):
    """Run the benchmark suite; write ``bench.json``, plots and ``bench.md`` in ``out_dir`` only.

    ``study``, a module-level function ``study(scene_text, out_dir) -> record`` (the record
    with ``stages`` and ``files``), times the skipping of unrequested outputs of a command-line
    study; without it that part is left out (see :mod:`viscobem_bench.skipping`).
    """
    import scipy

    import bem

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()
    result = {
        "benchmark": "suite",
        "issue": 7,
        "quick": quick,
        "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "machine": {
            "cpu_count": os.cpu_count(),
            "platform": platform.platform(),
            "python": platform.python_version(),
            "numpy": np.__version__,
            "scipy": scipy.__version__,
            "load_average": instruments.load_average(),
        },
        "solvers": {},
        "scaling": {"rows": []},
        "notes": [],
    }
    with (
        tempfile.TemporaryDirectory(prefix="viscobem-bench-") as tmp,
        instruments.source_snapshot(bem, Path(tmp) / "src") as code,
    ):
        result["code"] = code
        tmp = Path(tmp)
        for name, entry in REGISTRY.items():
            if solvers and name not in solvers:
                continue
            echo(f"{name}: {entry.problem}")
            points = []
            for group in entry.groups(quick):
                try:
                    got = instruments.run_in_fresh_process(entry.measure, group, quick, env=entry.env, timeout=1800)
                except Exception as err:  # one failing group must not lose the others
                    result["notes"].append(f"{name} {group}: {type(err).__name__}: {err}")
                    echo("  " + result["notes"][-1])
                    continue
                points += got
                for p in got:
                    echo(
                        "  "
                        + ", ".join(f"{k} {p[k]:g}" for k in entry.knobs if k in p)
                        + f": time {p['time']:.3f} s"
                        + (f", error {p['error']:.2e}" if p.get("error") else "")
                    )
            points = FINISH.get(name, lambda x: x)(points)
            result["solvers"][name] = {
                "solver": entry.solver,
                "problem": entry.problem,
                "reference": entry.reference,
                "error": entry.error,
                "knobs": list(entry.knobs),
                "points": points,
                "pareto": pareto_front(points),
            }
        if scaling:
            echo("scaling with problem size (elastic, periodic BEM)")
            result["scaling"] = run_scaling(quick, tmp, echo)
        if skip:
            echo("skipping what a scene does not need")
            result["skip"] = run_skip(quick, tmp, echo, study=study)
    result["total_time"] = time.perf_counter() - started
    result["files"] = ["bench.json", "bench.md"] + plots(result, out)
    table = markdown(result)
    (out / "bench.json").write_text(json.dumps(result, indent=1, default=float) + "\n")
    (out / "bench.md").write_text("# viscobem bench\n\n" + table + "\n")
    echo("\n" + table)
    echo(f"\nwrote {', '.join(result['files'])} in {out}; total {result['total_time']:.0f} s")
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m viscobem_bench.suite", description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="smaller sizes (scaling to 512²)")
    parser.add_argument("--out", default="bench-out")
    parser.add_argument("--solvers", nargs="+", choices=sorted(REGISTRY))
    parser.add_argument("--no-scaling", action="store_true")
    parser.add_argument("--no-skip", action="store_true")
    args = parser.parse_args(argv)
    run(args.quick, args.out, solvers=args.solvers, scaling=not args.no_scaling, skip=not args.no_skip)
    return 0


if __name__ == "__main__":
    sys.exit(main())
