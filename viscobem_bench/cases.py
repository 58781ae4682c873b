"""Solver benchmarks of ``viscobem bench``: each sweeps its resolution and tolerance knobs
and reports, per point, the error against an exact or converged reference, the wall time
and the peak resident memory of its process (``ru_maxrss``).

Adding a solver takes one function and a decorator (the isolated uniform and adaptive BEM
entries, against Hunter's exact rolling cylinder, are written this way)::

    def _isolated_group(group, quick):  # runs in a fresh process; returns a list of points
        ...  # build the sphere on group["n"]², solve per rtol, compare with validation.references.hertz
        return [{"n": n, "rtol": rtol, "error": err, "time": t, "peak_rss": instruments.peak_rss()}]

    @register("isolated-hertz", solver="isolated BEM", measure=_isolated_group, knobs=("n", "rtol"),
              problem="rigid sphere on an SLS", reference="Hertz (exact, both limits)",
              error="rel. L2 pressure error")
    def _isolated(quick):  # one group = one fresh process
        for n in (64, 128) if quick else (64, 128, 256, 512):
            yield {"n": n}
"""

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from viscobem_bench import instruments

L = 0.01  # m: the cell of every periodic case (tamaas worker of viscobem_bench.periodic uses it too)
E_ELASTIC = 1e7  # Pa
RTOLS = (1e-4, 1e-6, 1e-8, 1e-10)
RTOL_REF = 1e-12


# ---------------------------------------------------------------- registry
@dataclass(frozen=True)
class SolverBenchmark:
    """One solver's error-against-time benchmark.

    ``groups(quick)`` yields picklable dicts; ``measure(group, quick)`` runs one group in a
    fresh process and returns a list of points, each with at least ``error`` (dimensionless),
    ``time`` (s) and ``peak_rss`` (bytes) and the knob values named in ``knobs``.
    """

    name: str
    solver: str
    problem: str
    reference: str
    error: str
    knobs: tuple
    groups: Callable
    measure: Callable
    env: dict = field(default_factory=lambda: instruments.thread_environment(1))


REGISTRY = {}


def register(name, *, solver, problem, reference, error, knobs, measure, env=None):
    """Decorator adding a :class:`SolverBenchmark` whose group generator it decorates."""

    def wrap(groups):
        REGISTRY[name] = SolverBenchmark(
            name,
            solver,
            problem,
            reference,
            error,
            tuple(knobs),
            groups,
            measure,
            env or instruments.thread_environment(1),
        )
        return groups

    return wrap


def timed(func):
    t0 = time.perf_counter()
    out = func()
    return out, time.perf_counter() - t0


# ---------------------------------------------------------------- periodic BEM, Westergaard
def _westergaard_group(group, quick):
    import bem
    from validation.references.westergaard import westergaard

    n, amplitude = group["n"], 1e-6
    m = bem.Material.elastic(E_ELASTIC)
    surface = bem.surfaces.sinusoid(n, L, amplitude=amplitude, dim=2, direction="x")
    exact = westergaard(amplitude, L, 0.5 * np.pi * m.E0 / (1 - m.nu**2) * amplitude / L, m.E0, m.nu)
    p_exact = np.broadcast_to(exact.pressure(surface.x)[:, None], surface.shape)
    # rtol 1e-12 on the same grid (the tolerance's share of the error); also warms up FFT plans
    tight = bem.solve(surface, m, speed=0.0, load=exact.mean_pressure * L**2, rtol=RTOL_REF).pressure
    points = []
    for rtol in RTOLS:
        res, t = timed(lambda rtol=rtol: bem.solve(surface, m, speed=0.0, load=exact.mean_pressure * L**2, rtol=rtol))
        err = float(np.linalg.norm(res.pressure - p_exact) / np.linalg.norm(p_exact))
        points.append(
            {
                "n": n,
                "rtol": rtol,
                "error": err,
                "time": t,
                "peak_rss": instruments.peak_rss(),
                "iterations": res.iterations,
                "matvecs": res.matvecs,
                "contact_fraction": res.contact_fraction,
                "tolerance_error": float(np.linalg.norm(res.pressure - tight) / np.linalg.norm(tight)),
            }
        )
    return points


@register(
    "periodic-westergaard",
    solver="periodic BEM",
    measure=_westergaard_group,
    problem="2-D cell, rigid sinusoid (ridges along y) on an elastic half-space, p = p*/2",
    reference="Westergaard (exact)",
    error="rel. L2 pressure error at the nodes",
    knobs=("n", "rtol"),
)
def _westergaard(quick):
    for n in (64, 128, 256, 512) if quick else (64, 128, 256, 512, 1024):
        yield {"n": n}


# ---------------------------------------------------------------- periodic BEM, rough viscoelastic
BASE_N = 64
ROUGH = dict(hurst=0.8, scales=16, rms_slope=0.1, seed=1)


def rough_heights(n):
    """The benchmark surface (generated on 64², 16 scales) on an ``n x n`` grid, n >= 64: the
    spectrum is zero-padded, so every size sees exactly the same band-limited surface."""
    import bem
    from bem import fft

    h = bem.surfaces.self_affine(BASE_N, L, **ROUGH).heights
    if n == BASE_N:
        return np.array(h)
    hq, half = fft.forward(h), BASE_N // 2  # Nyquist row and column are zero (16 < 32 scales)
    big = np.zeros((n, n // 2 + 1), dtype=complex)
    big[:half, : half + 1] = hq[:half, : half + 1]
    big[n - half :, : half + 1] = hq[half:, : half + 1]
    return fft.inverse(big, (n, n))


def rough_load(material):
    """Load (N) for ~10 % contact: Persson's A/A0 ~ sqrt(8/pi) p / (E* slope), with E0."""
    e_star = material.E0 / (1 - material.nu**2)
    return 0.1 * e_star * ROUGH["rms_slope"] / np.sqrt(8 / np.pi) * L**2


def seed_material():
    import bem

    return bem.Material.standard_linear_solid(E0=E_ELASTIC / 3, E_inf=E_ELASTIC, creep_time=0.01)


def _rough_group(group, quick):
    import bem

    m = seed_material()
    speed = 1e-2 * L / m.creep_times[0]  # xi = 1e-2
    surface = bem.surfaces.from_heights(rough_heights(group["n"]), L)
    bem.solve(surface, m, speed=speed, load=rough_load(m), rtol=1e-4)  # warm-up (FFT plans), untimed
    points = []
    for rtol in group["rtols"]:
        res, t = timed(lambda rtol=rtol: bem.solve(surface, m, speed=speed, load=rough_load(m), rtol=rtol))
        points.append(
            {
                "n": group["n"],
                "rtol": rtol,
                "friction": res.friction,
                "time": t,
                "peak_rss": instruments.peak_rss(),
                "iterations": res.iterations,
                "matvecs": res.matvecs,
                "contact_fraction": res.contact_fraction,
                "pressure": res.pressure,
            }
        )
    # the tolerance's own share of the error: pressure against the same grid at rtol 1e-12
    tight = (
        points[-1]["pressure"]
        if group["rtols"][-1] == RTOL_REF
        else bem.solve(surface, m, speed=speed, load=rough_load(m), rtol=RTOL_REF).pressure
    )
    for p in points:
        p["tolerance_error"] = float(np.linalg.norm(p.pop("pressure") - tight) / np.linalg.norm(tight))
    return points


@register(
    "periodic-rough-viscoelastic",
    solver="periodic BEM",
    measure=_rough_group,
    problem="self-affine surface (H 0.8, 16 scales, rms slope 0.1), seed SLS at xi = 1e-2, ~10 % contact",
    reference="converged: finest grid at rtol 1e-12",
    error="rel. friction error",
    knobs=("n", "rtol"),
)
# (each point also carries ``tolerance_error``: rel. L2 pressure error against rtol 1e-12 on its own grid)
def _rough(quick):
    sizes = (64, 128, 256) if quick else (64, 128, 256, 512)
    for n in sizes:
        yield {"n": n, "rtols": RTOLS}
    yield {"n": 2 * sizes[-1], "rtols": (RTOL_REF,), "reference": True}


def _rough_finish(points):
    """Errors of every point against the reference point (finest grid, tightest rtol)."""
    ref = [p for p in points if p["rtol"] == RTOL_REF]
    if not ref:
        return points
    mu = ref[0]["friction"]
    for p in points:
        p["error"] = abs(p["friction"] / mu - 1) if p is not ref[0] else None
        p["reference"] = p is ref[0]
    return points


# ---------------------------------------------------------------- FEM, Hunter
def _fem_group(group, quick):
    from viscobem_bench.fem import rolling_case, standard_solid

    r = rolling_case(standard_solid(), 1.0, group["resolution"], group["domain"])
    return [
        {
            "resolution": group["resolution"],
            "domain": group["domain"],
            "error": abs(r["friction_error"]),
            "peak_pressure_error": abs(r["peak_pressure_error"]),
            "time": r["wall_s"],
            "peak_rss": instruments.peak_rss(),
            "unknowns": r["unknowns"],
        }
    ]


@register(
    "fem-hunter",
    solver="FEM (scikit-fem)",
    measure=_fem_group,
    env=instruments.thread_environment(2),
    problem="rigid cylinder rolling on an SLS (E_inf/E0 = 3), V lambda = a0, P = 100 N/m, R = 10 mm",
    reference="Hunter (exact)",
    error="rel. friction error",
    knobs=("resolution", "domain"),
)
def _fem(quick):
    for res in (2, 3, 4) if quick else (2, 3, 4, 6, 8):
        yield {"resolution": res, "domain": 30}
    for dom in (3, 10) if quick else (3, 10, 100):
        yield {"resolution": 3, "domain": dom}


# ---------------------------------------------------------------- isolated BEM (uniform, adaptive), Hunter
def _hunter_reference(factor):
    """Hunter's exact friction and peak pressure for viscobem_bench.isolated's cylinder problem."""
    from validation.references.hunter import rolling_cylinder
    from viscobem_bench.isolated import LOADS, RADIUS, contact_half_width, seed_material

    m = seed_material()
    exact = rolling_cylinder(
        m, radius=RADIUS, load=LOADS["cylinder"], speed=factor * contact_half_width("cylinder", m) / m.creep_times[0]
    )
    return exact.friction, exact.peak_pressure


def _isolated_group(group, quick):
    from viscobem_bench.isolated import run_case

    mu, peak = _hunter_reference(group["factor"])
    row = run_case("cylinder", group["factor"], group["method"], group["n"], group.get("levels", 0))
    error = max(abs(row["friction"] / mu - 1), abs(row["peak_pressure"] / peak - 1))
    return [
        {
            "n": group["n"],
            "levels": group.get("levels", 0),
            "error": error,
            "time": row["wall_s"],
            "peak_rss": instruments.peak_rss(),
            "friction_error": abs(row["friction"] / mu - 1),
            "peak_pressure_error": abs(row["peak_pressure"] / peak - 1),
            "iterations": row["iterations"],
            "elements": row["elements"],
        }
    ]


_HUNTER_PROBLEM = "rigid cylinder rolling on an SLS (E_inf/E0 = 3), V lambda = a0, P = 1000 N/m, R = 10 mm, domain 3 a0"


@register(
    "isolated-uniform-hunter",
    solver="isolated BEM (uniform DC-FFT)",
    measure=_isolated_group,
    problem=_HUNTER_PROBLEM,
    reference="Hunter (exact)",
    error="max(rel. friction error, rel. peak-pressure error)",
    knobs=("n",),
)
def _isolated_uniform(quick):
    for n in (128, 256, 512, 1024) if quick else (128, 256, 512, 1024, 2048, 4096, 8192):
        yield {"method": "uniform", "n": n, "factor": 1.0}


@register(
    "isolated-adaptive-hunter",
    solver="isolated BEM (adaptive mesh)",
    measure=_isolated_group,
    problem=_HUNTER_PROBLEM,
    reference="Hunter (exact)",
    error="max(rel. friction error, rel. peak-pressure error)",
    knobs=("n", "levels"),
)
def _isolated_adaptive(quick):
    for n in (128, 256, 512) if quick else (128, 256, 512, 1024, 2048):
        yield {"method": "adaptive", "n": n, "levels": int(np.log2(n // 32)), "factor": 1.0}


FINISH = {"periodic-rough-viscoelastic": _rough_finish}


def elastic():
    import bem

    return bem.Material.elastic(E_ELASTIC)
