"""Plausibility from physics: numbers no solid, surface or temperature can have, most often a unit
mistake (MPa typed as Pa, micrometres as metres, degrees Celsius as kelvin). One place, used by
the API (materials, surfaces, temperatures, :func:`bem.solve`) and so by the CLI, which calls it.

Units SI: moduli in Pa, lengths in m, temperatures in K.

- **Moduli** (:func:`check_moduli`): every solid's Young's modulus lies between
  :data:`MIN_MODULUS` (the softest gels, about 1 kPa) and :data:`MAX_MODULUS` (diamond is
  1.2e12 Pa), and no material's glassy modulus is more than :data:`MAX_RATIO` times its relaxed
  one (rubbers span 1e2 to 1e4). Outside, the message names the unit the value most likely is in.
- **Heights** (:func:`height_checks`): a contact surface's heights span less than its lateral
  size, and its rms slope is of order 0.1 (the half-space theory assumes small slopes; above 1
  it does not hold). Heights that span more than the cell are refused, a slope above 1 is
  warned about; both name micrometres, the usual mistake.
- **Temperatures**: no polymer is a viscoelastic solid above :data:`MAX_KELVIN`, which
  :func:`bem.materials.temperature.check_kelvin` refuses wherever a temperature enters.
  :func:`temperature_warnings` warns where a shift law measured near its reference temperature
  is used more than :data:`FAR_KELVIN` from it, or a fitted material more than :data:`FAR_DATA`
  outside the temperatures of its data.
"""

import numpy as np

from .errors import InputError

__all__ = [
    "MIN_MODULUS",
    "MAX_MODULUS",
    "MAX_RATIO",
    "MAX_KELVIN",
    "FAR_KELVIN",
    "FAR_DATA",
    "MODULUS_UNITS",
    "check_moduli",
    "height_checks",
    "temperature_warnings",
]

MIN_MODULUS = 1e3  # Pa: the softest hydrogels
MAX_MODULUS = 1e12  # Pa: diamond, 1.2e12 Pa, is the stiffest solid
MAX_RATIO = 1e6  # E_inf / E0: rubbers span 1e2 to 1e4, no material 1e6
MAX_KELVIN = 1000.0  # K: polymers have decomposed well below
FAR_KELVIN = 100.0  # K: WLF holds from about T_g to T_g + 100 K; no law is measured over more
FAR_DATA = 20.0  # K: a fitted law's curvature is unknown beyond a couple of sweep spacings (~10 K)
MODULUS_UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9}  # the one table of modulus units


def _likely_unit(value):
    """The modulus unit a value in Pa most likely was typed in: the one that puts it nearest
    1e7 Pa, a rubber's (``MPa`` for 2.4)."""
    if not 0 < value < MIN_MODULUS:
        return "no solid has it"
    larger = [(unit, factor) for unit, factor in MODULUS_UNITS.items() if factor > 1]
    unit, factor = min(larger, key=lambda u: abs(np.log10(value * u[1]) - 7))
    return f"looks like {unit}: multiply by {factor:g}"


def check_moduli(E0, E_inf, *, names=("E0", "E_inf"), hint=""):
    """Refuse a relaxed ``E0`` or glassy ``E_inf`` modulus (Pa) that no solid has, or a ratio
    ``E_inf / E0`` beyond :data:`MAX_RATIO`; ``names`` name the two in the message, ``hint`` is
    added to it (how to set the unit where the values came from)."""
    extra = f", {hint}" if hint else ""
    for name, value in zip(names, (E0, E_inf)):
        if not MIN_MODULUS <= value <= MAX_MODULUS:
            raise InputError(
                f"{name} must be in [{MIN_MODULUS:g}, {MAX_MODULUS:g}] Pa (the moduli of solids), got "
                f"{value:.4g} Pa ({_likely_unit(value)}{extra})"
            )
    if E_inf / E0 > MAX_RATIO:
        raise InputError(
            f"{names[1]} / {names[0]} must be at most {MAX_RATIO:g} (rubbers: 1e2 to 1e4), got {E_inf / E0:.4g} "
            f"({E0:.4g} Pa and {E_inf:.4g} Pa: a modulus in the wrong unit?{extra})"
        )


UNIT_ADVICE = "Heights in micrometres given as metres? Give unit='um' (scene: unit = \"um\") or multiply by 1e-6"


def height_checks(heights, side, *, name="heights", advice=UNIT_ADVICE):
    """Warnings (sentences) about heights (m) on a cell of lateral size ``side`` (m); an
    InputError when they span more than the cell, ending with ``advice`` (which unit to fix)."""
    h = np.asarray(heights, dtype=float)
    span = float(h.max() - h.min())
    if span > side:
        raise InputError(
            f"{name} span {span:.4g} m on a cell of {side:.4g} m: taller than wide, which no contact surface is. "
            + advice
        )
    spacing = side / h.shape[0]
    grads = [np.gradient(h, spacing)] if h.ndim == 1 else np.gradient(h, spacing, spacing)
    slope = float(np.sqrt(np.mean(sum(g**2 for g in grads))))
    if slope > 1:
        return [
            f"{name} have an rms slope of {slope:.3g}: the half-space theory assumes small slopes (real surfaces "
            "have about 0.1 over their measured scales). Heights in micrometres given as metres? Give unit='um'"
        ]
    return []


def temperature_warnings(T, *, reference=None, data=None):
    """Sentences where temperature ``T`` (K) is outside the temperatures of the ``data`` (K) a
    material was fitted to or, without data (an imposed law), far from the law's ``reference``
    temperature. ``T`` has passed :func:`bem.materials.temperature.check_kelvin`."""
    if data is not None and len(data):
        low, high = float(np.min(data)), float(np.max(data))
        if T < low - FAR_DATA or T > high + FAR_DATA:
            return [
                f"{T:g} K is outside the temperatures the material was fitted to ({low:g} to {high:g} K) by more "
                f"than {FAR_DATA:g} K: its shift there is extrapolated; measure nearer it"
            ]
        return []
    out = []
    if reference is not None and abs(T - reference) > FAR_KELVIN:
        out.append(
            f"{T:g} K is {abs(T - reference):.4g} K from the shift law's reference temperature {reference:g} K: "
            f"no shift law holds over more than about {FAR_KELVIN:g} K (WLF: from T_g to T_g + 100 K); "
            "its shift there is not to be trusted"
        )
    return out
