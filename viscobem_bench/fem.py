"""Benchmark of the FEM reference: error against run time and memory.

Cases (all SI; R = 10 mm):

- ``rolling``: a standard linear solid (E0 = 1 MPa, E_inf/E0 = 3, nu = 0.5) rolling at
  retardation length ``V lambda = ell a0`` under P = 100 N/m, against Hunter's exact
  solution (validation.references.hunter): friction and peak-pressure errors of the uniform mesh
  (``mesh="uniform"``) over its resolution (elements per glassy half-width) and domain size (in units of ``V lambda``);
- ``solvers``: the same rolling case factorised with SuperLU and, if installed, PARDISO;
- ``indentation``: creep under a step load (P = 1 N) against Lee & Radok, over mesh
  resolution and at the defaults, with the result's own error estimates beside the errors;
- ``rubber``: real rubbers on the default (graded) mesh with SuperLU: an 8-term
  Prony series with E_inf/E0 = 300 and a 20-term one with E_inf/E0 = 1000 (E0 = 1 MPa,
  relaxation times 1e-5..1e-1 s, equal moduli; R = 20 mm, P = 1500 N/m) at the isolated
  BEM's friction peak and a decade below, against the BEM on 2^14 points (friction,
  peak pressure, edges over the contact width), with unknowns, assemble / factor /
  flexibility / contact times, linear residual and peak memory.
- ``high_ratio``: a standard linear solid with E_inf/E0 = 1000 (E0 = 2 MPa, relaxation time
  10 ms, nu = 0.5, R = 20 mm, P = 500 N/m) at Hunter's friction peak on the graded mesh, against
  Hunter's exact solution: friction (both forms), peak pressure and edges over the resolution,
  the grading ratio and the block size, with unknowns, CPU time and peak memory.
- ``broad``: broad-spectrum rubbers with the default linear solver at five speeds (two decades
  and a decade below the BEM's friction peak, the peak, a decade and two decades above), against the
  isolated BEM on 2^13 points (its adaptive mesh where the uniform solve does not converge):
  ``lognormal10`` (10 terms, E_inf/E0 = 500, log-normal weights of one decade's width over
  tau = 10^-5.5..10^-0.5 s, E0 = 1.5 MPa, R = 15 mm, 1000 N/m), ``power12`` (12 terms,
  E_inf/E0 = 1000, weights ``tau^-1/2`` over 1e-7..1 s, E0 = 2 MPa, R = 20 mm, 500 N/m) and
  ``equal20`` (the 20-term rubber above) and ``glass18`` (a glass transition: 18 terms,
  E_inf/E0 = 2000, weights ``tau^-0.3`` rising toward short times over 1e-9..1e2 s, E0 = 1 MPa,
  R = 20 mm, 1000 N/m); with unknowns, system and factor entries, condensed
  terms, CPU time and peak resident memory (``--quick``: ``lognormal10`` at its peak).

Each case runs in a fresh interpreter (:func:`viscobem_bench.instruments.run_in_fresh_process`)
with BLAS/MKL threads pinned to 2, so its peak resident set size is its own.

Run: ``python -m viscobem_bench.fem --quick --out DIR`` (writes ``DIR/fem_benchmark.json``).
"""

from __future__ import annotations

import time

import numpy as np

from viscobem_bench.instruments import bench_main, peak_rss, run_in_fresh_process, thread_environment, write_record


def _peak_rss_mb():
    return peak_rss() / 2**20


def standard_solid():
    from bem import Material

    return Material.standard_linear_solid(E0=1e6, E_inf=3e6, relaxation_time=0.01, nu=0.5)


def hunter_errors(r, h, length, name):
    """Relative errors of a rolling result ``r`` against Hunter's ``h``: friction (both forms), peak
    pressure, and the edges over ``length`` (keys ``*_over_<name>``)."""
    return {
        "friction_error": r.friction / h.friction - 1,
        "dissipation_friction_error": r.friction_dissipation / h.friction - 1,
        "peak_pressure_error": r.peak_pressure / h.peak_pressure - 1,
        f"leading_edge_error_over_{name}": (r.leading_edge - h.leading_edge) / length,
        f"trailing_edge_error_over_{name}": (r.trailing_edge - h.trailing_edge) / length,
    }


def path(r):
    """The factorisations a rolling result took, in order (``carried``: every term carried)."""
    steps = (s["solver"] + (" carried" if s["form"] == "carried" else "") for s in r.solver_path)
    return {"solver_path": " > ".join(steps)}


def estimates(r):
    """The rolling result's error estimates of the friction in both forms (NaN where it has none)."""
    nan = float("nan")
    return {
        "friction_estimate": r.error_estimate.get("friction", nan),
        "dissipation_friction_estimate": r.error_estimate.get("friction_dissipation", nan),
    }


def rolling_case(material, ell, resolution, domain_factor, solver="auto", grading=1.3):
    from fem_reference import rolling_cylinder
    from validation.references import hunter
    from validation.references.hertz import line_contact

    R, P = 0.01, 100.0
    a0 = line_contact(material.E0, material.nu, R, P).a
    V = ell * a0 / material.creep_times[0]
    domain = max(40 * a0, domain_factor * ell * a0)
    t0 = time.perf_counter()
    # the uniform mesh, whose resolution counts elements per glassy half-width (its convergence in h)
    r = rolling_cylinder(
        material,
        radius=R,
        load=P,
        speed=V,
        resolution=resolution,
        domain=domain,
        grading=grading,
        solver=solver,
        mesh="uniform",
    )
    wall = time.perf_counter() - t0
    h = hunter.rolling_cylinder(material, radius=R, load=P, speed=V)
    return {
        "ell_r_over_a0": ell,
        "resolution": resolution,
        "domain_over_ell_r": domain / (ell * a0),
        "grading": grading,
        "solver": solver,
        "unknowns": r.n_unknowns,
        "elements": r.n_elements,
        "friction": r.friction,
        "friction_hunter": h.friction,
        **hunter_errors(r, h, a0, "a0"),
        "wall_s": wall,
        "timings": r.timings,
        "peak_rss_mb": _peak_rss_mb(),
    }


def _indentation_case(resolution=None, steps_per_decade=None):
    """One creep run against Lee & Radok; ``None`` leaves the argument at its default (the row
    the users get)."""
    from bem import Material
    from fem_reference import indentation

    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, creep_time=1.0, nu=0.5)
    R, P = 0.01, 1.0
    times = np.array([0.0, 0.3, 1.0, 3.0, 10.0, 100.0])
    mesh = {k: v for k, v in (("resolution", resolution), ("steps_per_decade", steps_per_decade)) if v is not None}
    t0 = time.perf_counter()
    r = indentation(m, radius=R, load=P, times=times, **mesh)
    wall = time.perf_counter() - t0
    a_lr = (0.75 * R * P * (1 - m.nu**2) * m.creep_compliance(times)) ** (1 / 3)
    return {
        "resolution": resolution or "default",
        "steps_per_decade": steps_per_decade or "default",
        "unknowns": r.n_unknowns,
        "steps": r.n_steps,
        "max_radius_error": float(np.max(np.abs(r.contact_radius / a_lr - 1))),
        "max_approach_error": float(np.max(np.abs(r.approach / (a_lr**2 / R) - 1))),
        "max_radius_estimate": float(np.max(r.error_estimate["contact_radius"])),
        "max_approach_estimate": float(np.max(r.error_estimate["approach"])),
        "wall_s": wall,
        "peak_rss_mb": _peak_rss_mb(),
    }


def _rubber_material(terms, ratio):
    from bem import Material

    return Material.from_prony(
        E0=1e6, moduli=np.full(terms, (ratio - 1) * 1e6 / terms), times=np.logspace(-5, -1, terms), nu=0.5
    )


def _rubber_bem(terms, ratio, speed, n=2**14):
    import bem
    from bem.surfaces import cylinder

    m = _rubber_material(terms, ratio)
    R, P = 0.02, 1500.0
    a0 = np.sqrt(4 * P * R * (1 - m.nu**2) / (np.pi * m.E0))
    s = cylinder(radius=R, n=n, length=2.2 * a0)
    r = bem.solve(s, m, speed=speed, load=P, periodic=False, method="uniform")
    act = np.flatnonzero(r.pressure > 0)
    dx = s.x[1] - s.x[0]
    lead, trail = s.x[act[-1]] + dx / 2, s.x[act[0]] - dx / 2
    return {
        "friction": r.friction,
        "peak_pressure": float(r.pressure.max()),
        "leading_edge": lead,
        "trailing_edge": trail,
        "width": lead - trail,
    }


def _rubber_peak_speed(terms, ratio):
    import scipy.optimize as so

    res = so.minimize_scalar(
        lambda lv: -_rubber_bem(terms, ratio, 10**lv, n=2**12)["friction"],
        bounds=(-4.5, -1.5),
        method="bounded",
        options={"xatol": 0.01},
    )
    return float(10**res.x)


def _rubber_case(terms, ratio, speed, resolution):
    from fem_reference import rolling_cylinder

    ref = _rubber_bem(terms, ratio, speed)
    t0, c0 = time.perf_counter(), time.process_time()
    r = rolling_cylinder(
        _rubber_material(terms, ratio), radius=0.02, load=1500.0, speed=speed, resolution=resolution, solver="splu"
    )
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    w = ref["width"]
    return {
        "terms": terms,
        "ratio": ratio,
        "speed": speed,
        "resolution": resolution,
        "unknowns": r.n_unknowns,
        "nonzeros": r.n_nonzeros,
        "factor_nonzeros": r.factor_nonzeros,
        "cpu_s": cpu,
        "peak_resolved": r.peak_resolved,
        "elements": r.n_elements,
        "passes": r.passes,
        "kept": len(r.terms["kept"]),
        "friction_error": r.friction / ref["friction"] - 1,
        "dissipation_friction_error": r.friction_dissipation / ref["friction"] - 1,
        **estimates(r),
        "peak_pressure_error": r.peak_pressure / ref["peak_pressure"] - 1,
        "leading_edge_error_over_width": (r.leading_edge - ref["leading_edge"]) / w,
        "trailing_edge_error_over_width": (r.trailing_edge - ref["trailing_edge"]) / w,
        "assemble_s": r.timings["assemble"],
        "factor_s": r.timings["factor"],
        "flexibility_s": r.timings["flexibility"],
        "contact_s": r.timings["contact"],
        "linear_residual": r.linear_residual,
        "linear_residual_limit": r.linear_residual_limit,
        "success": r.success,
        "wall_s": wall,
        "peak_rss_mb": _peak_rss_mb(),
    }


def rubber_rows(quick=True, fresh=None):
    """The ``rubber`` rows: each material at the BEM's friction peak and a decade below."""
    fresh = fresh or (lambda func, *args: func(*args))
    rows = []
    for terms, ratio in [(8, 300.0)] if quick else [(8, 300.0), (20, 1000.0)]:
        peak = _rubber_peak_speed(terms, ratio)
        for speed in (peak, peak / 10):
            rows.append(fresh(_rubber_case, terms, ratio, speed, 6))
    cols = [
        "terms",
        "ratio",
        "speed",
        "unknowns",
        "passes",
        "friction_error",
        "dissipation_friction_error",
        "friction_estimate",
        "dissipation_friction_estimate",
        "peak_pressure_error",
        "leading_edge_error_over_width",
        "trailing_edge_error_over_width",
        "factor_s",
        "flexibility_s",
        "wall_s",
        "linear_residual",
        "linear_residual_limit",
        "success",
        "peak_rss_mb",
    ]
    print("\nrubbers on the graded mesh vs the isolated BEM (SuperLU)")
    print(table(rows, cols))
    return rows


def high_ratio_peak_speed(ratio=1000.0):
    """Hunter's friction peak speed (m/s) of the ``high_ratio`` solid."""
    import scipy.optimize as so

    from validation.references import hunter

    m, R, P = _high_ratio_material(ratio), 0.02, 500.0
    res = so.minimize_scalar(
        lambda lv: -hunter.rolling_cylinder(m, radius=R, load=P, speed=10**lv).friction,
        bounds=(-7.0, 1.0),
        method="bounded",
        options={"xatol": 1e-4},
    )
    return float(10**res.x)


def _high_ratio_material(ratio):
    from bem import Material

    return Material.standard_linear_solid(E0=2e6, E_inf=2e6 * ratio, relaxation_time=0.01, nu=0.5)


def high_ratio_case(ratio, speed, resolution, grading, domain_factor=None):
    """One graded-mesh FEM run of the ``high_ratio`` solid against Hunter; ``domain_factor`` scales
    the default block (``None``: the default)."""
    from fem_reference import domain_size, rolling_cylinder
    from validation.references import hunter

    m, R, P = _high_ratio_material(ratio), 0.02, 500.0
    L = domain_size(m, R, P, speed)
    domain = None if domain_factor is None else domain_factor * L
    t0, c0 = time.perf_counter(), time.process_time()
    r = rolling_cylinder(m, radius=R, load=P, speed=speed, resolution=resolution, grading=grading, domain=domain)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    h = hunter.rolling_cylinder(m, radius=R, load=P, speed=speed)
    width = 2 * h.half_width
    return {
        "ratio": ratio,
        "speed": speed,
        "resolution": resolution,
        "grading": grading,
        "domain_factor": 1.0 if domain_factor is None else domain_factor,
        "domain": r.domain_width,
        "unknowns": r.n_unknowns,
        "elements": r.n_elements,
        "passes": r.passes,
        **path(r),
        **hunter_errors(r, h, width, "width"),
        **estimates(r),
        "success": r.success,
        "cpu_s": cpu,
        "wall_s": wall,
        "peak_rss_mb": _peak_rss_mb(),
    }


HIGH_RATIO_COLS = [
    "resolution",
    "grading",
    "domain_factor",
    "unknowns",
    "passes",
    "solver_path",
    "friction_error",
    "dissipation_friction_error",
    "friction_estimate",
    "dissipation_friction_estimate",
    "peak_pressure_error",
    "leading_edge_error_over_width",
    "trailing_edge_error_over_width",
    "cpu_s",
    "peak_rss_mb",
]


def high_ratio_rows(quick=True, fresh=None):
    """The ``high_ratio`` rows at the friction peak: resolution (grading 1.5), grading (resolution 6)
    and block size (resolution 6, grading 1.5)."""
    fresh = fresh or (lambda func, *args: func(*args))
    V = high_ratio_peak_speed()
    settings = [(3, 1.5, None), (6, 1.5, None)]
    if not quick:
        settings += [(12, 1.5, None), (6, 1.3, None), (6, 1.5, 0.5), (6, 1.5, 2.0)]
    rows = [fresh(high_ratio_case, 1000.0, V, n, g, d) for n, g, d in settings]
    print(f"\nSLS E_inf/E0 = 1000 at its friction peak (V = {V:.4g} m/s), graded mesh, against Hunter")
    print(table(rows, HIGH_RATIO_COLS))
    return rows


def broad_material(name):
    """``(material, R, P)`` of a ``broad`` rubber (see the module docstring)."""
    from bem import Material

    if name == "lognormal10":
        t = np.logspace(-5.5, -0.5, 10)
        w = np.exp(-0.5 * (np.log10(t) + 3.0) ** 2)
        return Material.from_prony(E0=1.5e6, moduli=499 * 1.5e6 * w / w.sum(), times=t, nu=0.5), 0.015, 1000.0
    if name == "power12":
        t = np.logspace(-7, 0, 12)
        w = t**-0.5
        return Material.from_prony(E0=2e6, moduli=999 * 2e6 * w / w.sum(), times=t, nu=0.5), 0.02, 500.0
    if name == "equal20":
        return _rubber_material(20, 1000.0), 0.02, 1500.0
    if name == "glass18":
        t = np.logspace(-9, 2, 18)
        w = t**-0.3
        return Material.from_prony(E0=1e6, moduli=1999 * 1e6 * w / w.sum(), times=t, nu=0.5), 0.02, 1000.0
    raise ValueError(f"unknown broad rubber {name!r}")


def broad_bem(name, speed, n=2**13, fallback=True):
    """Friction of the isolated BEM on ``n`` points (uniform; adaptive where that fails)."""
    import bem
    from bem.errors import ConvergenceError
    from bem.surfaces import cylinder

    m, R, P = broad_material(name)
    a0 = np.sqrt(4 * P * R * (1 - m.nu**2) / (np.pi * m.E0))
    surface = cylinder(radius=R, n=n, length=2.2 * a0)
    try:
        return bem.solve(surface, m, speed=speed, load=P, periodic=False, method="uniform").friction
    except ConvergenceError:
        if not fallback:
            raise
        return bem.solve(surface, m, speed=speed, load=P, periodic=False, method="adaptive").friction


def broad_peak_speed(name):
    """The BEM's friction peak (m/s) on 2^12 points: half-decade scan, then tenths of a decade."""
    from bem.errors import ConvergenceError

    def friction(lv):
        try:
            return broad_bem(name, 10**lv, n=2**12, fallback=False)
        except ConvergenceError:
            return -1.0

    coarse = np.arange(-7.0, 1.01, 0.5)
    best = coarse[int(np.argmax([friction(v) for v in coarse]))]
    fine = np.linspace(best - 0.5, best + 0.5, 11)
    return float(10 ** fine[int(np.argmax([friction(v) for v in fine]))])


def broad_case(name, speed, decades):
    """One default FEM run of a ``broad`` rubber against the BEM."""
    from fem_reference import rolling_cylinder

    m, R, P = broad_material(name)
    ref = broad_bem(name, speed)
    t0, c0 = time.perf_counter(), time.process_time()
    r = rolling_cylinder(m, radius=R, load=P, speed=speed)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    return {
        "rubber": name,
        "decades_from_peak": decades,
        "speed": speed,
        "unknowns": r.n_unknowns,
        "nonzeros": r.n_nonzeros,
        "factor_nonzeros": r.factor_nonzeros,
        **path(r),
        "passes": r.passes,
        "kept": len(r.terms["kept"]),
        "condensed": sum(r.condensed),
        "friction_bem": ref,
        "friction_error": r.friction / ref - 1,
        "dissipation_friction_error": r.friction_dissipation / ref - 1,
        **estimates(r),
        "success": r.success,
        "cpu_s": cpu,
        "wall_s": wall,
        "peak_rss_mb": _peak_rss_mb(),
    }


BROAD_COLS = [
    "rubber",
    "decades_from_peak",
    "speed",
    "unknowns",
    "nonzeros",
    "factor_nonzeros",
    "solver_path",
    "kept",
    "condensed",
    "friction_error",
    "dissipation_friction_error",
    "friction_estimate",
    "dissipation_friction_estimate",
    "success",
    "cpu_s",
    "wall_s",
    "peak_rss_mb",
]


def broad_rows(quick=True, fresh=None):
    """The ``broad`` rows: each broad-spectrum rubber at four speeds around its friction peak."""
    fresh = fresh or (lambda func, *args: func(*args))
    rows = []
    for name in ["lognormal10"] if quick else ["lognormal10", "power12", "equal20", "glass18"]:
        peak = broad_peak_speed(name)
        for decades in [0] if quick else [-2, -1, 0, 1, 2]:
            rows.append(fresh(broad_case, name, peak * 10.0**decades, decades))
    print("\nbroad-spectrum rubbers on the graded mesh vs the isolated BEM (default solver)")
    print(table(rows, BROAD_COLS))
    return rows


def table(rows, cols):
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

    m = standard_solid()
    resolutions = [2, 3, 4] if quick else [2, 3, 4, 6, 8]
    domains = [3, 10, 30] if quick else [3, 10, 30, 100]
    rolling = [fresh(rolling_case, m, 1.0, n, 30) for n in resolutions]
    rolling += [fresh(rolling_case, m, 10.0, 3, d) for d in domains]
    rolling += [fresh(rolling_case, m, 100.0, n, 30, "auto", 2.0) for n in ([3, 5] if quick else [3, 5, 8])]
    solvers = ["splu"] + (["pardiso"] if pardiso_available() else [])
    solver_rows = [fresh(rolling_case, m, 1.0, 4 if quick else 6, 30, s) for s in solvers]
    ind = [fresh(_indentation_case, n, 20) for n in ([4, 6] if quick else [4, 6, 8, 16])]
    ind.append(fresh(_indentation_case))

    cols = [
        "ell_r_over_a0",
        "resolution",
        "domain_over_ell_r",
        "grading",
        "unknowns",
        "friction_error",
        "dissipation_friction_error",
        "peak_pressure_error",
        "wall_s",
        "peak_rss_mb",
    ]
    print("rolling cylinder vs Hunter (SLS, E_inf/E0 = 3, nu = 0.5)")
    print(table(rolling, cols))
    print("\nsparse direct solvers (same case)")
    srows = [
        dict(r, factor_s=r["timings"]["assemble_factor"], flexibility_s=r["timings"]["flexibility"])
        for r in solver_rows
    ]
    print(table(srows, ["solver", "unknowns", "factor_s", "flexibility_s", "wall_s", "friction_error"]))
    print("\nindentation vs Lee-Radok (SLS, creep time 1 s)")
    print(
        table(
            ind,
            [
                "resolution",
                "steps_per_decade",
                "unknowns",
                "steps",
                "max_radius_error",
                "max_radius_estimate",
                "max_approach_error",
                "max_approach_estimate",
                "wall_s",
                "peak_rss_mb",
            ],
        )
    )
    rubber = rubber_rows(quick, fresh)
    high = high_ratio_rows(quick, fresh)
    broad = broad_rows(quick, fresh)
    result = {
        "quick": quick,
        "rolling": rolling,
        "solvers": srows,
        "indentation": ind,
        "rubber": rubber,
        "high_ratio": high,
        "broad": broad,
    }
    write_record(out_dir, "fem_benchmark.json", result)
    return result


def main(argv=None):
    bench_main(run, __doc__.splitlines()[0], "fem_benchmark.json", argv)


if __name__ == "__main__":
    main()
