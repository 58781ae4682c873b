"""Ablation of the contact solver: every mechanism switched off in turn, over a fixed case set.

Run it with ``python -m viscobem_bench.contact [--quick] --out DIR`` (or ``viscobem bench contact``).
It prints a table and writes ``DIR/contact.json`` and ``.md``; ``docs/theory.md`` §4 quotes it.

A mechanism of :mod:`bem.contact` stays when switching it off costs the case set products, or
loses a case (STYLE.md: "a mechanism stays when an ablation table shows that it pays; its
constant cites that row"). Each row of the table is one variant: everything on, or one
mechanism off (:data:`MECHANISMS`, applied by :func:`switched_off`, which patches the solver's
module constants or its options for the duration of the row and restores them). Per row: the
operator products over the set and their ratio to the all-on row, the same products in elastic
solves (the unit: each case's surface and load solved on the relaxed solid ``E0`` at rest with
everything on, measured in the same run), the wall time, the cases that failed, and the largest
relative L2 pressure error against a tight reference (rtol :data:`REFERENCE_RTOL`, everything on)
in units of the solve's rtol. One expensive case can dominate the total, so the per-case ratios
(off over on) are given too, as their geometric mean and their largest. A mechanism pays when
switching it off loses a case, breaks the ``10 rtol`` pressure bound, or costs more than
:data:`PAYS` of the products in total or in the geometric mean of the cases.

The case set (:func:`cases`) follows the stress suite's (``tests/bem/test_stress.py``): rough
cells at 5 % of their full-contact load on standard linear solids from ``E_inf/E0 = 3`` to 1e4
over 10 decades of speed, 1-D profiles, Prony series of up to 40 terms over 12 decades, loads
from one spot to near full contact, the isolated cylinder on a 14-term rubber, and warm-started
friction curves of broad-spectrum rubbers on 1-D and 2-D rough cells and on the isolated
cylinder. Beyond the stress set: a 128² cell on the 20-term rubber of the periodic benchmark at
its friction peak (the line preconditioner's regime), an isolated sphere on the 14-term rubber,
and a sinusoid near full contact on ``E_inf/E0 = 1e4``. ``--quick`` keeps the small cases.
"""

import argparse
import contextlib
import dataclasses
import functools
import importlib
import sys
import time

import numpy as np

import bem
from bem.contact import ContactOptions, krylov, line_preconditioner
from bem.contact.operator import ExactInverse, strongly_nonsymmetric
from viscobem_bench.instruments import load_average
from viscobem_bench.periodic.report import finish, table

L = 0.01  # m, cell side of the rough cases (the stress suite's)
RTOL, REFERENCE_RTOL, MAXITER = 1e-8, 1e-11, 400
CURVE_XI = (1e-6, 1e-4, 1e-2, 1.0, 1e2, 1e4)
PAYS = 0.05  # a mechanism pays when switching it off costs more than this share of products


# ---------------------------------------------------------------- mechanisms and their switch
# (name, what it does, option overrides, module patches {"module:NAME": value})
def _never(*args, **kw):
    return False


def _eta_min_at_once(eta, *, damped):
    from bem.contact import forcing

    return forcing.ETA_MIN if damped else eta


def _own_rtol(rtol):
    return rtol


def _start_rtol_1e_3(rtol):
    return max(rtol, 1e-3)


def _eta_kept(eta, *, damped):
    return eta


def _full_step(p, g, p_new, g_new, c, *, full):
    return 1.0


def _default_choice(attempt, options):
    return attempt.precondition if attempt.precondition is not None else options.precondition


def _no_exact(op, pb, attempt, options, strong):
    choice = _default_choice(attempt, options)
    return not isinstance(op, ExactInverse) if choice is None else choice


def _exact_from_2_17(op, pb, attempt, options, strong):
    choice = _default_choice(attempt, options)
    exact = pb.ht.size >= 2**17 and not strong
    return (not isinstance(op, ExactInverse) or exact) if choice is None else choice


def _coarse_large_unless_strong(op, heights, mean_pressure, options):
    from bem.contact import start

    wanted = start.wants_coarse_start(op, heights, mean_pressure, options)
    return wanted and (heights.size >= 2**18 or strongly_nonsymmetric(op))


MECHANISMS = [
    ("all on", "the solver as it is", {}, {}),
    ("coarse start", "nested iteration from the grid with half the points", {"coarsen": False}, {}),
    ("warm start across speeds", "friction curves start each speed from the last", {}, {"warm": False}),
    (
        "symmetric-part start",
        "strongly non-symmetric problems start from A_s's contact",
        {"symmetric_start": False},
        {},
    ),
    ("line preconditioner", "2-D periodic strong operators: exact creep inverse on lines", {"line_budget": 0}, {}),
    ("preconditioners", "every preconditioner (isolated: padded inverse; lines)", {"precondition": False}, {}),
    ("float32 inner solves", "loose inner products in single precision", {"single_precision": False}, {}),
    ("inexact Newton", "inner solves stop at eta of their rhs (off: eta 1e-6)", {"inner_eta": 1e-6}, {}),
    ("damped tighten", "a damped step tightens eta", {}, {"forcing:next_eta": _eta_kept}),
    (
        "decade tightening",
        "eta tightens a decade a damped step (off: to ETA_MIN at once)",
        {},
        {"forcing:next_eta": _eta_min_at_once},
    ),
    ("eta floor", "eta never tightens below ETA_MIN", {}, {"forcing:ETA_MIN": 0.0}),
    ("cycling stop", "damping and the symmetric start's stop after CYCLING_STEPS", {}, {"newton:CYCLING_STEPS": 10**9}),
    ("cycling steps 3", "three steps show cycling (off: two)", {}, {"newton:CYCLING_STEPS": 2}),
    ("cycling steps 3 vs 5", "three steps show cycling (off: five)", {}, {"newton:CYCLING_STEPS": 5}),
    ("lines maxiter share", "the line attempt may take half of maxiter", {}, {"solver:LINES_MAXITER_SHARE": 1.0}),
    (
        "near-full start",
        "the clipped full-contact pressure when it is nearly right",
        {},
        {"start:NEAR_FULL_CONTACT": 0.0},
    ),
    ("coarse start on small grids", "coarsen from 128 points (off: from 2**18)", {}, {"start:COARSEN_MIN_SIZE": 2**18}),
    (
        "symmetric coarse start on small grids",
        "coarsen from 128 points (off: from 2**18 unless strongly non-symmetric)",
        {},
        {"solver:wants_coarse_start": _coarse_large_unless_strong},
    ),
    ("gap scale 0.3", "GAP_SCALE 0.3 cells in the residual's gap scale (off: 1)", {}, {"newton:GAP_SCALE": 1.0}),
    (
        "gap scale 0.3 vs 10",
        "GAP_SCALE 0.3 cells in the residual's gap scale (off: 10)",
        {},
        {"newton:GAP_SCALE": 10.0},
    ),
    ("gap floor", "the gap scale is held above GAP_FLOOR_SHARE of the heights", {}, {"newton:GAP_FLOOR_SHARE": 0.0}),
    ("exact preconditioner", "periodic cells: the exact inverse on the set", {}, {"newton:_preconditioner": _no_exact}),
    (
        "exact preconditioner on small grids",
        "the exact inverse on every grid (off: from 2**17 points)",
        {},
        {"newton:_preconditioner": _exact_from_2_17},
    ),
    (
        "line batches",
        "the line preconditioner inverts CHUNK lines per batched call (off: one line per call)",
        {},
        {"inner:line_preconditioner": functools.partial(line_preconditioner.line_preconditioner, chunk=1)},
    ),
    ("long GMRES restarts", "restart length up to RESTART_MAX by memory (off: 30)", {}, {"krylov:RESTART_MAX": 30}),
    ("round-off floor stop", "stop at the residual's round-off floor", {}, {"newton:FLOOR_MARGIN": 0.0}),
    (
        "reorthogonalisation",
        "GMRES's second Gram-Schmidt pass on cancellation (off: one pass)",
        {},
        {"krylov:gmres": functools.partial(krylov.gmres, reorthogonalise=0.0)},
    ),
    (
        "loose starts",
        "the coarse solve and symmetric start stop at sqrt(rtol) (off: rtol)",
        {},
        {"solver:start_rtol": _own_rtol, "newton:start_rtol": _own_rtol},
    ),
    (
        "square-root start",
        "the starts stop at sqrt(rtol) (off: at 1e-3)",
        {},
        {"solver:start_rtol": _start_rtol_1e_3, "newton:start_rtol": _start_rtol_1e_3},
    ),
    (
        "line search",
        "damped steps to the merit's first minimum over 1/2, 1/4, ... (off: full steps)",
        {},
        {"newton:line_search": _full_step},
    ),
]


@contextlib.contextmanager
def switched_off(patches):
    """Set ``patches`` (``{"module:NAME": value}``, modules of :mod:`bem.contact`) for the duration
    of the block, in every module of the package that holds the same object under that name (a
    constant imported by a sibling is patched there too), and restore them after."""
    saved = []
    names = ("forcing", "inner", "krylov", "line_preconditioner", "newton", "operator", "solver", "start")
    modules = [importlib.import_module(f"bem.contact.{m}") for m in names]
    try:
        for key, value in patches.items():
            if key == "warm":
                continue
            module, name = key.split(":")
            owner = importlib.import_module(f"bem.contact.{module}")
            original = getattr(owner, name)
            # a function is replaced where it is looked up; a constant wherever a sibling imported it
            for m in [owner] if callable(original) else modules:
                if getattr(m, name, None) is original:
                    saved.append((m, name, original))
                    setattr(m, name, value)
        yield
    finally:
        for m, name, original in reversed(saved):
            setattr(m, name, original)


# ---------------------------------------------------------------- cases
@dataclasses.dataclass(frozen=True)
class Case:
    """One solve (``speeds`` of one) or a warm-started friction curve (several)."""

    name: str
    surface: object
    material: object
    speeds: tuple
    load: float
    periodic: bool = True
    quick: bool = True


def sls(ratio):
    return bem.Material.standard_linear_solid(E0=1e7 / ratio, E_inf=1e7, creep_time=0.01)


def prony(terms, ratio=1e3):
    times = np.logspace(-8, 4, terms) if terms > 1 else np.array([1e-2])
    return bem.Material.from_prony(E0=1e6, moduli=np.full(terms, 1e6 * (ratio - 1) / terms), times=times)


def rubber14(ratio=800.0, E0=2.5e6):
    """A broad-spectrum rubber: 14 Prony terms, relaxation times 1e-6..1 s, moduli from two
    log-normal bands (around 10^-4.5 s and 10^-1.5 s), scaled to ``E_inf/E0 = ratio``."""
    tau = np.logspace(-6, 0, 14)
    lt = np.log10(tau)
    w = np.exp(-(((lt + 4.5) / 0.6) ** 2) / 2) + 0.6 * np.exp(-(((lt + 1.5) / 0.8) ** 2) / 2)
    return bem.Material.from_prony(E0=E0, moduli=w / w.sum() * (ratio - 1) * E0, times=tau)


def rubber30(ratio=1000.0, E0=1e6):
    """30 Prony terms over 1e-9..1e3 s with a flat-topped spectrum: E_inf/E0 = ``ratio``."""
    tau = np.logspace(-9, 3, 30)
    w = 1.0 / (1.0 + ((np.log10(tau) + 3.0) / 4.0) ** 8)
    return bem.Material.from_prony(E0=E0, moduli=w / w.sum() * (ratio - 1) * E0, times=tau)


def rough(n, dim=2, hurst=0.8, scales=None, seed=2):
    scales = scales or min(16, n // 2)
    return bem.surfaces.self_affine(n, L, hurst=hurst, scales=scales, rms_height=2e-5, seed=seed, dim=dim)


def _speed(material, xi, length=L):
    return 0.0 if material.is_elastic else xi * length / float(material.creep_times.max())


def _load(surface, material, speed, level):
    """``level`` times the load at which the cell comes into full contact."""
    op = bem.sliding.operator_for(surface, material, speed)
    h = surface.heights
    return level * float(-op.pressure_from_displacement(h - h.max()).min()) * surface.length**surface.ndim


def _rough_case(name, surface, material, xi, level=0.05, quick=True):
    speed = _speed(material, xi)
    return Case(name, surface, material, (speed,), _load(surface, material, speed, level), quick=quick)


def _curve_case(name, surface, material, level=0.05, quick=True):
    speeds = tuple(_speed(material, xi) for xi in CURVE_XI)
    return Case(name, surface, material, speeds, _load(surface, material, speeds[0], level), quick=quick)


def _cylinder(n, width, material):
    e_star = material.E0 / (1 - material.nu**2)
    a0 = float(np.sqrt(4 * 1200.0 * 12e-3 / (np.pi * e_star)))
    return bem.surfaces.cylinder(radius=12e-3, n=n, length=width * a0)


def _sphere(n, width, material):
    e_star = material.E0 / (1 - material.nu**2)
    a0 = float((3 * 1.0 * 5e-3 / (4 * e_star)) ** (1 / 3))
    return bem.surfaces.sphere(radius=5e-3, n=n, length=width * a0)


def cases(quick=False):
    """The case set (module docstring); ``quick`` keeps the small cases."""
    out = []
    for ratio, xi in ((3.0, 1e-2), (1e4, 1.0), (1e2, 1e4)):
        out.append(_rough_case(f"2-D 32², SLS {ratio:g}, xi {xi:g}", rough(32), sls(ratio), xi))
    for ratio, xi in ((3.0, 1e-2), (1e4, 1.0), (1e4, 1e6)):
        out.append(_rough_case(f"1-D 512, SLS {ratio:g}, xi {xi:g}", rough(512, 1, scales=64), sls(ratio), xi))
    out.append(_rough_case("2-D 32², elastic", rough(32), bem.Material.elastic(1e7), 0.0))
    for terms, xi in ((20, 1.0), (40, 1e2)):
        out.append(_rough_case(f"2-D 32², Prony {terms}, xi {xi:g}", rough(32), prony(terms), xi))
    out.append(_rough_case("2-D 32², SLS 1e4, xi 1, load 0.001", rough(32), sls(1e4), 1.0, 1e-3))
    r14 = rubber14()
    out.append(Case("isolated cylinder 1024, rubber14, 1e-6 m/s", _cylinder(1024, 4, r14), r14, (1e-6,), 1200.0, False))
    out.append(_curve_case("curve 1-D 1024, rubber14", rough(1024, 1, hurst=0.7, scales=256, seed=5), r14))
    out.append(_curve_case("curve 2-D 64², rubber30", rough(64, scales=32, seed=6), rubber30()))
    # beyond the stress set
    r20 = bem.Material.from_prony(E0=1e6, moduli=np.full(20, (1e9 - 1e6) / 20), times=np.logspace(-10, 2, 20))
    s = bem.surfaces.self_affine(128, L, scales=16, seed=1, hurst=0.8, rms_slope=0.1)
    out.append(_curve_case("curve 2-D 128², rubber20 (viscobem bench curve)", s, r20, level=0.01))
    out.append(Case("isolated sphere 64², rubber14, 1e-4 m/s", _sphere(64, 4, r14), r14, (1e-4,), 1.0, False))
    s = bem.surfaces.sinusoid(64, L, amplitude=2e-6)
    out.append(_rough_case("sinusoid 64², SLS 1e4, xi 1, load 0.8", s, sls(1e4), 1.0, 0.8))
    if not quick:
        # near full contact: the near-full start's case (28 products with it, 21,390 without)
        out.append(_rough_case("2-D 32², SLS 1e4, xi 1, load 0.9", rough(32), sls(1e4), 1.0, 0.9))
        # the path-sensitive case of docs/theory.md §4.2 (at 32², E_inf/E0 1e4, xi 100)
        out.append(_rough_case("2-D 32², SLS 10000, xi 100", rough(32), sls(1e4), 1e2))
        s = bem.surfaces.sinusoid(256, L, amplitude=2e-6)
        out.append(_rough_case("sinusoid 256², SLS 1e4, xi 1, load 0.8", s, sls(1e4), 1.0, 0.8))
        for ratio, xi in ((3.0, 1e-2), (1e4, 1.0), (1e4, 1e2)):
            out.append(_rough_case(f"2-D 128², SLS {ratio:g}, xi {xi:g}", rough(128, scales=64), sls(ratio), xi))
        out.append(_rough_case("1-D 4096, SLS 1e4, xi 1e2", rough(4096, 1, scales=1024), sls(1e4), 1e2))
        out.append(_rough_case("2-D 128², rubber20, xi 1e-2", rough(128, scales=64, seed=3), r20, 1e-2))
        out.append(
            Case(
                "curve isolated cylinder 2048, rubber14",
                _cylinder(2048, 4, r14),
                r14,
                tuple(np.logspace(-8, 0, 5)),
                1200.0,
                False,
            )
        )
        out.append(_curve_case("curve 2-D 128², rubber30", rough(128, scales=64, seed=6), rubber30()))
        s = bem.surfaces.self_affine(256, L, scales=16, seed=1, hurst=0.8, rms_slope=0.1)
        out.append(_curve_case("curve 2-D 256², rubber20 (viscobem bench curve)", s, r20, level=0.01))
        s = bem.surfaces.self_affine(1024, L, hurst=0.8, scales=512, rms_slope=0.1, seed=1)
        out.append(Case("2-D 1024², elastic, 512 scales", s, bem.Material.elastic(1e7), (0.0,), 50.0))
    return out


# ---------------------------------------------------------------- measuring
def _solve_case(case, options, warm=True, rtol=RTOL):
    """``(products, pressures or None per speed, converged points, contact of the first point)``."""
    common = dict(
        load=case.load, rtol=rtol, maxiter=MAXITER, periodic=case.periodic, error_estimate=None, contact_options=options
    )
    if len(case.speeds) == 1:
        res = bem.solve(case.surface, case.material, speed=case.speeds[0], raise_on_failure=False, **common)
        return res.matvecs, [res.pressure if res.success else None], int(res.success), res.contact_fraction
    curve = bem.friction_curve(case.surface, case.material, speeds=list(case.speeds), warm_start=warm, **common)
    products = sum(r.matvecs for r in curve.results if r is not None)
    pressures = [None if r is None else r.pressure for r in curve.results]
    first = next((r.contact_fraction for r in curve.results if r is not None), 1.0)
    return products, pressures, sum(r is not None for r in curve.results), first


def _elastic_products(case, contact):
    """Products of one elastic solve of the case's surface (relaxed modulus, at rest) at the load
    that gives the case's ``contact`` fraction (secant steps on log contact against log load, as
    in :mod:`viscobem_bench.curve`): the same contact problem without the viscoelastic operator."""
    elastic = bem.Material.elastic(case.material.E0, nu=case.material.nu)
    common = dict(speed=0.0, periodic=case.periodic, error_estimate=None)
    load, history = case.load, []
    for _ in range(8):
        frac = bem.solve(case.surface, elastic, load=load, rtol=1e-6, **common).contact_fraction
        history.append((np.log(load), np.log(max(frac, 1e-9))))
        if abs(frac / contact - 1) < 0.03 or frac >= 1.0 and contact >= 1.0:
            break
        slope = 1.0
        if len(history) > 1 and history[-1][1] != history[-2][1]:
            slope = (history[-1][1] - history[-2][1]) / (history[-1][0] - history[-2][0])
        load *= (contact / max(frac, 1e-9)) ** (1.0 / min(max(slope, 0.3), 3.0))
    return bem.solve(case.surface, elastic, load=load, rtol=RTOL, **common).matvecs


def _error(p, ref):
    if p is None or ref is None:
        return None
    return float(np.linalg.norm(p - ref) / np.linalg.norm(ref))


def run(quick=False, out_dir=None, echo=print, only=None):
    """Measure every variant over the case set (module docstring); print, write and return the record."""
    started, load_start = time.perf_counter(), load_average()
    case_set = cases(quick)
    refs, units = [], []
    for case in case_set:
        _, pressures, _, contact = _solve_case(case, ContactOptions(), rtol=REFERENCE_RTOL)
        refs.append(pressures)
        units.append(_elastic_products(case, contact) * len(case.speeds))
    variants = []
    for name, what, option_overrides, patches in MECHANISMS:
        if only and name not in only and name != "all on":
            continue
        options = ContactOptions(**option_overrides)
        per_case, wall = [], time.perf_counter()
        with switched_off(patches):
            for case, ref in zip(case_set, refs):
                t = time.perf_counter()
                products, pressures, converged, _ = _solve_case(case, options, warm=patches.get("warm", True))
                errors = [_error(p, r) for p, r in zip(pressures, ref)]
                known = [e for e in errors if e is not None]
                per_case.append(
                    dict(
                        products=products,
                        converged=converged,
                        points=len(case.speeds),
                        error=max(known) / RTOL if known else None,
                        wall_time=time.perf_counter() - t,
                    )
                )
        wall = time.perf_counter() - wall
        products = sum(c["products"] for c in per_case)
        failed = [case.name for case, c in zip(case_set, per_case) if c["converged"] < c["points"]]
        errors = [c["error"] for c in per_case if c["error"] is not None]
        variants.append(
            dict(
                mechanism=name,
                what=what,
                products=products,
                elastic_solves=products / sum(units),
                wall_time=wall,
                failed=failed,
                max_error_in_rtol=max(errors) if errors else None,
                per_case=per_case,
            )
        )
        v = variants[-1]
        echo(
            f"{name:28s} {products:7d} products, {v['elastic_solves']:6.1f} elastic solves, {wall:6.1f} s, "
            f"failed {len(failed)}, error {v['max_error_in_rtol'] or 0:.2f} rtol"
        )
    base = variants[0]
    for v in variants:
        v["products_ratio"] = v["products"] / base["products"]
        v["wall_ratio"] = v["wall_time"] / base["wall_time"]
        ratios = [max(p["products"], 1) / max(b["products"], 1) for p, b in zip(v["per_case"], base["per_case"])]
        v["case_ratio_geomean"] = float(np.exp(np.mean(np.log(ratios))))
        v["case_ratio_max"] = max(ratios)
        v["pays"] = bool(
            v["failed"] != base["failed"]
            or v["products_ratio"] > 1 + PAYS
            or v["case_ratio_geomean"] > 1 + PAYS
            or (v["max_error_in_rtol"] or 0) > 10
        )
    fields = dict(
        quick=quick,
        rtol=RTOL,
        reference_rtol=REFERENCE_RTOL,
        cases=[dict(name=c.name, points=len(c.speeds), elastic_products=u) for c, u in zip(case_set, units)],
        variants=variants,
        load_average=[load_start, load_average()],
    )
    return finish("contact", started, _report, out_dir, echo, **fields)


def _report(result, markdown=False):
    n_points = sum(c["points"] for c in result["cases"])
    head = (
        f"{len(result['cases'])} cases ({n_points} solves), rtol {result['rtol']:g}; pressure error against "
        f"rtol {result['reference_rtol']:g} with everything on; unit: one elastic solve (relaxed modulus, at rest) "
        f"of each case's surface and load per point, measured in the same run; load average "
        f"{result['load_average'][0]} -> {result['load_average'][1]}"
    )
    rows = [
        [
            v["mechanism"] if i == 0 else f"{v['mechanism']} off",
            v["products"],
            f"{v['products_ratio']:.2f}",
            f"{v['elastic_solves']:.2f}",
            f"{v['wall_time']:.1f}",
            f"{v['wall_ratio']:.2f}",
            f"{v['case_ratio_geomean']:.2f}",
            f"{v['case_ratio_max']:.2f}",
            len(v["failed"]),
            "-" if v["max_error_in_rtol"] is None else f"{v['max_error_in_rtol']:.2f}",
            "" if i == 0 else ("yes" if v["pays"] else "no"),
        ]
        for i, v in enumerate(result["variants"])
    ]
    headers = ["variant", "products", "/ all on", "elastic solves", "wall s", "/ all on"]
    headers += ["case ratio (geo. mean)", "case ratio (max)", "failed", "error / rtol", "pays"]
    cases = [[c["name"], c["points"], c["elastic_products"]] for c in result["cases"]]
    changed = [
        f"{v['mechanism']} off: "
        + ", ".join(
            f"{c['name']} {b['products']} -> {p['products']}"
            for c, b, p in zip(result["cases"], result["variants"][0]["per_case"], v["per_case"])
            if abs(p["products"] - b["products"]) > 0.2 * b["products"]
        )
        for v in result["variants"][1:]
    ]
    failed = [f"{v['mechanism']} off: {', '.join(v['failed'])}" for v in result["variants"][1:] if v["failed"]]
    parts = [head, table(headers, rows, markdown), table(["case", "points", "elastic products"], cases, markdown)]
    if failed:
        parts.append("cases lost:\n\n" + "\n".join(f"- {f}" for f in failed))
    parts.append("products changed by more than 20 % (all on -> off):\n\n" + "\n".join(f"- {c}" for c in changed))
    parts.append(f"total time {result['total_time']:.0f} s")
    return "\n\n".join(parts)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m viscobem_bench.contact", description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="the small cases only (CI)")
    parser.add_argument("--only", nargs="*", help="mechanisms to switch off (default: each in turn)")
    parser.add_argument("--out", default=None, help="directory for contact.json and .md")
    args = parser.parse_args(argv)
    run(args.quick, args.out, only=args.only)
    return 0


if __name__ == "__main__":
    sys.exit(main())
