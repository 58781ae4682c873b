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
``L_k alpha = R_k eps`` the element-wise streamline memory of
:mod:`fem_reference.memory`. The system is sparse and not symmetric.

Each term's viscous strain is not kept at every point: an element passes downstream only its
outflow values ``beta_k`` (one per row crossing it and strain component), and ``alpha_k =
D_k eps + E_k beta_k`` with ``L_k beta_k = R_k eps``
(:func:`~fem_reference.memory.state_operators`), exact. The ``D_k`` part joins the strain
operator, ``B_v = (I - sum_k g_k D_k) B``, and ``beta_k`` are the unknowns of the third block
row. Every coupling stays within an element and its upstream neighbour, so the system's entries
grow linearly with the number of terms and of elements, whatever ``V tau_k``. A term whose
memory is short may instead be condensed: ``alpha_k = A_k eps`` with the truncated memory
``A_k`` (:func:`~fem_reference.memory.condensed_memory`) joins ``B_v`` and the term has no
unknowns; that is cheaper only while ``A_k`` reaches an element or two upstream
(:func:`condensable`).

Boundary conditions: bottom fixed, sides on rollers (``u_x = 0``), top free except for
the contact forces.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .kinematics import deviatoric_matrix, inverse_bulk_modulus, mixed_blocks, trace_vector
from .linsolve import RESIDUAL_LIMIT, factorize, solve_refined, solver_path
from .memory import condensed_memory, memory_operators, memory_reach, state_operators

__all__ = [
    "SteadyOperator",
    "steady_operator",
    "condensable",
    "condensed_terms",
    "system_path",
    "viscous_strain",
    "stress_and_dissipation",
    "solution_fields",
]


# Entries of the work arrays of one flexibility block (unknowns times columns solved together)
FLEXIBILITY_ENTRIES = 5e7


@dataclass
class SteadyOperator:
    """The factorised steady operator for one material and speed (state: the LU factors).

    Use :meth:`solve` with nodal forces (N/m) on the displacement DOFs; it returns the
    displacement (m), pressure (Pa) and viscous strains at the quadrature points.
    ``residual`` is the relative residual of the solve so far that came closest to its limit
    (force balance against the load, constraints against their own terms:
    :func:`~fem_reference.linsolve.relative_residual`) and ``residual_limit`` that limit
    (:func:`~fem_reference.linsolve.residual_limit`); ``condensed`` flags the terms whose viscous
    strains were eliminated (the others are carried by their elements' outflow values).
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
    states: dict = None
    residual: float = 0.0
    residual_limit: float = RESIDUAL_LIMIT
    timings: dict = None

    def solve(self, forces, strains=True, refine=True):
        """Solve for nodal ``forces`` of shape ``(N_u,)`` or ``(N_u, m)`` (N/m).

        ``strains=False`` leaves ``alpha`` empty (it holds a field per term and right-hand side).
        ``refine=False`` takes the factor's solve as it is: no iterative refinement, no residual
        (it is neither checked nor kept), for a caller that corrects the error itself.

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
        if refine:
            x, res, limit = solve_refined(self.matrix, self.factor, rhs, n_equilibrium=self.free.size)
            if res / limit >= self.residual / self.residual_limit:  # keep the solve closest to its limit
                self.residual, self.residual_limit = res, limit
        else:
            x = self.factor.solve(rhs)
        u = np.zeros(forces.shape)
        u[self.free] = x[: self.free.size]
        u = self.ops.complete(u)
        off = self.free.size
        p = self.ops.N_p @ x[off : off + npr] * E
        off += npr
        alpha = []
        if not strains:
            return u, p, alpha
        eps = self.ops.B @ u
        ncomp = self.ops.ncomp
        for k, tau in enumerate(self.material.relaxation_times):
            if self.condensed[k]:
                alpha.append(viscous_strain(self.ops, self.speed * tau, eps))
                continue
            D, E, size = self.states[k]
            beta = x[off : off + size]
            off += size
            e = eps.reshape((-1, ncomp) + eps.shape[1:])
            b = beta.reshape((-1, ncomp) + beta.shape[1:])
            a = np.stack([D @ e[:, i] + E @ b[:, i] for i in range(ncomp)], axis=1)
            alpha.append(a.reshape(eps.shape))
        return u, p, alpha

    def flexibility(self, rows, cols, refine=True):
        """Depression (m, into the solid) of the displacement DOFs ``rows`` per unit downward force
        (N/m) on each of the vertical DOFs ``cols``: ``(rows.size, cols.size)``; ``refine`` as in
        :meth:`solve`."""
        w = np.empty((rows.size, cols.size))
        # each column solved costs arrays of the system's size: solve them in blocks, keep the rows
        chunk = max(1, int(FLEXIBILITY_ENTRIES // self.n_unknowns))
        for lo in range(0, cols.size, chunk):
            block = np.arange(lo, min(lo + chunk, cols.size))
            F = np.zeros((self.ops.basis.N, block.size))
            F[cols[block], np.arange(block.size)] = -1.0  # unit downward force on the body
            u, _, _ = self.solve(F, strains=False, refine=refine)
            w[:, block] = -u[rows]
        return w


def viscous_strain(ops, ell, eps):
    """``alpha`` (Voigt, point-major) of one term from the strain ``eps`` (exact update)."""
    Lk, Rk = memory_operators(ops.flow, ell)
    lu = spla.splu(sp.csc_matrix(Lk))
    ncomp = ops.ncomp
    e = eps.reshape((-1, ncomp) + eps.shape[1:])
    out = np.stack([lu.solve(np.asarray(Rk @ e[:, c])) for c in range(ncomp)], axis=1)
    return out.reshape(eps.shape)


def _fixed_dofs(ops):
    """The bottom, and the sides on rollers unless the cell is periodic (its right side is then
    constrained to its left side instead: :mod:`fem_reference.periodic`)."""
    basis = ops.basis
    bottom = basis.get_dofs("bottom").all()
    if ops.periodic:
        return np.unique(bottom)
    sides = basis.get_dofs({"left", "right"}).all("u^1")
    return np.unique(np.concatenate([bottom, sides]))


# A term is condensed while its truncated memory reaches at most this many elements upstream on
# average. Condensed, it adds no unknowns, and its band joins the others' (the entries of B_v
# follow the longest reach, not the number of terms); carried by the outflow values its entries
# stay local, but the system is harder for the direct solvers (measured on a 10-term rubber at
# its friction peak: PARDISO's first residual 1 against 3e-9 condensed, SuperLU's factor 6 times
# PARDISO's). So only terms whose memory spans most of a row (several tens of elements, where the
# band would grow with the square of the row) are carried by their outflow values.
MAX_REACH = 60.0


def condensable(ops, material, speed, max_reach=MAX_REACH):
    """Mask of the terms whose truncated memory reaches at most ``max_reach`` elements upstream
    on average (:func:`~fem_reference.memory.memory_reach`)."""
    return np.array(
        [
            speed * tau > 0 and memory_reach(ops.flow, speed * tau, limit=max_reach) <= max_reach
            for tau in material.relaxation_times
        ],
        dtype=bool,
    )


def condensed_terms(ops, material, speed, condense):
    """Mask of the terms whose viscous strains are eliminated: all with ``True``, none with
    ``False``, those of :func:`condensable` with ``"auto"``, or the given mask; never a term that
    does not move (``V tau_k = 0``)."""
    if isinstance(condense, str):
        if condense != "auto":
            raise ValueError(f"condense must be a bool, 'auto' or a mask, got {condense!r}")
        cmask = condensable(ops, material, speed)
    else:
        cmask = np.broadcast_to(np.asarray(condense, dtype=bool), (material.relaxation_times.size,)).copy()
    return cmask & (speed * material.relaxation_times > 0)


def system_path(material, speed, cmask, solver="auto", squares=False, closed=False):
    """The :func:`~fem_reference.linsolve.solver_path` of the steady system whose condensed terms
    are ``cmask``, on a mesh of squares or not, on a periodic cell (``closed`` streamlines) or not."""
    moving = speed * material.relaxation_times > 0
    return solver_path(
        solver, carries=bool(np.any(moving & ~cmask)), condenses=bool(np.any(cmask)), squares=squares, closed=closed
    )


def steady_operator(ops, material, speed, *, solver="auto", condense=False, memory=None):
    """Assemble and factor the steady operator (see module docstring).

    Parameters
    ----------
    ops : QuadratureOperators
        Plane-strain operators on a tensor mesh (rows of points are streamlines).
    material : bem.Material
    speed : float
        Rolling speed ``V`` (m/s), ``>= 0``.
    solver : str
        See :func:`fem_reference.linsolve.factorize`; ``"auto"`` is the first step of the system's
        :func:`system_path`.
    condense : bool, "auto" or array of bool
        Eliminate the viscous strains of these terms (all with ``True``, those of
        :func:`condensable` with ``"auto"``) through their truncated memory; the others are
        carried by their elements' outflow values.
    memory : float, optional
        Most bytes SuperLU's factor may take (:func:`~fem_reference.linsolve.factorize`).
    """
    t0 = time.perf_counter()
    mb = mixed_blocks(ops, material.nu)
    M, T, BtWd, c = mb.M, mb.T, mb.BtWd, mb.c
    B = ops.B
    g = material.moduli / material.E_inf
    cmask = condensed_terms(ops, material, speed, condense)

    free = np.setdiff1d(np.arange(B.shape[1]), np.concatenate([_fixed_dofs(ops), ops.constrained]))
    Bf = B[:, free]
    ncomp = ops.ncomp
    eye = sp.identity(ncomp, format="csr")
    n = ops.n_points
    S = sp.csr_matrix((n, n))
    if np.any(cmask):
        S = condensed_memory(ops.flow, speed * material.relaxation_times[cmask], g[cmask])
    states, chains = {}, []
    for k in np.flatnonzero(~cmask):
        D, E, Lk, Rk = state_operators(ops.flow, speed * material.relaxation_times[k])
        S = S + g[k] * D
        Ek = sp.kron(E, eye, format="csr")
        states[k] = (D, E, Ek.shape[1])
        chains.append((k, Ek, sp.kron(Lk, eye, format="csr"), sp.kron(Rk, eye, format="csr")))
    Bv = (Bf - sp.kron(S, eye, format="csr") @ Bf).tocsr() if S.nnz else Bf
    Kv = (BtWd[free] @ Bv).tocsr()
    Gf = mb.G[free]
    blocks = [
        [Kv, -Gf] + [-g[k] * (BtWd[free] @ Ek) for k, Ek, _, _ in chains],
        [-(T @ Bv), -c * M] + [g[k] * (T @ Ek) for k, Ek, _, _ in chains],
    ]
    for i, (_, _, Lk, Rk) in enumerate(chains):
        row = [-(Rk @ Bf), None] + [None] * len(chains)
        row[2 + i] = Lk
        blocks.append(row)
    A = sp.bmat(blocks, format="csc")
    t1 = time.perf_counter()
    fac = factorize(A, system_path(material, speed, cmask, solver, closed=ops.periodic)[0].solver, memory=memory)
    t2 = time.perf_counter()
    return SteadyOperator(
        ops,
        material,
        float(speed),
        free,
        (free.size, M.shape[0], sum(size for _, _, size in states.values())),
        fac,
        A.shape[0],
        matrix=A.tocsr(),
        condensed=cmask,
        states=states,
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


def solution_fields(mesh, ops, out, material):
    """The fields a result keeps and :func:`fem_reference.vtk.write_fields` writes, from a solve's
    ``out`` (``u``, ``p``, ``alpha``, ``eps``, ``sigma``, ``diss``): the mesh, its basis and operators,
    the displacement and, at the quadrature points, strain, stress, viscous strains, pressure and
    dissipation."""
    return dict(
        mesh=mesh,
        basis=ops.basis,
        ops=ops,
        u=out["u"],
        points=ops.points,
        weights=ops.weights,
        strain=out["eps"],
        stress=out["sigma"],
        alpha=out["alpha"],
        pressure=out["p"],
        taus=np.array(material.relaxation_times),
        dissipation=out["diss"],
    )
