"""Linear viscoelastic material: Prony (relaxation) and creep (retardation) series.

Units are SI: moduli in Pa, compliances in 1/Pa, times in s, angular frequencies in rad/s.

Conventions (the theory page of the documentation, section 2), with ``s = i w``:

- relaxation (generalised Maxwell):
  ``E(t) = E0 + sum_k E_k exp(-t/tau_k)``,
  ``E(w) = E0 + sum_k E_k i w tau_k / (1 + i w tau_k)``,
  ``E_inf = E0 + sum_k E_k`` (``E0`` relaxed, ``E_inf`` glassy);
- creep (retardation):
  ``J(t) = 1/E0 - sum_k C_k exp(-t/lambda_k)``,
  ``J(w) = 1/E_inf + sum_k C_k / (1 + i w lambda_k)``,
  ``1/E_inf = 1/E0 - sum_k C_k``.

The two are converted exactly (to round-off) by partial fractions
(:mod:`bem.materials.interconversion`).

The Poisson ratio ``nu`` is the same for every term, so the half-space responds
through the plane-strain modulus ``E(w) / (1 - nu**2)``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..checks import check_array, check_positive, check_range
from ..errors import InputError
from ..plausibility import check_moduli, temperature_warnings
from . import master_curve
from .coverage import band_warnings
from .interconversion import creep_to_prony, prony_to_creep
from .prony_fit import check_dma, default_times, fit_prony_series
from .temperature import check_kelvin

__all__ = ["Material"]


def _sorted_terms(amplitudes, times):
    order = np.argsort(times)[::-1]  # longest time first
    return amplitudes[order], times[order]


def _check_series(name, amplitudes, unit, times):
    """Validate a series' amplitudes (> 0, in ``unit``) and times (> 0 s, distinct)."""
    a = check_array(name, amplitudes, ndim=1, min_size=0)
    t = check_array("times", times, ndim=1, min_size=0)
    if a.shape != t.shape:
        raise InputError(f"{name} and times must have the same length, got {a.size} and {t.size}")
    if np.any(a <= 0):
        raise InputError(f"{name} must all be > 0 {unit}, got min {a.min()!r}")
    if np.any(t <= 0):
        raise InputError(f"times must all be > 0 s, got min {t.min()!r}")
    if np.unique(t).size != t.size:
        raise InputError("times must be distinct (merge terms with equal times)")
    return a, t


@dataclass(frozen=True)
class Material:
    """Isotropic linear viscoelastic solid with a constant Poisson ratio.

    Build it with one of the class methods; the attributes hold both series.

    Attributes
    ----------
    E0 : float
        Relaxed (long-time, low-frequency) Young's modulus, Pa.
    E_inf : float
        Glassy (instantaneous, high-frequency) Young's modulus, Pa.
    moduli, relaxation_times : ndarray
        Prony series ``E_k`` (Pa) and ``tau_k`` (s), longest time first.
    compliances, creep_times : ndarray
        Creep series ``C_k`` (1/Pa) and ``lambda_k`` (s), longest time first.
    nu : float
        Poisson ratio in [0, 0.5].
    fit_report : FitReport or None
        For fitted materials, how well the series reproduces the data it was fitted to and
        the band the data cover (see :mod:`bem.materials.prony_fit`); None otherwise.
    warnings : tuple of str
        What is doubtful about the material itself, in plain sentences: a master-curve sweep
        far off the curve (:meth:`fit_master_curve`), a shift law applied outside its range
        (:meth:`at_temperature`). Empty for a material as given.
    """

    E0: float
    moduli: np.ndarray
    relaxation_times: np.ndarray
    nu: float = 0.5
    compliances: np.ndarray = field(init=False, repr=False)
    creep_times: np.ndarray = field(init=False, repr=False)
    E_inf: float = field(init=False)
    fit_report: object = field(default=None, repr=False, compare=False)
    warnings: tuple = field(default=(), repr=False, compare=False)

    def __post_init__(self):
        E0 = check_positive("E0", self.E0)
        nu = check_range("nu", self.nu, 0.0, 0.5)
        Ek, tk = _sorted_terms(*_check_series("moduli", self.moduli, "Pa", self.relaxation_times))
        check_moduli(E0, float(E0 + Ek.sum()))  # a solid's moduli (bem.plausibility)
        if Ek.size:
            Ck, lk = prony_to_creep(E0, Ek, tk)
            Ck, lk = _sorted_terms(Ck, lk)
        else:
            Ck, lk = np.zeros(0), np.zeros(0)
        for name, value in [
            ("E0", E0),
            ("nu", nu),
            ("moduli", Ek),
            ("relaxation_times", tk),
            ("compliances", Ck),
            ("creep_times", lk),
            ("E_inf", float(E0 + Ek.sum())),
        ]:
            if isinstance(value, np.ndarray):
                value.setflags(write=False)
            object.__setattr__(self, name, value)

    # ------------------------------------------------------------------ constructors
    @classmethod
    def elastic(cls, E, nu=0.5):
        """Linear elastic solid of Young's modulus ``E`` (Pa)."""
        return cls(check_positive("E", E), np.zeros(0), np.zeros(0), nu)

    @classmethod
    def standard_linear_solid(cls, *, E0, E_inf, relaxation_time=None, creep_time=None, nu=0.5):
        """One-term solid: relaxed ``E0``, glassy ``E_inf`` (Pa) and exactly one time (s).

        ``creep_time`` (retardation time, the seed paper's ``tau``) and
        ``relaxation_time`` are related by ``creep_time = relaxation_time * E_inf / E0``.
        """
        E0 = check_positive("E0", E0)
        E_inf = check_positive("E_inf", E_inf)
        if not E_inf > E0:
            raise InputError(f"E_inf must be > E0 = {E0!r} Pa (glassy stiffer than relaxed), got {E_inf!r}")
        if (relaxation_time is None) == (creep_time is None):
            raise InputError("give exactly one of relaxation_time or creep_time (s)")
        if relaxation_time is not None:
            tau = check_positive("relaxation_time", relaxation_time)
        else:
            tau = check_positive("creep_time", creep_time) * E0 / E_inf
        return cls(E0, np.array([E_inf - E0]), np.array([tau]), nu)

    @classmethod
    def from_prony(cls, *, E0, moduli, times, nu=0.5):
        """Relaxation series ``E(t) = E0 + sum E_k exp(-t/tau_k)`` (Pa, s).

        The terms are stored sorted by time, longest first, whatever their order here:
        ``moduli[k]`` stays paired with ``times[k]``, and two materials with the same terms in
        different orders are equal.
        """
        return cls(E0, check_array("moduli", moduli, ndim=1), check_array("times", times, ndim=1), nu)

    @classmethod
    def from_creep(cls, *, E0, compliances, times, nu=0.5):
        """Creep series ``J(t) = 1/E0 - sum C_k exp(-t/lambda_k)`` (1/Pa, s), all ``C_k > 0``."""
        E0 = check_positive("E0", E0)
        Ck, lk = _check_series("compliances", compliances, "1/Pa", times)
        if not Ck.size:
            raise InputError("compliances must have at least 1 entry (use Material.elastic for none)")
        if not Ck.sum() < 1.0 / E0:
            raise InputError(
                f"compliances must sum to < 1/E0 = {1 / E0!r} 1/Pa (so that E_inf is finite), got {Ck.sum()!r}"
            )
        Ek, tk = creep_to_prony(E0, Ck, lk)
        return cls(E0, Ek, tk, nu)

    @classmethod
    def fit_prony(
        cls, frequencies, storage, loss, *, times=None, terms_per_decade=3.0, hz=False, nu=0.5, smoothing=0.0
    ):
        """Fit a non-negative Prony series to DMA data (a master curve), in relative error.

        Parameters
        ----------
        frequencies : array_like
            Angular frequencies (rad/s), or Hz with ``hz=True``.
        storage, loss : array_like
            ``E'(w)`` and ``E''(w)`` in Pa.
        times : array_like, optional
            Relaxation times (s) to fit with; by default log-spaced over
            ``[1/w_max, 1/w_min]`` widened by one decade each side, with
            ``terms_per_decade`` per decade.
        nu : float
            Poisson ratio.
        smoothing : float
            Weight (>= 0, dimensionless) of the second-difference penalty on the relative
            spectrum; 0 fits by least squares alone.

        Returns
        -------
        Material
            With ``fit_report`` (a :class:`bem.materials.prony_fit.FitReport`): the max and rms
            relative errors of ``E'`` and ``E''`` against the data.

        Notes
        -----
        See :mod:`bem.materials.prony_fit`: non-negative least squares on ``E'_fit/E' - 1`` and
        ``E''_fit/E'' - 1``, so both moduli are fitted in relative error; terms fitted as
        zero are dropped. On the default times (``times=None``, ``smoothing=0``) the kept
        terms' times are then optimised too; given ``times`` are kept as they are.
        """
        w, e1, e2 = check_dma(frequencies, storage, loss, hz=hz)
        if times is None:
            taus = default_times(w, terms_per_decade)
        else:
            taus = check_array("times", times, ndim=1, positive=True)
        E0, moduli, taus, report = fit_prony_series(w, e1, e2, taus, smoothing=smoothing, refine=times is None)
        return cls(E0, moduli, taus, nu, fit_report=report)

    @classmethod
    def fit_master_curve(
        cls,
        frequencies,
        temperatures,
        storage,
        loss,
        *,
        reference_temperature=None,
        shift="wlf",
        hz=False,
        terms_per_decade=3.0,
        smoothing=0.0,
        nu=0.5,
        temperature_tolerance=0.5,
        min_overlap=0.25,
        max_mismatch=0.05,
        joint=True,
    ):
        """Master curve and shift law from DMA sweeps at several temperatures.

        Parameters
        ----------
        frequencies, storage, loss : array_like
            One entry per measured point: frequency (rad/s, or Hz with ``hz=True``),
            ``E'`` and ``E''`` (Pa, both > 0).
        temperatures : array_like
            Temperature of each point, K (>= 100 K: a smaller value looks like degrees
            Celsius and is an InputError). Points within ``temperature_tolerance`` (K) of
            each other form one isothermal sweep.
        reference_temperature : float
            ``T_ref`` (K) of the returned material and law; measured or not. Required when
            the law is fitted; with an imposed law it defaults to the law's own, and another
            value refers the law to it (the same shifts).
        shift : {"wlf", "arrhenius"} or WLF or Arrhenius
            A name fits that law (at least 3 sweeps for WLF, 2 for Arrhenius); a law
            (:class:`bem.materials.temperature.WLF` with known constants, say) is imposed and
            only the series is fitted (1 sweep or more, overlapping or not).
        terms_per_decade, smoothing, nu
            As for :meth:`fit_prony`.
        min_overlap : float
            Decades of frequency two neighbouring sweeps must share, once shifted, for their
            overlay to count as a measured shift (the default 0.25 takes the 0.3-0.4 decades
            that 5 K steps of 0.1-100 Hz sweeps leave near the glass transition).
        max_mismatch : float
            Largest rms difference of log10 moduli (decades) between overlapping sweeps
            overlaid, and between every sweep and the master curve under the law; beyond
            it the data do not superpose and an InputError says where.
        joint : bool
            Fit the law's parameters together with the series (default). False keeps the
            law fitted to the overlap shifts alone, which then need every sweep to overlap a
            neighbour.

        Returns
        -------
        (Material, WLF or Arrhenius)
            The material at ``T_ref`` (its ``fit_report`` a
            :class:`bem.materials.master_curve.MasterCurveReport`: the fit's relative errors
            on the data and its worst points, the reduced-frequency band the data cover and
            whether they reach the plateaus, the shifts) and the law, so that
            ``material.at_temperature(T, law)`` describes the material at ``T``.

        Notes
        -----
        The method (overlap shifts anchored through the law, the joint fit of law and
        series) is described in :mod:`bem.materials.master_curve`; what the band means for
        a computation, in :meth:`extrapolation_warnings`.
        """
        E0, moduli, taus, law, report = master_curve.fit_master_curve(
            frequencies,
            temperatures,
            storage,
            loss,
            reference_temperature=reference_temperature,
            shift=shift,
            hz=hz,
            terms_per_decade=terms_per_decade,
            smoothing=smoothing,
            temperature_tolerance=temperature_tolerance,
            min_overlap=min_overlap,
            max_mismatch=max_mismatch,
            joint=joint,
        )
        return cls(E0, moduli, taus, nu, fit_report=report, warnings=report.notes), law

    def at_temperature(self, T, shift):
        """The material at temperature ``T`` (K) under the shift law ``shift``.

        ``shift(T)`` gives ``log10 a_T`` (e.g. :class:`bem.materials.temperature.WLF`); every
        relaxation and creep time is multiplied by ``a_T``, so that
        ``E*(w)`` at ``T`` equals ``E*(a_T w)`` of this material (the reference), exactly:
        the moduli and compliances are unchanged and the times scale by one rounding each.

        A fitted material's ``fit_report`` moves with it (its band divided by ``a_T``). Where
        the law is used outside its range (``shift.range_warnings(T)``: for WLF below
        ``T_ref - C2 + 10 K``, for any law a shift of more than 15 decades), or ``T`` is far
        outside the temperatures of the data the material was fitted to or, for a law imposed
        without data, far from its reference temperature (:mod:`bem.plausibility`), the returned
        material's ``warnings`` say so. A temperature above 1000 K is an InputError. A temperature below 100 K (degrees Celsius typed as
        kelvin), or one whose shift puts the times outside floating point, is an InputError.
        """
        if not callable(shift):
            raise InputError(
                f"shift must be a callable giving log10 a_T(T) (e.g. bem.materials.temperature.WLF), got {shift!r}"
            )
        T = check_kelvin("T (K, absolute)", T)
        data = getattr(self.fit_report, "temperatures", None) or None
        far = temperature_warnings(T, reference=getattr(shift, "reference_temperature", None), data=data)
        try:
            log_a = float(shift(T))
        except OverflowError:
            log_a = float("inf")
        times = np.concatenate([self.relaxation_times, self.creep_times])
        with np.errstate(over="ignore", under="ignore", invalid="ignore"):
            shifted = times * np.power(10.0, log_a)
        if not (np.isfinite(log_a) and np.all((shifted >= 1e-280) & (shifted <= 1e280))):
            raise InputError(
                f"T = {T:g} K is outside the shift law's range: it gives log10 a_T = {log_a:.4g}, which moves "
                "the material's times outside 1e-280 to 1e280 s, beyond what floating point holds (the law "
                "cannot be used that far from its reference temperature)"
            )
        factor = 10.0**log_a
        range_warnings = getattr(shift, "range_warnings", None)
        notes = tuple(getattr(self.fit_report, "notes", ())) + (tuple(range_warnings(T)) if range_warnings else ())
        notes += tuple(far)
        report = self.fit_report.shifted(log_a) if self.fit_report is not None else None
        out = Material(self.E0, self.moduli, self.relaxation_times * factor, self.nu, fit_report=report, warnings=notes)
        creep = self.creep_times * factor
        creep.setflags(write=False)
        object.__setattr__(out, "compliances", self.compliances)
        object.__setattr__(out, "creep_times", creep)
        return out

    @property
    def data_band(self):
        """``(w_min, w_max)`` (rad/s) of the data a fitted material was fitted to, in this
        material's frame (moved by :meth:`at_temperature`); None when not fitted."""
        return None if self.fit_report is None else tuple(self.fit_report.frequency_band)

    def extrapolation_warnings(self, w_low, w_high):
        """Plain sentences (a tuple) on what is not measured in the band ``[w_low, w_high]``
        (rad/s) a computation uses.

        For a fitted material: one sentence per end of the band that lies outside the data's
        band, saying how far, whether the data reach the plateau there (so whether ``E0`` or
        ``E_inf`` is measured or a guess) and what to change
        (:func:`bem.materials.coverage.band_warnings`). After these, the material's own
        ``warnings`` (a shift law used outside its range). Empty for a material as given, or
        when the data cover ``[w_low, w_high]``.
        """
        w_low = check_positive("w_low (rad/s)", w_low, allow_zero=True)
        w_high = check_positive("w_high (rad/s)", w_high)
        if w_low > w_high:
            raise InputError(f"w_low must be <= w_high = {w_high!r} rad/s, got {w_low!r}")
        band = () if self.fit_report is None else band_warnings(self.fit_report, w_low, w_high)
        return tuple(band) + tuple(self.warnings)

    # ------------------------------------------------------------------ responses
    @property
    def is_elastic(self):
        """True when there are no viscous terms."""
        return self.moduli.size == 0

    @property
    def plane_strain_factor(self):
        """``1 - nu**2``: the half-space responds to ``E / (1 - nu**2)``."""
        return 1.0 - self.nu**2

    def complex_modulus(self, w):
        """``E*(w) = E' + i E''`` (Pa) at angular frequency ``w`` (rad/s, any sign)."""
        w = np.asarray(w, dtype=float)
        iwt = 1j * w[..., None] * self.relaxation_times
        return self.E0 + np.sum(self.moduli * iwt / (1.0 + iwt), axis=-1)

    def complex_compliance(self, w):
        """``J*(w) = 1 / E*(w)`` (1/Pa) from the creep series."""
        w = np.asarray(w, dtype=float)
        return 1.0 / self.E_inf + np.sum(self.compliances / (1.0 + 1j * w[..., None] * self.creep_times), axis=-1)

    def creep_compliance(self, t):
        """``J(t)`` (1/Pa) for ``t >= 0`` (s): strain under a unit step stress."""
        t = np.asarray(t, dtype=float)
        return 1.0 / self.E0 - np.sum(self.compliances * np.exp(-t[..., None] / self.creep_times), axis=-1)

    def relaxation_modulus(self, t):
        """``E(t)`` (Pa) for ``t >= 0`` (s): stress under a unit step strain."""
        t = np.asarray(t, dtype=float)
        return self.E0 + np.sum(self.moduli * np.exp(-t[..., None] / self.relaxation_times), axis=-1)

    def folded(self, w_min, w_max, *, tol=1e-6):
        """Copy with the terms inactive over ``[w_min, w_max]`` (rad/s) folded in.

        A relaxation term with ``w_max * tau_k < tol`` is fully relaxed there and dropped;
        one with ``w_min * tau_k > 1/tol`` is glassy there and added to ``E0``. The complex
        modulus changes by at most about ``tol * E_k`` per folded term inside the band.
        """
        w_min = check_positive("w_min", w_min, allow_zero=True)
        w_max = check_positive("w_max", w_max)
        if w_min > w_max:
            raise InputError(f"w_min must be <= w_max = {w_max!r} rad/s, got {w_min!r}")
        relaxed = w_max * self.relaxation_times < tol
        glassy = w_min * self.relaxation_times > 1.0 / tol
        active = ~(relaxed | glassy)
        return Material(
            self.E0 + self.moduli[glassy].sum(),
            self.moduli[active],
            self.relaxation_times[active],
            self.nu,
            fit_report=self.fit_report,
            warnings=self.warnings,
        )

    def __eq__(self, other):
        if not isinstance(other, Material):
            return NotImplemented
        return (
            self.E0 == other.E0
            and self.nu == other.nu
            and np.array_equal(self.moduli, other.moduli)
            and np.array_equal(self.relaxation_times, other.relaxation_times)
        )

    __hash__ = None
