"""Cost of a whole friction curve of the 20-term rubber, in elastic solves of the same surface.

Run it with ``python -m viscobem_bench.curve [--quick] --out DIR`` (or ``viscobem bench curve``).
It prints a table and writes ``DIR/curve.json`` and ``.md``.

For a rubber user the cost that matters is a friction curve, not one speed. The periodic
benchmark's surface and 20-term rubber (``E_inf/E0 = 1000``) are solved at 13 speeds,
``xi = v tau / L`` from 1e-6 to 1e4 on the longest creep time ``tau``, at one load: the one that
gives about 15 % contact at the slowest (rubbery) speed; the contact shrinks as the rubber
stiffens with speed. The unit is the elastic solve of the same surface at the same load, with
the rubber's relaxed modulus ``E0`` (same contact at the slow end): its operator products, and
its wall time (the fastest of three). Everything runs in this process, so machine noise
largely cancels in the ratios.

Three ways of sweeping are measured, each at rtol 1e-8:

- ``cold``: every speed from scratch (large grids start from the grid with half the points);
- ``warm``: :func:`bem.friction_curve`, each speed warm-started from the neighbour's solution
  (on large grids the warm start goes through the coarse grid, see :mod:`bem.contact.start`);
- ``warm_fine_only``: the same warm starts with ``ContactOptions(coarsen_warm=False)``, the
  neighbour's solution used as it is on the fine grid.
"""

import argparse
import sys
import time

import numpy as np

import bem
from bem.contact import ContactOptions
from viscobem_bench.periodic.problem import LENGTH, load_for_contact, materials, surface_heights
from viscobem_bench.periodic.report import finish, table

XIS = tuple(np.logspace(-6, 4, 13))
SIZE, QUICK_SIZE = 512, 128
CONTACT = 0.15
RTOL, MAXITER = 1e-8, 1000
MODES = {
    "cold": dict(warm_start=False),
    "warm": dict(warm_start=True),
    "warm_fine_only": dict(warm_start=True, options=ContactOptions(coarsen_warm=False)),
}


def _load(surface, rubber, speed):
    """Load (N) for about ``CONTACT`` at ``speed``: the periodic benchmark's secant steps toward
    10 %, scaled by the ratio of the fractions (contact grows about linearly with load here)."""
    history = load_for_contact(surface, rubber, speed, 1.0, maxiter=MAXITER, tol=0.005, steps=8)
    load, frac, _ = history[-1]
    return load * CONTACT / frac


def _sweep(surface, rubber, speeds, load, warm_start, options=None):
    rows, previous = [], None
    started = time.perf_counter()
    for speed in speeds:
        t0 = time.perf_counter()
        res = bem.solve(
            surface,
            rubber,
            speed=float(speed),
            load=load,
            rtol=RTOL,
            maxiter=MAXITER,
            initial=previous if warm_start else None,
            contact_options=options,
            raise_on_failure=False,
        )
        rows.append(
            dict(
                matvecs=res.matvecs,
                iterations=res.iterations,
                wall_time=time.perf_counter() - t0,
                contact_fraction=res.contact_fraction,
                friction=res.friction,
                success=res.success,
            )
        )
        previous = res.pressure if res.success else None
    return rows, time.perf_counter() - started


def run(quick=False, out_dir=None, size=None, echo=print):
    """Measure the three sweeps (module docstring); print, write and return the record."""
    n = size or (QUICK_SIZE if quick else SIZE)
    surface = bem.surfaces.from_heights(surface_heights(n), LENGTH)
    rubber, _ = materials()["rubber20"]
    tau = float(rubber.creep_times.max())
    speeds = np.asarray(XIS) * LENGTH / tau
    started = time.perf_counter()
    load = _load(surface, rubber, speeds[0])
    elastic = bem.Material.elastic(rubber.E0, nu=rubber.nu)
    times = []
    for _ in range(4):  # the first call also plans the FFTs: not kept
        ref = bem.solve(surface, elastic, speed=0.0, load=load, rtol=RTOL)
        times.append(ref.wall_time)
    unit = {"matvecs": ref.matvecs, "wall_time": min(times[1:]), "contact_fraction": ref.contact_fraction}
    modes = {}
    for name, kw in MODES.items():
        rows, total = _sweep(surface, rubber, speeds, load, kw["warm_start"], kw.get("options"))
        products = sum(r["matvecs"] for r in rows)
        modes[name] = dict(
            rows=rows,
            products=products,
            wall_time=total,
            products_in_elastic_solves=products / unit["matvecs"],
            time_in_elastic_solves=total / unit["wall_time"],
            all_converged=all(r["success"] for r in rows),
        )
        echo(
            f"{name:15s} {products:6d} products = {modes[name]['products_in_elastic_solves']:5.1f} elastic solves, "
            f"{total:6.2f} s = {modes[name]['time_in_elastic_solves']:5.1f} elastic solves"
        )
    fields = dict(n=n, rtol=RTOL, xis=list(XIS), speeds_m_s=speeds.tolist(), load_N=load, elastic=unit, modes=modes)
    return finish("curve", started, _report, out_dir, echo, **fields)


def _report(result, markdown=False):
    e = result["elastic"]
    head = (
        f"{result['n']}² grid, load {result['load_N']:.4g} N, rtol {result['rtol']:g}; unit: the elastic solve "
        f"(E0, same load, contact {e['contact_fraction']:.3f}): {e['matvecs']} products, {e['wall_time']:.3f} s"
    )
    summary = [
        [name, m["products"], f"{m['products_in_elastic_solves']:.1f}", f"{m['wall_time']:.2f}"]
        + [f"{m['time_in_elastic_solves']:.1f}", "yes" if m["all_converged"] else "NO"]
        for name, m in result["modes"].items()
    ]
    per_speed = [
        [f"{xi:.2g}", f"{result['modes']['cold']['rows'][i]['contact_fraction']:.4f}"]
        + [str(m["rows"][i]["matvecs"]) for m in result["modes"].values()]
        for i, xi in enumerate(result["xis"])
    ]
    return "\n\n".join(
        [
            head,
            table(
                ["sweep", "products", "elastic solves", "wall s", "elastic solves (time)", "converged"],
                summary,
                markdown,
            ),
            table(["xi", "contact"] + [f"products {k}" for k in result["modes"]], per_speed, markdown),
            f"total time {result['total_time']:.0f} s",
        ]
    )


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m viscobem_bench.curve", description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help=f"n = {QUICK_SIZE} (smoke test)")
    parser.add_argument("--size", type=int, help=f"grid size (default {SIZE})")
    parser.add_argument("--out", default=None, help="directory for curve.json and .md")
    args = parser.parse_args(argv)
    run(args.quick, args.out, args.size)
    return 0


if __name__ == "__main__":
    sys.exit(main())
