"""Dense system of the adaptive BEM: influence and slope matrices of a mesh, and the contact
operator in element forces that :func:`bem.contact.solve_contact` solves.

Contact: :func:`bem.contact.solve_contact` (semismooth Newton, GMRES inner solves) on the dense
system written for the element *forces* ``f_i = A_i p_i`` (N; N/m for profiles), so that its
load constraint ``mean(f) = load / N_e`` is exactly the total force. Its complementarity
residual is therefore stated in forces: ``max |min(f_i / f_mean, g_i / h_ref)|``.
"""

import numpy as np

from .square import matrices_2d
from .strip import matrices_1d

__all__ = ["influence_matrix", "ForceOperator", "phase_symbol"]


def influence_matrix(mesh, material, speed, with_slope=True):
    """Dense influence matrix ``K`` (m/Pa) and slope matrix ``S`` (1/Pa) of ``mesh``:
    ``u_i = sum_j K_ij p_j`` and ``du/dx (x_i) = sum_j S_ij p_j`` at the element centres
    (see the module docstring), for the material sliding at ``speed`` (m/s). ``S`` is
    ``None`` unless ``with_slope`` (2-D; it is cheap in 1-D and always returned)."""
    if mesh.ndim == 1:
        return matrices_1d(mesh, material, speed)
    return matrices_2d(mesh, material, speed, with_slope)


# ------------------------------------------------------------------------------ contact
class ForceOperator:
    """Dense response to element forces (m/N): ``u = K (f / area)``, for :mod:`bem.contact`."""

    def __init__(self, K, areas, phase_symbol):
        self.matrix = K / areas[None, :]
        self.shape = (K.shape[0],)
        self.symbol = phase_symbol
        self.is_symmetric = False

    @property
    def size(self):
        return self.shape[0]

    def displacement(self, f):
        return self.matrix @ f

    def max_phase(self):
        """Largest phase (rad) of the material's compliance over the mesh's wavenumbers."""
        return 0.0 if self.is_symmetric else float(np.max(np.abs(np.angle(self.symbol))))

    def self_influence(self):
        return float(np.mean(np.diag(self.matrix)))

    def symmetric_part(self):
        twin = object.__new__(ForceOperator)
        twin.__dict__.update(self.__dict__)
        twin.matrix = 0.5 * (self.matrix + self.matrix.T)
        twin.symbol = np.real(self.symbol)
        twin.is_symmetric = True
        return twin

    def initial_pressure(self, ht, *, mean_pressure, approach=None):
        """First iterate for :mod:`bem.contact` (load control): Winkler forces."""
        return _winkler_start(ht, 1.0 / np.diag(self.matrix), mean_pressure * self.shape[0])

    def pressure_from_displacement(self, u):
        """Zero-sum forces whose displacement is ``u`` up to a constant (full contact)."""
        n = self.shape[0]
        a = np.zeros((n + 1, n + 1))
        a[:n, :n], a[:n, n], a[n, :n] = self.matrix, -1.0, 1.0
        return np.linalg.solve(a, np.concatenate([u, [0.0]]))[:n]


def phase_symbol(material, speed, mesh):
    """``J(-q v)`` sampled over the mesh's wavenumbers: its phase tells the contact solver how
    far from symmetric the operator is (as the periodic symbol does)."""
    if material.is_elastic or speed == 0:
        return np.zeros(1)
    q = np.geomspace(np.pi / mesh.length, np.pi / mesh.spacing, 64)
    return material.complex_compliance(np.concatenate([-q, q]) * speed)


def _winkler_start(heights, stiffness, load):
    """Initial forces of a Winkler foundation (each element a spring of ``stiffness``, N/m)
    pressed to carry ``load``: ``f = k max(h - max h + d, 0)`` with ``d`` by bisection."""
    ht = heights - heights.max()

    def total(d):
        return float(np.sum(stiffness * np.maximum(ht + d, 0.0)))

    stiffness = np.abs(stiffness)
    lo, hi = 0.0, max(float(np.ptp(ht)), 1e-300)
    for _ in range(2000):
        if total(hi) >= load:
            break
        hi *= 2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if total(mid) < load else (lo, mid)
    return stiffness * np.maximum(ht + hi, 0.0)
