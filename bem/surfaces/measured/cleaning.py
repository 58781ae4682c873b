"""Cleaning a measured topography before it is solved: removing its trend (a tilt is not roughness:
left in, it adds its slope to every contact and to both friction forms).

**Detrending** (:func:`detrend`): the least-squares plane by default, in
:func:`~bem.surfaces.measured.from_scan`, :func:`~bem.surfaces.measured.to_surface` and the scene
kind alike, applied to the square patch that is solved and recorded in
``surface.metadata["measured"]["detrend"]``.
"""

from dataclasses import replace

import numpy as np

from ...errors import InputError

__all__ = ["DETREND_MODES", "detrend"]

DETREND_MODES = ("none", "mean", "plane", "curvature")


def _basis(shape, sizes, mode):
    """Polynomial basis (columns) on the pixel centres, coordinates scaled to [-1, 1]."""
    axes = [(np.arange(n) + 0.5) / n * 2 - 1 for n in shape]
    grids = np.meshgrid(*axes, indexing="ij")
    cols = [np.ones(shape)]
    if mode in ("plane", "curvature"):
        cols += list(grids)
    if mode == "curvature":
        cols += [g * g for g in grids]
        if len(grids) == 2:
            cols.append(grids[0] * grids[1])
    return np.stack([c.ravel() for c in cols], axis=1)


def detrend(measurement, mode="plane"):
    """Remove the least-squares fit of a polynomial: ``"mean"`` (a constant), ``"plane"`` (the
    mean plane; a line for a line scan), ``"curvature"`` (a quadratic surface: plane plus
    ``x**2``, ``y**2``, ``x y``) or ``"none"``. Returns a new :class:`Measurement` recording it."""
    if mode not in DETREND_MODES:
        raise InputError(f"detrend must be one of {', '.join(map(repr, DETREND_MODES))}, got {mode!r}")
    h = measurement.heights
    if mode != "none":
        basis = _basis(h.shape, measurement.physical_sizes, mode)
        coef, *_ = np.linalg.lstsq(basis, h.ravel(), rcond=None)
        h = (h.ravel() - basis @ coef).reshape(h.shape)
    done = _stronger(measurement.source.get("detrend", "none"), mode)
    return replace(measurement, heights=h, source={**measurement.source, "detrend": done})


def _stronger(done, mode):
    """The detrending a measurement has had after ``mode`` is applied over ``done``."""
    order = DETREND_MODES
    return order[max(order.index(done), order.index(mode))] if done in order else mode
