"""VTK (.vtu) export of FEM fields through meshio, for ParaView.

Point data (at mesh vertices): ``displacement`` (m, 3 components, z = 0). Cell data
(element averages over the 3x3 Gauss points, weighted by the quadrature weights):
``strain`` and ``stress`` (Voigt, engineering shear; Pa for stress), ``alpha_k`` (viscous
strain of Prony term ``k``), ``dissipation`` (W/m^3).
"""
from __future__ import annotations

import numpy as np

__all__ = ["write_fields", "fields_to_meshio"]


def _cell_average(values, weights, nel):
    """Weighted element average of quadrature-point values (ngp[, ncomp])."""
    nqp = weights.size // nel
    w = weights.reshape(nel, nqp)
    v = values.reshape(nel, nqp, -1)
    return np.einsum("eq,eqc->ec", w, v) / w.sum(axis=1)[:, None]


def fields_to_meshio(fields):
    """Build a ``meshio.Mesh`` from ``RollingResult.fields``-style ``fields``."""
    import meshio

    mesh, basis, u = fields["mesh"], fields["basis"], fields["u"]
    nel = mesh.t.shape[1]
    weights = fields["weights"]
    ncomp = fields["strain"].shape[1]
    disp = np.zeros((mesh.p.shape[1], 3))
    disp[:, :2] = u[basis.nodal_dofs].T
    cell = {
        "strain": _cell_average(fields["strain"].reshape(-1, ncomp), weights, nel),
        "stress": _cell_average(fields["stress"].reshape(-1, ncomp), weights, nel),
        "dissipation": _cell_average(fields["dissipation"], weights, nel)[:, 0],
    }
    for k, a in enumerate(fields["alpha"]):
        cell[f"alpha_{k}"] = _cell_average(np.asarray(a).reshape(-1, ncomp), weights, nel)
    points = np.zeros((mesh.p.shape[1], 3))
    points[:, :2] = mesh.p.T
    return meshio.Mesh(points, [("quad", mesh.t.T.copy())], point_data={"displacement": disp},
                       cell_data={k: [v] for k, v in cell.items()})


def write_fields(path, fields):
    """Write ``fields`` (see :func:`fields_to_meshio`) to the ``.vtu`` file ``path``."""
    fields_to_meshio(fields).write(str(path))
