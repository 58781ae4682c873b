"""Monolithic steady-rolling operator of a viscoelastic block (plane strain).

Frame: the indenter's. Material flows through the fixed mesh at ``-V e_x``; upstream
(inflow, the indenter's leading side) is ``+x``. Material (docs/theory.md §2, Prony form, one
Poisson ratio for every term)::

    sigma = D(nu) [E_inf eps - sum_k E_k alpha_k],    -V tau_k d(alpha_k)/dx + alpha_k = eps,

with ``alpha_k`` the viscous strain of Maxwell arm ``k`` (``alpha_k = eps`` at inflow).
Written in the mixed form of :mod:`fem_reference.kinematics` and scaled by ``E_inf``
(``g_k = E_k / E_inf``, ``p_hat = p / E_inf``) the unknowns ``[u, p_hat, alpha_1..K]``
satisfy::

    [ K_dev      -G          -g_k B^T W D_dev ] [u]       [f / E_inf]
    [ -G^T       -c M         g_k N^T W m^T   ] [p_hat] = [0]
    [ -R_k B      0           L_k             ] [alpha_k] [0]

``K_dev = B^T W D_dev B``, ``G = B^T W m N``, ``M = N^T W N``, ``c = 3 (1 - 2 nu)``,
``L_k alpha = R_k eps`` the exponential streamline update of
:mod:`fem_reference.transport`. The system is sparse and not symmetric. A term may
instead be condensed: ``alpha_k = A_k eps`` with the truncated explicit memory ``A_k`` of
:mod:`fem_reference.condense`, so that ``B`` becomes ``B_v = (I - sum_k g_k A_k) B`` in the
first two block rows and the term has no unknowns. That trades unknowns for a band along
the streamlines of width ``~ 30 V tau_k``: cheap where the elements are long compared
with ``V tau_k``, and the only affordable form on strongly graded meshes, where the
monolithic system fills under SuperLU.

Boundary conditions: bottom fixed, sides on rollers (``u_x = 0``), top free except for
the contact forces.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .condense import band_width, condensed_operator
from .kinematics import deviatoric_matrix, inverse_bulk_modulus, mixed_blocks, trace_vector
from .linsolve import RESIDUAL_LIMIT, factorize, solve_refined
from .transport import streamline_operators

__all__ = ["SteadyOperator", "steady_operator", "condensable", "viscous_strain"]


@dataclass
class SteadyOperator:
    """The factorised steady operator for one material and speed (state: the LU factors).

    Use :meth:`solve` with nodal forces (N/m) on the displacement DOFs; it returns the
    displacement (m), pressure (Pa) and viscous strains at the quadrature points.
    ``residual`` is the relative residual of the solve so far that came closest to its limit
    (force balance against the load, constraints against their own terms:
    :func:`~fem_reference.linsolve.relative_residual`) and ``residual_limit`` that limit
    (:func:`~fem_reference.linsolve.residual_limit`); ``condensed`` flags the terms whose viscous
    strains were eliminated.
    """

    ops: object
    material: object
    speed: float
    free: np.ndarray
    sizes: tuple
    factor: object
    n_unknowns: int
    matrix: object = None
    condensed: np.ndarray = None
    residual: float = 0.0
    residual_limit: float = RESIDUAL_LIMIT
    timings: dict = None

    def solve(self, forces, strains=True):
        """Solve for nodal ``forces`` of shape ``(N_u,)`` or ``(N_u, m)`` (N/m).

        ``strains=False`` leaves ``alpha`` empty (it holds a field per term and right-hand side).

        Returns
        -------
        u : ndarray (N_u[, m])
            Nodal displacements (m), zero on the fixed DOFs.
        p : ndarray (ngp[, m])
            Pressure ``-tr(sigma)/3`` at the quadrature points (Pa).
        alpha : list of ndarray (ncomp * ngp[, m])
            Viscous strain of each Prony term at the quadrature points.
        """
        forces = np.asarray(forces, dtype=float)
        E = self.material.E_inf
        npr = self.sizes[1]
        rhs = np.zeros((self.n_unknowns,) + forces.shape[1:])
        rhs[: self.free.size] = forces[self.free] / E
        x, res, limit = solve_refined(self.matrix, self.factor, rhs, n_equilibrium=self.free.size)
        if res / limit >= self.residual / self.residual_limit:  # keep the solve closest to its limit
            self.residual, self.residual_limit = res, limit
        u = np.zeros(forces.shape)
        u[self.free] = x[: self.free.size]
        off = self.free.size
        p = self.ops.N_p @ x[off : off + npr] * E
        off += npr
        alpha = []
        if not strains:
            return u, p, alpha
        eps = None
        for k, tau in enumerate(self.material.relaxation_times):
            if self.condensed[k]:
                if eps is None:
                    eps = self.ops.B @ u
                alpha.append(viscous_strain(self.ops, self.speed * tau, eps))
            else:
                alpha.append(x[off : off + self.sizes[2]])
                off += self.sizes[2]
        return u, p, alpha


def viscous_strain(ops, ell, eps):
    """``alpha`` (Voigt, point-major) of one term from the strain ``eps`` (exact update)."""
    Lk, Rk = streamline_operators(ops.row, ops.points[0], ell)
    lu = spla.splu(sp.csc_matrix(Lk))
    ncomp = ops.ncomp
    e = eps.reshape((-1, ncomp) + eps.shape[1:])
    out = np.stack([lu.solve(np.asarray(Rk @ e[:, c])) for c in range(ncomp)], axis=1)
    return out.reshape(eps.shape)


def _fixed_dofs(basis):
    bottom = basis.get_dofs("bottom").all()
    sides = basis.get_dofs({"left", "right"}).all("u^1")
    return np.unique(np.concatenate([bottom, sides]))


def condensable(ops, material, speed, max_band=8.0):
    """Mask of the terms whose truncated memory couples at most ``max_band`` points on average."""
    return np.array(
        [
            speed * tau > 0 and band_width(ops.row, ops.points[0], speed * tau) <= max_band
            for tau in material.relaxation_times
        ],
        dtype=bool,
    )


def steady_operator(ops, material, speed, *, solver="auto", condense=False):
    """Assemble and factor the steady operator (see module docstring).

    Parameters
    ----------
    ops : QuadratureOperators
        Plane-strain operators on a tensor mesh (rows of points are streamlines).
    material : bem.Material
    speed : float
        Rolling speed ``V`` (m/s), ``>= 0``.
    solver : str
        See :func:`fem_reference.linsolve.factorize`.
    condense : bool or array of bool
        Eliminate the viscous strains of these terms (all with ``True``) through the
        truncated operator of :mod:`fem_reference.condense`; the others stay unknowns.
    """
    t0 = time.perf_counter()
    mb = mixed_blocks(ops, material.nu)
    M, T, BtWd, c = mb.M, mb.T, mb.BtWd, mb.c
    B = ops.B
    g = material.moduli / material.E_inf
    ntau = g.size
    cmask = np.broadcast_to(np.asarray(condense, dtype=bool), (ntau,)).copy()
    cmask &= speed * material.relaxation_times > 0

    free = np.setdiff1d(np.arange(B.shape[1]), _fixed_dofs(ops.basis))
    Bf = B[:, free]
    ncomp = ops.ncomp
    eye = sp.identity(ncomp, format="csr")
    Bv = Bf
    if np.any(cmask):
        S = condensed_operator(ops.row, ops.points[0], speed * material.relaxation_times[cmask], g[cmask])
        Bv = (Bf - sp.kron(S, eye, format="csr") @ Bf).tocsr()
    Kv = (BtWd[free] @ Bv).tocsr()
    Gf = mb.G[free]
    mono = np.flatnonzero(~cmask)
    blocks = [[Kv, -Gf] + [-g[k] * BtWd[free] for k in mono], [-(T @ Bv), -c * M] + [g[k] * T for k in mono]]
    for i, k in enumerate(mono):
        Lk, Rk = streamline_operators(ops.row, ops.points[0], speed * material.relaxation_times[k])
        row = [-(sp.kron(Rk, eye) @ Bf), None] + [None] * mono.size
        row[2 + i] = sp.kron(Lk, eye)
        blocks.append(row)
    A = sp.bmat(blocks, format="csc")
    t1 = time.perf_counter()
    fac = factorize(A, solver)
    t2 = time.perf_counter()
    return SteadyOperator(
        ops,
        material,
        float(speed),
        free,
        (free.size, M.shape[0], ncomp * ops.n_points),
        fac,
        A.shape[0],
        matrix=A.tocsr(),
        condensed=cmask,
        timings={"assemble": t1 - t0, "factor": t2 - t1},
    )


def stress_and_dissipation(ops, material, u, p, alpha):
    """Stress (Pa, Voigt) and dissipation density (W/m^3) at the quadrature points.

    ``d = sum_k (E_k / tau_k) (eps - alpha_k) . D(nu) (eps - alpha_k)`` with ``D`` the unit
    elastic matrix (its volumetric part is dropped for ``nu = 0.5``, where it vanishes).
    """
    kind, nu = ops.kind, material.nu
    m = trace_vector(kind)
    ddev = deviatoric_matrix(kind, nu)
    c = inverse_bulk_modulus(nu)
    d_full = ddev + (np.outer(m, m) / c if c > 0 else 0.0)
    ncomp = ops.ncomp
    eps = (ops.B @ u).reshape(-1, ncomp)
    s_eff = material.E_inf * eps
    diss = np.zeros(eps.shape[0])
    for Ek, tau, a in zip(material.moduli, material.relaxation_times, alpha):
        a = a.reshape(-1, ncomp)
        s_eff = s_eff - Ek * a
        e = eps - a
        diss += (Ek / tau) * np.einsum("gi,ij,gj->g", e, d_full, e)
    sigma = s_eff @ ddev.T - p[:, None] * m[None, :]
    return eps, sigma, diss
