"""What :func:`bem.solve` adds to every result: its error estimate and its warnings.

:func:`assess` takes a finished solve, computes the indicators of :mod:`bem.accuracy.indicators`
(a few FFTs of the pressure), the estimate asked for (:mod:`bem.accuracy.estimate` by default,
:mod:`bem.accuracy.refined` on request) and the findings of :mod:`bem.accuracy.findings`, and
returns the result with ``error_estimate`` and ``warnings`` filled in.
"""

import dataclasses
import time

import numpy as np

from ..errors import InputError
from . import indicators as ind
from .estimate import from_indicators, not_estimated
from .findings import Finding, findings_of

__all__ = ["ESTIMATES", "assess", "check_estimate", "indicators_of", "material_findings"]

ESTIMATES = ("indicators", "refined", None)


def check_estimate(value):
    """``value`` if it is one of :data:`ESTIMATES`, else :class:`~bem.errors.InputError`."""
    if value not in ESTIMATES:
        raise InputError(
            f"error_estimate must be 'indicators' (default, from the solution itself), 'refined' (a solve "
            f"on the grid twice as fine) or None (no estimate), got {value!r}"
        )
    return value


def indicators_of(result, surface, material, *, periodic, direction=0.0):
    """The indicators of one solution (a dict of plain numbers; see :mod:`bem.accuracy.indicators`)."""
    p = result.pressure
    contact = p > 0
    cells = int(np.count_nonzero(contact))
    sharp, to_edge = ind.peak_sharpness(p, periodic)
    spike, growth = ind.leading_edge_layers(
        p, material, result.speed, surface.spacing, periodic=periodic, direction=direction
    )
    out = {
        "contact_cells": cells,
        "contact_edge_faces": int(round(ind.contact_perimeter(contact, periodic) * cells)),
        "dissipation_moment": ind.dissipation_moment(
            p, material, result.speed, surface.length, periodic=periodic, direction=direction
        ),
        "interior_roughness": ind.interior_roughness(p, periodic),
        "peak_sharpness": sharp,
        "peak_cells_to_edge": to_edge,
        "subcell_layers": ind.subcell_layers(material, result.speed, surface.spacing),
        "edge_spike": spike,
        "edge_growth": growth,
        "spacing": surface.spacing,
        "form_gap": ind.form_gap(result.friction, result.friction_eq6),
        # the heights' spectrum means nothing across an isolated domain's edges
        "points_per_wavelength": ind.points_per_wavelength(surface.heights) if periodic else None,
    }
    if not periodic:
        out["edge_load"] = ind.edge_load(p)
    return out


def assess(result, surface, material, *, periodic, direction=0.0, estimate="indicators", resolve=None):
    """``result`` with ``error_estimate`` and ``warnings`` (see the module docstring).

    ``estimate``: ``"indicators"``, ``"refined"`` (needs ``resolve(surface, initial)``, a solve of
    the same problem on another surface from a first iterate) or ``None``. A solve that did not
    converge gets no estimate and a warning that says so; ``None`` gives neither estimate nor
    warnings.
    """
    t0 = time.perf_counter()
    if not result.success:
        est = not_estimated("the solve did not converge")
        found = findings_of(result, est, {}, surface.n)
    elif estimate is None:
        est, found = not_estimated("not requested (error_estimate=None)"), ()
    else:
        values = indicators_of(result, surface, material, periodic=periodic, direction=direction)
        est = from_indicators(values, surface.ndim)
        if estimate == "refined":
            from .refined import refined_estimate  # scipy.interpolate: only when asked for

            est = refined_estimate(result, surface, resolve, periodic=periodic, indicators=values, fallback=est)
        found = findings_of(result, est, values, surface.n) + material_findings(
            result, surface, material, periodic=periodic, direction=direction
        )
    est = dataclasses.replace(est, seconds=time.perf_counter() - t0)
    return dataclasses.replace(result, error_estimate=est, warnings=tuple(found))


def material_findings(result, surface, material, *, periodic, direction=0.0):
    """What the material's data do not cover of the frequencies this solve loads it at
    (:func:`bem.accuracy.indicators.loading_band`; :meth:`bem.Material.extrapolation_warnings`),
    as findings of kind ``"material_data"``: a fitted material used beyond its DMA data, or a
    shift law beyond its range. Empty at rest and for a material given by its constants."""
    w_low, w_high = ind.loading_band(surface, result.speed, periodic=periodic, direction=direction)
    if w_high == 0.0:
        return tuple(Finding(text, "material_data") for text in material.warnings)
    return tuple(Finding(text, "material_data") for text in material.extrapolation_warnings(w_low, w_high))
