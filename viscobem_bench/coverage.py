"""How often the default error estimate covers the measured error, over a varied set of cases.

Run it with ``viscobem bench coverage [--quick] --out DIR`` (or ``python -m
viscobem_bench.coverage``). It prints a table and writes ``DIR/coverage.json`` and ``.md``.

Each case is drawn from its own seed (``numpy.random.default_rng(seed)``): a cylinder or a sphere
on an isolated domain, or a rough profile or surface on a periodic cell; a rubber of 1 to 20
Prony terms (``E_inf/E0`` 10 to 3000, relaxation times over up to ten decades); a speed from
five decades below to three above the one whose ``V tau`` spans the contact; a load from a
contact a few cells wide (or 1 % contact) to near full contact. Each is solved with
``error_estimate="refined"``, which measures the error against the same surface content on the
grid twice as fine and keeps the default estimate's indicators, so both come from one run.

The constants of :mod:`bem.accuracy.estimate` were set on the tuning seeds
(:data:`TUNING`); the statistics that count are those on the held-out seeds (:data:`HELD_OUT`),
which were not looked at while tuning. Targets (docs/theory.md §13.5):

1. ``friction`` and ``contact_fraction``: the estimate within a factor 3 of the measured error
   in at least 90 % of the cases (errors below :data:`FLOOR` count as covered when the estimate
   is below 3 x ``FLOOR``: the fluctuations of theory §13.1 dominate there);
2. no estimate below 1 % where the measured error exceeds 5 % (an unresolved peak, ``None``,
   is no such miss);
3. fewer than 5 % of the warnings where the measured error is below 2 %; also given among the
   warnings other than an unresolved peak's (whose change on the next grid is not its error), and
   among those whose measurement resolves 2 % (a contact fraction whose finer grid's cell is less
   than 2 % of the contact).
"""

import math
import sys
import time

import numpy as np

import bem
from bem.accuracy import QUANTITIES
from bem.accuracy.assess import assess
from bem.accuracy.findings import WARN
from viscobem_bench.periodic.report import finish, quick_out_main, table

TUNING = range(0, 120)
HELD_OUT = range(1000, 1120)
QUICK = 12  # cases per set with --quick
FLOOR = 1e-3  # measured errors below this are grid-to-grid fluctuations (theory §13.1)
_MEASURED = {"peak_unresolved": "peak_pressure"}  # the quantity a finding kind is about
KINDS = ("cylinder", "sphere", "profile", "rough")


def _rubber(rng):
    terms = int(rng.choice([1, 2, 4, 8, 14, 20]))
    ratio = 10 ** rng.uniform(1.0, math.log10(3000.0))
    tau_min = 10 ** rng.uniform(-8.0, -4.0)
    span = 0.0 if terms == 1 else rng.uniform(1.0, 10.0)
    times = np.geomspace(tau_min, tau_min * 10**span, terms)
    weights = rng.dirichlet(np.full(terms, 2.0))
    E0 = 1e6
    material = bem.Material.from_prony(E0=E0, moduli=E0 * (ratio - 1) * weights, times=times)
    return material, dict(terms=terms, ratio=ratio, tau_min=tau_min, decades=span)


def _modulus(material, omega):
    return abs(complex(material.complex_modulus(omega))) / (1 - material.nu**2)


def case(seed):
    """``(name, surface, material, solve keywords, description)`` of case ``seed``."""
    rng = np.random.default_rng(seed)
    kind = KINDS[seed % len(KINDS)]
    material, rubber = _rubber(rng)
    tau_mid = float(np.sqrt(material.relaxation_times.min() * material.relaxation_times.max()))
    u = rng.uniform(-5.0, 3.0)  # decades of V tau_mid against the contact scale
    if kind in ("cylinder", "sphere"):
        n = int(rng.choice([128, 256, 512] if kind == "cylinder" else [32, 48, 64]))
        cells = 10 ** rng.uniform(math.log10(3.0), math.log10(n / 3))  # contact half-width in cells
        radius, a = 0.01, 1e-3
        speed = a / tau_mid * 10**u
        e_star = _modulus(material, speed / a)
        load = math.pi * a**2 * e_star / (4 * radius) if kind == "cylinder" else 4 * e_star * a**3 / (3 * radius)
        make = bem.surfaces.cylinder if kind == "cylinder" else bem.surfaces.sphere
        surface = make(radius=radius, n=n, length=n * a / cells)
        kw = dict(speed=speed, load=load, periodic=False)
        desc = dict(kind=kind, n=n, half_width_cells=cells)
    else:
        dim = 1 if kind == "profile" else 2
        n = int(rng.choice([256, 512, 1024] if dim == 1 else [48, 64, 96]))
        ppw = float(rng.choice([2, 3, 4, 6, 8, 12]))
        length, slope = 0.01, rng.uniform(0.1, 0.3)
        surface = bem.surfaces.self_affine(
            n, length, hurst=rng.uniform(0.5, 0.9), scales=max(2, int(n / ppw)), rms_slope=slope, seed=seed, dim=dim
        )
        spot = length / (n / ppw)
        speed = spot / tau_mid * 10**u
        fraction = 10 ** rng.uniform(-2.0, math.log10(0.9))
        pressure = fraction * _modulus(material, speed / spot) * slope / 2.0
        kw = dict(speed=speed, load=pressure * length**dim)
        desc = dict(kind=kind, n=n, points_per_wavelength=ppw, target_fraction=fraction)
    return f"{seed}:{kind}", surface, material, kw, dict(desc, **rubber, speed=speed, decades_vs_contact=u)


def measure(seed):
    """The record of case ``seed``: default estimate, measured error and times."""
    name, surface, material, kw, desc = case(seed)
    t0 = time.perf_counter()
    fine = bem.solve(surface, material, error_estimate="refined", raise_on_failure=False, **kw)
    if not fine.success:
        return dict(seed=seed, name=name, **desc, success=False)
    ref = fine.error_estimate
    coarse = assess(fine, surface, material, periodic=kw.get("periodic", True), estimate="indicators")
    est = coarse.error_estimate
    return dict(
        seed=seed,
        name=name,
        **desc,
        success=ref.method == "refined",
        contact_fraction=fine.contact_fraction,
        estimate=dict(est.values),
        reasons=dict(est.reasons),
        measured=dict(ref.values),
        warned=sorted({w.kind for w in coarse.warnings if w.kind in QUANTITIES + ("peak_unresolved",)}),
        ndim=surface.ndim,
        contact_cells=est.indicators.get("contact_cells", 0),
        seconds=time.perf_counter() - t0,
    )


def _covered(e, m, resolution=0.0):
    """Whether estimate ``e`` covers measured error ``m`` within a factor 3; a measured error that is
    below what the measurement resolves (``FLOOR``, or ``resolution``) is covered by an estimate below
    three times that."""
    if e is None or m is None:
        return None
    floor = max(FLOOR, resolution)
    if m < floor and e < 3 * floor:
        return True
    return m / 3 <= e <= 3 * m


def _resolution(record, quantity):
    """What the measured error of ``quantity`` resolves: for the contact fraction, one cell of the finer
    grid among its contact cells (the count changes by whole cells, so a cylinder's error is 0 or at
    least that)."""
    if quantity != "contact_fraction" or not record["contact_cells"]:
        return 0.0
    return 1.0 / (2 ** record["ndim"] * record["contact_cells"])


def statistics(records):
    """The three targets' statistics over ``records`` (module docstring)."""
    ok = [r for r in records if r.get("success")]
    out = {"cases": len(ok)}
    for q in QUANTITIES:
        hits = [_covered(r["estimate"][q], r["measured"][q], _resolution(r, q)) for r in ok]
        hits = [h for h in hits if h is not None]
        out[f"{q}_within_3x"] = sum(hits) / len(hits) if hits else None
        out[f"{q}_counted"] = len(hits)
        out[f"{q}_unresolved"] = sum(r["estimate"][q] is None and r["measured"][q] is not None for r in ok)
    low = [
        (r["name"], q)
        for r in ok
        for q in QUANTITIES
        if r["estimate"][q] is not None
        and r["measured"][q] is not None
        and r["estimate"][q] < 0.01
        and r["measured"][q] > WARN
    ]
    out["below_1pct_where_above_5pct"] = low
    # (case, finding kind, measured error of its quantity, what that measurement resolves)
    warnings = [
        (r["name"], q, r["measured"][_MEASURED.get(q, q)], _resolution(r, _MEASURED.get(q, q)))
        for r in ok
        for q in r["warned"]
    ]

    def share(ws):
        false = [w for w in ws if w[2] is not None and w[2] < 0.02]
        return false, (len(false) / len(ws) if ws else 0.0)

    false, out["false_alarm_share"] = share(warnings)
    out["warnings"], out["false_alarms"] = len(warnings), len(false)
    # an unresolved peak's change on the next grid is not its error (the spike grows until the cells
    # are as thin as the layers): the share among the other warnings
    out["false_alarm_share_estimated"] = share([w for w in warnings if w[1] != "peak_unresolved"])[1]
    # a contact a few cells wide changes by whole cells of the finer grid: where one such cell is 2 %
    # of the contact or more, a measured 0 does not show that the warning was false
    out["false_alarm_share_resolved"] = share([w for w in warnings if w[3] < 0.02])[1]
    out["false_alarm_cases"] = [w[:3] for w in false]
    return out


def run(quick=False, out_dir=None, echo=print):
    """Measure every case of both sets; print, write and return the record."""
    started = time.perf_counter()
    sets = {}
    for label, seeds in (("tuning", TUNING), ("held_out", HELD_OUT)):
        seeds = list(seeds)[:QUICK] if quick else list(seeds)
        records = []
        for seed in seeds:
            records.append(measure(seed))
            echo(f"{label} {records[-1]['name']:>14s} {records[-1].get('seconds', 0.0):6.2f} s")
        sets[label] = dict(records=records, statistics=statistics(records))
    return finish("coverage", started, _report, out_dir, echo, quick=quick, sets=sets)


def _pct(x):
    return "-" if x is None else f"{100 * x:.0f} %"


def _report(result, markdown=False):
    rows = []
    for label, s in result["sets"].items():
        st = s["statistics"]
        rows.append(
            [label, st["cases"]]
            + [f"{_pct(st[f'{q}_within_3x'])} of {st[f'{q}_counted']}" for q in QUANTITIES]
            + [st["peak_pressure_unresolved"], len(st["below_1pct_where_above_5pct"])]
            + [f"{st['false_alarms']} of {st['warnings']} ({_pct(st['false_alarm_share'])})"]
            + [_pct(st["false_alarm_share_estimated"]), _pct(st["false_alarm_share_resolved"])]
        )
    head = ["set", "cases", *(f"{q} within 3x" for q in QUANTITIES), "peak unresolved", "<1 % where >5 %"]
    return "\n\n".join(
        [
            table(head + ["warnings at error < 2 %", "same, peak estimated", "same, resolvable"], rows, markdown),
            f"total time {result['total_time']:.0f} s",
        ]
    )


def main(argv=None):
    return quick_out_main("coverage", __doc__, run, f"{QUICK} cases per set (smoke test)", argv)


if __name__ == "__main__":
    sys.exit(main())
