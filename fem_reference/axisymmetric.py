"""Axisymmetric viscoelastic solid, time-stepped with the exact exponential update.

Coordinates ``(r, z)`` with the solid in ``z <= 0``; Voigt strains ``(rr, zz, tt, rz)``
(see :mod:`fem_reference.kinematics`). Material as in :mod:`fem_reference.steady`:
``sigma = D(nu) [E_inf eps - sum_k E_k alpha_k]`` with ``tau_k alpha_k' + alpha_k = eps``.
Over a step ``dt`` (weights ``a_k, wp_k, wn_k`` of
:func:`fem_reference.transport.exponential_weights` at ``dt / tau_k``)::

    alpha_k^{n+1} = a_k alpha_k^n + wp_k eps^n + wn_k eps^{n+1},

so the effective strain ``eps - sum_k g_k alpha_k^{n+1}`` (``g_k = E_k / E_inf``) is
``e eps^{n+1} - hist`` with ``e = 1 - sum_k g_k wn_k`` and the history strain
``hist = sum_k g_k (a_k alpha_k^n + wp_k eps^n)``. Each step is a mixed elastic problem
of modulus ``e E_inf`` with an eigenstrain. Scaling the displacement, ``u~ = e u``, turns
it into the glassy problem (modulus ``E_inf``) for every step::

    [ K    -G  ] [u~]    [f / E_inf + B^T W D_dev hist]
    [ -G^T -c M] [p~]  = [-N^T W m^T hist             ],     u = u~ / e,

so one factorisation serves all steps, whatever their lengths.

Boundary conditions: ``u_r = 0`` on the axis and on the outer side, bottom fixed.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .kinematics import mixed_blocks
from .linsolve import RESIDUAL_LIMIT, factorize, solve_refined
from .transport import exponential_weights

__all__ = ["AxisymmetricStepper", "fixed_dofs_axisymmetric"]


def fixed_dofs_axisymmetric(basis):
    """Axis and outer side: ``u_r = 0``; bottom: fixed."""
    bottom = basis.get_dofs("bottom").all()
    sides = basis.get_dofs({"left", "right"}).all("u^1")
    return np.unique(np.concatenate([bottom, sides]))


class AxisymmetricStepper:
    """State of a time-stepped axisymmetric viscoelastic solid (state: strains, alphas).

    Parameters
    ----------
    ops : QuadratureOperators
        Axisymmetric operators (``kind="axi"``).
    material : bem.Material
    fixed : ndarray of int
        Fixed displacement DOFs (set to zero).
    solver : str
        See :func:`fem_reference.linsolve.factorize`.
    memory : float, optional
        Most bytes SuperLU's factor may take.
    """

    def __init__(self, ops, material, fixed, *, solver="auto", memory=None):
        self.ops, self.material = ops, material
        self.blocks = mixed_blocks(ops, material.nu)
        self.free = np.setdiff1d(np.arange(ops.B.shape[1]), fixed)
        self.g = material.moduli / material.E_inf
        n = ops.ncomp * ops.n_points
        self.eps = np.zeros(n)
        self.alpha = [np.zeros(n) for _ in self.g]
        mb, f = self.blocks, self.free
        A = sp.bmat([[mb.K[f][:, f], -mb.G[f]], [-mb.G[f].T, -mb.c * mb.M]], format="csc")
        self.matrix = A.tocsr()
        self.factor = factorize(A, solver, memory=memory)
        # relative residual of the solve closest to its acceptance limit, and that limit
        self.residual, self.residual_limit = 0.0, RESIDUAL_LIMIT
        self._pending, self._hist = None, None

    @property
    def n_unknowns(self):
        return self.free.size + self.blocks.M.shape[0]

    def _history(self, dt):
        a, wp, wn = exponential_weights(dt / self.material.relaxation_times)
        hist = np.zeros_like(self.eps)
        for gk, ak, wpk, alpha in zip(self.g, a, wp, self.alpha):
            hist += gk * (ak * alpha + wpk * self.eps)
        return hist

    def _solve_scaled(self, rhs_u, rhs_p, pressure=False):
        """``u~`` (and, with ``pressure``, the scaled pressure unknowns ``p~``) of the glassy system."""
        f = self.free
        rhs = np.zeros((self.n_unknowns,) + rhs_u.shape[1:])
        rhs[: f.size] = rhs_u[f]
        rhs[f.size :] = rhs_p
        if np.any(rhs):
            x, res, limit = solve_refined(self.matrix, self.factor, rhs, n_equilibrium=f.size)
            if res / limit >= self.residual / self.residual_limit:  # keep the solve closest to its limit
                self.residual, self.residual_limit = res, limit
        else:
            x = rhs
        u = np.zeros((self.ops.B.shape[1],) + rhs_u.shape[1:])
        u[f] = x[: f.size]
        return (u, x[f.size :]) if pressure else u

    def unit_response(self, forces):
        """Glassy response ``u~`` (m) to nodal ``forces`` (N), shape ``(N_u[, m])``; the
        displacement in a step of factor ``e`` (see :meth:`prepare`) is ``u~ / e``."""
        forces = np.asarray(forces, dtype=float)
        zeros = np.zeros((self.blocks.M.shape[0],) + forces.shape[1:])
        return self._solve_scaled(forces / self.material.E_inf, zeros)

    def prepare(self, dt):
        """Set up the step of length ``dt`` (s); returns ``(e, u_hist)``.

        A force ``f`` applied in this step displaces the solid by
        ``unit_response(f) / e``; ``u_hist`` (m) is the displacement the history alone
        produces with no force.
        """
        a, wp, wn = exponential_weights(dt / self.material.relaxation_times)
        e = 1.0 - float(np.sum(self.g * wn))
        hist = self._history(dt)
        mb = self.blocks
        u_hist = self._solve_scaled(mb.BtWd @ hist, -(mb.T @ hist)) / e
        self._pending, self._hist = dt, hist
        return e, u_hist

    def pressure(self, forces):
        """Pressure ``-tr(sigma)/3`` (Pa) at the quadrature points at the end of the prepared step
        under the nodal ``forces`` (N): the mixed solve's own pressure unknown, which does not scale
        with ``e`` (equilibrium fixes it), from one more solve with the step's history strain. Call
        it before :meth:`commit`."""
        mb, E = self.blocks, self.material.E_inf
        rhs_u = np.asarray(forces, dtype=float) / E + mb.BtWd @ self._hist
        _, p = self._solve_scaled(rhs_u, -(mb.T @ self._hist), pressure=True)
        return self.ops.N_p @ p * E

    def commit(self, u):
        """Accept the displacement ``u`` (m) at the end of the prepared step."""
        dt = self._pending
        a, wp, wn = exponential_weights(dt / self.material.relaxation_times)
        eps_new = self.ops.B @ u
        self.alpha = [ak * al + wpk * self.eps + wnk * eps_new for ak, wpk, wnk, al in zip(a, wp, wn, self.alpha)]
        self.eps = eps_new
        self._pending = None
