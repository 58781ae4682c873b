"""Cleaning a measured topography before it is solved: missing points, steps and trend.

**Missing points** (:func:`fill_missing`, one policy for arrays and every file): each is filled by
harmonic interpolation from its neighbours (the discrete Laplace equation over the missing
points, the known ones held), the smoothest surface through the hole, with a warning that says
how many and what fraction. A filled hole holds no roughness, so filling a fraction ``f`` of the
points removes about ``f`` of the mean square slope, the quantity friction and contact grow with;
above :data:`MAX_MISSING` (a tenth: about 5 % of the rms slope) the filled surface is no longer
the measured one within the accuracy the solver is held to, and the scan is refused.

**Steps** (:func:`find_steps`): a line across which the heights jump by more than the
pixel-to-pixel change of the roughness explains and by more than :data:`STEP_RMS` rms heights
(of the surface without the step) is a stitching or terrace artefact, or a real edge; either way
the top of the surface, where contact is, is the step's, so it is warned about.

**Trend** (a tilt is not roughness: left in, it adds its slope to every contact and to both
friction forms).

**Detrending** (:func:`detrend`): the least-squares plane by default, in
:func:`~bem.surfaces.measured.from_scan`, :func:`~bem.surfaces.measured.to_surface` and the scene
kind alike, applied to the square patch that is solved and recorded in
``surface.metadata["measured"]["detrend"]``.
"""

from dataclasses import replace

import numpy as np

from ...errors import InputError

__all__ = ["DETREND_MODES", "MAX_MISSING", "STEP_RMS", "detrend", "fill_missing", "find_steps"]

DETREND_MODES = ("none", "mean", "plane", "curvature")
MAX_MISSING = 0.1  # fraction of points: the module docstring gives the reason
STEP_RMS = 2.0  # rms heights: a jump above it puts the surface's top on the step's edge
# A jump across a line counts when its median over the line is this many times the robust rms of
# the pixel-to-pixel differences: a rough surface's median jump over a line is below one of them.
STEP_DIFFERENCES = 5.0


def fill_missing(heights):
    """``(filled, record, warnings)``: ``heights`` with every NaN replaced by the harmonic
    interpolation of its neighbours; ``record`` has ``filled_points`` and ``filled_fraction``;
    ``warnings`` a sentence when any was filled. More than :data:`MAX_MISSING` of the points
    missing is an InputError."""
    h = np.asarray(heights, dtype=float)
    missing = np.isnan(h)
    count = int(np.count_nonzero(missing))
    record = {"filled_points": count, "filled_fraction": count / h.size}
    if count == 0:
        return h, record, []
    if count > MAX_MISSING * h.size:
        raise InputError(
            f"scan has {count} of {h.size} points missing ({100 * count / h.size:.3g} %), more than "
            f"{100 * MAX_MISSING:g} %: filled, they would carry none of the roughness that friction comes from. "
            "Crop the scan to a region that was measured (or re-measure)"
        )
    from scipy import sparse
    from scipy.sparse.linalg import spsolve

    index = -np.ones(h.shape, dtype=int)
    index[missing] = np.arange(count)
    rows, cols, vals = [], [], []
    rhs = np.zeros(count)
    degree = np.zeros(count)
    known = np.where(missing, 0.0, h)
    for axis in range(h.ndim):
        for shift in (1, -1):
            # neighbour along `axis`, inside the scan only (no wrap-around: a scan is not periodic)
            nb_index = np.roll(index, -shift, axis=axis)
            nb_known = np.roll(known, -shift, axis=axis)
            inside = np.ones(h.shape, dtype=bool)
            edge = [slice(None)] * h.ndim
            edge[axis] = -1 if shift == 1 else 0
            inside[tuple(edge)] = False
            sel = missing & inside
            me = index[sel]
            degree[me] += 1
            other = nb_index[sel]
            is_missing = other >= 0
            rows.extend(me[is_missing])
            cols.extend(other[is_missing])
            vals.extend([-1.0] * int(np.count_nonzero(is_missing)))
            np.add.at(rhs, me[~is_missing], nb_known[sel][~is_missing])
    matrix = sparse.coo_matrix((vals, (rows, cols)), shape=(count, count)).tocsr() + sparse.diags(degree)
    filled = h.copy()
    filled[missing] = spsolve(matrix.tocsc(), rhs)
    text = (
        f"{count} of {h.size} points of the scan ({100 * count / h.size:.3g} %) were missing and were filled by "
        "harmonic interpolation from their neighbours (smooth: the holes carry no roughness)"
    )
    return filled, record, [text]


def find_steps(heights, spacing):
    """Sentences naming each line of the map (or point of a line scan) across which the heights
    jump by a step (module docstring); ``spacing`` (m) per axis places it."""
    h = np.asarray(heights, dtype=float)
    found = []
    for axis in range(h.ndim):
        d = np.diff(h, axis=axis)
        scale = 1.4826 * np.median(np.abs(d - np.median(d)))
        jumps = np.median(d, axis=tuple(a for a in range(h.ndim) if a != axis)) if h.ndim > 1 else d
        lines = np.flatnonzero(np.abs(jumps) > STEP_DIFFERENCES * max(scale, 1e-300))
        # neighbouring lines are one step spread over a few pixels (a smoothed edge)
        for run in np.split(lines, np.flatnonzero(np.diff(lines) > 1) + 1) if lines.size else []:
            found.append((axis, int(run[-1]), float(jumps[run].sum())))
    if not found:
        return []
    flat = h.copy()
    for axis, i, jump in found:
        later = [slice(None)] * h.ndim
        later[axis] = slice(i + 1, None)
        flat[tuple(later)] -= jump
    rms = float(flat.std())
    out = []
    for axis, i, jump in found:
        if abs(jump) > STEP_RMS * rms:
            name = "xy"[axis]
            where = (i + 1) * spacing[axis]
            out.append(
                f"the heights jump by {1e6 * jump:.3g} um ({abs(jump) / rms:.2g} times the rms height "
                f"{1e6 * rms:.3g} um of the rest) across {name} = {1e3 * where:.4g} mm: a stitching or terrace "
                "artefact, or a real edge, carries the contact there. Level it out of the data, or solve a patch "
                "that avoids it (patch=...)"
            )
    return out


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
