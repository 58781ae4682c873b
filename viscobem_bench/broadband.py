"""Cost of the periodic BEM against the bandwidth of the roughness.

Run it with ``python -m viscobem_bench.broadband [--quick] [--sizes ...] --out DIR`` (or ``viscobem
bench broadband``). It prints a table and writes ``DIR/broadband.json`` and ``.md``.

Real surfaces are rough over many decades of wavelength. This benchmark holds the sampling
fixed, 4 grid points per shortest wavelength, and widens the band with the grid: on an
``n x n`` grid the self-affine surface (H = 0.8, rms slope 0.1, seed 1) has ``n / 4`` scales,
from the cell size ``L`` down to ``L / (n / 4)``, pressed by one load (50 N on a 1 cm cell, ``E
= 10 MPa``: about 60 % contact at every size; 25 N for the softer seed solid, 45-75 %). Per size it reports, at rtol 1e-8, operator
products, active-set iterations, wall time, peak memory of the process so far and contact,
for the elastic solid and (``--seed``) the seed's standard linear solid at ``xi = 1e-2`` on its
creep time. The contact solver's products should grow slowly with the band: a solve whose
sets oscillate or diverge at the finest scales would show here as a jump.
"""

import argparse
import sys
import time

import bem
from viscobem_bench import instruments
from viscobem_bench.periodic.report import finish, table

LENGTH, LOAD, SEED_LOAD, E = 0.01, 50.0, 25.0, 1e7
SURFACE = dict(hurst=0.8, rms_slope=0.1, seed=1)
POINTS_PER_WAVELENGTH = 4
SIZES, QUICK_SIZES = (512, 1024, 2048, 4096), (128, 256)
RTOL = 1e-8


def materials(seed=False):
    """``{name: (Material, speed m/s, load N)}``: the elastic solid and, with ``seed``, the seed's SLS."""
    out = {"elastic": (bem.Material.elastic(E), 0.0, LOAD)}
    if seed:
        sls = bem.Material.standard_linear_solid(E0=E / 3, E_inf=E, creep_time=0.01)
        out["seed"] = (sls, 1e-2 * LENGTH / sls.creep_times[0], SEED_LOAD)
    return out


def run(quick=False, out_dir=None, sizes=None, seed=False, echo=print):
    """Solve each size (module docstring); print, write and return the record."""
    sizes = tuple(sizes or (QUICK_SIZES if quick else SIZES))
    started = time.perf_counter()
    rows = []
    for n in sizes:
        surface = bem.surfaces.self_affine(n, LENGTH, scales=n // POINTS_PER_WAVELENGTH, **SURFACE)
        for name, (material, speed, load) in materials(seed).items():
            res = bem.solve(surface, material, speed=speed, load=load, rtol=RTOL, raise_on_failure=False)
            rows.append(
                dict(
                    n=n,
                    scales=n // POINTS_PER_WAVELENGTH,
                    case=name,
                    load_N=load,
                    matvecs=res.matvecs,
                    iterations=res.iterations,
                    wall_time=res.wall_time,
                    peak_rss=instruments.peak_rss(),
                    contact_fraction=res.contact_fraction,
                    success=res.success,
                    message=res.message,
                )
            )
            r = rows[-1]
            echo(
                f"n = {n:5d}, {r['scales']:4d} scales, {name:7s}: {r['matvecs']:5d} products, "
                f"{r['iterations']:3d} iterations, {r['wall_time']:7.1f} s, contact {r['contact_fraction']:.3f}"
            )
    fields = dict(rtol=RTOL, points_per_wavelength=POINTS_PER_WAVELENGTH, surface=SURFACE, rows=rows)
    return finish("broadband", started, _report, out_dir, echo, **fields)


def _report(result, markdown=False):
    headers = ["n", "scales", "case", "load N", "products", "iterations", "wall s", "peak GiB", "contact", "converged"]
    body = [
        [r["n"], r["scales"], r["case"], r["load_N"], r["matvecs"], r["iterations"], f"{r['wall_time']:.1f}"]
        + [f"{r['peak_rss'] / 2**30:.2f}", f"{r['contact_fraction']:.3f}", "yes" if r["success"] else "NO"]
        for r in result["rows"]
    ]
    head = (
        f"self-affine H = {result['surface']['hurst']}, rms slope {result['surface']['rms_slope']}, "
        f"{result['points_per_wavelength']} points per shortest wavelength, "
        f"rtol {result['rtol']:g}"
    )
    return "\n\n".join([head, table(headers, body, markdown), f"total time {result['total_time']:.0f} s"])


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m viscobem_bench.broadband", description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help=f"n = {QUICK_SIZES} (smoke test)")
    parser.add_argument("--sizes", type=int, nargs="+", help=f"grid sizes (default {SIZES})")
    parser.add_argument("--seed", action="store_true", help="also the seed's standard linear solid")
    parser.add_argument("--out", default=None, help="directory for broadband.json and .md")
    args = parser.parse_args(argv)
    run(args.quick, args.out, args.sizes, args.seed)
    return 0


if __name__ == "__main__":
    sys.exit(main())
