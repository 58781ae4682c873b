"""Time-temperature superposition: shift laws giving ``log10 a_T(T)``.

A thermorheologically simple material at temperature ``T`` responds at angular frequency
``w`` as it does at the reference temperature ``T_ref`` at ``a_T w``:
``E*(w; T) = E*(a_T(T) w; T_ref)``. Equivalently every relaxation and creep time is
multiplied by ``a_T``. Above the reference temperature the material is faster, so
``a_T < 1`` (``log10 a_T < 0``); below it ``a_T > 1``; ``a_T(T_ref) = 1``.

Temperatures are absolute (kelvin); activation energies are in J/mol.

- WLF (Williams, Landel and Ferry 1955, doi:10.1021/ja01619a008):
  ``log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref)``, with ``C1 > 0`` (dimensionless) and
  ``C2 > 0`` (K); defined for ``T > T_ref - C2``.
- Arrhenius: ``log10 a_T = E_a / (R ln 10) (1/T - 1/T_ref)``, with ``E_a > 0`` (J/mol) and
  ``R`` the molar gas constant.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..checks import check_positive
from ..errors import InputError

__all__ = ["WLF", "Arrhenius", "GAS_CONSTANT", "fit_wlf", "fit_arrhenius"]

GAS_CONSTANT = 8.314462618  # J/(mol K), CODATA 2018 (exact)


def _temperatures(T):
    t = np.asarray(T, dtype=float)
    if not np.all(np.isfinite(t)) or np.any(t <= 0):
        raise InputError(f"temperature T must be finite and > 0 K (absolute), got {T!r}")
    return t


@dataclass(frozen=True)
class WLF:
    """Williams-Landel-Ferry shift law ``log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref)``.

    Parameters
    ----------
    C1 : float
        Dimensionless, > 0.
    C2 : float
        Kelvin, > 0. The law holds for ``T > reference_temperature - C2``.
    reference_temperature : float
        ``T_ref`` in kelvin, > 0.

    Examples
    --------
    >>> law = WLF(8.86, 101.6, 296.15)
    >>> float(law(296.15)), bool(law(320.0) < 0)
    (0.0, True)
    """

    C1: float
    C2: float
    reference_temperature: float

    def __post_init__(self):
        object.__setattr__(self, "C1", check_positive("C1", self.C1))
        object.__setattr__(self, "C2", check_positive("C2 (K)", self.C2))
        object.__setattr__(
            self, "reference_temperature", check_positive("reference_temperature (K)", self.reference_temperature)
        )

    def __call__(self, T):
        """``log10 a_T`` at ``T`` (K; scalar or array)."""
        dt = _temperatures(T) - self.reference_temperature
        if np.any(dt <= -self.C2):
            raise InputError(
                f"WLF: temperature T must be > reference_temperature - C2 = "
                f"{self.reference_temperature - self.C2:g} K, got {T!r}"
            )
        out = self.C1 * (self.reference_temperature - _temperatures(T)) / (self.C2 + dt)  # +0.0 at T_ref
        return float(out) if out.ndim == 0 else out

    def shift_factor(self, T):
        """``a_T`` (dimensionless) at ``T`` (K)."""
        return 10.0 ** self(T)


@dataclass(frozen=True)
class Arrhenius:
    """Arrhenius shift law ``log10 a_T = E_a / (R ln 10) (1/T - 1/T_ref)``.

    Parameters
    ----------
    activation_energy : float
        ``E_a`` in J/mol, > 0.
    reference_temperature : float
        ``T_ref`` in kelvin, > 0.
    """

    activation_energy: float
    reference_temperature: float

    def __post_init__(self):
        object.__setattr__(
            self, "activation_energy", check_positive("activation_energy (J/mol)", self.activation_energy)
        )
        object.__setattr__(
            self, "reference_temperature", check_positive("reference_temperature (K)", self.reference_temperature)
        )

    def __call__(self, T):
        """``log10 a_T`` at ``T`` (K; scalar or array)."""
        t = _temperatures(T)
        out = self.activation_energy / (GAS_CONSTANT * np.log(10.0)) * (1.0 / t - 1.0 / self.reference_temperature)
        return float(out) if out.ndim == 0 else out

    def shift_factor(self, T):
        """``a_T`` (dimensionless) at ``T`` (K)."""
        return 10.0 ** self(T)


def fit_wlf(temperatures, log_shift, reference_temperature, weights=None):
    """Least-squares WLF law through the points ``(T_i, log10 a_T,i)``.

    The start is the linear form ``dT / log a = -C2/C1 - dT/C1`` (points at ``T_ref``
    excluded), refined by nonlinear least squares on ``log10 a_T`` itself.
    """
    from scipy.optimize import least_squares

    T = np.asarray(temperatures, dtype=float)
    y = np.asarray(log_shift, dtype=float)
    w = np.ones_like(y) if weights is None else np.asarray(weights, dtype=float)
    dt = T - reference_temperature
    off = np.abs(y) > 1e-12
    if off.sum() < 2:
        raise InputError("fit_wlf needs at least 2 temperatures away from the reference temperature")
    slope, icpt = np.polyfit(dt[off], dt[off] / y[off], 1)
    c1 = -1.0 / slope if slope < 0 else 10.0
    c2 = icpt * -c1 if icpt * -c1 > 0 else 50.0
    c2 = max(c2, 2.0 - dt.min())

    def residual(p):
        return w * (-p[0] * dt / (p[1] + dt) - y)

    # C2 stays 1 K beyond the coldest point, where the law has its pole
    sol = least_squares(
        residual,
        [c1, c2],
        bounds=([1e-6, 1.0 - min(dt.min(), 0.0)], [np.inf, np.inf]),
        x_scale="jac",
        xtol=1e-14,
        ftol=1e-14,
        gtol=1e-14,
    )
    return WLF(float(sol.x[0]), float(sol.x[1]), float(reference_temperature))


def fit_arrhenius(temperatures, log_shift, reference_temperature, weights=None):
    """Weighted linear least squares of ``log10 a_T`` on ``1/T - 1/T_ref`` through the origin."""
    T = np.asarray(temperatures, dtype=float)
    y = np.asarray(log_shift, dtype=float)
    w = np.ones_like(y) if weights is None else np.asarray(weights, dtype=float)
    x = 1.0 / T - 1.0 / reference_temperature
    denom = np.sum((w * x) ** 2)
    if denom == 0:
        raise InputError("fit_arrhenius needs at least 1 temperature away from the reference temperature")
    slope = np.sum(w**2 * x * y) / denom
    if not slope > 0:
        raise InputError(
            f"fit_arrhenius: the shift factors do not fall with temperature (slope {slope:g}); "
            "check the temperature column and its unit"
        )
    return Arrhenius(float(slope * GAS_CONSTANT * np.log(10.0)), float(reference_temperature))
