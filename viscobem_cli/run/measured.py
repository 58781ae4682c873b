"""The record of a measured surface in ``results.json``, and its PSD plot (scene kind ``measured``,
:mod:`viscobem_cli.scene.measured`)."""

import numpy as np

from bem.surfaces.measured import speed_limit

from ..plots.measured import psd_plot

__all__ = ["report"]


def _plain(value):
    if hasattr(value, "items"):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, (np.floating, np.integer, np.bool_)):
        return value.item()
    return value


def report(scene, record, out):
    """Put the measured surface's record in ``record["measured"]`` (with ``patch_loads``, the loads
    on the scanned patch, ``speed_limit`` and ``patches``, one per square when the scan is
    covered) and a warning if speeds exceed the speed limit; the PSD plot if plots are on.
    Returns the files written."""
    rec = _plain(scene.surface.metadata["measured"])
    rec["patch_loads"] = list(scene.loads)  # what was asked; bem.solve gives the cell its share
    rec["cell_loads"] = [load * rec["load_factor"] for load in scene.loads]
    rec["speed_limit"] = speed_limit(scene.surface, scene.material)  # the curve's warnings say where
    if len(scene.realisations) > 1:
        rec["patches"] = [_plain(s.metadata["measured"]["patch"]) for s in scene.realisations]
    record["measured"] = rec
    if not scene.outputs.get("plots"):
        return []
    psd_plot(rec, out / "measured_psd.png")
    return ["measured_psd.png"]
