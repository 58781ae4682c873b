"""Time-temperature superposition: shift laws giving ``log10 a_T(T)``.

A thermorheologically simple material at temperature ``T`` responds at angular frequency
``w`` as it does at the reference temperature ``T_ref`` at ``a_T w``:
``E*(w; T) = E*(a_T(T) w; T_ref)``. Equivalently every relaxation and creep time is
multiplied by ``a_T``. Above the reference temperature the material is faster, so
``a_T < 1`` (``log10 a_T < 0``); below it ``a_T > 1``; ``a_T(T_ref) = 1``.

Temperatures are absolute (kelvin); activation energies are in J/mol. A temperature below
:data:`MIN_KELVIN` (100 K) is rejected: no rubber is used there, and the value is almost
certainly in degrees Celsius.

- WLF (Williams, Landel and Ferry 1955, doi:10.1021/ja01619a008):
  ``log10 a_T = -C1 (T - T_ref) / (C2 + T - T_ref)``, with ``C1 > 0`` (dimensionless) and
  ``C2 > 0`` (K); defined for ``T > T_ref - C2`` (the pole), and an empirical law that holds
  from about the glass transition upward. Below ``T_ref - C2 + 10 K`` it is steeper than any
  measured material, and :meth:`WLF.range_warnings` says so.
- Arrhenius: ``log10 a_T = E_a / (R ln 10) (1/T - 1/T_ref)``, with ``E_a > 0`` (J/mol) and
  ``R`` the molar gas constant.

Either law is also warned about where it shifts by more than :data:`MAX_LOG_SHIFT` (15)
decades, which no DMA measurement supports.

Fitting (:func:`fit_law`): the law through measured shifts ``(T_i, log10 a_i)``, optionally
with a free additive constant per group of shifts. Shifts found by overlaying sweeps are known
only relative to one sweep of their group; the constants carry that unknown offset, so the law
itself passes through zero at ``T_ref`` whether or not a sweep was measured there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..checks import check_positive, show
from ..errors import InputError
from ..plausibility import MAX_KELVIN

__all__ = [
    "WLF",
    "Arrhenius",
    "GAS_CONSTANT",
    "MIN_KELVIN",
    "MAX_LOG_SHIFT",
    "check_kelvin",
    "fit_law",
    "fit_wlf",
    "fit_arrhenius",
]

GAS_CONSTANT = 8.314462618  # J/(mol K), CODATA 2018 (exact)
MIN_KELVIN = 100.0  # K: below it a "temperature" is taken for degrees Celsius
MAX_LOG_SHIFT = 15.0  # decades: no shift law is measured that far
WLF_MARGIN = 10.0  # K above the WLF pole T_ref - C2 where the law is still believed


def check_kelvin(name, T):
    """``T`` as a float (or float array) of absolute temperatures from 100 K to
    :data:`bem.plausibility.MAX_KELVIN`, else InputError.

    A value below 100 K (or <= 0) is named as looking like degrees Celsius; one above the
    largest is no polymer's (a column of moduli or frequencies read as temperatures).
    """
    try:
        t = np.asarray(T, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be an absolute temperature in K (a number), got {T!r}") from None
    if not np.all(np.isfinite(t)):
        raise InputError(f"{name} must be a finite absolute temperature in K, got {show(T)}")
    if np.any(t < MIN_KELVIN):
        low = float(t.min())
        raise InputError(
            f"{name} must be an absolute temperature >= {MIN_KELVIN:g} K, got {low:g}: that looks like "
            f"degrees Celsius (use {low + 273.15:g} K)"
        )
    if np.any(t > MAX_KELVIN):
        hint = "is a column of moduli or frequencies read as temperatures?" if t.ndim else "temperatures are in K"
        raise InputError(
            f"{name} must be an absolute temperature <= {MAX_KELVIN:g} K (polymers decompose below it), got "
            f"{float(t.max()):g} K: {hint}"
        )
    return float(t) if t.ndim == 0 else t


def _scalar(out):
    return float(out) if np.ndim(out) == 0 else out


def _large_shift_warning(law, T, log_a, max_log_shift):
    if abs(log_a) <= max_log_shift:
        return ()
    return (
        f"the shift law gives log10 a_T = {log_a:.3g} at {T:g} K, a shift of more than "
        f"{max_log_shift:g} decades that no DMA measurement supports: {law.describe()} is "
        "extrapolated there; use temperatures nearer its reference",
    )


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
        ``T_ref`` in kelvin, >= 100 K.

    Examples
    --------
    >>> law = WLF(8.86, 101.6, 296.15)
    >>> float(law(296.15)), bool(law(320.0) < 0)
    (0.0, True)
    >>> law.range_warnings(296.15)
    ()
    """

    C1: float
    C2: float
    reference_temperature: float

    def __post_init__(self):
        object.__setattr__(self, "C1", check_positive("C1", self.C1))
        object.__setattr__(self, "C2", check_positive("C2 (K)", self.C2))
        object.__setattr__(
            self, "reference_temperature", check_kelvin("reference_temperature (K)", self.reference_temperature)
        )

    def __call__(self, T):
        """``log10 a_T`` at ``T`` (K; scalar or array)."""
        t = check_kelvin("temperature T", T)
        dt = t - self.reference_temperature
        if np.any(dt <= -self.C2):
            raise InputError(
                f"WLF: temperature T must be > reference_temperature - C2 = "
                f"{self.reference_temperature - self.C2:g} K, got {show(T)}"
            )
        return _scalar(-self.C1 * dt / (self.C2 + dt) + 0.0)  # +0.0: no -0.0 at T_ref

    def shift_factor(self, T):
        """``a_T`` (dimensionless) at ``T`` (K)."""
        return 10.0 ** self(T)

    @property
    def lowest_believed(self):
        """``T_ref - C2 + 10 K``: below it the law is steeper than any measured material."""
        return self.reference_temperature - self.C2 + WLF_MARGIN

    def range_warnings(self, T, max_log_shift=MAX_LOG_SHIFT):
        """Plain sentences (a tuple, empty when none) where ``T`` (K, scalar) is outside the
        law's range: below ``T_ref - C2 + 10 K``, or a shift of more than ``max_log_shift``
        decades."""
        T = check_kelvin("temperature T", T)
        out = ()
        if T < self.lowest_believed:
            out += (
                f"{T:g} K is below the WLF law's range (T_ref - C2 + 10 K = {self.lowest_believed:g} K, "
                f"10 K above its pole): {self.describe()} is extrapolated there and its shift is not to be "
                "trusted; use temperatures nearer its reference or a law measured there",
            )
        return out + _large_shift_warning(self, T, self(T), max_log_shift)

    def describe(self):
        """One line naming the law and its constants."""
        return f"WLF(C1 = {self.C1:.4g}, C2 = {self.C2:.4g} K, T_ref = {self.reference_temperature:g} K)"

    def referenced_to(self, temperature):
        """The same law referred to another reference temperature (K): the shifts relative to it,
        ``law(T) - law(temperature)``, are again WLF, with ``C2' = C2 + T' - T_ref`` and
        ``C1' = C1 C2 / C2'``."""
        t = check_kelvin("reference_temperature (K)", temperature)
        c2 = self.C2 + t - self.reference_temperature
        if not c2 > 0:
            raise InputError(
                f"reference_temperature must be > {self.reference_temperature - self.C2:g} K (the WLF pole), got {t:g}"
            )
        return WLF(self.C1 * self.C2 / c2, c2, t)

    # the parameter vector of a fit and the derivatives of log10 a_T with respect to it
    @property
    def parameters(self):
        return np.array([self.C1, self.C2])

    def with_parameters(self, p):
        return WLF(float(p[0]), float(p[1]), self.reference_temperature)

    def parameter_bounds(self, temperatures):
        """Bounds of ``(C1, C2)`` in a fit to data at ``temperatures`` (K): ``C1 > 0`` and the
        pole ``T_ref - C2`` at least 1 K below the coldest temperature."""
        return np.array([1e-6, wlf_c2_min(temperatures, self.reference_temperature)]), np.array([np.inf, np.inf])

    def gradient(self, T):
        """``d log10 a_T / d (C1, C2)`` at the temperatures ``T`` (K), shape ``(2, len(T))``."""
        dt = np.asarray(T, dtype=float) - self.reference_temperature
        return np.array([-dt / (self.C2 + dt), self.C1 * dt / (self.C2 + dt) ** 2])


@dataclass(frozen=True)
class Arrhenius:
    """Arrhenius shift law ``log10 a_T = E_a / (R ln 10) (1/T - 1/T_ref)``.

    Parameters
    ----------
    activation_energy : float
        ``E_a`` in J/mol, > 0.
    reference_temperature : float
        ``T_ref`` in kelvin, >= 100 K.
    """

    activation_energy: float
    reference_temperature: float

    def __post_init__(self):
        object.__setattr__(
            self, "activation_energy", check_positive("activation_energy (J/mol)", self.activation_energy)
        )
        object.__setattr__(
            self, "reference_temperature", check_kelvin("reference_temperature (K)", self.reference_temperature)
        )

    def __call__(self, T):
        """``log10 a_T`` at ``T`` (K; scalar or array)."""
        t = check_kelvin("temperature T", T)
        out = self.activation_energy / (GAS_CONSTANT * np.log(10.0)) * (1.0 / t - 1.0 / self.reference_temperature)
        return _scalar(out + 0.0)

    def shift_factor(self, T):
        """``a_T`` (dimensionless) at ``T`` (K)."""
        return 10.0 ** self(T)

    def range_warnings(self, T, max_log_shift=MAX_LOG_SHIFT):
        """Plain sentences (a tuple, empty when none) where ``T`` (K, scalar) shifts by more than
        ``max_log_shift`` decades."""
        T = check_kelvin("temperature T", T)
        return _large_shift_warning(self, T, self(T), max_log_shift)

    def describe(self):
        """One line naming the law and its constants."""
        return f"Arrhenius(E_a = {self.activation_energy:.4g} J/mol, T_ref = {self.reference_temperature:g} K)"

    def referenced_to(self, temperature):
        """The same law referred to another reference temperature (K)."""
        return Arrhenius(self.activation_energy, check_kelvin("reference_temperature (K)", temperature))

    @property
    def parameters(self):
        return np.array([self.activation_energy])

    def with_parameters(self, p):
        return Arrhenius(float(p[0]), self.reference_temperature)

    def parameter_bounds(self, temperatures):
        """Bounds of ``E_a`` (J/mol) in a fit: > 0."""
        return np.array([1e-3]), np.array([np.inf])

    def gradient(self, T):
        """``d log10 a_T / d E_a`` at the temperatures ``T`` (K), shape ``(1, len(T))``."""
        x = 1.0 / np.asarray(T, dtype=float) - 1.0 / self.reference_temperature
        return (x / (GAS_CONSTANT * np.log(10.0)))[None, :]


def wlf_c2_min(temperatures, reference_temperature):
    """Smallest ``C2`` (K) a WLF fit allows: its pole 1 K below the coldest temperature."""
    return max(1.0, 1.0 + reference_temperature - float(np.min(temperatures)))


def _group_matrix(groups, n):
    """Indicator columns of the groups (none without groups): one free constant per group."""
    if groups is None:
        return np.zeros((n, 0))
    g = np.asarray(groups)
    labels = np.unique(g)
    return (g[:, None] == labels[None, :]).astype(float)


def _wlf_with_offsets(dt, y, w, G, c2_min):
    """WLF plus group constants: for each C2 on a grid the model is linear in (C1, constants);
    the best grid point starts a nonlinear least-squares refinement of all of them."""
    from scipy.optimize import least_squares

    best = None
    for c2 in np.geomspace(c2_min * (1 + 1e-6), max(50 * c2_min, 2000.0), 120):
        a = np.column_stack([-dt / (c2 + dt), G]) * w[:, None]
        coef, *_ = np.linalg.lstsq(a, w * y, rcond=None)
        if coef[0] <= 0:
            continue
        cost = np.sum((a @ coef - w * y) ** 2)
        if best is None or cost < best[0]:
            best = (cost, c2, coef)
    if best is None:
        raise InputError(
            "the measured shifts do not fall with temperature, so no WLF law (C1 > 0) fits them; "
            "check the temperature column and its unit"
        )
    _, c2, coef = best
    k = G.shape[1]

    def residual(p):
        return w * (-p[0] * dt / (p[1] + dt) + G @ p[2:] - y)

    lo = np.concatenate([[1e-6, c2_min], np.full(k, -np.inf)])
    sol = least_squares(
        residual,
        np.concatenate([[coef[0], c2], coef[1:]]),
        bounds=(lo, np.full(2 + k, np.inf)),
        x_scale="jac",
        xtol=1e-14,
        ftol=1e-14,
        gtol=1e-14,
    )
    return sol.x[:2], sol.x[2:]


def fit_law(kind, temperatures, log_shift, reference_temperature, *, groups=None, weights=None):
    """Least-squares shift law through ``(T_i, log10 a_i)``: ``(law, offsets)``.

    Parameters
    ----------
    kind : {"wlf", "arrhenius"}
    temperatures, log_shift : array_like
        K and decades.
    reference_temperature : float
        ``T_ref`` (K) of the returned law, which is zero there by construction.
    groups : array_like, optional
        A label per point. Each group gets a free additive constant: the model is
        ``log10 a_i = law(T_i) + c_group(i)`` and ``offsets`` holds the constants (one per
        label, in ``numpy.unique`` order). Without groups the shifts are taken as anchored
        (``c = 0``) and ``offsets`` is empty.
    weights : array_like, optional
        Per-point weights of the residuals.

    Notes
    -----
    For WLF, for each ``C2`` on a grid beyond the coldest point's pole the model is linear in
    ``C1`` and the constants; the best start is refined by nonlinear least squares with
    ``C2 >= T_ref - T_min + 1 K``. Arrhenius is linear least squares.
    """
    T = check_kelvin("temperatures", temperatures)
    T = np.atleast_1d(T)
    y = np.asarray(log_shift, dtype=float)
    w = np.ones_like(y) if weights is None else np.asarray(weights, dtype=float)
    tref = check_kelvin("reference_temperature (K)", reference_temperature)
    G = _group_matrix(groups, y.size)
    free = y.size - G.shape[1]  # independent shift differences
    if kind == "wlf":
        dt = T - tref
        if free < 2 or (groups is None and np.sum(np.abs(dt) > 0) < 2):
            raise InputError(f"fitting a WLF law needs shifts at >= 2 more temperatures than groups, got {y.size}")
        c2_min = wlf_c2_min(T, tref)
        (c1, c2), offsets = _wlf_with_offsets(dt, y, w, G, c2_min)
        return WLF(float(c1), float(c2), float(tref)), offsets
    if kind == "arrhenius":
        x = 1.0 / T - 1.0 / tref
        if free < 1 or not np.any(x != 0):
            raise InputError(
                f"fitting an Arrhenius law needs shifts at >= 1 more temperature than groups, got {y.size}"
            )
        a = np.column_stack([x, G]) * w[:, None]
        coef, *_ = np.linalg.lstsq(a, w * y, rcond=None)
        if not coef[0] > 0:
            raise InputError(
                f"fit_arrhenius: the shift factors do not fall with temperature (slope {coef[0]:g}); "
                "check the temperature column and its unit"
            )
        return Arrhenius(float(coef[0] * GAS_CONSTANT * np.log(10.0)), float(tref)), coef[1:]
    raise InputError(f"shift law kind must be 'wlf' or 'arrhenius', got {kind!r}")


def fit_wlf(temperatures, log_shift, reference_temperature, weights=None):
    """Least-squares WLF law through anchored shifts ``(T_i, log10 a_T,i)`` (zero at ``T_ref``)."""
    return fit_law("wlf", temperatures, log_shift, reference_temperature, weights=weights)[0]


def fit_arrhenius(temperatures, log_shift, reference_temperature, weights=None):
    """Least-squares Arrhenius law through anchored shifts ``(T_i, log10 a_T,i)``."""
    return fit_law("arrhenius", temperatures, log_shift, reference_temperature, weights=weights)[0]
