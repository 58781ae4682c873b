"""Sensitivity of the validation checks: does each case catch deliberately wrong inputs?

For every case and every :data:`validation.perturb.PERTURBATIONS` entry the case is rerun with
its solvers under test fed the wrong input (references keep the true one; their results are
reused between the reruns). A perturbation is *detected* for a solver when at least one judged
check attributed to that solver fails (a comparison ``"A vs B"`` is attributed to ``A``, the
solver under test); ``by`` lists those checks' metrics. It is *required* when it changed the
solver's inputs: every such perturbation changes the physics the checks compare, so an
undetected one means a tolerance too loose for the discretisation error it guards.

Entries: ``{case, solver, perturbation, outcome, detected, by, required}`` with ``outcome`` one of
``detected`` (a judged check failed), ``missed`` (every check passed) and ``error`` (the case raised
under the perturbation: ``by`` holds the exception). An exception is its own outcome, not a
detection: whatever the solver's error was, no check measured it.
"""

from __future__ import annotations

import logging

from .cases import CASES
from .perturb import NONE, PERTURBATIONS, Tamper
from .runner import select

__all__ = ["run_sensitivity", "summary"]
log = logging.getLogger(__name__)


def _owner(solver):
    return solver.split(" vs ")[0]


def _case_entries(name, quick, progress):
    case = CASES[name]
    cache = {}
    base = Tamper(NONE, cache)
    out = case(quick=quick, vtk_dir=None, root=None, tamper=base)
    failing_base = {c.key for c in out.checks if not c.passed}
    entries = []
    for pert in PERTURBATIONS:
        tamper = Tamper(pert, cache)
        try:
            res = case(quick=quick, vtk_dir=None, root=None, tamper=tamper)
        except Exception as err:  # noqa: BLE001 -- reported as its own outcome, not as a detection
            log.warning("case %s raised under %s: %s", name, pert.name, err)
            for solver in sorted(tamper.changed):
                entries.append(
                    dict(
                        case=name,
                        solver=solver,
                        perturbation=pert.name,
                        outcome="error",
                        detected=False,
                        by=[f"{type(err).__name__}: {err}"],
                        required=True,
                    )
                )
            continue
        by = {}
        for c in res.checks:
            if c.judged and not c.passed and c.key not in failing_base:
                by.setdefault(_owner(c.solver), set()).add(c.metric)
        for solver in _solvers_under_test(res, tamper):
            found = sorted(by.get(solver, ()))
            entries.append(
                dict(
                    case=name,
                    solver=solver,
                    perturbation=pert.name,
                    outcome="detected" if found else "missed",
                    detected=bool(found),
                    by=found,
                    required=solver in tamper.changed,
                )
            )
        if progress:
            log.info("sensitivity %s %s: %s", name, pert.name, {s: sorted(v) for s, v in by.items()})
    return entries, sorted(failing_base)


def _solvers_under_test(res, tamper):
    judged = {_owner(c.solver) for c in res.checks if c.judged}
    return sorted(judged | tamper.changed)


def run_sensitivity(names, *, quick, progress=True, jobs=1):
    """Rerun the named cases (all if empty) under every perturbation, ``jobs`` cases at a time in
    separate processes (:func:`validation.runner.in_processes`); returns ``(entries, base_failures)``
    with ``base_failures[case]`` the checks that fail without perturbation (those cannot show a
    detection and are left out of ``by``)."""
    from tqdm.auto import tqdm

    from .runner import check_jobs, in_processes

    check_jobs(jobs)
    names = select(names)
    if jobs > 1 and len(names) > 1:
        with tqdm(total=len(names), desc="sensitivity", unit="case", disable=not progress) as bar:
            by_case = in_processes(_case_entries, names, min(jobs, len(names)), bar, quick=quick, progress=False)
    else:
        by_case = {
            name: _case_entries(name, quick, progress)
            for name in tqdm(names, desc="sensitivity", unit="case", disable=not progress)
        }
    entries, base = [], {}
    for name in names:
        e, failing = by_case[name]
        entries += e
        base[name] = failing
    return entries, base


def summary(entries):
    """``(missed, n_required)``: the required perturbations no check caught (those that raised
    included: an exception is not a detection), and how many there are."""
    required = [e for e in entries if e["required"]]
    return [e for e in required if not e["detected"]], len(required)


def outcome(entry):
    """``detected``, ``missed`` or ``error`` (records written before the field existed: from ``detected``)."""
    return entry.get("outcome") or ("detected" if entry["detected"] else "missed")


def attach(record, names, *, quick, progress=True, jobs=1):
    """Run :func:`run_sensitivity` and store it in ``record["sensitivity"]`` (the entries) and
    ``record["sensitivity_base_failures"]``; returns the entries."""
    entries, base = run_sensitivity(names, quick=quick, progress=progress, jobs=jobs)
    record["sensitivity"] = entries
    record["sensitivity_base_failures"] = base
    return entries


def print_summary(record):
    """Print the perturbations no check caught; returns 1 if there are any, else 0."""
    missed, n = summary(record["sensitivity"])
    for e in missed:
        if outcome(e) == "error":
            print(f"  RAISED {e['case']}: {e['solver']} with {e['perturbation']}: {e['by'][0]} (not a detection)")
        else:
            print(f"  UNDETECTED {e['case']}: {e['solver']} with {e['perturbation']} passes every check")
    errors = sum(outcome(e) == "error" for e in missed)
    print(
        f"  sensitivity: {n - len(missed)}/{n} perturbations that change a solver's inputs detected"
        + (f"; {errors} raised instead (not counted as detected)" if errors else "")
    )
    return 1 if missed else 0
