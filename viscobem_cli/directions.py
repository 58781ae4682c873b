"""Sliding direction in scenes: ``[loading] direction_deg`` (a number, or a list: a sweep).

``direction_deg`` is measured from ``+x`` toward ``+y`` in degrees (``bem.solve``'s
``direction`` in radians); 1-D profiles take 0 or 180 only, the adaptive mesh multiples of 90.
One direction: every point of the study slides along it. A list: the study runs once per
direction, each in its own folder ``direction_DDD.DDD/`` (its own results.json, fields and
plots, resumable like any study), and the top-level ``results.json`` gathers
``directions`` (friction, its eq. 6 form and the contact fraction per direction and speed,
first load, ensemble means) beside the first direction's full record, with a polar plot
``friction_polar.png`` of mu(theta) at each speed.
"""

import dataclasses
import json
import math
import time
from pathlib import Path

import numpy as np

from bem import direction as sliding_direction
from bem.errors import InputError

__all__ = ["folder_name", "parse", "polar_plot", "run_sweep"]


def parse(loading, surface, periodic, method="auto"):
    """The scene's directions (radians, a tuple) from ``[loading] direction_deg``."""
    value = loading.get("direction_deg", 0.0)
    values = value if isinstance(value, list) else [value]
    if not values or not all(
        isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in values
    ):
        raise InputError(
            f"[loading] direction_deg must be a finite angle in degrees or a non-empty list of them, got {value!r}"
        )
    if len({float(v) for v in values}) != len(values):
        raise InputError(f"[loading] direction_deg must not repeat an angle, got {value!r}")
    out = []
    for v in values:
        theta = math.radians(float(v))
        try:
            sliding_direction.plan(theta, surface.ndim, periodic, method)
        except InputError as err:
            raise InputError(f"[loading] direction_deg = {v!r}: {err}") from None
        out.append(theta)
    return tuple(out)


def folder_name(theta):
    """Sub-folder of one direction of a sweep."""
    return f"direction_{math.degrees(theta):07.3f}".replace("-", "m")


def run_sweep(run_scene, scene, out_dir, **options):
    """``run_scene`` once per direction of ``scene`` (each in its folder); the gathered record.

    The top-level ``results.json`` is the first direction's record plus ``directions``; it is
    rewritten after each direction, so an interrupted sweep keeps the directions it finished.
    """
    from .sweep import write_atomic

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    records = []
    record = None
    for theta in scene.directions:
        one = dataclasses.replace(scene, directions=(theta,))
        records.append(run_scene(one, out / folder_name(theta), **options))
        record = dict(records[0])
        record["directions"] = gather(scene, records)
        write_atomic(out / "results.json", json.dumps(record, indent=1))
    record["all_converged"] = all(r["all_converged"] for r in records)
    record["resumed_points"] = sum(r["resumed_points"] for r in records)
    files = ["results.json"] + [f"{folder_name(t)}/{f}" for t, r in zip(scene.directions, records) for f in r["files"]]
    if scene.outputs.get("plots"):
        polar_plot(record["directions"], out / "friction_polar.png")
        files.append("friction_polar.png")
    record["files"] = files
    record["stages"] = dict(record["stages"], total=time.perf_counter() - t0)
    write_atomic(out / "results.json", json.dumps(record, indent=1))
    return record


def gather(scene, records):
    """mu(theta) per speed (first load; ensemble means), degrees and radians, from the records."""
    keys = ("friction", "friction_eq6", "contact_fraction")
    table = {k: [r["friction_curve"][k] for r in records] for k in keys}
    thetas = scene.directions[: len(records)]
    return {
        "direction_deg": [round(math.degrees(t), 9) for t in thetas],
        "direction_rad": list(thetas),
        "speed": records[0]["friction_curve"]["speed"],
        "xi": records[0]["friction_curve"]["xi"],
        "load": records[0]["friction_curve"]["load"],
        **table,
        "folders": [folder_name(t) for t in thetas],
        "note": "rows per direction, columns per speed; friction opposes the motion along each direction",
    }


def polar_plot(table, path):
    """Polar plot of mu(theta): one closed curve per speed (directions as given, sorted)."""
    from .plot_style import _pyplot, _save

    plt = _pyplot()
    fig = plt.figure(figsize=(5.6, 5.2), constrained_layout=True)
    ax = fig.add_subplot(projection="polar")
    theta = np.asarray(table["direction_rad"], dtype=float)
    order = np.argsort(theta % (2 * np.pi))
    mu = np.array([[np.nan if v is None else v for v in row] for row in table["friction"]], dtype=float)
    for j, xi in enumerate(table["xi"]):
        t, m = theta[order], mu[order, j]
        closed = len(t) > 2
        ax.plot(
            np.append(t, t[0]) if closed else t, np.append(m, m[0]) if closed else m, "o-", ms=4, label=f"xi = {xi:.3g}"
        )
    ax.set_title("friction coefficient against sliding direction\n(angle from +x toward +y)", fontsize=9)
    ax.legend(fontsize=7, loc="lower left", bbox_to_anchor=(-0.1, -0.12))
    _save(fig, path)
