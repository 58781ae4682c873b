"""Sliding direction in scenes: ``[loading] direction_deg`` (a number, or a list: a sweep).

``direction_deg`` is measured from ``+x`` toward ``+y`` in degrees (``bem.solve``'s
``direction`` in radians); 1-D profiles take 0 or 180 only, the adaptive mesh multiples of 90.
One direction: every point of the study slides along it. A list: the study runs once per
direction, each in its own folder ``direction_DDD.DDD/`` (its own results.json, fields and
plots, resumable like any study), and the top-level ``results.json`` gathers
``directions`` (friction, its eq. 6 form and the contact fraction per direction and speed,
first load, ensemble means) beside the first direction's full record, with a polar plot
``friction_polar.png`` of mu(theta) at each speed.
"""

import math

from bem import direction as sliding_direction
from bem.errors import InputError

__all__ = ["parse"]


def parse(loading, surface, periodic, method="auto"):
    """The scene's directions (radians, a tuple) from ``[loading] direction_deg``."""
    value = loading.get("direction_deg", 0.0)
    values = value if isinstance(value, list) else [value]
    if not values or not all(
        isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in values
    ):
        raise InputError(
            f"[loading] direction_deg must be a finite angle in degrees or a non-empty list of them, got {value!r}"
        )
    if len({float(v) for v in values}) != len(values):
        raise InputError(f"[loading] direction_deg must not repeat an angle, got {value!r}")
    out = []
    for v in values:
        theta = math.radians(float(v))
        try:
            sliding_direction.plan(theta, surface.ndim, periodic, method)
        except InputError as err:
            raise InputError(f"[loading] direction_deg = {v!r}: {err}") from None
        out.append(theta)
    return tuple(out)
