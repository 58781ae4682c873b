"""Cost and accuracy of the FEM on rough profiles (:func:`fem_reference.sliding_profile`) over a friction curve.

Each row is one speed of a rubber on a seeded self-affine profile
(:func:`validation.cases.rough_profile.profile_heights`, 64 samples over 1 mm, 20 um peak to valley):
the FEM's default call against the BEM converged on the profile's interpolant (4096 points, rtol
1e-10), in a fresh interpreter with two BLAS threads. It prints the FEM's unknowns on its last mesh,
meshes, wall time and peak resident memory, the errors of both friction forms and of the contact
fraction against the BEM, each form's error estimate and whether the result warned. The cost targets
are 10 minutes and 8 GiB a speed on 2 cores; the errors are judged against 2 % (friction) and 3 %
(contact fraction), or an estimate that covers them.

- the validation case's 4-term rubber (E_inf/E0 = 111, tau 1e-6..1e-3 s) on its profile at 40 N/m,
  from two decades below its friction peak (3e-2 m/s) to two above;
- a 20-term rubber (E_inf/E0 = 1000, equal moduli, tau 1e-9..1e-1 s) on the seed-5 profile at
  200 N/m, from two decades below its friction peak (1e-4 m/s) to two above.

Run: ``viscobem bench fem_profile [--quick] --out DIR`` (writes ``DIR/fem_profile.json``); ``--quick``
runs the 4-term rubber at its peak and a decade above on 64 squares a period.
"""

from __future__ import annotations

import time

import numpy as np

from viscobem_bench.fem import table
from viscobem_bench.instruments import bench_main, run_in_fresh_process, thread_environment, write_record

__all__ = ["RUBBERS", "profile_case", "run", "main"]


def _rubber(name):
    import bem
    from validation.cases.rough_profile import rubber

    if name == "4-term":
        return rubber()
    return bem.Material.from_prony(E0=1e6, moduli=np.full(20, 999e6 / 20), times=np.logspace(-9, -1, 20), nu=0.5)


# name: (profile seed, load N/m, speeds m/s)
# squares a period of the --quick rows (the default's squares at the spot edges, half its squares elsewhere)
QUICK_SQUARES = 64
RUBBERS = {"4-term": (22, 40.0, (3e-4, 3e-3, 3e-2, 3e-1, 3.0)), "20-term": (5, 200.0, (1e-6, 1e-5, 1e-4, 1e-3, 1e-2))}


def profile_case(name, speed, elements=None):
    """One row: the FEM's default call (or ``elements`` squares a period) against the converged BEM
    of the validation case ``rough_profile`` (its reference points and tolerance)."""
    import bem
    from bem import surfaces
    from fem_reference import sliding_profile
    from fem_reference.profile import profile_nodes
    from validation.cases.rough_profile import REF_POINTS, RTOL, L, profile_heights

    seed, load, _ = RUBBERS[name]
    m = _rubber(name)
    h = profile_heights(seed)
    fine, _ = profile_nodes(h, L, np.arange(REF_POINTS) * L / REF_POINTS)
    ref = bem.solve(surfaces.Surface(fine, L), m, speed=speed, load=load, rtol=RTOL)
    t0 = time.perf_counter()
    kwargs = {} if elements is None else {"elements": elements}
    f = sliding_profile(m, heights=h, length=L, load=load, speed=speed, **kwargs)
    wall = time.perf_counter() - t0
    return {
        "rubber": name,
        "speed": float(speed),
        "contact": float(ref.contact_fraction),
        "unknowns": int(f.n_unknowns),
        "meshes": int(f.passes),
        "wall_s": wall,
        "peak_gib": f.peak_memory / 1024.0,
        "moment_error": f.friction / ref.friction_eq6 - 1,
        "moment_estimate": f.error_estimate.get("friction", float("nan")),
        "dissipation_error": f.friction_dissipation / ref.friction - 1,
        "dissipation_estimate": f.error_estimate.get("friction_dissipation", float("nan")),
        "contact_error": f.contact_fraction / ref.contact_fraction - 1,
        "warned": bool(f.warnings),
        "success": bool(f.success),
    }


def run(quick: bool = True, out_dir=".") -> dict:
    """Run the rows; print the table and write ``out_dir/fem_profile.json``."""
    env = thread_environment(2)
    if quick:
        jobs = [("4-term", V, QUICK_SQUARES) for V in (3e-2, 3e-1)]
    else:
        jobs = [(name, V, None) for name, (_, _, speeds) in RUBBERS.items() for V in speeds]
    rows = [run_in_fresh_process(profile_case, *job, env=env) for job in jobs]
    print(
        "FEM on rough profiles against the converged BEM (4096 points): default call"
        + (f", {QUICK_SQUARES} squares" if quick else "")
    )
    cols = ["rubber", "speed", "contact", "unknowns", "meshes", "wall_s", "peak_gib", "moment_error", "moment_estimate"]
    cols += ["dissipation_error", "dissipation_estimate", "contact_error", "warned", "success"]
    print(table(rows, cols))
    result = {"quick": quick, "rows": rows}
    write_record(out_dir, "fem_profile.json", result)
    return result


def main(argv=None):
    bench_main(
        run,
        __doc__.splitlines()[0],
        "fem_profile.json",
        argv,
        quick_help=f"the 4-term rubber at two speeds on {QUICK_SQUARES} squares",
    )


if __name__ == "__main__":
    main()
