"""Derived fields of a steady-rolling solution: full stress and strain tensors, von Mises,
hydrostatic pressure, and the complementarity residual of the contact from the field solve.

Plane strain (``eps_zz = 0``) with the mixed pressure ``p = -tr(sigma)/3``: the out-of-plane
stress follows from the trace, ``sigma_zz = -3 p - sigma_xx - sigma_yy``; it is not zero (for
``nu = 0.5`` it is the mean of the in-plane normal stresses). Voigt order of the solver:
``(xx, yy, xy)`` with engineering shear strain ``gamma_xy = 2 eps_xy``. Tensors are returned
as ``(n, 9)`` arrays in ParaView's row-major order ``xx, xy, xz, yx, yy, yz, zx, zy, zz``.
"""

from __future__ import annotations

import numpy as np

from .surface import band, top_surface

__all__ = ["full_tensor", "stress_tensor", "strain_tensor", "von_mises", "hydrostatic_pressure", "contact_residual"]


def full_tensor(xx, yy, zz, xy):
    """Rows of 3x3 tensors, row-major (VTK's order), from the normal components and one shear
    ``xy`` (the ``xz`` and ``yz`` shears are zero in plane strain and axisymmetry)."""
    out = np.zeros((xx.size, 9))
    out[:, 0], out[:, 4], out[:, 8] = xx, yy, zz
    out[:, 1] = out[:, 3] = xy
    return out


def stress_tensor(sigma, p):
    """Full Cauchy stress (Pa) from the in-plane Voigt ``sigma`` (n, 3) and pressure ``p`` (n,)."""
    sigma = np.asarray(sigma, float).reshape(-1, 3)
    p = np.asarray(p, float).ravel()
    return full_tensor(sigma[:, 0], sigma[:, 1], -3.0 * p - sigma[:, 0] - sigma[:, 1], sigma[:, 2])


def strain_tensor(eps):
    """Full small strain from the Voigt ``eps`` (n, 3) (engineering shear halved; ``eps_zz = 0``)."""
    eps = np.asarray(eps, float).reshape(-1, 3)
    return full_tensor(eps[:, 0], eps[:, 1], np.zeros(eps.shape[0]), 0.5 * eps[:, 2])


def von_mises(tensor):
    """``sqrt(3/2 s:s)`` of full tensors (n, 9), ``s`` the deviator (Pa)."""
    t = np.asarray(tensor, float).reshape(-1, 3, 3)
    dev = t - np.trace(t, axis1=1, axis2=2)[:, None, None] * np.eye(3) / 3.0
    return np.sqrt(1.5 * np.einsum("nij,nij->n", dev, dev))


def hydrostatic_pressure(tensor):
    """``-tr(sigma)/3`` of full tensors (n, 9) (Pa, positive in compression)."""
    t = np.asarray(tensor, float)
    return -(t[:, 0] + t[:, 4] + t[:, 8]) / 3.0


def contact_residual(result):
    """Complementarity residual of a :class:`~fem_reference.RollingResult` recomputed from its
    displacement field (needs ``keep_fields=True``).

    The gap ``g_i = w_i - h_i - d`` at every candidate node uses the depression ``w`` of the
    final linear solve with the contact forces applied (not the flexibility the contact
    iteration used), so it measures the contact condition as the fields satisfy it. Returns
    ``max_i |min(lam_i / mean(lam), g_i / |d|)|`` over the candidate nodes (dimensionless):
    nodes in contact must touch, nodes out of contact must not penetrate.
    """
    f = result.fields
    if not f:
        raise ValueError("contact_residual needs the fields: call rolling_cylinder(..., keep_fields=True)")
    top = top_surface(f["basis"])
    x_c = np.asarray(result.x)
    cand = band(top, x_c)
    w = -np.asarray(f["u"])[top.ydofs[cand]]
    x = top.x[cand]
    g = w + x**2 / (2 * result.radius) - result.approach
    lam = np.asarray(result.forces)
    scale_l = lam.sum() / max(np.count_nonzero(lam > 0), 1)
    return float(np.max(np.abs(np.minimum(lam / scale_l, g / abs(result.approach)))))
