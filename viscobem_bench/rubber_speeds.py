"""Cost of the periodic benchmark's 20-term rubber over sliding speed (issue 2).

Run it with ``python -m viscobem_bench.rubber_speeds [--quick] --out DIR`` (or ``viscobem bench
rubber_speeds``). It prints a table and writes ``DIR/rubber_speeds.json`` and ``.md``.

The periodic benchmark (:mod:`viscobem_bench.periodic`) measures the rubber (E_inf/E0 = 1000,
20 Prony terms) at one speed, xi = 1e-2 on its longest creep time, where it needs 4-7x the
elastic case's operator products. This one asks whether that is the speed or the material:
the same surface and rubber at xi = v tau / L from 1e-6 (rubbery) to 1e4 (glassy for every
mode that slides), each loaded to about 10 % contact on the first grid (secant steps at rtol
1e-6, as the periodic benchmark does), then solved at rtol 1e-8 on every grid, next to the
elastic case (E = 1e7 Pa, also at about 10 % contact). Reported per speed: the largest and
median symbol phase ``|arg a_q|`` (0 for a symmetric operator; the solver's strongly
non-symmetric path starts above 45 degrees), operator products, active-set iterations, wall
time, contact fraction and friction. Everything runs in this process, one solve at a time.
"""

import argparse
import sys
import time

import numpy as np

import bem
from bem.sliding import operator_for
from viscobem_bench.periodic.problem import LENGTH, TARGET_CONTACT, load_for_contact, materials, surface_heights
from viscobem_bench.periodic.report import publish, table

XIS = (1e-6, 1e-4, 1e-2, 1.0, 1e2, 1e4)
SIZES, QUICK_SIZES, QUICK_XIS = (256, 512), (64, 128), (1e-4, 1e-2, 1e4)
RTOL, MAXITER = 1e-8, 1000


def _calibrated(surface, material, speed, load):
    """Load (N) for about 10 % contact: the periodic benchmark's secant steps, to within 0.004
    of the target fraction."""
    return load_for_contact(surface, material, speed, load, maxiter=MAXITER, tol=0.004, steps=8)[-1][0]


def _solve_row(case, xi, material, speed, surfaces, load):
    op = operator_for(surfaces[0], material, speed)
    phase = np.degrees(np.abs(np.angle(op.symbol)))
    row = {
        "case": case,
        "xi": xi,
        "speed_m_s": speed,
        "load_N": load,
        "max_phase_deg": float(phase.max()),
        "median_phase_deg": float(np.median(phase)),
        "by_n": {},
    }
    for s in surfaces:
        t0 = time.perf_counter()
        res = bem.solve(s, material, speed=speed, load=load, rtol=RTOL, maxiter=MAXITER, raise_on_failure=False)
        row["by_n"][str(s.n)] = {
            "matvecs": res.matvecs,
            "iterations": res.iterations,
            "wall_time": time.perf_counter() - t0,
            "success": res.success,
            "contact_fraction": res.contact_fraction,
            "friction": res.friction,
            "message": res.message,
        }
    return row


def run(quick=False, out_dir=None, sizes=None, xis=None, echo=print):
    """Solve the rubber at each ``xi`` and the elastic case on each grid; print, write, return."""
    sizes = tuple(sizes or (QUICK_SIZES if quick else SIZES))
    xis = tuple(xis or (QUICK_XIS if quick else XIS))
    surfaces = [bem.surfaces.from_heights(surface_heights(n), LENGTH) for n in sizes]
    mats = materials()
    rubber, _ = mats["rubber20"]
    elastic, _ = mats["elastic"]
    tau = float(rubber.creep_times[0])
    started = time.perf_counter()
    load = _calibrated(surfaces[0], elastic, 0.0, 6.0)
    rows = [_solve_row("elastic", None, elastic, 0.0, surfaces, load)]
    guess = load * rubber.E0 / elastic.E0
    for xi in xis:
        speed = xi * LENGTH / tau
        load = _calibrated(surfaces[0], rubber, speed, guess)
        rows.append(_solve_row("rubber20", xi, rubber, speed, surfaces, load))
        guess = load  # stiffer with speed: start the next calibration from here
        echo(_row_text(rows[-1], sizes))
    result = {
        "benchmark": "rubber_speeds",
        "issue": 2,
        "date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        "sizes": list(sizes),
        "rtol": RTOL,
        "target_contact_fraction": TARGET_CONTACT,
        "longest_creep_time_s": tau,
        "rows": rows,
        "total_time": time.perf_counter() - started,
    }
    publish(result, _report, out_dir, "rubber_speeds", echo)
    return result


def _row_text(row, sizes):
    xi = "-" if row["xi"] is None else f"{row['xi']:.0e}"
    cells = [
        f"{row['case']:8s} xi {xi:>6s}",
        f"phase max {row['max_phase_deg']:4.1f} median {row['median_phase_deg']:4.1f}",
        f"load {row['load_N']:.4g} N",
    ]
    for n in sizes:
        r = row["by_n"][str(n)]
        cells.append(
            f"{n}²: {r['matvecs']} products, {r['iterations']} it, {r['wall_time']:.2f} s, "
            f"contact {r['contact_fraction']:.3f}{'' if r['success'] else ' NOT CONVERGED'}"
        )
    return " | ".join(cells)


def _report(result, markdown=False):
    sizes = result["sizes"]
    elastic = next(r for r in result["rows"] if r["case"] == "elastic")
    headers = ["case", "xi", "max phase deg", "median phase deg", "load N"]
    for n in sizes:
        headers += [f"{n}² products", f"{n}² / elastic", f"{n}² it", f"{n}² s", f"{n}² contact"]
    headers += ["friction"]
    rows = []
    for r in result["rows"]:
        cells = [
            r["case"],
            "-" if r["xi"] is None else f"{r['xi']:.0e}",
            f"{r['max_phase_deg']:.1f}",
            f"{r['median_phase_deg']:.1f}",
            f"{r['load_N']:.4g}",
        ]
        for n in sizes:
            b, e = r["by_n"][str(n)], elastic["by_n"][str(n)]
            cells += [
                str(b["matvecs"]) + ("" if b["success"] else " (not converged)"),
                f"{b['matvecs'] / e['matvecs']:.1f}",
                str(b["iterations"]),
                f"{b['wall_time']:.2f}",
                f"{b['contact_fraction']:.3f}",
            ]
        cells.append(f"{r['by_n'][str(sizes[-1])]['friction']:.4f}")
        rows.append(cells)
    title = "Rubber (E_inf/E0 = 1000, 20 terms) over speed: cost against the elastic case"
    return "\n\n".join(
        [
            ("# " if markdown else "") + title,
            f"rtol {result['rtol']:g}; each load gives about {result['target_contact_fraction']:.0%} "
            f"contact on {sizes[0]}²; xi = v tau / L, tau = {result['longest_creep_time_s']:.4g} s",
            table(headers, rows, markdown),
            f"total time {result['total_time']:.0f} s",
        ]
    )


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m viscobem_bench.rubber_speeds", description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help=f"n = {QUICK_SIZES}, xi = {QUICK_XIS} (smoke test)")
    parser.add_argument("--sizes", type=int, nargs="+", help=f"grid sizes (default {SIZES})")
    parser.add_argument("--xi", type=float, nargs="+", help=f"dimensionless speeds (default {XIS})")
    parser.add_argument("--out", default=None, help="directory for rubber_speeds.json and .md")
    args = parser.parse_args(argv)
    run(args.quick, args.out, args.sizes, args.xi)
    return 0


if __name__ == "__main__":
    sys.exit(main())
