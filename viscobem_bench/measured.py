"""Boundary treatments of a measured scan, chosen by measurement: patches cut from periodic surfaces
whose friction is known.

Run it with ``viscobem bench measured [--quick] --out DIR`` (or ``python -m viscobem_bench.measured``).
It prints a table and writes ``DIR/measured.json`` and ``.md`` (the tables) and
``DIR/measured_solves.json`` (every solve).

A measured scan is a patch of a larger surface. Here the larger surface is known: a periodic
self-affine surface (the *parent*, side ``L = 1 mm``, 256² points, Hurst 0.8, 32 scales so 8
points per shortest wavelength, rms slope 0.2, roll-off ``q_r = rolloff q_L``), solved on its
periodic cell at a nominal pressure ``P0`` and four speeds on a standard linear solid. Square
patches of side ``L/4`` and ``L/2`` (a sixteenth and a quarter of its area) are cut from it at
random places (seeded), at the parent's own resolution, plane-detrended as the scene kind
``measured`` does, and solved at the same nominal pressure with each treatment:

- ``isolated``: the patch as the whole loaded domain of an isolated contact;
- ``isolated_taper``: the same with the edges lowered by a Tukey taper (25 %) below the lowest
  point, so that they cannot touch;
- ``guard_band``: an isolated domain of the patch plus a band of its mirror images (an eighth of
  the side on each edge); friction and load counted on the patch only;
- ``mirror``, ``periodic_component``, ``tukey`` (alpha 0.25), ``hann``, ``none``: a periodic cell
  made by :func:`bem.surfaces.measured.to_surface` with that window.

Each is scored by its friction (dissipation form) against the parent's at the same speed, and by
the gap between its two friction forms. The parent's own two forms agree to about 1 %.
Everything runs in this process, one solve at a time; CPU times are recorded beside wall times.
"""

import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import bem
from bem.surfaces import measured
from viscobem_bench import instruments
from viscobem_bench.periodic.report import finish, table

LENGTH = 1e-3  # m, parent cell side
HURST, RMS_SLOPE = 0.8, 0.2
MATERIAL = dict(E0=1e6, E_inf=1e7, creep_time=0.01)  # Pa, Pa, s
P0 = 3e4  # Pa, nominal pressure (parent contact 3-25 % over the speeds)
SPEEDS = (1e-3, 1e-2, 1e-1)  # m/s: below, at and above the parents' friction peak
FRACTIONS = (0.25, 0.5)  # patch side / parent side
TREATMENTS = ("isolated", "isolated_taper", "guard_band", "mirror", "periodic_component", "tukey", "hann", "none")
FULL = dict(n=256, rolloffs=(2, 8), seeds=(1, 2, 3), positions=4, speeds=SPEEDS, treatments=TREATMENTS)
QUICK = dict(n=64, rolloffs=(4,), seeds=(1,), positions=2, speeds=(1e-3, 1e-2), treatments=TREATMENTS)
RTOL = 1e-8


def _solve(surface, material, speed, load, periodic):
    t0, c0 = time.perf_counter(), time.process_time()
    res = bem.solve(surface, material, speed=speed, load=load, periodic=periodic, rtol=RTOL, raise_on_failure=False)
    return res, time.perf_counter() - t0, time.process_time() - c0


def _inner_friction(res, surface, inner):
    """Both friction forms counted on the ``inner`` slice of an isolated domain: ``-sum p dh/dx /
    sum p`` and ``-sum p du/dx / sum p`` with central differences along x."""
    d = surface.spacing
    p = res.pressure[inner]
    dh = np.gradient(np.asarray(surface.heights), d, axis=0)[inner]
    du = np.gradient(res.displacement, d, axis=0)[inner]
    total = p.sum()
    return float(-(p * du).sum() / total), float(-(p * dh).sum() / total)


def _treatments(piece, names):
    """``{name: (surface, load, periodic, inner)}`` for a plane-detrended patch ``piece``
    (a Measurement); ``inner`` is the slice whose friction counts (None: the whole cell)."""
    with warnings.catch_warnings():  # the treatments' own warnings are the subject here
        warnings.simplefilter("ignore", UserWarning)
        return {name: _treatment(piece, name) for name in names}


def _treatment(piece, name):
    side = piece.physical_sizes[0]
    m = piece.heights.shape[0]
    if name in ("isolated", "isolated_taper"):
        s = measured.to_surface(piece, m, boundary="isolated", detrend="none")
        if name == "isolated_taper":
            import scipy.signal as ssig

            w = ssig.windows.tukey(m, 0.25)
            h = np.asarray(s.heights)
            s = bem.surfaces.from_heights(h - (1 - np.outer(w, w)) * np.ptp(h), side, centered=True)
        return s, P0 * side**2, False, None
    if name == "guard_band":
        band = max(1, m // 8)
        mirrored = np.pad(piece.heights, band, mode="symmetric")
        s = bem.surfaces.from_heights(mirrored, side * (m + 2 * band) / m, centered=True)
        return s, P0 * s.length**2, False, (slice(band, band + m), slice(band, band + m))
    s = measured.to_surface(piece, m, boundary="periodic", window=name, detrend="none")
    return s, P0 * side**2, True, None  # on the patch: bem.solve gives the mirrored cell its share


def _parent(n, rolloff, seed, material, speeds):
    surface = bem.surfaces.self_affine(
        n, LENGTH, hurst=HURST, scales=n // 8, rolloff=rolloff, rms_slope=RMS_SLOPE, seed=seed
    )
    rows = []
    for v in speeds:
        res, wall, cpu = _solve(surface, material, v, P0 * LENGTH**2, True)
        rows.append(
            dict(
                speed=v,
                friction=res.friction,
                friction_eq6=res.friction_eq6,
                contact_fraction=res.contact_fraction,
                success=res.success,
                wall_time=wall,
                cpu_time=cpu,
            )
        )
    return surface, rows


def _patches(surface, fraction, count, rng):
    """``count`` square patches of side ``fraction L`` at random places (the parent wraps)."""
    h = np.asarray(surface.heights)
    n = h.shape[0]
    m = int(round(fraction * n))
    side = m * surface.spacing
    for i0, j0 in rng.integers(0, n, size=(count, 2)):
        piece = np.roll(h, (-int(i0), -int(j0)), axis=(0, 1))[:m, :m]
        yield (int(i0), int(j0)), measured.detrend(measured.Measurement(piece, (side, side)), "plane")


def run(quick=False, out_dir=None, echo=print, **overrides):
    """Measure every treatment on every patch (module docstring); print, write, return the record."""
    cfg = {**(QUICK if quick else FULL), **overrides}
    material = bem.Material.standard_linear_solid(**MATERIAL)
    started, cpu0 = time.perf_counter(), time.process_time()
    load_start = instruments.load_average()
    parents, solves = [], []
    for rolloff in cfg["rolloffs"]:
        for seed in cfg["seeds"]:
            surface, prow = _parent(cfg["n"], rolloff, seed, material, cfg["speeds"])
            parents.append(dict(rolloff=rolloff, seed=seed, n=cfg["n"], rows=prow))
            rng = np.random.default_rng(1000 * rolloff + seed)
            for fraction in FRACTIONS:
                for position, piece in _patches(surface, fraction, cfg["positions"], rng):
                    for name, (s, load, periodic, inner) in _treatments(piece, cfg["treatments"]).items():
                        for k, v in enumerate(cfg["speeds"]):
                            res, wall, cpu = _solve(s, material, v, load, periodic)
                            mu, mu6 = (
                                (res.friction, res.friction_eq6) if inner is None else _inner_friction(res, s, inner)
                            )
                            ref = prow[k]["friction"]
                            solves.append(
                                dict(
                                    treatment=name,
                                    rolloff=rolloff,
                                    seed=seed,
                                    fraction=fraction,
                                    position=list(position),
                                    speed=v,
                                    friction=mu,
                                    friction_eq6=mu6,
                                    parent_friction=ref,
                                    error=mu / ref - 1,
                                    form_gap=abs(mu6 - mu) / max(abs(mu), abs(mu6), 1e-300),
                                    contact_fraction=res.contact_fraction,
                                    cell_points=s.n,
                                    success=res.success,
                                    wall_time=wall,
                                    cpu_time=cpu,
                                )
                            )
                    echo(f"rolloff {rolloff} seed {seed} patch {fraction:g} L at {position}: done")
            if out_dir is not None:  # the solves so far, in case the run is stopped
                instruments.write_record(out_dir, "measured.partial.json", dict(parents=parents, solves=solves))
    summary = _summary(solves, cfg)
    fields = dict(
        issue=25,
        parent=dict(
            n=cfg["n"],
            length_m=LENGTH,
            hurst=HURST,
            scales=cfg["n"] // 8,
            rms_slope=RMS_SLOPE,
            material=MATERIAL,
            nominal_pressure_Pa=P0,
            rtol=RTOL,
        ),
        speeds_m_s=list(cfg["speeds"]),
        machine=dict(
            cpu_count=os.cpu_count(),
            load_average_start=load_start,
            load_average_end=instruments.load_average(),
            shared=True,
        ),
        cpu_time=time.process_time() - cpu0,
        chosen=measured.DEFAULT_WINDOW,
        summary=summary,
        ranking=_ranking(summary),
        by_seed=_by_seed(solves, cfg),
        parents=parents,
    )
    if out_dir is not None:  # every solve, beside the record (the record keeps the tables)
        instruments.write_record(out_dir, "measured_solves.json", solves)
        (Path(out_dir) / "measured.partial.json").unlink(missing_ok=True)
    return finish("measured", started, _report, out_dir, echo, **fields)


def _stats(rows):
    err = np.array([r["error"] for r in rows])
    gap = np.array([r["form_gap"] for r in rows])
    return dict(
        patches=len(rows),
        mean_error=float(err.mean()),
        rms_error=float(np.sqrt(np.mean(err**2))),
        max_abs_error=float(np.abs(err).max()),
        within_15_percent=float(np.mean(np.abs(err) <= 0.15)),
        max_form_gap=float(gap.max()),
        median_form_gap=float(np.median(gap)),
        converged=all(r["success"] for r in rows),
    )


def _summary(solves, cfg):
    """Per treatment, patch size, roll-off and speed: the patches' friction errors against the
    parent and their friction-form gaps."""
    out = []
    for name in cfg["treatments"]:
        for fraction in FRACTIONS:
            for rolloff in cfg["rolloffs"]:
                for v in cfg["speeds"]:
                    rows = [
                        r
                        for r in solves
                        if r["treatment"] == name
                        and r["fraction"] == fraction
                        and r["rolloff"] == rolloff
                        and r["speed"] == v
                    ]
                    out.append(dict(treatment=name, fraction=fraction, rolloff=rolloff, speed=v, **_stats(rows)))
    return out


def _by_seed(solves, cfg):
    """Per treatment, patch size, roll-off, parent seed and speed: the mean error of the patches
    cut from that parent and their worst form gap."""
    out = []
    for name in cfg["treatments"]:
        for fraction in FRACTIONS:
            for rolloff in cfg["rolloffs"]:
                for seed in cfg["seeds"]:
                    for v in cfg["speeds"]:
                        rows = [
                            r
                            for r in solves
                            if (r["treatment"], r["fraction"], r["rolloff"], r["seed"], r["speed"])
                            == (name, fraction, rolloff, seed, v)
                        ]
                        out.append(
                            dict(
                                treatment=name,
                                fraction=fraction,
                                rolloff=rolloff,
                                seed=seed,
                                speed=v,
                                mean_error=float(np.mean([r["error"] for r in rows])),
                                max_abs_error=float(max(abs(r["error"]) for r in rows)),
                                max_form_gap=float(max(r["form_gap"] for r in rows)),
                            )
                        )
    return out


def _ranking(summary):
    """Per treatment and patch size, over roll-offs and speeds: rms of the friction errors (the
    patches' rms errors pooled), the worst error and the worst form gap."""
    out = []
    for name in dict.fromkeys(r["treatment"] for r in summary):
        for fraction in FRACTIONS:
            rows = [r for r in summary if r["treatment"] == name and r["fraction"] == fraction]
            weights = np.array([r["patches"] for r in rows], dtype=float)
            out.append(
                dict(
                    treatment=name,
                    fraction=fraction,
                    rms_error=float(
                        np.sqrt(np.sum(weights * np.array([r["rms_error"] ** 2 for r in rows])) / weights.sum())
                    ),
                    mean_abs_bias=float(np.mean([abs(r["mean_error"]) for r in rows])),
                    max_abs_error=max(r["max_abs_error"] for r in rows),
                    within_15_percent=float(np.sum(weights * [r["within_15_percent"] for r in rows]) / weights.sum()),
                    max_form_gap=max(r["max_form_gap"] for r in rows),
                )
            )
    return out


def _report(result, markdown=False):
    p = result["parent"]
    head = (
        f"Patches of a periodic self-affine parent ({p['n']}² over {1e3 * p['length_m']:g} mm, H {p['hurst']}, "
        f"{p['scales']} scales, rms slope {p['rms_slope']}); standard linear solid {p['material']}; nominal "
        f"pressure {p['nominal_pressure_Pa']:g} Pa; speeds {result['speeds_m_s']} m/s. Error = patch friction / "
        f"parent friction - 1; form gap = |eq. 6 - dissipation| / max. Default window: {result['chosen']}. "
        f"Load average {result['machine']['load_average_start']} -> {result['machine']['load_average_end']} "
        f"on {result['machine']['cpu_count']} shared cores; CPU {result['cpu_time']:.0f} s."
    )
    rank = [
        [
            r["treatment"],
            f"{r['fraction']:g}",
            f"{100 * r['rms_error']:.1f}",
            f"{100 * r['mean_abs_bias']:.1f}",
            f"{100 * r['max_abs_error']:.0f}",
            f"{100 * r['within_15_percent']:.0f}",
            f"{100 * r['max_form_gap']:.1f}",
        ]
        for r in result["ranking"]
    ]
    detail = [
        [
            r["treatment"],
            f"{r['fraction']:g}",
            f"{r['rolloff']:g}",
            f"{r['speed']:g}",
            f"{100 * r['mean_error']:+.1f}",
            f"{100 * r['rms_error']:.1f}",
            f"{100 * r['max_abs_error']:.0f}",
            f"{100 * r['max_form_gap']:.1f}",
            "yes" if r["converged"] else "NO",
        ]
        for r in result["summary"]
    ]
    parents = [
        [f"{q['rolloff']:g}", str(q["seed"]), f"{r['speed']:g}", f"{r['friction']:.4f}"]
        + [f"{100 * abs(r['friction_eq6'] / r['friction'] - 1):.2f}", f"{r['contact_fraction']:.3f}"]
        for q in result["parents"]
        for r in q["rows"]
    ]
    return "\n\n".join(
        [
            ("# " if markdown else "") + "Measured patches against their parent surface",
            head,
            table(
                ["treatment", "patch side / L", "rms error %", "mean |bias| %", "max |error| %", "within 15 % (%)"]
                + ["max form gap %"],
                rank,
                markdown,
            ),
            table(
                ["treatment", "side / L", "rolloff", "speed", "mean error %", "rms %", "max |error| %", "max gap %"]
                + ["conv"],
                detail,
                markdown,
            ),
            table(["rolloff", "seed", "speed", "parent friction", "form gap %", "contact"], parents, markdown),
            f"total time {result['total_time']:.0f} s",
        ]
    )


def main(argv=None):
    instruments.bench_main(run, __doc__.split("\n")[0], "measured.json and .md", argv)
    return 0


if __name__ == "__main__":
    sys.exit(main())
