"""Cost of whole friction curves of the 20-term rubber, in elastic solves of the same surface.

Run it with ``python -m viscobem_bench.curve [--quick] --out DIR`` (or ``viscobem bench curve``).
It prints a table and writes ``DIR/curve.json`` and ``.md``.

For a rubber user the cost that matters is a friction curve, not one speed. The periodic
benchmark's 20-term rubber (``E_inf/E0 = 1000``) slides over self-affine surfaces (H = 0.8, rms
slope 0.1) of different seeds and bandwidths (16 to 256 scales on 512²), each at two loads:
the ones that give about 3 % and 15 % contact at the rubbery end, where the rubber is its
relaxed self (``E0``). Each curve is :func:`bem.friction_curve` at 13 speeds, ``xi = v tau / L``
from 1e-6 to 1e4 on the longest creep time ``tau``, at rtol 1e-8; the contact shrinks as the
rubber stiffens with speed.

The unit is the elastic solve of the same surface at the same load with the relaxed modulus
``E0`` (the same contact at the slow end): its operator products, and its wall and CPU time
(the fastest of three, measured before and after the curve in the same process, so that the
machine's load changes cancel in the ratios as far as they can). A curve costs
``products / elastic products`` elastic solves by products, and the same by wall and CPU time;
per point, that over the 13 speeds, against the target of :data:`TARGET_PER_POINT`.
"""

import argparse
import sys
import time

import numpy as np

import bem
from viscobem_bench.instruments import load_average
from viscobem_bench.periodic.problem import LENGTH, materials
from viscobem_bench.periodic.report import finish, table

XIS = tuple(np.logspace(-6, 4, 13))
SIZE, QUICK_SIZE = 512, 128
SURFACES = ((1, 16), (2, 64), (3, 256))  # (seed, scales)
QUICK_SURFACES = ((1, 16), (3, 64))
CONTACTS = (0.03, 0.15)
ROUGHNESS = dict(hurst=0.8, rms_slope=0.1)
RTOL, MAXITER = 1e-8, 1000
REPEATS = 3
TARGET_PER_POINT = 2.0  # elastic solves a speed of a curve should cost at most, by products and by CPU time


def _load(surface, elastic, target):
    """Load (N) that gives about ``target`` contact on the relaxed solid: secant steps on
    ``log(contact)`` against ``log(load)`` (contact grows about linearly with load here)."""
    load, history = 1.0, []
    for _ in range(10):
        frac = bem.solve(surface, elastic, speed=0.0, load=load, rtol=1e-6).contact_fraction
        history.append((np.log(load), np.log(frac)))
        if abs(frac / target - 1) < 0.02:
            break
        slope = 1.0
        if len(history) > 1 and history[-1][1] != history[-2][1]:
            slope = (history[-1][1] - history[-2][1]) / (history[-1][0] - history[-2][0])
        load *= (target / frac) ** (1.0 / min(max(slope, 0.3), 3.0))
    return load


def _elastic(surface, elastic, load):
    """Operator products, and the fastest wall and CPU times (s) of ``REPEATS`` elastic solves."""
    walls, cpus = [], []
    for _ in range(REPEATS):
        wall, cpu = time.perf_counter(), time.process_time()
        res = bem.solve(surface, elastic, speed=0.0, load=load, rtol=RTOL)
        walls.append(time.perf_counter() - wall)
        cpus.append(time.process_time() - cpu)
    return {"matvecs": res.matvecs, "wall_time": min(walls), "cpu_time": min(cpus), "contact": res.contact_fraction}


def _curve(surface, rubber, speeds, load):
    """One warm-started friction curve: per speed products, iterations, contact, friction."""
    rows = []
    wall, cpu = time.perf_counter(), time.process_time()
    curve = bem.friction_curve(surface, rubber, speeds=speeds, load=load, rtol=RTOL, maxiter=MAXITER)
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    for res, message in zip(curve.results, curve.messages):
        ok = res is not None
        rows.append(
            dict(
                matvecs=res.matvecs if ok else None,
                iterations=res.iterations if ok else None,
                contact_fraction=res.contact_fraction if ok else None,
                friction=res.friction if ok else None,
                success=ok,
                message=message,
            )
        )
    return rows, wall, cpu


def run(quick=False, out_dir=None, size=None, echo=print):
    """Measure every (surface, load) curve (module docstring); print, write and return the record."""
    n = size or (QUICK_SIZE if quick else SIZE)
    rubber, _ = materials()["rubber20"]
    elastic = bem.Material.elastic(rubber.E0, nu=rubber.nu)
    speeds = np.asarray(XIS) * LENGTH / float(rubber.creep_times.max())
    started, load_start = time.perf_counter(), load_average()
    curves = []
    for seed, scales in QUICK_SURFACES if quick else SURFACES:
        surface = bem.surfaces.self_affine(n, LENGTH, scales=scales, seed=seed, **ROUGHNESS)
        for target in CONTACTS:
            load = _load(surface, elastic, target)
            before = _elastic(surface, elastic, load)
            rows, wall, cpu = _curve(surface, rubber, speeds, load)
            after = _elastic(surface, elastic, load)
            unit = {k: min(before[k], after[k]) for k in ("wall_time", "cpu_time")}
            unit.update(matvecs=before["matvecs"], contact=before["contact"])
            products = sum(r["matvecs"] or 0 for r in rows)
            curves.append(
                dict(
                    seed=seed,
                    scales=scales,
                    target_contact=target,
                    load_N=load,
                    elastic=unit,
                    rows=rows,
                    products=products,
                    wall_time=wall,
                    cpu_time=cpu,
                    products_in_elastic_solves=products / unit["matvecs"],
                    wall_in_elastic_solves=wall / unit["wall_time"],
                    cpu_in_elastic_solves=cpu / unit["cpu_time"],
                    all_converged=all(r["success"] for r in rows),
                )
            )
            c = curves[-1]
            echo(
                f"seed {seed}, {scales:3d} scales, contact {unit['contact']:.3f}: {products:6d} products = "
                f"{c['products_in_elastic_solves']:5.1f} elastic solves; wall {wall:6.1f} s = "
                f"{c['wall_in_elastic_solves']:5.1f}, CPU {cpu:6.1f} s = {c['cpu_in_elastic_solves']:5.1f}"
                + ("" if c["all_converged"] else "; NOT ALL CONVERGED")
            )
    fields = dict(
        n=n,
        rtol=RTOL,
        xis=list(XIS),
        speeds_m_s=speeds.tolist(),
        surface=ROUGHNESS,
        curves=curves,
        load_average=[load_start, load_average()],
        worst=dict(
            products=max(c["products_in_elastic_solves"] for c in curves),
            wall=max(c["wall_in_elastic_solves"] for c in curves),
            cpu=max(c["cpu_in_elastic_solves"] for c in curves),
        ),
        target_per_point=TARGET_PER_POINT,
    )
    return finish("curve", started, _report, out_dir, echo, **fields)


def _report(result, markdown=False):
    head = (
        f"{result['n']}² grids, 20-term rubber (E_inf/E0 = 1000), {len(result['xis'])} speeds xi = "
        f"{result['xis'][0]:g}..{result['xis'][-1]:g}, rtol {result['rtol']:g}; unit: the elastic solve of the "
        f"same surface and load (E0); load average {result['load_average'][0]} -> {result['load_average'][1]} "
        "(a shared machine: wall times are noisy, CPU times less so)"
    )
    summary = [
        [c["seed"], c["scales"], f"{c['elastic']['contact']:.3f}", c["products"], c["elastic"]["matvecs"]]
        + [f"{c['products_in_elastic_solves']:.1f}", f"{c['wall_time']:.1f}", f"{c['wall_in_elastic_solves']:.1f}"]
        + [f"{c['cpu_time']:.1f}", f"{c['cpu_in_elastic_solves']:.1f}"]
        + [
            f"{c['products_in_elastic_solves'] / len(c['rows']):.2f}",
            f"{c['cpu_in_elastic_solves'] / len(c['rows']):.2f}",
        ]
        + ["yes" if c["all_converged"] else "NO"]
        for c in result["curves"]
    ]
    headers = ["seed", "scales", "contact", "products", "elastic products", "elastic solves"]
    headers += ["wall s", "elastic solves (wall)", "CPU s", "elastic solves (CPU)"]
    headers += ["per point (products)", "per point (CPU)", "converged"]
    names = [f"{c['seed']}/{c['scales']}/{c['target_contact']:g}" for c in result["curves"]]
    per_speed = [
        [f"{xi:.2g}"]
        + [f"{c['rows'][i]['matvecs']} ({c['rows'][i]['contact_fraction'] or 0:.3f})" for c in result["curves"]]
        for i, xi in enumerate(result["xis"])
    ]
    worst, points = result["worst"], len(result["xis"])
    return "\n\n".join(
        [
            head,
            table(headers, summary, markdown),
            "products (contact) per speed, by seed/scales/contact:",
            table(["xi"] + names, per_speed, markdown),
            f"worst curve: {worst['products']:.1f} elastic solves by products, {worst['wall']:.1f} by wall time, "
            f"{worst['cpu']:.1f} by CPU time; per point {worst['products'] / points:.2f} by products, "
            f"{worst['cpu'] / points:.2f} by CPU time (target {result.get('target_per_point', TARGET_PER_POINT):g}); "
            f"total time {result['total_time']:.0f} s",
        ]
    )


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m viscobem_bench.curve", description=__doc__.split("\n")[0])
    parser.add_argument(
        "--quick", action="store_true", help=f"n = {QUICK_SIZE}, surfaces {QUICK_SURFACES} (smoke test)"
    )
    parser.add_argument("--size", type=int, help=f"grid size (default {SIZE})")
    parser.add_argument("--out", default=None, help="directory for curve.json and .md")
    args = parser.parse_args(argv)
    run(args.quick, args.out, args.size)
    return 0


if __name__ == "__main__":
    sys.exit(main())
