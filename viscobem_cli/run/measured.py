"""The record of a measured surface in ``results.json``, and its PSD plot (scene kind ``measured``,
:mod:`viscobem_cli.scene.measured`)."""

import numpy as np

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
    """Put the measured surface's record in ``record["measured"]``; the PSD plot if plots are on.
    Returns the files written."""
    rec = _plain(scene.surface.metadata["measured"])
    record["measured"] = rec
    if not scene.outputs.get("plots"):
        return []
    psd_plot(rec, out / "measured_psd.png")
    return ["measured_psd.png"]
