"""Newton points of the contact solver: the linear problem on a given contact set.

For a contact set ``C`` the Newton point solves ``A_CC p_C = h_C + delta`` (zero pressure off
``C``), under load control with ``sum p_C`` fixed (enforced by projecting out the mean on
``C``), as a correction to the current pressure: conjugate gradients when ``A`` is symmetric,
restarted GMRES otherwise (:mod:`bem.contact.krylov`), to the absolute tolerance
``max(eta ||b||, final_atol sqrt|C| tighten)``. A loose GMRES solve (``eta > 0``) stops after one
restart cycle at the latest, with its iterate: the active-set loop is its restart loop.

Preconditioners, chosen once per solve:

- ``"lines"``: :func:`bem.contact.line_preconditioner.line_preconditioner`, for strongly
  non-symmetric 2-D periodic operators;
- ``True``: ``R M R^T``, the operator's (approximate) inverse restricted to ``C``: exact on
  periodic cells (one FFT pair), the padded periodic cell's on isolated domains;
- ``False``: none.

Inexact inner solves (stopping at least :data:`~bem.contact.forcing.ETA_MIN` of their right-hand
side, far above single-precision round-off) use the operator's float32 twin
(``op.single_precision()``); each Newton point's displacement is recomputed in float64, so
the solution keeps full accuracy.
"""

from dataclasses import dataclass

import numpy as np

from . import krylov
from .forcing import ETA_MIN, TIGHTEN
from .line_preconditioner import line_preconditioner
from .operator import SinglePrecision

__all__ = ["InnerSolver", "Problem", "projected", "restricted"]


@dataclass(frozen=True)
class Problem:
    """One contact problem, scaled. ``ht`` = heights minus their maximum (m); ``p_ref`` (Pa)
    and ``h_ref`` (m) the pressure and gap scales of the residual; ``c = 1 / a0`` (Pa/m) the
    stiffness of one grid cell; ``final_atol`` (m) the inner solves' absolute tolerance per
    unit root of the set size; ``approach`` given under displacement control."""

    ht: np.ndarray
    load_control: bool
    approach: float | None
    p_ref: float
    h_ref: float
    c: float
    final_atol: float


def restricted(apply, idx, shape, project, dtype=float):
    """``z -> (apply(E z))[idx]`` with ``E`` the zero extension from ``idx``; with ``project``,
    in and out are made zero-mean on ``idx`` (the load constraint). ``apply`` must not
    modify its argument: the buffer (of ``dtype``, the precision ``apply`` works in) is zero
    off ``idx`` once and for all. The result is float64."""
    z_full = np.zeros(shape, dtype=dtype)
    z_flat = z_full.reshape(-1)  # a view: scatter/gather by index, not by mask

    def f(z):
        z_flat[idx] = z
        return np.take(apply(z_full).reshape(-1), idx).astype(float, copy=False)

    return projected(f) if project else f


def projected(f):
    """``z -> P f(P z)`` with ``P`` the removal of the mean (the load constraint)."""

    def g(z):
        out = f(z - z.mean())
        return out - out.mean()

    return g


class InnerSolver:
    """Newton points for one solve. It counts its operator products (``matvecs``) and keeps the
    line preconditioner's cache of line inverses (while a line's contact is unchanged).

    ``precondition``: ``"lines"``, ``True`` or ``False`` (module docstring); ``options`` the
    solver's :class:`~bem.contact.ContactOptions` (single precision, memory budgets)."""

    def __init__(self, op, precondition, options):
        self.op, self.options = op, options
        single = options.single_precision and isinstance(op, SinglePrecision)
        self.single = op.single_precision() if single else op
        self.precondition = precondition
        # CG ends within n steps in exact arithmetic; restarted GMRES need not, and n only caps its
        # tight solves (loose ones take one restart cycle, _krylov)
        self.maxiter = op.size
        self.matvecs = 0
        self.line_cache = {}

    def _krylov(self, matvec, b, atol, M, loose):
        """``krylov.cg`` or ``krylov.gmres`` to ``atol``; a ``loose`` GMRES solve for one restart cycle."""
        if self.op.is_symmetric:
            return krylov.cg(matvec, b, atol=atol, maxiter=self.maxiter, M=M)
        restart = krylov.restart_length(b.size, budget=self.options.restart_budget)
        # a loose Newton point only moves the set: one restart cycle (the memory budget's basis) and
        # its iterate. Cycles past it on a set that then changes are lost; on a repeated set the next
        # active-set step starts again from the step's iterate, a restart that also checks the set
        maxiter = restart if loose else self.maxiter
        return krylov.gmres(matvec, b, atol=atol, maxiter=maxiter, M=M, restart=restart)

    def _preconditioner(self, pb, work, contact, idx):
        """The preconditioner on this set (a counted map), or None."""
        inverse = None
        if self.precondition == "lines":  # None where the dense line inverses would be too large
            inverse = line_preconditioner(work, contact, cache=self.line_cache, budget=self.options.line_budget)
            if inverse is not None and pb.load_control:
                inverse = projected(inverse)
        elif self.precondition:
            dtype = getattr(work, "dtype", float)
            inverse = restricted(work.approximate_inverse, idx, pb.ht.shape, pb.load_control, dtype)
        if inverse is None:
            return None

        def M(r):
            self.matvecs += 1
            return inverse(r)

        return M

    @staticmethod
    def _atol(final_atol, norm_b, n, eta, tighten):
        """``(absolute inner tolerance, tighten)``; a repeated set (``eta == 0``) whose right-hand
        side is already under the floor would change nothing, so the floor tightens first."""
        while eta == 0.0 and 0 < norm_b <= final_atol * np.sqrt(n) * tighten:
            tighten *= TIGHTEN
        return max(final_atol * np.sqrt(n) * tighten, eta * norm_b), tighten

    def _on_set(self, pb, contact, p):
        """``p`` restricted to the set (the load rescaled onto it) and its displacement."""
        p = np.where(contact, p, 0.0)
        if pb.load_control:
            p *= pb.p_ref * p.size / p.sum() if p.sum() > 0 else 0.0
            if not p.any():
                p[contact] = pb.p_ref * p.size / np.count_nonzero(contact)
        self.matvecs += 1
        return p, self.op.displacement(p)

    def newton_point(self, pb, contact, p, u, eta, tighten=1.0):
        """``(pressure, displacement, approach, tighten)`` solving the linear problem of ``pb`` (a
        :class:`Problem`) on ``contact`` from ``p`` (whose displacement is ``u``, if known) to the
        forcing term ``eta``; ``tighten`` scales the absolute floor of tight solves (``eta == 0``)
        and comes back as it was used."""
        op = self.op
        idx = np.flatnonzero(contact)
        if u is None or np.count_nonzero(p) != np.count_nonzero(p.reshape(-1)[idx]):  # p off the set
            p, u = self._on_set(pb, contact, p)
        else:
            p = p.copy()
        misfit = pb.ht.reshape(-1)[idx] - u.reshape(-1)[idx]
        d = float(pb.approach) if not pb.load_control else -float(np.mean(misfit))
        b = misfit + d
        if pb.load_control:
            b -= b.mean()
        norm_b = float(np.linalg.norm(b))
        atol, tighten = self._atol(pb.final_atol, norm_b, idx.size, eta, tighten)
        # an inexact Newton point (at least ETA_MIN of its rhs) keeps float32 round-off, ~1e-7
        # times the conditioning, far below its tolerance (ablation row "float32 inner solves")
        work = self.single if atol >= ETA_MIN * norm_b else op
        matvec = restricted(work.displacement, idx, pb.ht.shape, pb.load_control, getattr(work, "dtype", float))
        z, _, k = self._krylov(matvec, b, atol, self._preconditioner(pb, work, contact, idx), eta > 0)
        self.matvecs += k
        if pb.load_control:
            z -= z.mean()
        p.reshape(-1)[idx] += z
        u = op.displacement(p)
        self.matvecs += 1
        if pb.load_control:
            d = float(np.mean(u.reshape(-1)[idx] - pb.ht.reshape(-1)[idx]))
        return p, u, d, tighten
