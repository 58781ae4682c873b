"""Strain operators at quadrature points, for plane strain and axisymmetry.

Discretisation (shared by the rolling and the indentation models): 9-node biquadratic
displacements (``ElementQuad2``) on a rectangle mesh with a 3x3 Gauss rule, and a
discontinuous linear pressure (three unknowns per element: ``1, (x - x_c)/h_x,
(y - y_c)/h_y``). This Q2/P1-discontinuous pair is inf-sup stable, so the mixed
(displacement-pressure) form below does not lock for any Poisson ratio up to 0.5.

Voigt layout (engineering shear strains):

- plane strain: ``(xx, yy, xy)``;
- axisymmetric ``(r, z)``: ``(rr, zz, tt, rz)`` with ``tt`` the hoop strain ``u_r / r``.

Vectors of quadrature-point quantities are ordered point-major: entry ``g * ncomp + c``
is component ``c`` at point ``g``, and point ``g = e * nqp + q`` is local point ``q`` of
element ``e``.

Constitutive law for unit Young's modulus with constant Poisson ratio ``nu``::

    sigma = D_dev eps - p m,    p / K + m . eps = 0,

with ``m`` the trace vector, ``K = 1 / (3 (1 - 2 nu))`` the bulk modulus and
``D_dev = 2 G (I - m m^T / 3)`` (shear entries ``G``), ``G = 1 / (2 (1 + nu))``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.sparse as sp

__all__ = [
    "QuadratureOperators",
    "quadrature_operators",
    "deviatoric_matrix",
    "trace_vector",
    "inverse_bulk_modulus",
    "MixedBlocks",
    "mixed_blocks",
]


def trace_vector(kind):
    """The Voigt vector ``m`` with ``m . eps = tr(eps)``."""
    return np.array([1.0, 1.0, 0.0]) if kind == "plane" else np.array([1.0, 1.0, 1.0, 0.0])


def deviatoric_matrix(kind, nu):
    """``D_dev`` for unit Young's modulus (Pa per unit strain, engineering shear)."""
    g = 1.0 / (2.0 * (1.0 + nu))
    if kind == "plane":
        normal = 2 * g * (np.eye(2) - 1.0 / 3.0)
        d = np.zeros((3, 3))
        d[:2, :2] = normal
        d[2, 2] = g
    else:
        d = np.zeros((4, 4))
        d[:3, :3] = 2 * g * (np.eye(3) - 1.0 / 3.0)
        d[3, 3] = g
    return d


def inverse_bulk_modulus(nu):
    """``1 / K`` for unit Young's modulus; 0 for an incompressible solid."""
    return 3.0 * (1.0 - 2.0 * nu)


@dataclass(frozen=True)
class QuadratureOperators:
    """Sparse maps from nodal unknowns to quadrature-point fields.

    Attributes
    ----------
    basis : skfem.CellBasis
        Displacement basis (Q2, vector).
    kind : str
        ``"plane"`` or ``"axi"``.
    B : scipy.sparse.csr_matrix, (ncomp * ngp, N_u)
        Strain (Voigt) at the quadrature points from nodal displacements.
    N_p : scipy.sparse.csr_matrix, (ngp, 3 * n_elements)
        Pressure at the quadrature points from the element pressure unknowns.
    weights : ndarray, (ngp,)
        Quadrature weights times the Jacobian: areas (m^2, plane strain, per unit
        thickness) or volumes ``2 pi r dA`` (m^3, axisymmetric).
    points : ndarray, (2, ngp)
        Coordinates of the quadrature points (m).
    constraint : scipy.sparse.csr_matrix, (N_u, N_u), optional
        ``u = constraint @ u`` sets the hanging DOFs from the others (a mesh whose elements halve
        across some faces, :func:`fem_reference.quadtree.constraint_matrix`); ``B`` already
        includes it. None where no node hangs.
    constrained : ndarray of int
        The hanging DOFs (and a periodic cell's right side): not unknowns of a solve.
    periodic : bool
        The mesh is one period of a periodic cell (:mod:`fem_reference.periodic`): its right side's
        DOFs are its left side's, and the flow wraps from the left end of each row to its right end.
    """

    basis: object
    kind: str
    B: sp.csr_matrix
    N_p: sp.csr_matrix
    weights: np.ndarray
    points: np.ndarray
    constraint: object = None
    constrained: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    periodic: bool = False

    def complete(self, u):
        """Nodal ``u`` with its hanging DOFs set from the others (``u`` itself where none hang)."""
        return u if self.constraint is None else self.constraint @ u

    @property
    def ncomp(self):
        return 3 if self.kind == "plane" else 4

    @property
    def n_points(self):
        return self.weights.size

    @cached_property
    def flow(self):
        """The rows of points as streamlines of a flow along ``-x``
        (:class:`~fem_reference.memory.Flow`): each element row takes its inflow from the elements
        upstream of its ``x = x_max`` face (on a periodic cell, those at the row's other end)."""
        from .memory import mesh_flow

        nel, nqp = self.basis.dx.shape
        mesh = self.basis.mesh
        return mesh_flow(mesh.p, mesh.t, self.points.reshape(2, nel, nqp), periodic=self.periodic)

    @property
    def cell(self):
        """Element of each quadrature point (points are stored element by element)."""
        nel, nqp = self.basis.dx.shape
        return np.repeat(np.arange(nel), nqp)

    def pointwise(self, d):
        """Block-diagonal ``diag(weights) (x) d`` for a small matrix ``d`` (or vector)."""
        d = np.atleast_2d(np.asarray(d, dtype=float))
        return sp.kron(sp.diags(self.weights), sp.csr_matrix(d), format="csr")


def quadrature_operators(mesh, kind="plane", hanging=None, periodic=False):
    """Build :class:`QuadratureOperators` on a rectangle ``mesh`` (``skfem.MeshQuad``), whose
    ``hanging`` vertices ``(M, A, B)`` (:class:`fem_reference.quadtree.QuadtreeMesh`) hang at the
    middle of the faces ``A``-``B`` of larger elements; ``periodic``: the mesh is one period of a
    periodic cell (:mod:`fem_reference.periodic`)."""
    from skfem import Basis, ElementQuad2, ElementVector

    if kind not in ("plane", "axi"):
        raise ValueError(f"kind must be 'plane' or 'axi', got {kind!r}")
    ib = Basis(mesh, ElementVector(ElementQuad2()), intorder=4)  # 3x3 Gauss
    nel, nqp = ib.dx.shape
    ncomp = 3 if kind == "plane" else 4
    pts = ib.mapping.F(ib.X)  # (2, nel, nqp)
    r = pts[0]
    rows, cols, vals = [], [], []
    gp = np.arange(nel)[:, None] * nqp + np.arange(nqp)[None, :]  # (nel, nqp)
    for j in range(ib.Nbfun):
        f = ib.basis[j][0]
        g = f.grad  # (2 comp, 2 deriv, nel, nqp)
        dof = np.broadcast_to(ib.element_dofs[j][:, None], (nel, nqp))
        comps = [g[0, 0], g[1, 1]]
        if kind == "axi":
            comps.append(np.asarray(f)[0] / r)
        comps.append(g[0, 1] + g[1, 0])
        for c, v in enumerate(comps):
            rows.append((gp * ncomp + c).ravel())
            cols.append(dof.ravel())
            vals.append(v.ravel())
    B = sp.coo_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(nel * nqp * ncomp, ib.N)
    ).tocsr()
    constraint, constrained = None, np.zeros(0, dtype=int)
    if hanging is not None and len(hanging):
        from .quadtree import constraint_matrix

        constraint, constrained = constraint_matrix(ib, hanging)
    if periodic:
        from .periodic import periodic_constraint

        wrap, right = periodic_constraint(ib)
        # the hanging DOFs first (some hang on a right-side corner), then the right side from the left
        constraint = wrap if constraint is None else (constraint @ wrap).tocsr()
        constrained = np.union1d(constrained, right)
    if constraint is not None:
        B = (B @ constraint).tocsr()
    B.eliminate_zeros()

    # element pressure basis 1, (x - xc)/hx, (y - yc)/hy
    pv = mesh.p[:, mesh.t]  # (2, 4, nel)
    lo, hi = pv.min(axis=1), pv.max(axis=1)
    centre, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    sx = (pts[0] - centre[0][:, None]) / half[0][:, None]
    sy = (pts[1] - centre[1][:, None]) / half[1][:, None]
    pcols = np.arange(nel)[:, None] * 3
    N_p = sp.coo_matrix(
        (
            np.concatenate([np.ones(nel * nqp), sx.ravel(), sy.ravel()]),
            (
                np.tile(gp.ravel(), 3),
                np.concatenate([np.broadcast_to(pcols + i, (nel, nqp)).ravel() for i in range(3)]),
            ),
        ),
        shape=(nel * nqp, 3 * nel),
    ).tocsr()

    weights = ib.dx.ravel() * (2.0 * np.pi * r.ravel() if kind == "axi" else 1.0)
    return QuadratureOperators(ib, kind, B, N_p, weights, pts.reshape(2, -1), constraint, constrained, bool(periodic))


@dataclass(frozen=True)
class MixedBlocks:
    """Blocks of the mixed form for unit Young's modulus (see the module docstring).

    ``K = B^T W D_dev B`` (deviatoric stiffness), ``G = B^T W m N_p`` (divergence),
    ``M = N_p^T W N_p`` (pressure mass), ``T = N_p^T W m^T`` (trace of a quadrature-point
    strain, tested with the pressure basis), ``BtWd = B^T W D_dev`` (force from a
    quadrature-point strain), ``c = 1 / K_bulk``.
    """

    K: sp.csr_matrix
    G: sp.csr_matrix
    M: sp.csr_matrix
    T: sp.csr_matrix
    BtWd: sp.csr_matrix
    c: float


def mixed_blocks(ops, nu):
    """Assemble :class:`MixedBlocks` for the operators ``ops`` and Poisson ratio ``nu``."""
    m = trace_vector(ops.kind)
    Wd = ops.pointwise(deviatoric_matrix(ops.kind, nu))
    Wm = ops.pointwise(m[:, None])  # (ncomp*ngp, ngp)
    BtWd = (ops.B.T @ Wd).tocsr()
    return MixedBlocks(
        K=(BtWd @ ops.B).tocsr(),
        G=(ops.B.T @ Wm @ ops.N_p).tocsr(),
        M=(ops.N_p.T @ sp.diags(ops.weights) @ ops.N_p).tocsr(),
        T=(ops.N_p.T @ Wm.T).tocsr(),
        BtWd=BtWd,
        c=inverse_bulk_modulus(nu),
    )
