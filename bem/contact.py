"""Unilateral frictionless contact of a rigid indenter: the complementarity solver.

Problem (SPEC §2.3). Heights ``h`` (m) are positive toward the half-space, so contact
starts at ``max(h)``. With ``A`` the surface response operator (zero-mean displacement
per pressure, m/Pa; any linear operator whose symmetric part is positive definite, so
the non-symmetric steady-sliding operator is included), find the pressure ``p`` (Pa) and
the rigid approach ``delta`` (m) with

    g = A p - (h - max(h) + delta) >= 0,   p >= 0,   p g = 0,

and either ``mean(p) = p_mean`` (load control) or ``delta`` given (displacement control).

Algorithm: primal–dual active set (a semismooth Newton method; Hintermüller, Ito &
Kunisch, SIAM J. Optim. 13 (2002) 865, doi:10.1137/S1052623401383558) with inexact
inner solves: on the current contact set ``C`` the linear system ``A_CC p_C = h_C + delta``
(with the load constraint ``sum p_C`` fixed, enforced by projecting out the mean on
``C``) is solved by conjugate gradients when ``A`` is symmetric and by GMRES otherwise,
loosely while the set still changes and tightly once it settles. The first iterate is
the full-contact solution, exact in Fourier space.

Convergence test, stated exactly: the solve succeeds when the complementarity residual

    r = max_i | min(p_i / p_ref, g_i / h_ref) |

is ``<= rtol``, where ``p_ref`` is the mean pressure and ``h_ref`` the peak-to-valley
height (or the displacement ``A p_ref`` at one point for a flat surface). ``r = 0`` iff
``p >= 0``, ``g >= 0`` and ``p g = 0``. Under load control the load balance holds to
round-off. Otherwise :class:`bem.errors.ConvergenceError` is raised.
"""
import logging
from dataclasses import dataclass

import numpy as np

from . import krylov
from .errors import ConvergenceError

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class ContactSolution:
    """Raw output of :func:`solve_contact` (fields shaped like the heights)."""

    pressure: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    approach: float
    iterations: int
    matvecs: int
    residual: float
    success: bool
    message: str


def complementarity_residual(p, g, p_ref, h_ref):
    """``max |min(p / p_ref, g / h_ref)|`` (dimensionless); 0 iff the contact conditions hold."""
    return float(np.max(np.abs(np.minimum(p / p_ref, g / h_ref))))


def _full_contact_pressure(op, ht):
    """Pressure that makes the gap vanish everywhere (zero mean), exact in Fourier space."""
    return op.pressure_from_displacement(ht)


def solve_contact(op, heights, *, mean_pressure=None, approach=None, rtol=1e-8, maxiter=100,
                  inner_maxiter=None, inner_eta=0.1, initial=None, raise_on_failure=True):
    """Solve the contact problem for operator ``op`` (see module docstring).

    Parameters
    ----------
    op : PeriodicHalfSpace or compatible
        Provides ``displacement(p)``, ``pressure_from_displacement(u)``,
        ``self_influence()`` and ``is_symmetric``.
    heights : ndarray
        Indenter heights (m), positive toward the half-space.
    mean_pressure : float, optional
        Load control: mean pressure over the cell (Pa) = load / area.
    approach : float, optional
        Displacement control: rigid approach ``delta`` (m) from first touch.
    rtol : float
        Tolerance on the complementarity residual.
    maxiter : int
        Maximum number of active-set (outer) iterations.
    inner_maxiter : int, optional
        Maximum operator products per inner solve (default ``20 sqrt(N) + 200``).
    initial : ndarray, optional
        Warm start pressure (Pa), e.g. the solution at a neighbouring speed.
    """
    shape = heights.shape
    ht = heights - heights.max()
    load_control = mean_pressure is not None
    a0 = op.self_influence()
    if load_control:
        p_ref = float(mean_pressure)
    else:
        p_ref = max(float(approach), np.ptp(ht) * 1e-3) / a0
    h_ref = float(np.ptp(ht)) or a0 * p_ref
    inner_maxiter = inner_maxiter or int(20 * np.sqrt(ht.size) + 200)
    solve_inner = krylov.cg if op.is_symmetric else krylov.gmres
    final_atol = 0.1 * rtol * h_ref

    if initial is not None:
        p = np.maximum(np.asarray(initial, dtype=float), 0.0)
    elif load_control:
        p = np.maximum(_full_contact_pressure(op, ht) + p_ref, 0.0)
    else:
        p = np.where(ht + approach > 0, np.maximum(_full_contact_pressure(op, ht), 0.0), 0.0)
    if load_control and not np.any(p > 0):
        p = np.where(ht == 0, 1.0, 0.0)
    contact = p > 0

    matvecs = 0
    residual = np.inf
    delta = float(approach) if not load_control else 0.0
    tighten = 1.0
    for outer in range(1, maxiter + 1):
        if load_control:
            p *= p_ref * p.size / p.sum()
        u = op.displacement(p)
        matvecs += 1
        if load_control:
            delta = float(np.mean(u[contact] - ht[contact]))
        g = u - ht - delta
        residual = complementarity_residual(p, g, p_ref, h_ref)
        log.debug("active set %d: %d products, residual %.3e, contact %.4f",
                  outer, matvecs, residual, contact.mean())
        if residual <= rtol:
            break
        new = (contact & (p > 0)) | (~contact & (g < 0))
        if not new.any():
            new = g == g.min()
        changed = int(np.count_nonzero(new != contact))
        if changed:
            p[~new] = 0.0
            contact = new
            if load_control:
                p *= p_ref * p.size / p.sum() if p.sum() > 0 else 0.0
                if not p.any():
                    p[contact] = p_ref * p.size / contact.sum()
            u = op.displacement(p)
            matvecs += 1
        b = ht[contact] + delta - u[contact]
        if load_control:
            b -= b.mean()
        idx = np.flatnonzero(contact)
        z_full = np.zeros(shape)

        def matvec(z):
            zf = z - z.mean() if load_control else z
            z_full.flat[idx] = zf
            out = op.displacement(z_full)[contact]
            z_full.flat[idx] = 0.0
            return out - out.mean() if load_control else out

        bnorm = float(np.linalg.norm(b))
        # loose while the set changes (Eisenstat–Walker-like), to the final accuracy once settled
        if changed:
            tighten = 1.0
            atol = max(final_atol * np.sqrt(idx.size), inner_eta * bnorm)
        else:  # settled set but not yet converged: the inner accuracy was not enough
            tighten *= 0.1
            atol = final_atol * np.sqrt(idx.size) * tighten
        z, _, k = solve_inner(matvec, b, atol=atol, maxiter=inner_maxiter)
        matvecs += k
        if load_control:
            z -= z.mean()
        p.flat[idx] += z
    else:
        outer = maxiter

    p = np.maximum(p, 0.0)
    if load_control and p.sum() > 0:
        p *= p_ref * p.size / p.sum()
    success = residual <= rtol
    if success:
        message = f"converged: complementarity residual {residual:.2e} <= rtol {rtol:.1e} " \
                  f"after {outer} active-set iterations ({matvecs} operator products)"
    else:
        message = f"not converged: complementarity residual {residual:.2e} > rtol {rtol:.1e} " \
                  f"after {outer} active-set iterations ({matvecs} operator products)"
    sol = ContactSolution(p, u, g, delta, outer, matvecs, residual, success, message)
    if not success and raise_on_failure:
        raise ConvergenceError(message, sol)
    return sol
