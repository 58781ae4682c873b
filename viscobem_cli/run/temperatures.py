"""Friction against speed and temperature: the study once per temperature of the scene, and the
combined record (the scene keys are described in :mod:`viscobem_cli.scene.temperatures`); or,
with ``superposition = true``, one curve over the reduced speeds (:func:`superposed`).

Each temperature's study (:func:`viscobem_cli.scene.temperatures.scene_at`) lists its own
material, ``xi_time`` and ``xi``, all from the material at that temperature."""

import json
import time
from pathlib import Path

import numpy as np

from bem.materials.master_curve import MasterCurveReport

from ..files import write_atomic
from ..plots.temperatures import plot_grosch, plot_master_curve, plot_temperature_sweep
from ..scene.temperatures import scene_at

__all__ = ["combine", "folder_name", "studies", "summary", "superposed", "write_master_curve"]


def folder_name(T):
    return f"T_{T:.2f}K"


def studies(scene):
    """``(study, folder)`` per temperature of ``scene``: the scene at that temperature (the material
    at T, and xi with its time: :func:`viscobem_cli.scene.temperatures.scene_at`) and the sub-folder
    its study writes to."""
    return [(scene_at(scene, T), folder_name(T)) for T in scene.temperatures]


def combine(scene, records, out, started):
    """The combined record of the per-temperature ``records`` (also written to ``out``), and the
    master-curve files; ``started`` is the sweep's start (``time.perf_counter()``)."""
    out = Path(out)
    law = scene.shift
    table = {
        "temperature": list(scene.temperatures),
        "units": {"temperature": "K", "speed": "m/s"},
        "shift": {"law": type(law).__name__, **vars(law)},
        "log10_shift_factor": [float(law(T)) for T in scene.temperatures],
        "folders": [folder_name(T) for T in scene.temperatures],
        "loads": [],
    }
    for k, load in enumerate(scene.loads):
        curves = [r["curves"][k] for r in records]
        table["loads"].append(
            {
                "load": load,
                "speed": curves[0]["speed"],
                "friction": [c["friction"] for c in curves],
                "contact_fraction": [c["contact_fraction"] for c in curves],
            }
        )
    nearest = int(np.argmin(np.abs(np.array(scene.temperatures) - law.reference_temperature)))
    record = {
        key: records[nearest][key]
        for key in (
            "title",
            "scene",
            "material",
            "surface",
            "units",
            "conventions",
            "solver",
            "outputs",
            "friction_curve",
            "curves",
        )
    }
    extra = [
        f"at {T:g} K: {w}" for T, r in zip(scene.temperatures, records) for w in r["warnings"][len(scene.warnings) :]
    ]
    record.update(
        temperature_sweep=table,
        friction_curve_temperature=scene.temperatures[nearest],
        warnings=list(scene.warnings) + extra,
        resumed_points=sum(r["resumed_points"] for r in records),
        all_converged=all(r["all_converged"] for r in records),
        complete=True,
        stages={"total": time.perf_counter() - started},
    )
    files = [f"{folder_name(T)}/{name}" for T, r in zip(scene.temperatures, records) for name in r["files"]]
    if scene.outputs.get("plots"):
        files += plot_temperature_sweep(table, out)
    files += write_master_curve(scene, out)
    record["files"] = ["results.json"] + files
    write_atomic(out / "results.json", json.dumps(record, indent=1))
    return record


def summary(record):
    """Text table of the friction coefficient per speed (rows) and temperature (columns)."""
    table = record["temperature_sweep"]
    lines = []
    if table.get("method"):  # superposed: how the map was made
        for sweep in table["loads"]:
            est = [e for row in sweep["interpolation_error"] for e in row if e is not None]
            lines.append(
                f"  {table['method']}: {sweep['solves']} solves ({sweep['operator_products']} operator products) "
                f"for {len(table['temperature'])} temperatures x {len(sweep['speed'])} speeds"
                + (f"; largest estimated interpolation error {max(est):.2g}" if est else "")
            )
    for sweep in table["loads"]:
        lines.append(f"  friction coefficient at load {sweep['load']:g} (N; N/m for profiles), by temperature (K):")
        lines.append("  " + f"{'speed (m/s)':>12}" + "".join(f"{T:>10.2f}" for T in table["temperature"]))
        for i, v in enumerate(sweep["speed"]):
            cells = [sweep["friction"][k][i] for k in range(len(table["temperature"]))]
            lines.append("  " + f"{v:12.4e}" + "".join(f"{'failed':>10}" if c is None else f"{c:10.5f}" for c in cells))
    return "\n".join(lines)


def write_master_curve(scene, out):
    """``master_curve.png`` when the material was fitted to DMA sweeps at several temperatures."""
    report = scene.material.fit_report
    if not (isinstance(report, MasterCurveReport) and scene.outputs.get("plots") and scene.dma is not None):
        return []
    return [plot_master_curve(scene.dma, scene.material, report.law, Path(out) / "master_curve.png")]


def superposed(scene, out):
    """The temperature study from one curve per load on the reference material over the reduced
    speeds (:func:`bem.friction_map`); writes ``results.json`` (the ``temperature_sweep`` of
    :func:`combine`, with the reduced speeds, which points were interpolated and their estimated
    errors) and the plots, and returns the record."""
    import bem
    from bem.errors import InputError

    if np.any(np.asarray(scene.speeds) <= 0):
        raise InputError("[loading] superposition = true needs speeds > 0 m/s: a speed of 0 has no reduced speed")
    if len(scene.realisations) > 1:
        raise InputError("[loading] superposition = true maps one surface: give one realisation (seed)")
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    started = time.perf_counter()
    law = scene.shift
    options = dict(rtol=scene.rtol, maxiter=scene.maxiter, periodic=scene.periodic, method=scene.method)
    maps = [
        bem.friction_map(
            scene.surface,
            scene.material,
            speeds=scene.speeds,
            temperatures=scene.temperatures,
            shift=law,
            load=load,
            error_estimate=scene.error_estimate,
            **options,
        )
        for load in scene.loads
    ]
    table = {
        "temperature": list(scene.temperatures),
        "units": {"temperature": "K", "speed": "m/s", "reduced_speed": "m/s"},
        "shift": {"law": type(law).__name__, **vars(law)},
        "log10_shift_factor": [float(law(T)) for T in scene.temperatures],
        "method": maps[0].method,
        "loads": [
            {
                "load": m.load,
                "speed": [float(v) for v in m.speeds],
                "friction": _rows(m.friction),
                "contact_fraction": _rows(m.contact_fraction),
                "reduced_speed": _rows(m.reduced_speeds),
                "interpolated": m.interpolated.tolist(),
                "interpolation_error": _rows(m.interpolation_error),
                "curve": None
                if m.curve is None
                else {
                    "reduced_speed": [float(v) for v in m.curve.speeds],
                    "friction": _rows(m.curve.friction),
                    "contact_fraction": _rows(m.curve.contact_fraction),
                },
                "solves": len(m.results),
                "operator_products": m.matvecs,
            }
            for m in maps
        ],
    }
    record = {
        "title": scene.title,
        "scene": scene.source,
        "units": {"speed": "m/s", "temperature": "K", "load": "N (N/m for 1-D profiles)"},
        "temperature_sweep": table,
        "warnings": list(scene.warnings) + [w for m in maps for w in m.warnings],
        "all_converged": all(r is not None for m in maps for r in m.results),
        "complete": True,
        "stages": {"total": time.perf_counter() - started},
    }
    files = []
    if scene.outputs.get("plots"):
        files += plot_temperature_sweep(table, out) + plot_grosch(table, out)
    files += write_master_curve(scene, out)
    record["files"] = ["results.json"] + files
    write_atomic(out / "results.json", json.dumps(record, indent=1))
    return record


def _rows(a):
    """A float array as JSON lists, None where it is NaN (a failed solve)."""
    a = np.asarray(a, dtype=float)
    return np.where(np.isfinite(a), a, None).tolist()
