"""What DMA data cover, and the warnings when a fitted material is used outside it.

A material fitted to data is measured only over the data's (reduced) angular-frequency band
``[w_lo, w_hi]``; outside it the fit extrapolates. How far that extrapolation can be trusted
depends on whether the data reach the plateaus:

- at the low end, the relaxed (rubbery) plateau is reached when ``E'`` has stopped falling:
  the log-slope ``n = d ln E' / d ln w`` of the fit at ``w_lo`` is small. The fit matches
  both ``E'`` and ``E''`` there, and its ``E'`` and ``E''`` are tied by the Kramers-Kronig
  relations of a Prony series, so the slope is the data's, not the extrapolation's: a fit
  whose relaxed modulus ``E0`` sits far from the truth still shows the steep ``E'`` the data
  end on;
- at the high end, the glassy plateau is reached when ``n`` is small at ``w_hi``.

A plateau counts as reached for ``n <= PLATEAU_SLOPE = 0.05`` (``E'`` changing by less than
12 % per decade). Beyond a plateau that was not reached, ``E0`` (or ``E_inf``) is the fit's
guess, not a measurement, and friction at speeds that load the material there rests on it.
"""

from __future__ import annotations

import numpy as np

__all__ = ["PLATEAU_SLOPE", "end_slopes", "band_warnings", "per_decade"]

PLATEAU_SLOPE = 0.05  # log-slope of E' below which a plateau counts as reached (12 % per decade)


def end_slopes(w, E0, moduli, times):
    """``(n_lo, n_hi)``: the log-slope ``d ln E' / d ln w`` of the series ``(E0, moduli, times)``
    (Pa, s) at the lowest and highest of the frequencies ``w`` (rad/s)."""
    u = np.array([w.min(), w.max()])[:, None] * np.asarray(times)[None, :]
    storage = E0 + (u**2 / (1 + u**2)) @ moduli
    slope = ((2 * u**2 / (1 + u**2) ** 2) @ moduli) / storage
    return float(slope[0]), float(slope[1])


def per_decade(slope):
    """``E'`` change per decade of frequency (a fraction) for a log-slope ``slope``."""
    return 10.0**slope - 1.0


def _side(report, low):
    lo, hi = report.frequency_band
    if low:
        slope, name, modulus, value = report.end_slopes[0], "relaxed (rubbery)", "E0", report.relaxed_modulus
        edge, other = lo, "higher temperatures or lower frequencies"
    else:
        slope, name, modulus, value = report.end_slopes[1], "glassy", "E_inf", report.glassy_modulus
        edge, other = hi, "lower temperatures or higher frequencies"
    if slope <= PLATEAU_SLOPE:
        state = (
            f"the data reach the {name} plateau there (E' changes by {100 * per_decade(slope):.2g} % per decade at "
            f"the band's end), so E' stays near {modulus} = {value:.4g} Pa, but the loss modulus there is the fit's guess"
        )
    else:
        state = (
            f"the data do not reach the {name} plateau (E' still changes by {100 * per_decade(slope):.2g} % per decade "
            f"at the band's end), so {modulus} = {value:.4g} Pa is not measured and the friction there rests on the "
            "fit's guess"
        )
    return edge, state, other


def band_warnings(report, w_low, w_high):
    """Plain sentences (a tuple) for the parts of ``[w_low, w_high]`` (rad/s) outside the band
    of ``report`` (a :class:`bem.materials.prony_fit.FitReport`), and for the holes in it that
    ``[w_low, w_high]`` reaches (a master curve's ``band_gaps``); empty when the data cover
    ``[w_low, w_high]``."""
    lo, hi = report.frequency_band
    out = []
    for a, b, t1, t2 in getattr(report, "band_gaps", ()):
        if a < w_high and b > w_low:
            out.append(
                f"the material is interpolated: the DMA data leave a gap from {a:.3g} to {b:.3g} rad/s "
                f"({np.log10(b / a):.2g} decades, between the sweeps at {t1:g} K and {t2:g} K once shifted) "
                "inside the frequencies the sliding excites; measure at temperatures between those sweeps"
            )
    for low, beyond, w in ((True, w_low < lo * (1 - 1e-9), w_low), (False, w_high > hi * (1 + 1e-9), w_high)):
        if not beyond:
            continue
        edge, state, other = _side(report, low)
        where = "down to" if low else "up to"
        decades = abs(np.log10(w / edge)) if w > 0 else np.inf
        out.append(
            f"the material is extrapolated: the sliding excites frequencies {where} {w:.3g} rad/s, "
            f"{decades:.2g} decades beyond the DMA data's band ({lo:.3g} to {hi:.3g} rad/s at this "
            f"temperature); {state}. Measure at {other}, or keep the speeds inside the band"
        )
    return tuple(out)
