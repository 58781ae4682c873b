"""The refined estimate: the same surface content solved on a grid twice as fine.

:func:`refine_surface` puts the heights on the grid with twice the points per axis without
adding roughness: on periodic cells by zero-padding their spectrum (band-limited
interpolation; the coarse points are fine points ``2i`` and keep their heights exactly), on
isolated domains, whose heights are not periodic, by a cubic spline through the element
centres (exact for the paraboloids of :func:`bem.surfaces.sphere` and
:func:`bem.surfaces.cylinder`). :func:`refined_estimate` solves it and measures each quantity's
change, ``|Q_n - Q_2n| / |Q_2n|``. Its cost is that of a solve with ``2**ndim`` times the
points (a warm start from the coarse pressure saves a share of it), and as many times the
memory.
"""

import dataclasses

import numpy as np
import scipy.fft as sfft
from scipy.interpolate import CubicSpline

from ..errors import ConvergenceError, InputError
from ..halfspace.periodic import PeriodicHalfSpace
from .estimate import QUANTITIES, ErrorEstimate

__all__ = ["refine_surface", "refined_estimate"]


def _pad_axis(spectrum, axis):
    """Zero-pad a full complex spectrum (``numpy.fft`` layout) to twice its length along ``axis``;
    an even length's Nyquist coefficient is split between the two modes ``±n/2`` it stands for."""
    n = spectrum.shape[axis]
    shape = list(spectrum.shape)
    shape[axis] = 2 * n
    out = np.zeros(shape, dtype=complex)

    def at(index):
        sl = [slice(None)] * spectrum.ndim
        sl[axis] = index
        return tuple(sl)

    half = (n + 1) // 2  # modes 0 .. half-1 and -(n-half) .. -1; for even n, index n/2 is Nyquist
    out[at(slice(0, half))] = spectrum[at(slice(0, half))]
    tail = n - half - (1 if n % 2 == 0 else 0)
    if tail:
        out[at(slice(2 * n - tail, 2 * n))] = spectrum[at(slice(n - tail, n))]
    if n % 2 == 0:
        nyquist = 0.5 * spectrum[at(n // 2)]
        out[at(n // 2)] = nyquist
        out[at(2 * n - n // 2)] = nyquist
    return out


def refine_surface(surface, periodic):
    """The surface on the grid with twice the points per axis and the same content (module doc)."""
    h = np.asarray(surface.heights, dtype=float)
    if periodic:
        spectrum = sfft.fftn(h, norm="forward")
        for axis in range(h.ndim):
            spectrum = _pad_axis(spectrum, axis)
        fine = sfft.ifftn(spectrum, norm="forward").real
    else:
        n = surface.n
        x = (np.arange(n) + 0.5) / n - 0.5
        xf = (np.arange(2 * n) + 0.5) / (2 * n) - 0.5
        fine = h
        for axis in range(h.ndim):
            fine = CubicSpline(x, fine, axis=axis)(xf)
    meta = dict(surface.metadata)
    meta["refined_from"] = surface.n
    return dataclasses.replace(surface, heights=fine, metadata=meta)


def _prolonged(pressure, periodic):
    """A first iterate on the finer grid: periodic linear interpolation (fine point ``2i`` is coarse
    point ``i``), or each element's pressure on its ``2**ndim`` children (isolated domains)."""
    if periodic:
        return PeriodicHalfSpace.prolong(pressure)
    fine = pressure
    for axis in range(pressure.ndim):
        fine = np.repeat(fine, 2, axis=axis)
    return fine


def refined_estimate(result, surface, resolve, *, periodic, indicators, fallback):
    """Measured errors of ``result`` against ``resolve(finer_surface, initial)``, a solve of the
    refined surface (:func:`refine_surface`) started from ``initial``.

    If that solve fails (it did not converge, or the finer grid is refused, e.g. an adaptive mesh
    above its ``max_elements``), ``fallback`` (the default estimate) is returned, with the reason in
    its indicators under ``refined``.
    """
    fine_surface = refine_surface(surface, periodic)
    try:
        fine = resolve(fine_surface, _prolonged(result.pressure, periodic))
    except (ConvergenceError, InputError) as err:
        note = {**fallback.indicators, "refined": f"the finer solve failed: {err}"}
        return dataclasses.replace(fallback, indicators=note)
    values, reasons, extra = {}, {}, {}
    for q in QUANTITIES:
        coarse, refined = _value(result, q), _value(fine, q)
        extra[f"refined_{q}"] = refined
        if refined == 0.0 or not np.isfinite(refined):
            reasons[q] = f"{q} is zero on the finer grid" if refined == 0.0 else f"{q} is not finite"
        else:
            values[q] = abs(coarse - refined) / abs(refined)
    extra["refined_points"] = int(fine_surface.n)
    extra["refined_wall_time"] = float(fine.wall_time)
    return ErrorEstimate(values, method="refined", reasons=reasons, indicators={**indicators, **extra})


def _value(result, quantity):
    if quantity == "peak_pressure":
        return float(np.max(result.pressure))
    return float(getattr(result, quantity))
