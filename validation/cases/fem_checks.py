"""Checks of an FEM rolling solution against itself: the energy balance, the contact condition
as the fields satisfy it, and the linear solve.

- ``dissipation_balance_rel_diff``: the viscous dissipation integrated over the block (from the
  internal variables) against the power ``mu P V`` of the moment of the contact forces. Both
  converge to the same number; they differ by the discretisation and by the energy carried
  through the truncated boundaries, so the tolerance is set per configuration from the
  measured difference.
- ``contact_residual_from_fields``: :func:`fem_reference.fields.contact_residual`, the
  complementarity residual with the gap taken from the final displacement field.
- ``linear_solve_residual``: ``||K u - f|| / ||f||`` of the factorised solve, whichever solver ran (the
  constraint rows measured against their own terms, :func:`fem_reference.linsolve.relative_residual`).
- ``contact_force_balance_rel_diff``: the sum of the nodal contact forces against the load the case
  asked for (not the one the solver was given): a contact solved at another load and reported as this
  one fails it.
"""

from __future__ import annotations

from fem_reference.contact import COMPLEMENTARITY_LIMIT, complementarity_limit

__all__ = ["fem_self_checks", "force_balance_check", "CONTACT_TOL", "LINEAR_TOL", "FORCE_TOL"]

# The linear solve's error in the gap. Measured with SuperLU: 5e-11 to 2.7e-9 (27-34k unknowns,
# E_inf/E0 = 3, s = 0.3 and 3, every sensitivity perturbation), 1.4e-8 (three Prony terms, grading 2,
# 40k unknowns). A factor of 7 above the largest: the FEM's own limit for a solve at its default limit.
CONTACT_TOL = COMPLEMENTARITY_LIMIT
CONTACT_WHY = (
    "gap from the field solve (SuperLU): measured 5e-11 to 2.7e-9 (SLS, res 3), 1.4e-8 (three Prony "
    "terms, grading 2); margin 7x"
)
LINEAR_TOL = 1e-8
LINEAR_WHY = (
    "a direct solve with iterative refinement reaches round-off: measured 1e-11 (cylinders at res 4, SuperLU "
    "and PARDISO); the limit asked of the FEM"
)


# Load control makes the active-set solve carry sum(lam) = P as one of its equations: measured 1e-16 to
# 4e-15 relative; a load error of 1e-9 is far below any the perturbations make (2 %).
FORCE_TOL = 1e-9
FORCE_WHY = "load control: sum of the nodal contact forces = load, one equation of the contact solve; measured <= 4e-15"


def force_balance_check(out, label, force_sum, load, solver="fem"):
    """Append ``contact_force_balance_rel_diff``: ``|sum(forces) - load| / load``, ``load`` the case's own."""
    out.check("contact_force_balance_rel_diff", solver, label, abs(force_sum - load) / load, FORCE_TOL, FORCE_WHY)


def fem_self_checks(out, label, sol, balance_tol, balance_why, solver="fem", load=None):
    """Append the self-checks of the FEM adapter output ``sol`` (see module docstring); ``load`` is the
    case's load (N/m), against which the contact forces are summed."""
    if load is not None:
        force_balance_check(out, label, sol["force_sum"], load, solver)
    if sol["power_moment"] > 0:
        out.check(
            "dissipation_balance_rel_diff",
            solver,
            label,
            abs(sol["power_fields"] - sol["power_moment"]) / sol["power_moment"],
            balance_tol,
            balance_why,
        )
    limit = sol.get("linear_residual_limit") or LINEAR_TOL
    # the active gaps err as the field solve does: where its limit is raised, theirs is too
    contact_tol = complementarity_limit(limit)
    contact_why = CONTACT_WHY if contact_tol <= CONTACT_TOL else f"{CONTACT_WHY}; here the linear solve's limit"
    out.check("contact_residual_from_fields", solver, label, sol["contact_residual"], contact_tol, contact_why)
    if sol["linear_residual"] is not None:
        why = LINEAR_WHY if limit <= LINEAR_TOL else f"{LINEAR_WHY}; here 10x the round-off floor of the force balance"
        out.check("linear_solve_residual", solver, label, sol["linear_residual"], limit, why)
    else:
        out.check(
            "linear_solve_residual",
            solver,
            label,
            float("nan"),
            None,
            "not judged: this FEM build does not report the residual of its linear solve",
        )
