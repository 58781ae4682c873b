"""Every tunable of the contact solver (:func:`bem.contact.solve_contact`) in one frozen object.

Each field says what it trades and why its default; the defaults were chosen on the periodic
benchmark (rough self-affine surfaces at about 10 % contact: elastic, a standard linear solid
and a 20-term rubber with ``E_inf/E0 = 1000``), the 32² robustness sweep and the isolated
rolling cylinders of the validation. Variants are made with :func:`dataclasses.replace`.
"""

import math
from dataclasses import dataclass, fields

import numpy as np

from ..errors import InputError

__all__ = ["ContactOptions"]

# (low, high, low inclusive) of every numeric field; booleans and ``precondition`` are checked apart
_RANGES = {
    "inner_eta": (0.0, 1.0, False),
    "inner_eta_min": (0.0, 1.0, False),
    "nested_eta": (0.0, 1.0, False),
    "gap_scale": (0.0, math.inf, False),
    "gap_scale_strong": (0.0, math.inf, False),
    "gap_floor_share": (0.0, 1.0, True),
    "inner_relax": (1.0, math.inf, True),
    "oscillation_decrease": (0.0, math.inf, True),
    "inner_tighten": (0.0, 1.0, False),
    "inner_maxiter_per_sqrt_n": (0.0, math.inf, True),
    "inner_maxiter_base": (0, math.inf, True),
    "final_atol_share": (0.0, 1.0, False),
    "atol_floor": (0.0, 1.0, False),
    "stall_ratio": (0.0, 1.0, False),
    "tighten_changes": (0, math.inf, True),
    "tighten_share": (0.0, 1.0, True),
    "strong_phase": (0.0, math.pi / 2, True),
    "precondition_min_size": (1, math.inf, True),
    "single_precision_rtol": (0.0, 1.0, False),
    "near_full_contact": (0.0, 1.0, True),
    "symmetric_start_rtol": (0.0, 1.0, False),
    "stall_limit": (1, math.inf, True),
    "ascents": (1, math.inf, True),
    "search_decrease": (0.0, 1.0, True),
    "search_halvings": (1, 60, True),
    "fast_share": (0.0, 1.0, False),
    "lines_eta": (0.0, 1.0, False),
    "residual_stall": (0, math.inf, True),
    "lines_maxiter_share": (0.0, 1.0, False),
    "line_budget": (0, math.inf, True),
    "line_chunk": (1, math.inf, True),
    "coarsen_min_size": (4, math.inf, True),
    "coarse_rtol": (0.0, 1.0, False),
    "restart_budget": (1, math.inf, True),
    "restart_min": (1, math.inf, True),
    "restart_max": (1, math.inf, True),
    "reorthogonalise": (0.0, 1.0, True),
}
_INTEGERS = {
    "inner_maxiter_base",
    "tighten_changes",
    "precondition_min_size",
    "stall_limit",
    "ascents",
    "search_halvings",
    "residual_stall",
    "line_budget",
    "line_chunk",
    "coarsen_min_size",
    "restart_budget",
    "restart_min",
    "restart_max",
}


@dataclass(frozen=True)
class ContactOptions:
    """Tunables of :func:`bem.contact.solve_contact`; validated on creation (``InputError``)."""

    # Newton iteration and its inexact inner solves
    inner_eta: float = 0.1
    """Inner forcing term while the set changes: loose solves are cheap and the set is wrong anyway."""
    nested_eta: float = 0.01
    """Forcing term of symmetric problems started from the coarser grid (nested iteration), whose set is nearly
    right: looser solves flip points at the margin of broad-band contacts (2048², 1024 scales: 397 -> 287
    products). Non-symmetric ones keep ``inner_eta``: their GMRES pays more per decade (seed SLS 1024² +11 %)."""
    inner_eta_min: float = 1e-4
    """Tightest forcing term that damping may impose: below it an inexact step is as good as exact."""
    oscillation_decrease: float = 0.7
    """A set whose changes fall by less than this factor per step while growing, or mostly undoing the last
    step's, is not converging: the forcing term drops a decade for good (converging sets halve their changes)."""
    inner_tighten: float = 0.1
    """Factor on the forcing term (and the floor) when a step had to be damped or stalled: one decade per step."""
    inner_relax: float = 3.0
    """Factor that loosens the forcing term after a full step (fast attempt): cheap solves again once on track."""
    inner_maxiter_per_sqrt_n: float = 20.0
    """Inner products cap per sqrt(grid points): Krylov counts grow like sqrt(N) on these operators."""
    inner_maxiter_base: int = 200
    """Inner products cap added to the above: small grids still get a useful solve."""
    gap_scale: float = 10.0
    """Residual's gap scale in one cell's displacement under the mean pressure: larger is cheaper; 10 keeps
    the pressure error under 4 rtol on the tested cases."""
    gap_scale_strong: float = 0.3
    """The same for strongly non-symmetric operators, whose pressure error per gap error is larger (3 rtol)."""
    gap_floor_share: float = 1e-4
    """Smallest gap scale as a share of the height range: below it round-off of the gap would stop tight solves."""
    final_atol_share: float = 0.1
    """Inner absolute tolerance as a share of ``rtol`` times the gap scale: a decade below the outer test."""
    atol_floor: float = 1e-3
    """Lowest share of that absolute tolerance a stalled settled set may tighten to: beyond it only round-off."""
    stall_ratio: float = 0.5
    """An unchanged set whose residual fell by less than this factor tightens the inner solves: they limit it."""
    tighten_changes: int = 100
    """A damped step tightens the inner solves only with at most this many set changes (a nearly settled set)."""
    tighten_share: float = 0.01
    """... or at most this share of the set: earlier, damping comes from the set, not from the inner solves."""
    stall_limit: int = 5
    """Steps without a new low in set changes that count as cycling (ends the symmetric-part start)."""
    ascents: int = 3
    """Rising residuals in a row after which a symmetric problem starts damping: plain steps are cycling."""
    search_decrease: float = 1e-4
    """Sufficient decrease of the merit for the full step (Armijo): any real decrease is enough."""
    search_halvings: int = 12
    """Step lengths 1/2 ... 1/2**k tried by the line search: costs no product, 1/4096 is short enough."""
    fast_share: float = 0.5
    """Share of ``maxiter`` for the fast attempt (inner tolerances relax again) before the monotone retry."""
    # operator classification and preconditioning
    strong_phase: float = math.pi / 4
    """Symbol phase (rad) above which an operator is strongly non-symmetric: other start, steps and preconditioner."""
    precondition: bool | None = None
    """Restricted full-contact inverse as preconditioner: None chooses by grid size and phase, or force it."""
    precondition_min_size: int = 2**17
    """Grid points from which that preconditioner pays its extra FFT pair: smaller restricted systems are easy."""
    single_precision: bool = True
    """Loose inner solves' products in float32: half the memory traffic, far above float32 round-off."""
    single_precision_rtol: float = 1e-3
    """Relative inner tolerance from which float32 products are used (round-off ~1e-7 times conditioning)."""
    # first iterate
    symmetric_start_1d: bool = True
    """Every non-symmetric 1-D problem starts from its symmetric part's contact: smooth indenters need it."""
    symmetric_start_rtol: float = 1e-3
    """Residual of the symmetric-part start: it only has to place the set."""
    near_full_contact: float = 0.1
    """Tension share under which the clipped full-contact pressure is the start (it is nearly the answer)."""
    coarsen: bool = True
    """Start large even grids from the solution on the grid with half the points per axis (nested iteration)."""
    coarsen_warm: bool = True
    """A warm start (``initial``) goes to the coarse grid, whose solution then starts this one."""
    coarsen_min_size: int = 2**18
    """Grid points from which the coarse start pays: below it the first set is cheap to find anyway."""
    coarse_rtol: float = 1e-4
    """Residual of the coarse solve (at least the caller's rtol): interpolation error dominates anyway."""
    # line preconditioner (strongly non-symmetric 2-D periodic operators)
    lines: bool = True
    """Try the line preconditioner first for strongly non-symmetric 2-D periodic operators: far fewer products."""
    lines_eta: float = 0.01
    """Inner forcing term of that attempt: looser Newton points send fine grids into long damped runs."""
    residual_stall: int = 30
    """Steps without a new low in the residual that end that attempt (it cycles on some near-full contacts)."""
    lines_maxiter_share: float = 0.5
    """Share of ``maxiter`` that attempt may take, leaving the rest to the unpreconditioned retry."""
    line_budget: int = 2**30
    """Bytes of dense line inverses (with their cache); above it the attempt runs unpreconditioned."""
    line_chunk: int = 32
    """x-lines per batched dense inverse: large enough for BLAS, small enough to pad little."""
    line_dtype: type = np.float32
    """Storage of the line inverses: the line systems are well conditioned, float32 halves the traffic."""
    # Krylov
    restart_budget: int = 2**26
    """Doubles of GMRES basis (512 MiB): restarts are what make the strongly non-symmetric systems slow."""
    restart_min: int = 30
    """Fewest GMRES basis vectors, whatever the budget."""
    restart_max: int = 200
    """Most GMRES basis vectors: orthogonalisation cost grows with the basis."""
    reorthogonalise: float = 1 / math.sqrt(2)
    """Second Gram–Schmidt pass when the first kept less than this share of the norm ("twice is enough")."""

    def __post_init__(self):
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in _RANGES:
                _check_number(f.name, value, *_RANGES[f.name])
            elif f.name == "precondition":
                if value is not None and not isinstance(value, bool):
                    raise InputError(f"options.precondition must be None, True or False, got {value!r}")
            elif f.name == "line_dtype":
                if value not in (np.float32, np.float64):
                    raise InputError(f"options.line_dtype must be numpy.float32 or numpy.float64, got {value!r}")
            elif not isinstance(value, bool):
                raise InputError(f"options.{f.name} must be True or False, got {value!r}")
        if self.restart_min > self.restart_max:
            raise InputError(f"options.restart_min must be <= restart_max = {self.restart_max}, got {self.restart_min}")


def _check_number(name, value, low, high, closed):
    integer = name in _INTEGERS
    kind = "an integer" if integer else "a real number"
    ok = isinstance(value, (int, np.integer) if integer else (int, float, np.integer, np.floating))
    ok = ok and not isinstance(value, bool) and math.isfinite(value)
    ok = ok and (low <= value if closed else low < value) and value <= high
    if not ok:
        bracket = "[" if closed else "("
        raise InputError(f"options.{name} must be {kind} in {bracket}{low}, {high}], got {value!r}")
