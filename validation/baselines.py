"""Regression baselines of the quick validation set (``validation/baselines/quick.json``).

The file holds every check's value (``values[case][solver/metric/label]``), the comparison
tolerances, and its provenance (commit, date, machine, command). Regenerate it with

    viscobem validate --quick --update-baselines --out DIR

Comparison (two-sided: an unexplained improvement is a change too):
``|value - baseline| <= max(rel * |baseline|, floor * tolerance)`` with ``rel = 0.05`` and
``floor = 0.01`` of the check's own tolerance (``1e-12`` absolute for unjudged checks). Solver
residuals (:data:`ROUND_OFF_METRICS`) are not compared: they are round-off, bounded by their checks.
Why: every solver here is deterministic (direct FEM factorisations, BEM at ``rtol <= 1e-8``), so
reruns reproduce the errors to ~1e-6 of themselves across BLAS builds; a 5 % change of a
discretisation error, or of a round-off-level one by more than 1 % of its tolerance, means the
numerics changed.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

__all__ = ["DEFAULT", "compare", "write", "REL", "FLOOR"]

DEFAULT = Path(__file__).resolve().parent / "baselines" / "quick.json"
REL, FLOOR, ABS = 0.05, 0.01, 1e-12
# solver residuals sit at round-off and move with the linear solver (SuperLU or PARDISO, with or
# without equilibration) and the BLAS, not with the numerics; each run bounds them by its own check
ROUND_OFF_METRICS = frozenset({"linear_solve_residual", "contact_residual_from_fields"})
RULE = (
    "|value - baseline| <= max(rel * |baseline|, floor_of_tolerance * tolerance) (abs for unjudged checks); "
    "regenerate: viscobem validate --quick --update-baselines --out DIR"
)


def _values(record):
    return {
        name: {f"{k['solver']}/{k['metric']}/{k['label']}": k["value"] for k in c["checks"]}
        for name, c in record["cases"].items()
    }


NOTE = (
    "made by `viscobem validate --quick --update-baselines` once every case passed its tolerances; the values "
    "are discretisation errors of deterministic solves (direct FEM factorisations, BEM at rtol <= 1e-10), so the "
    "machine, its load and the FEM's linear solver (SuperLU or PARDISO) change them only at round-off (the "
    "linear solve's residual, <= 1e-7 of the contact gap)"
)


def write(record, path=DEFAULT, command=""):
    """Store ``record``'s check values with provenance and :data:`NOTE`; returns the path."""
    env = record["environment"]
    data = dict(
        provenance=dict(
            note=NOTE,
            commit=env["commit"],
            dirty=env.get("dirty", False),
            date=env["date"],
            machine=env["machine"],
            python=env["python"],
            numpy=env["numpy"],
            scipy=env["scipy"],
            command=command,
            seconds=record["seconds"],
            case_seconds={n: c["seconds"] for n, c in record["cases"].items()},
        ),
        comparison=dict(rel=REL, floor_of_tolerance=FLOOR, abs=ABS, rule=RULE),
        values=_values(record),
    )
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
    return path


def compare(record, path=DEFAULT):
    """Compare ``record`` with the stored baseline; returns a dict with ``ok``, ``regressions``
    (case, key, value, baseline, allowed), ``missing`` (keys without a baseline) and ``path``.
    Cases not in the record are not compared."""
    path = Path(path)
    stored = json.loads(path.read_text())
    base = stored["values"]
    regressions, missing = [], []
    for name, c in record["cases"].items():
        for k in c["checks"]:
            if k["metric"] in ROUND_OFF_METRICS:
                continue
            key = f"{k['solver']}/{k['metric']}/{k['label']}"
            if key not in base.get(name, {}):
                missing.append(dict(case=name, key=key))
                continue
            b, v = base[name][key], k["value"]
            tol = k["tolerance"]
            allowed = max(REL * abs(b), FLOOR * tol if tol is not None else ABS)
            if not (math.isfinite(v) and abs(v - b) <= allowed):
                regressions.append(dict(case=name, key=key, value=v, baseline=b, allowed=allowed))
    return dict(
        ok=not regressions and not missing,
        regressions=regressions,
        missing=missing,
        path=str(path),
        provenance=stored["provenance"],
    )
