"""Convergence of the FEM reference: observed orders in mesh size, domain size and time step.

Each study refines one parameter with the others fixed and prints the errors and the observed
order between successive rows, ``log(e_i / e_{i+1}) / log(s_i / s_{i+1})`` for a step size ``s``
(element size, inverse domain size, time step):

- ``mesh``: a standard linear solid (E_inf/E0 = 3, nu = 0.5) rolling at ``V lambda = a0`` (the
  leading-edge layer resolved) on a block of ``L = 300 a0`` (truncation below the mesh error),
  against Hunter's exact solution, over the resolution (elements per glassy half-width;
  ``h = a_inf / resolution``);
- ``domain``: the same at ``V lambda = 10 a0``, resolution 4, over the block's half-width
  ``L`` (= depth) in retardation lengths; the truncation error is taken against the largest
  block, so that the mesh error, common to all rows, cancels;
- ``graded``: the squares graded toward the contact in both directions (``mesh="quadtree"``) as a family:
  every size the contact sets times ``c`` and the growth ``grading - 1`` times ``c``, so that each
  element shrinks with ``c`` (:func:`graded_family_case`), on a block of ``4000 a0`` (truncation
  about 1e-6, below the mesh error of every row), against Hunter for standard solids at
  E_inf/E0 = 10 and 100 at ``V lambda = a0``; the order is in ``c``;
- ``time step``: creep indentation under a step load (E_inf/E0 = 3), the approach at
  ``t = 0.3, 1, 3 lambda`` over the steps per decade of time, against the finest run
  (self-convergence: the spatial error is common to all rows and cancels), and against
  Lee & Radok (spatial error included).

The rows run in fresh interpreters with two BLAS threads (:mod:`viscobem_bench.fem`).
Run: ``viscobem bench fem_convergence [--quick] --out DIR`` (writes
``DIR/fem_convergence.json``).
"""

from __future__ import annotations

import time

import numpy as np

from viscobem_bench.fem import hunter_errors, rolling_case, standard_solid, table
from viscobem_bench.instruments import bench_main, run_in_fresh_process, thread_environment, write_record

__all__ = ["observed_orders", "graded_family_case", "family_study", "time_step_study", "run", "main"]

TIMES = (0.3, 1.0, 3.0)  # output times of the time-step study, in creep times


def observed_orders(steps, errors):
    """Orders ``log(e_i / e_{i+1}) / log(s_i / s_{i+1})`` between successive rows (``nan`` where an
    error is zero or the step does not change)."""
    s = np.abs(np.asarray(steps, float))
    e = np.abs(np.asarray(errors, float))
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.log(e[:-1] / e[1:]) / np.log(s[:-1] / s[1:])
    return np.where(np.isfinite(out), out, np.nan)


FAMILY_BLOCK = 4000.0  # the graded family's block half-width, in relaxed half-widths a0


def graded_family_case(ratio, c, ell=1.0):
    """Hunter's standard solid (E0 = 1 MPa, ``E_inf = ratio E0``, creep time 10 ms, nu = 0.5;
    R = 10 mm, 1000 N/m) rolling at ``V lambda = ell a0`` on the quadtree of scale ``c``:
    resolution ``8 / c`` and growth ``1 + c (g - 1)`` about its default ``g``, on a block of
    :data:`FAMILY_BLOCK` ``a0``; the errors against Hunter (:func:`viscobem_bench.fem.hunter_errors`)."""
    from bem import Material
    from fem_reference import rolling_cylinder
    from fem_reference.rolling_inputs import QUADTREE_GRADING
    from validation.references import hunter
    from validation.references.hertz import line_contact

    m = Material.standard_linear_solid(E0=1e6, E_inf=ratio * 1e6, creep_time=0.01, nu=0.5)
    R, P = 0.01, 1000.0
    a0 = line_contact(m.E0, m.nu, R, P).a
    V = ell * a0 / float(m.creep_times[0])
    t0 = time.perf_counter()
    r = rolling_cylinder(
        m,
        radius=R,
        load=P,
        speed=V,
        resolution=round(8 / c),
        grading=1 + c * (QUADTREE_GRADING - 1),
        domain=FAMILY_BLOCK * a0,
        mesh="quadtree",
        estimate=False,
    )
    wall = time.perf_counter() - t0
    h = hunter.rolling_cylinder(m, radius=R, load=P, speed=V)
    return {
        "ratio": ratio,
        "ell_r_over_a0": ell,
        "scale": c,
        "unknowns": r.n_unknowns,
        "success": r.success,
        **hunter_errors(r, h, a0, "a0"),
        "wall_s": wall,
    }


def family_study(ratio, scales, fresh=None):
    """:func:`graded_family_case` over ``scales`` (decreasing), with the observed orders in the scale."""
    call = fresh or (lambda f, *a: f(*a))
    rows = [call(graded_family_case, ratio, c) for c in scales]
    for key in ("friction_error", "dissipation_friction_error", "peak_pressure_error"):
        _add_orders(rows, scales, key, "order_" + key[: -len("_error")])
    return rows


def _indentation_approach(resolution, steps_per_decade):
    from bem import Material
    from fem_reference import indentation

    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, creep_time=1.0, nu=0.5)
    R, P = 0.01, 1.0
    times = np.array([0.0, *TIMES]) * float(np.max(m.creep_times))
    t0 = time.perf_counter()
    r = indentation(m, radius=R, load=P, times=times, resolution=resolution, steps_per_decade=steps_per_decade)
    a_lr = (0.75 * R * P * (1 - m.nu**2) * m.creep_compliance(times)) ** (1 / 3)
    return {
        "steps_per_decade": steps_per_decade,
        "steps": r.n_steps,
        "approach": r.approach[1:].tolist(),
        "lee_radok_error": (r.approach[1:] / (a_lr[1:] ** 2 / R) - 1).tolist(),
        "wall_s": time.perf_counter() - t0,
    }


def time_step_study(resolution, steps, fresh=None):
    """Approach errors over ``steps`` (steps per decade, increasing), self-convergence against the
    last row; returns the rows with ``self_error`` (max over the output times) and ``order``."""
    call = fresh or (lambda f, *a: f(*a))
    rows = [call(_indentation_approach, resolution, n) for n in steps]
    finest = np.array(rows[-1]["approach"])
    for row in rows:
        row["self_error"] = float(np.max(np.abs(np.array(row["approach"]) / finest - 1)))
        row["lee_radok_error_max"] = float(np.max(np.abs(row["lee_radok_error"])))
    _add_orders(rows[:-1], [1.0 / n for n in steps[:-1]], "self_error", "order")
    rows[-1]["order"] = float("nan")
    return rows


def _add_orders(rows, steps, key, name):
    orders = observed_orders(steps, [r[key] for r in rows])
    for row, p in zip(rows, [float("nan"), *orders]):
        row[name] = float(p)


def run(quick: bool = True, out_dir=".") -> dict:
    """Run the three studies; print tables and write ``out_dir/fem_convergence.json``."""
    env = thread_environment(2)

    def fresh(func, *args):
        return run_in_fresh_process(func, *args, env=env)

    m = standard_solid()
    resolutions = [1, 2] if quick else [2, 3, 4, 6, 8]
    mesh = [fresh(rolling_case, m, 1.0, n, 300) for n in resolutions]
    for key in ("friction_error", "dissipation_friction_error", "peak_pressure_error", "leading_edge_error_over_a0"):
        _add_orders(mesh, [1.0 / n for n in resolutions], key, "order_" + key[: -len("_error")])
    domains = [5, 10] if quick else [5, 10, 20, 40, 100]
    domain = [fresh(rolling_case, m, 10.0, 2 if quick else 4, d) for d in domains]
    for row in domain:  # truncation error: against the largest block (the mesh error is common)
        row["truncation_error"] = row["friction"] / domain[-1]["friction"] - 1
    _add_orders(domain[:-1], [1.0 / d for d in domains[:-1]], "truncation_error", "order")
    domain[-1]["order"] = float("nan")
    scales = [2.0, 1.0] if quick else [4.0, 2.0, 1.0, 0.5]
    graded = [row for ratio in ((10.0,) if quick else (10.0, 100.0)) for row in family_study(ratio, scales, fresh)]
    steps = [2, 4, 8] if quick else [2, 4, 8, 16, 32, 64]
    tstep = time_step_study(2 if quick else 4, steps, fresh)

    print("mesh size: rolling SLS (E_inf/E0 = 3) at V lambda = a0 against Hunter, L = 300 a0; h = a_inf / resolution")
    cols = ["resolution", "unknowns", "friction_error", "order_friction", "dissipation_friction_error"]
    cols += ["order_dissipation_friction", "peak_pressure_error", "leading_edge_error_over_a0", "wall_s"]
    print(table(mesh, cols))
    print(f"\ndomain size: same at V lambda = 10 a0, resolution {domain[0]['resolution']}; L in retardation lengths;")
    print("truncation error of the friction against the largest block, order in 1/L")
    print(table(domain, ["domain_over_ell_r", "friction_error", "truncation_error", "order", "wall_s"]))
    print(
        f"\ngraded family: standard solids at V lambda = a0 on the quadtree, L = {FAMILY_BLOCK:g} a0, sizes and growth times c"
    )
    cols = ["ratio", "scale", "unknowns", "friction_error", "order_friction", "dissipation_friction_error"]
    print(table(graded, cols + ["order_dissipation_friction", "peak_pressure_error", "wall_s"]))
    print("\ntime step: creep indentation, approach at t = 0.3, 1, 3 lambda; against the finest run, order in 1/steps")
    print(table(tstep, ["steps_per_decade", "steps", "self_error", "order", "lee_radok_error_max", "wall_s"]))
    result = {"quick": quick, "mesh": mesh, "domain": domain, "graded": graded, "time_step": tstep}
    write_record(out_dir, "fem_convergence.json", result)
    return result


def main(argv=None):
    bench_main(run, __doc__.splitlines()[0], "fem_convergence.json", argv, quick_help="coarse rows (a smoke test)")


if __name__ == "__main__":
    main()
