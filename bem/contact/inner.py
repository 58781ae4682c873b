"""Newton points of the contact solver: the linear problem on a given contact set.

For a contact set ``C`` the Newton point solves ``A_CC p_C = h_C + delta`` (zero pressure off
``C``), under load control with ``sum p_C`` fixed (enforced by projecting out the mean on
``C``), as a correction to the current pressure: conjugate gradients when ``A`` is symmetric,
restarted GMRES otherwise (:mod:`bem.contact.krylov`), to the absolute tolerance
``max(eta ||b||, final_atol sqrt|C| tighten)``.

Preconditioners, chosen once per solve:

- ``"lines"``: :func:`bem.contact.line_preconditioner.line_preconditioner`, for strongly
  non-symmetric 2-D periodic operators;
- ``True``: ``R A^-1 R^T``, the exact full-contact inverse (one FFT pair) restricted to ``C``,
  for large grids, where the restricted system's conditioning grows;
- ``False``: none.

Inner solves that stop far above single-precision round-off use the operator's float32 twin
(``op.single_precision()``); each Newton point's displacement is recomputed in float64, so
the solution keeps full accuracy.
"""

from dataclasses import dataclass

import numpy as np

from . import krylov
from .line_preconditioner import line_preconditioner


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


def max_phase(op):
    """Largest phase ``|arg a_q|`` of the operator's symbol (0 when symmetric)."""
    if op.is_symmetric:
        return 0.0
    if hasattr(op, "max_phase"):  # operators without a Fourier symbol (isolated half-space)
        return float(op.max_phase())
    return float(np.max(np.abs(np.angle(op.symbol))))


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
    """Newton points for one solve: counts its operator products (``matvecs``), keeps the
    inner tolerance's ``tighten`` factor and the line preconditioner's cache."""

    def __init__(self, op, problem, precondition, options):
        self.op, self.problem, self.options = op, problem, options
        single = options.single_precision and hasattr(op, "single_precision")
        self.single = op.single_precision() if single else op
        if precondition != "lines":
            precondition = precondition and hasattr(op, "pressure_from_displacement")
        self.precondition = precondition
        self.maxiter = int(options.inner_maxiter_per_sqrt_n * np.sqrt(problem.ht.size) + options.inner_maxiter_base)
        self.matvecs = 0
        self.tighten = 1.0
        self.line_cache = {}  # line inverses, kept while a line's contact is unchanged

    def _krylov(self, matvec, b, atol, M):
        o = self.options
        if self.op.is_symmetric:
            return krylov.cg(matvec, b, atol=atol, maxiter=self.maxiter, M=M)
        restart = krylov.restart_length(b.size, budget=o.restart_budget, low=o.restart_min, high=o.restart_max)
        return krylov.gmres(
            matvec, b, atol=atol, maxiter=self.maxiter, M=M, restart=restart, reorthogonalise=o.reorthogonalise
        )

    def _preconditioner(self, work, contact, idx):
        """The preconditioner on this set (a counted map), or None."""
        pb, o = self.problem, self.options
        inverse = None
        if self.precondition == "lines":  # None where the dense line inverses would be too large
            inverse = line_preconditioner(
                work, contact, cache=self.line_cache, budget=o.line_budget, chunk=o.line_chunk, dtype=o.line_dtype
            )
            if inverse is not None and pb.load_control:
                inverse = projected(inverse)
        elif self.precondition:
            inverse = restricted(
                work.pressure_from_displacement, idx, pb.ht.shape, pb.load_control, getattr(work, "dtype", float)
            )
        if inverse is None:
            return None

        def M(r):
            self.matvecs += 1
            return inverse(r)

        return M

    def _atol(self, norm_b, n, eta):
        """Absolute inner tolerance; a repeated set (``eta == 0``) whose right-hand side is
        already under the floor would change nothing, so the floor tightens first."""
        o, final_atol = self.options, self.problem.final_atol
        while (
            eta == 0.0
            and 0 < norm_b <= final_atol * np.sqrt(n) * self.tighten
            and (np.sqrt(n) * self.tighten > o.atol_floor)
        ):
            self.tighten *= o.inner_tighten
        return max(final_atol * max(np.sqrt(n) * self.tighten, o.atol_floor), eta * norm_b)

    def _on_set(self, contact, p):
        """``p`` restricted to the set (the load rescaled onto it) and its displacement."""
        pb = self.problem
        p = np.where(contact, p, 0.0)
        if pb.load_control:
            p *= pb.p_ref * p.size / p.sum() if p.sum() > 0 else 0.0
            if not p.any():
                p[contact] = pb.p_ref * p.size / np.count_nonzero(contact)
        self.matvecs += 1
        return p, self.op.displacement(p)

    def newton_point(self, contact, p, u, eta):
        """Pressure, displacement and approach solving the linear problem on ``contact``,
        from ``p`` (whose displacement is ``u``, if known), to the forcing term ``eta``."""
        pb, op = self.problem, self.op
        idx = np.flatnonzero(contact)
        if u is None or np.count_nonzero(p) != np.count_nonzero(p.reshape(-1)[idx]):  # p off the set
            p, u = self._on_set(contact, p)
        else:
            p = p.copy()
        misfit = pb.ht.reshape(-1)[idx] - u.reshape(-1)[idx]
        d = float(pb.approach) if not pb.load_control else -float(np.mean(misfit))
        b = misfit + d
        if pb.load_control:
            b -= b.mean()
        norm_b = float(np.linalg.norm(b))
        atol = self._atol(norm_b, idx.size, eta)
        work = self.single if atol >= self.options.single_precision_rtol * norm_b else op
        matvec = restricted(work.displacement, idx, pb.ht.shape, pb.load_control, getattr(work, "dtype", float))
        z, _, k = self._krylov(matvec, b, atol, self._preconditioner(work, contact, idx))
        self.matvecs += k
        if pb.load_control:
            z -= z.mean()
        p.reshape(-1)[idx] += z
        u = op.displacement(p)
        self.matvecs += 1
        if pb.load_control:
            d = float(np.mean(u.reshape(-1)[idx] - pb.ht.reshape(-1)[idx]))
        return p, u, d
