"""Data types of the validation cases: checks, plotted series, solver runs, one case's output.

A *case* is a named problem with the solvers that apply to it; running it returns a
:class:`CaseOutput`: a list of :class:`Check` (one number against one tolerance, with the
reason for that tolerance), the series to plot, the cost of every solver call and the VTK
files written. Checks with ``tolerance=None`` are reported but not judged (quantities a
discretisation cannot resolve by construction, e.g. a boundary layer thinner than a cell).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Check", "Profile", "Sweep", "Run", "CaseOutput", "Case"]


@dataclass(frozen=True)
class Check:
    """One metric of one solver at one point (``label``, e.g. a speed) against its tolerance."""

    metric: str
    solver: str
    label: str
    value: float
    tolerance: float | None
    why: str = ""

    @property
    def judged(self):
        return self.tolerance is not None

    @property
    def passed(self):
        return (not self.judged) or (math.isfinite(self.value) and self.value <= self.tolerance)

    @property
    def key(self):
        return f"{self.solver}/{self.metric}/{self.label}"

    def as_dict(self):
        return dict(
            metric=self.metric,
            solver=self.solver,
            label=self.label,
            value=self.value,
            tolerance=self.tolerance,
            passed=self.passed,
            judged=self.judged,
            why=self.why,
        )


@dataclass
class Profile:
    """Pressure profiles at one point: ``curves[name] = (x, p)`` (m, Pa); ``reference`` names
    the curve the errors are taken against (an exact solution, or ``None``)."""

    label: str
    curves: dict
    reference: str | None = None
    errors: dict = field(default_factory=dict)  # name -> (x, p - p_ref) in Pa
    xlabel: str = "x (m)"


@dataclass
class Sweep:
    """A quantity against a parameter, per solver: ``curves[name] = (x, y)``."""

    title: str
    xlabel: str
    ylabel: str
    curves: dict
    logx: bool = True
    logy: bool = False


@dataclass(frozen=True)
class Run:
    """Cost of one solver call."""

    solver: str
    label: str
    seconds: float
    peak_mib: float
    detail: str = ""


@dataclass
class CaseOutput:
    checks: list = field(default_factory=list)
    profiles: list = field(default_factory=list)
    sweeps: list = field(default_factory=list)
    runs: list = field(default_factory=list)
    files: list = field(default_factory=list)  # paths relative to the report folder
    notes: list = field(default_factory=list)
    numbers: dict = field(default_factory=dict)  # anything else worth keeping in report.json

    def check(self, metric, solver, label, value, tolerance, why=""):
        self.checks.append(
            Check(metric, solver, str(label), float(value), None if tolerance is None else float(tolerance), why)
        )

    def converged(self, solver, label, sol):
        """Record a failed solve as a failed check; True when ``sol`` can be compared.

        Every adapter reports ``success`` (a missing key is an error, never a pass)."""
        if sol["success"]:
            return True
        self.check(
            "solver_success",
            solver,
            label,
            1.0,
            0.0,
            f"the solve must succeed (1 = failed): {sol['message']} (residual {sol['residual']:.3g})",
        )
        return False

    def cost(self, solver, label, cost, detail=""):
        self.runs.append(Run(solver, str(label), cost.seconds, cost.peak_mib, detail))


@dataclass(frozen=True)
class Case:
    """A named validation problem.

    ``run(quick, vtk_dir, root, tamper)`` returns a :class:`CaseOutput`; ``vtk_dir`` (a folder,
    or ``None`` for no VTK) is where the case writes its files, ``root`` the report folder the
    file names are given relative to, and ``tamper`` (:class:`validation.perturb.Tamper`) gives
    the solvers under test their inputs (deliberately wrong ones under ``--sensitivity``).
    """

    name: str
    title: str
    description: str
    solvers: tuple
    reference: str
    run: object
    # the full set's wall time of this case in seconds, measured on 2 cores: ``--jobs`` starts the
    # costliest cases first, so that the last one to start is a short one
    seconds: float = 1.0

    def __call__(self, quick=False, vtk_dir: Path | None = None, root: Path | None = None, tamper=None):
        from validation.perturb import Tamper

        return self.run(quick=quick, vtk_dir=vtk_dir, root=root, tamper=Tamper() if tamper is None else tamper)
