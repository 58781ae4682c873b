"""Friction over speed and temperature by superposition (:func:`bem.friction_map`) against direct
solves, and its cost against one friction curve.

Run it with ``python -m viscobem_bench.friction_map [--quick] --out DIR`` (or ``viscobem bench
friction_map``). It prints a table and writes ``DIR/friction_map.json`` and ``.md``.

A filled-rubber-like Prony series (one term a decade from 1e-7 to 1e3 s, E_inf/E0 = 200, WLF with
the universal constants at 23 C) slides over a rough profile at 25 speeds from 1e-6 to 1 m/s and
13 temperatures from -20 to 80 C. The map's operator products are compared with those of one
25-speed curve at the reference temperature, solved in the same process, and the map with a
direct friction curve (the material at that temperature) at several temperatures; the targets are
a ratio of at most 2.5 and a difference of at most 1 % at every point compared.
"""

import sys
import time

import numpy as np

import bem
from viscobem_bench.periodic.report import finish, quick_out_main, table

SPEEDS = np.logspace(-6, 0, 25)
TEMPERATURES = np.linspace(253.15, 353.15, 13)
CHECKED = (0, 4, 9, 12)  # rows compared with direct solves: both ends and two between
LOAD = 2e4  # N/m on the profile
N, QUICK_N = 2048, 512
TARGET_RATIO, TARGET_ERROR = 2.5, 0.01


def problem(n):
    """The rubber, its shift law and a rough profile of ``n`` points."""
    material = bem.Material.from_prony(E0=1e6, moduli=np.full(11, 199e6 / 11), times=np.logspace(-7, 3, 11))
    law = bem.temperature.WLF(8.86, 101.6, 296.15)
    heights = bem.surfaces.self_affine(n, 0.01, hurst=0.8, scales=32, rms_height=1e-5, seed=4).heights
    profile = bem.surfaces.from_heights(heights[:, 0] if heights.ndim == 2 else heights, 0.01)
    return material, law, profile


def run(quick=False, out_dir=None):
    started = time.perf_counter()
    material, law, profile = problem(QUICK_N if quick else N)
    t0 = time.perf_counter()
    fmap = bem.friction_map(profile, material, speeds=SPEEDS, temperatures=TEMPERATURES, shift=law, load=LOAD)
    map_time = time.perf_counter() - t0
    t0 = time.perf_counter()
    one = bem.friction_curve(profile, material, speeds=SPEEDS, load=LOAD)
    curve_time = time.perf_counter() - t0
    curve_products = int(sum(r.matvecs for r in one.results if r is not None))
    rows = []
    for i in CHECKED:
        direct = bem.friction_curve(profile, material.at_temperature(TEMPERATURES[i], law), speeds=SPEEDS, load=LOAD)
        diff = np.abs(fmap.friction[i] / direct.friction - 1)
        rows.append(
            dict(
                temperature=float(TEMPERATURES[i]),
                log10_shift=float(fmap.log10_shift[i]),
                max_difference=float(np.nanmax(diff)),
                max_estimate=float(np.nanmax(fmap.interpolation_error[i])),
                interpolated_points=int(fmap.interpolated[i].sum()),
            )
        )
    return finish(
        "friction_map",
        started,
        report,
        out_dir,
        n=profile.n,
        speeds=SPEEDS.size,
        temperatures=TEMPERATURES.size,
        nodes=len(fmap.results),
        map_products=fmap.matvecs,
        curve_products=curve_products,
        products_ratio=fmap.matvecs / curve_products,
        map_time=map_time,
        curve_time=curve_time,
        rows=rows,
        worst_difference=max(r["max_difference"] for r in rows),
        warnings=list(fmap.warnings),
        targets=dict(products_ratio=TARGET_RATIO, difference=TARGET_ERROR),
    )


def report(result, markdown=False):
    head = (
        f"{result['temperatures']} temperatures x {result['speeds']} speeds on a {result['n']}-point profile: "
        f"{result['nodes']} solves on the reference material, {result['map_products']} operator products against "
        f"{result['curve_products']} for one {result['speeds']}-speed curve: {result['products_ratio']:.2f}x "
        f"(target <= {result['targets']['products_ratio']:g}x); {result['map_time']:.1f} s against "
        f"{result['curve_time']:.1f} s"
    )
    rows = [
        [
            f"{r['temperature']:.2f}",
            f"{r['log10_shift']:.2f}",
            f"{r['max_difference']:.2e}",
            f"{r['max_estimate']:.2e}",
            r["interpolated_points"],
        ]
        for r in result["rows"]
    ]
    headers = ["T (K)", "log10 a_T", "largest |map / direct - 1|", "largest estimate", "interpolated points"]
    tail = (
        f"worst difference from direct solves {result['worst_difference']:.2e} (target <= "
        f"{result['targets']['difference']:g}); total time {result['total_time']:.0f} s"
    )
    return "\n\n".join([head, table(headers, rows, markdown), tail])


def main(argv=None):
    return quick_out_main("friction_map", __doc__, run, f"a {QUICK_N}-point profile (smoke test)", argv)


if __name__ == "__main__":
    sys.exit(main())
