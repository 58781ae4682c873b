"""What a validation report says in words: plain names for the metric identifiers, the basis of
every tolerance, the worst check of a case, and which checks a plot illustrates.

A tolerance has one of three bases, read from the reason every check carries (its ``why``):

- ``margin``: a regression margin, a small factor (the ``margin Nx`` in the reason) above the
  error this code was measured at when the tolerance was set. It catches a change in the code or
  in an input; it is not a statement that the method is only that accurate.
- ``bound``: a limit from the discretisation or the physics (one cell, round-off, an a-priori
  error estimate), independent of what the code happened to measure.
- ``info``: reported and stored in the baselines but not judged, because the discretisation
  cannot resolve the quantity by construction (the reason says why).
"""

from __future__ import annotations

import math
import re
import statistics

__all__ = ["METRIC_NAMES", "metric_name", "basis", "margin_factor", "basis_sentence", "worst_check", "illustrated"]

METRIC_NAMES = {
    "pressure_rel_l2": "pressure error, relative L2",
    "pressure_rel_max": "pressure error, largest over the points / peak",
    "binned_pressure_rel_l2": "pressure difference of bin averages, relative L2",
    "peak_pressure_rel_error": "peak pressure, relative error",
    "peak_pressure_rel_diff": "peak pressure, relative difference",
    "axis_pressure_rel_error": "pressure on the axis, relative error",
    "friction_rel_error": "friction coefficient, relative error",
    "friction_rel_diff": "friction coefficient, relative difference",
    "friction_eq6_rel_error": "friction by eq. 6 (moment of p dh/dx), relative error",
    "friction_eq6_rel_diff": "friction by eq. 6 (moment of p dh/dx), relative difference",
    "friction_moment_rel_error": "friction from the moment of the contact forces, relative error",
    "friction_moment_rel_diff": "friction from the moment of the contact forces, relative difference",
    "friction_forms_rel_diff": "friction: dissipation form against eq. 6, relative difference",
    "low_speed_asymptote_rel_error": "low-speed friction against its asymptote, relative error",
    "low_speed_asymptote_excess": "low-speed friction above its asymptote, signed relative",
    "peak_speed_friction_excess": "friction at its peak speed minus its neighbours' (below 0 at a maximum)",
    "leading_edge_error_elements": "leading contact edge, error in elements",
    "trailing_edge_error_elements": "trailing contact edge, error in elements",
    "leading_edge_error_widths": "leading contact edge, error in contact widths",
    "trailing_edge_error_widths": "trailing contact edge, error in contact widths",
    "leading_edge_diff_elements": "leading contact edge, difference in elements",
    "trailing_edge_diff_elements": "trailing contact edge, difference in elements",
    "contact_radius_error_elements": "contact radius, error in elements",
    "half_width_error_cells": "contact half-width, error in cells",
    "contact_set_mismatch_points": "contact set, points that differ",
    "contact_fraction_rel_diff": "contact fraction, relative difference",
    "spot_pressure_rel_l2": "pressure on the contact spots' nodes, relative L2 difference",
    "spot_edge_distance_per_L": "contact spot edges, largest distance from the reference's / period",
    "approach_rel_error": "approach (rigid-body indentation), relative error",
    "contact_force_balance_rel_diff": "contact forces against the load, relative difference",
    "dissipation_balance_rel_diff": "energy balance: field dissipation against mu P V, relative",
    "contact_residual_from_fields": "contact complementarity residual from the fields",
    "linear_solve_residual": "residual of the linear solve",
    "solver_success": "the solve succeeded (1 = it failed)",
}

# the metrics a plot of each quantity illustrates, by words of its identifier
_PRESSURE = ("pressure", "edge", "half_width", "contact_radius", "contact_set")
_SWEEPS = {
    "friction": ("friction", "asymptote"),
    "contact radius": ("contact_radius",),
    "contact fraction": ("contact_fraction",),
    "approach": ("approach",),
}
_MARGIN = re.compile(r"\b(?:margin|bound) (?:>= ?)?(\d+(?:\.\d+)?)x")


def metric_name(metric):
    """The plain name of a metric identifier (the identifier itself when it has none)."""
    return METRIC_NAMES.get(metric, metric)


def basis(check):
    """``"margin"``, ``"bound"`` or ``"info"``: how ``check``'s tolerance was set (module docstring)."""
    if not check["judged"]:
        return "info"
    return "margin" if _MARGIN.search(check["why"]) else "bound"


def margin_factor(check):
    """The factor of a regression margin (tolerance over the measured error), or None."""
    m = _MARGIN.search(check["why"])
    return float(m.group(1)) if m and check["judged"] else None


def basis_sentence(record):
    """One sentence saying which kinds of tolerance the report's checks use, with their counts."""
    checks = [k for c in record["cases"].values() for k in c.get("checks", [])]
    kinds = [basis(k) for k in checks]
    judged = len(checks) - kinds.count("info")
    if not judged:
        return "No check is judged against a tolerance."
    factors = [f for f in map(margin_factor, checks) if f is not None]
    bound = (
        f"{kinds.count('bound')} use a bound from the discretisation or the physics (one cell, round-off, an "
        "error estimate). "
    )
    if kinds.count("margin"):
        text = (
            f"{kinds.count('margin')} of the {judged} judged checks use a regression margin: a tolerance "
            + (f"{min(factors):g}-{max(factors):g}x (median {statistics.median(factors):g}x) " if factors else "")
            + "the error this code was measured at when it was set, so a failure says that the code or its input "
            "changed, not that the method is that inaccurate; " + bound
        )
    else:
        text = f"None of the {judged} judged checks uses a regression margin: all " + bound
    if kinds.count("info"):
        text += (
            f"{kinds.count('info')} rows are info: reported and kept in the baselines, not judged, because the "
            "discretisation cannot resolve the quantity there (each row says why)."
        )
    return text


def _ratio(check):
    if not check["judged"]:
        return -math.inf
    value, tol = check["value"], check["tolerance"]
    if not math.isfinite(value):
        return math.inf
    if tol == 0:
        return 0.0 if value <= 0 else math.inf
    return value / tol


def worst_check(checks):
    """The judged check closest to (or furthest past) its tolerance: failures first, then the
    largest value/tolerance; None when nothing is judged."""
    judged = [k for k in checks if k["judged"]]
    if not judged:
        return None
    return max(judged, key=lambda k: (not k["passed"], _ratio(k)))


def _squash(text):
    return re.sub(r"\s+", "", text)


def _plotted(solver, curves):
    """A check's solver is on a plot when its curve is, or, for a comparison ``"A vs B"``, both are."""
    return all(part in curves for part in solver.split(" vs "))


def illustrated(case, title, solvers, kind):
    """The checks a plot shows: those of the plotted ``solvers`` whose metric is the plot's
    quantity (pressures for an overlay, the swept quantity for a sweep), at the point the title
    names when it names one. ``kind`` is ``overlay`` or ``sweep``."""
    if kind == "overlay":
        words = _PRESSURE
    else:
        words = next((w for key, w in _SWEEPS.items() if key in title.lower()), ())
    checks = [k for k in case["checks"] if _plotted(k["solver"], solvers) and any(w in k["metric"] for w in words)]
    if kind == "overlay":
        here = _squash(title)
        at = [k for k in checks if re.search(re.escape(_squash(k["label"])) + r"(?![\d.])", here)]
        checks = at or checks
    return checks


def worst_by_metric(checks):
    """``{metric: [worst check of each solver, ...]}``, metrics and solvers in order of first
    appearance; the worst of a group is :func:`worst_check` (an unjudged group: its largest value)."""
    groups = {}
    for k in checks:
        groups.setdefault(k["metric"], {}).setdefault(k["solver"], []).append(k)
    return {
        metric: [worst_check(g) or max(g, key=lambda k: k["value"]) for g in by_solver.values()]
        for metric, by_solver in groups.items()
    }
