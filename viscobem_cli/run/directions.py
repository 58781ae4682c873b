"""A sweep over sliding directions: the study once per direction of the scene, each in its own
folder (run by :func:`viscobem_cli.run.study.run_scene`), and the gathered record (the scene key is described in :mod:`viscobem_cli.scene.directions`)."""

import dataclasses
import json
import math
import time
from pathlib import Path

from ..files import write_atomic
from ..plots.directions import polar_plot

__all__ = ["finish", "folder_name", "gather", "studies", "write_progress"]


def folder_name(theta):
    """Sub-folder of one direction of a sweep."""
    return f"direction_{math.degrees(theta):07.3f}".replace("-", "m")


def studies(scene):
    """``(study, folder)`` per direction of ``scene``: the scene along that direction alone and
    the sub-folder its study writes to."""
    return [(dataclasses.replace(scene, directions=(theta,)), folder_name(theta)) for theta in scene.directions]


def write_progress(scene, records, out):
    """The top-level ``results.json`` so far: the first direction's record plus ``directions``,
    with ``warnings`` gathering every direction's own (each prefixed by its direction); it is
    rewritten after each direction, so an interrupted sweep keeps the directions it finished."""
    record = dict(records[0])
    record["directions"] = gather(scene, records)
    record["warnings"] = list(scene.warnings) + [
        f"at direction {math.degrees(t):g} deg: {w}"
        for t, r in zip(scene.directions, records)
        for w in r["warnings"][len(scene.warnings) :]
    ]
    write_atomic(Path(out) / "results.json", json.dumps(record, indent=1))
    return record


def finish(scene, records, out, started):
    """The gathered record of the per-direction ``records`` (also written), with the polar plot;
    ``started`` is the sweep's start (``time.perf_counter()``)."""
    out = Path(out)
    record = write_progress(scene, records, out)
    record["all_converged"] = all(r["all_converged"] for r in records)
    record["resumed_points"] = sum(r["resumed_points"] for r in records)
    files = ["results.json"] + [f"{folder_name(t)}/{f}" for t, r in zip(scene.directions, records) for f in r["files"]]
    if scene.outputs.get("plots"):
        polar_plot(record["directions"], out / "friction_polar.png")
        files.append("friction_polar.png")
    record["files"] = files
    record["stages"] = dict(record["stages"], total=time.perf_counter() - started)
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
