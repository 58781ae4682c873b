"""Nodal values of quadrature-point fields: the L2 projection onto bilinear shape functions.

VTK's cell data holds element averages; ParaView draws point data as smooth fields. The
projection ``M s = integral(phi_i sigma)`` with ``M`` the (consistent) mass matrix of the
element's corner-node shape functions is exact for fields linear in x and y, and unlike the
average of the neighbouring elements it does not halve a gradient at a boundary such as the
contact surface.
"""

import numpy as np

__all__ = ["project_to_nodes"]


def project_to_nodes(values, basis):
    """Values at the mesh's vertices (``(nverts, ncomp)``, or ``(nverts,)`` for scalars) of
    quadrature-point ``values`` (``(nelems * nqp[, ncomp])`` in the order of ``basis``'s
    quadrature, which is the order of the FEM's fields)."""
    from scipy.sparse.linalg import splu
    from skfem import Basis, BilinearForm, ElementQuad1, LinearForm

    linear = Basis(basis.mesh, ElementQuad1(), quadrature=basis.quadrature)
    mass = splu(BilinearForm(lambda u, v, w: u * v).assemble(linear).tocsc())
    load = LinearForm(lambda v, w: w["s"] * v)
    values = np.asarray(values, float)
    flat = values.reshape(linear.nelems, -1, 1 if values.ndim == 1 else values.shape[-1])
    out = np.column_stack([mass.solve(load.assemble(linear, s=flat[:, :, c])) for c in range(flat.shape[2])])
    out = out[linear.nodal_dofs[0]]  # dof order -> vertex order
    return out[:, 0] if values.ndim == 1 else out
