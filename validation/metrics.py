"""Error metrics of the validation harness, and the cost (time, memory) of a solver call.

Pressures are compared *honestly* across discretisations (documented once, here):

- Against an exact solution, every solver is evaluated at its own sample points (BEM grid
  points, FEM surface nodes) and the exact pressure is evaluated there: no interpolation
  error is added to anybody's error. Integrals (the L2 norm) use the trapezoid rule on
  those samples, so they do not depend on how densely a solver samples.
- Between two solvers without an exact solution (BEM against FEM), both pressures are
  averaged over common bins as wide as the *coarser* sample spacing (exact integrals of
  each solver's piecewise-linear interpolant, :func:`bin_average`). Point values on two
  grids near a square-root contact edge differ by O(1) for sampling reasons alone; bin
  averages differ only by what the solvers disagree on, to second order in the bin width.

Relative errors are dimensionless; edge errors are in units of the solver's own sample
spacing (element or cell size), so "within one element" reads as ``<= 1``.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from dataclasses import dataclass

import numpy as np

__all__ = ["rel_l2", "rel_max", "rel_diff", "bin_average", "sampled_edges", "edge_error", "Cost", "measure"]


def _trapz(y, x):
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)))


def rel_l2(x, p, p_ref, weight=None):
    """``sqrt(int w (p - p_ref)^2 dx / int w p_ref^2 dx)`` by the trapezoid rule on ``x``
    (increasing, any spacing); ``weight`` ``w`` defaults to 1 (use ``r`` for axisymmetric
    fields). For 2-D fields pass flattened arrays with ``x = None``: the samples are then
    taken as equally weighted (uniform grid)."""
    p, p_ref = np.asarray(p, float), np.asarray(p_ref, float)
    if x is None:
        return float(np.sqrt(np.sum((p - p_ref) ** 2) / np.sum(p_ref**2)))
    x = np.asarray(x, float)
    w = 1.0 if weight is None else np.asarray(weight, float)
    return float(np.sqrt(_trapz(w * (p - p_ref) ** 2, x) / _trapz(w * p_ref**2, x)))


def rel_max(p, p_ref):
    """``max |p - p_ref| / max |p_ref|``."""
    p, p_ref = np.asarray(p, float), np.asarray(p_ref, float)
    return float(np.max(np.abs(p - p_ref)) / np.max(np.abs(p_ref)))


def rel_diff(value, ref):
    """``|value - ref| / |ref|``."""
    return float(abs(value - ref) / abs(ref))


def bin_average(x, p, edges):
    """Mean of the piecewise-linear interpolant of ``(x, p)`` over each bin ``[e_i, e_i+1]``.

    Exact for the interpolant: the integral is the trapezoid rule on the union of the
    samples and the bin edges. ``x`` increasing; outside ``[x[0], x[-1]]`` ``p`` is taken
    as 0 (contact pressures vanish there).
    """
    x, p, edges = np.asarray(x, float), np.asarray(p, float), np.asarray(edges, float)
    inside = np.clip(edges, x[0], x[-1])  # zero outside the samples: integrate over the overlap only
    pts = np.union1d(x, inside)
    vals = np.interp(pts, x, p)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (vals[1:] + vals[:-1]) * np.diff(pts))])
    at = np.interp(inside, pts, cum)
    return np.diff(at) / np.diff(edges)


def sampled_edges(x, p):
    """Contact edges ``(trailing, leading)`` (m) of sampled pressures: midway between the
    outermost sample in contact (``p > 0``) and its out-of-contact neighbour, so the
    sampling error is at most half a spacing. ``x`` increasing and uniform near the edges."""
    x, p = np.asarray(x, float), np.asarray(p, float)
    idx = np.flatnonzero(p > 0)
    lo, hi = idx[0], idx[-1]
    trail = 0.5 * (x[lo] + x[lo - 1]) if lo > 0 else x[lo]
    lead = 0.5 * (x[hi] + x[hi + 1]) if hi < x.size - 1 else x[hi]
    return float(trail), float(lead)


def edge_error(edge, ref, spacing):
    """``|edge - ref| / spacing``: the edge error in element (cell) sizes."""
    return float(abs(edge - ref) / spacing)


@dataclass(frozen=True)
class Cost:
    """Wall time (s) and peak memory (MiB) of one solver call."""

    seconds: float
    peak_mib: float


def _rss():
    """Current resident set size (bytes) from /proc (Linux), else the peak from getrusage."""
    try:
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        import resource

        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        return int(peak if sys.platform == "darwin" else peak * 1024)


def measure(fn, *args, interval=0.02, **kwargs):
    """Call ``fn(*args, **kwargs)``; return ``(result, Cost)``.

    Memory is the peak growth of the process's resident set during the call, sampled every
    ``interval`` seconds by a background thread: the true footprint, compiled libraries
    included (SuperLU factors, FFT buffers), but spikes shorter than ``interval`` can be
    missed and pages the process already held from earlier calls are not counted again.
    (``tracemalloc`` would be exact for NumPy arrays but slows the solvers 2-3x.)
    """
    base = _rss()
    peak = [base]
    done = threading.Event()

    def sample():
        while not done.wait(interval):
            peak[0] = max(peak[0], _rss())

    thread = threading.Thread(target=sample, daemon=True)
    thread.start()
    t0 = time.perf_counter()
    try:
        out = fn(*args, **kwargs)
    finally:
        seconds = time.perf_counter() - t0
        done.set()
        thread.join()
        peak[0] = max(peak[0], _rss())
    return out, Cost(seconds, (peak[0] - base) / 2**20)
