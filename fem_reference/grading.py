"""Coordinates graded geometrically toward focus points (for tensor meshes).

The element size requested at position ``x`` is

    h(x) = min( cap(x),  min_i [ s_i + (ratio - 1) |x - f_i| ] ),

the smallest size ``s_i`` at each focus point ``f_i``, growing linearly with the distance
(so consecutive elements grow by at most ``ratio`` inside a segment between foci;
at a focus, where a shrunk segment meets its neighbour, by up to about ``1.2 ratio``), limited by an optional piecewise
constant ``cap``. Every focus point is a node. The number of elements between a focus of
size ``s`` and a distance ``D`` grows like ``log(D / s) / log(ratio)``, so a scale many
decades below the domain size costs a few tens of elements.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["graded_coordinates"]


def _size(x, foci, sizes, ratio, caps):
    h = np.min(sizes + (ratio - 1.0) * np.abs(x - foci))
    for lo, hi, cap in caps:
        if lo <= x <= hi:
            h = min(h, cap)
    return h


def _segment(a, b, foci, sizes, ratio, caps):
    """Interior points of ``(a, b)``, marched from its finer end, scaled to end exactly."""
    fine_at_b = _size(b, foci, sizes, ratio, caps) < _size(a, foci, sizes, ratio, caps)
    start, stop, sign = (b, a, -1.0) if fine_at_b else (a, b, 1.0)
    pts = [start]
    pos = start
    while True:
        step = _size(pos, foci, sizes, ratio, caps)
        for _ in range(5):  # the size at the end of the step bounds it too
            end = pos + sign * step
            end = min(end, stop) if sign > 0 else max(end, stop)
            step = min(step, _size(end, foci, sizes, ratio, caps))
        # a step that ends within round-off of ``stop`` is the last: segments that hold a whole
        # number of elements (a zone of so many elements) keep it whatever the last bits of ``stop``
        if sign * (pos + sign * step - stop) >= -1e-9 * step:
            break
        pos += sign * step
        pts.append(pos)
    pts = np.asarray(pts)
    if pts.size > 1:
        # shrink the points so that the last full step ends on ``stop``
        last = pts[-1] + sign * _size(pts[-1], foci, sizes, ratio, caps)
        pts = start + (pts - start) * (stop - start) / (last - start)
    pts = pts[1:]
    return pts[::-1] if fine_at_b else pts


def graded_coordinates(lo, hi, foci, sizes, *, ratio=1.2, caps=()):
    """Sorted node coordinates on ``[lo, hi]`` graded toward ``foci``.

    Parameters
    ----------
    lo, hi : float
        Ends of the axis (m), ``lo < hi``.
    foci : sequence of float
        Focus points inside ``[lo, hi]`` (m); each becomes a node.
    sizes : sequence of float
        Element size at each focus (m), > 0.
    ratio : float
        Largest ratio of neighbouring element sizes, > 1.
    caps : sequence of (lo, hi, size)
        Upper bounds of the element size on sub-intervals (m).

    Returns
    -------
    ndarray
        Strictly increasing coordinates, ``lo`` first and ``hi`` last.
    """
    foci = np.asarray(foci, dtype=float)
    sizes = np.asarray(sizes, dtype=float)
    if foci.shape != sizes.shape or np.any(sizes <= 0) or not ratio > 1 or not lo < hi:
        raise ValueError("need matching foci and positive sizes, ratio > 1 and lo < hi")
    breaks = np.unique(np.clip(np.concatenate([[lo, hi], foci]), lo, hi))
    out = [np.array([lo])]
    for a, b in zip(breaks[:-1], breaks[1:]):
        out.append(_segment(a, b, foci, sizes, ratio, caps))
        out.append(np.array([b]))
    x = np.concatenate(out)
    keep = np.concatenate([[True], np.diff(x) > 1e-12 * max(abs(lo), abs(hi), math.ulp(1.0))])
    return x[keep]
