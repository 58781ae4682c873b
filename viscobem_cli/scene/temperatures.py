"""Temperature in scenes: DMA tables, shift laws, friction against speed and T, and what the
material's data cover.

Scene keys (temperatures are in kelvin wherever a scene gives one; a value below 100 K is
rejected as looking like degrees Celsius)::

    [material]
    dma = "sweeps.csv"            # frequency, E', E'' [, temperature]: by position, or named in a
                                  # header row (viscobem_cli.scene.dma)
    dma_frequency_unit = "Hz"     # "rad/s" (default) | "Hz"   (or written in the header)
    dma_modulus_unit = "MPa"      # "Pa" (default) | "kPa" | "MPa" | "GPa"
    dma_temperature_unit = "C"    # "K" (default) | "C" (degrees Celsius)
    dma_columns = { frequency = "f (Hz)", storage = "E'", loss = "E''", temperature = "T" }  # optional
    shift = { law = "wlf", C1 = 8.86, C2 = 101.6, reference_temperature = 296.15 }
         # or { law = "arrhenius", activation_energy = 1.5e5, reference_temperature = 296.15 } (J/mol, K)
         # with a temperature column: the full law is imposed (only the Prony series is fitted), or
         # { law = "wlf" | "arrhenius", reference_temperature = ... } fits the law's parameters
         # jointly with the series (bem.Material.fit_master_curve)
    [loading]
    temperatures = [273.15, 296.15, 323.15]   # K; needs a shift law
    superposition = true          # one curve over the reduced speeds v a_T stands for every temperature

The material of the scene is the one at the law's reference temperature. With
``temperatures``, the speed sweep runs once per temperature on
``material.at_temperature(T, law)`` (:func:`scene_at`: the speeds stay, and ``xi`` and its
time are those of the material at ``T``), each in its own folder ``T_<value>K`` (resumable
like any sweep), and the study's ``results.json`` gains ``temperature_sweep``: friction and
contact fraction per temperature and speed. With ``superposition = true`` the study is instead one
curve on the reference material over the reduced speeds ``v a_T`` that every temperature needs
(:func:`bem.friction_map`: exact for a material moved by a shift law, interpolated between the
curve's nodes within an estimated 0.5 %), written as the same ``temperature_sweep`` with the
reduced speeds and each point's interpolation estimate, and a Grosch plot
(``friction_master_curve.png``: friction against speed at each temperature, and against the
reduced speed, where every temperature falls on the one curve). Plots: ``friction_speed_temperature.png`` (a heat
map of the friction coefficient over log10 speed and T) and ``friction_curves_temperatures.png``
(one curve per temperature); ``master_curve.png`` when the material was fitted to sweeps at
several temperatures (raw data, data shifted by the law, and the fit).

**Coverage.** A material fitted to DMA data is measured only over the data's band of (reduced)
frequencies. :func:`excited_band` is the band of frequencies the scene's sliding loads the
material at, ``[2 pi v_min / L, q_max v_max]`` (``L`` the cell or domain side, ``q_max`` the
surface's largest wavenumber along the sliding direction: its roughness cutoff for a
generated rough surface, the grid's Nyquist wavenumber otherwise), and
:func:`material_warnings` adds to the scene's warnings what
:meth:`bem.Material.extrapolation_warnings` says about it, at every temperature of the scene.
"""

import dataclasses
import math

import numpy as np

from bem import Material
from bem.errors import InputError
from bem.materials.master_curve import MasterCurveReport
from bem.materials.temperature import WLF, Arrhenius, check_kelvin

from . import values as scene_values
from .dma import read_dma

__all__ = [
    "read_dma",
    "dma_material",
    "shift_law",
    "loading_temperatures",
    "scene_fields",
    "scene_at",
    "excited_band",
    "material_warnings",
    "with_material_warnings",
]

SHIFT_KEYS = {
    "wlf": {"law", "C1", "C2", "reference_temperature"},
    "arrhenius": {"law", "activation_energy", "reference_temperature"},
}


def _shift_table(t):
    table = t.get("shift")
    if table is None:
        return None
    if not isinstance(table, dict) or table.get("law") not in SHIFT_KEYS:
        raise InputError(f"[material] shift must be a table with law = 'wlf' or 'arrhenius', got {table!r}")
    unknown = sorted(set(table) - SHIFT_KEYS[table["law"]])
    if unknown:
        raise InputError(
            f"[material] shift: unknown key(s) {', '.join(map(repr, unknown))} for law = "
            f"{table['law']!r}; valid keys: {', '.join(sorted(SHIFT_KEYS[table['law']]))}"
        )
    if "reference_temperature" not in table:
        raise InputError("[material] shift: reference_temperature (K) is required")
    for key, value in table.items():
        if key != "law" and (isinstance(value, bool) or not isinstance(value, (int, float))):
            raise InputError(f"[material] shift: {key} must be a number, got {value!r}")
    check_kelvin("[material] shift: reference_temperature (K)", table["reference_temperature"])
    return table


def _law_of(table):
    """The law a complete shift table gives."""
    args = {k: v for k, v in table.items() if k != "law"}
    return WLF(**args) if table["law"] == "wlf" else Arrhenius(**args)


def dma_material(t, base, nu):
    """The material of a DMA table: a Prony fit (no temperature column) or a master curve,
    with the scene's shift law imposed (all its constants given) or fitted (only ``law`` and
    ``reference_temperature``)."""
    data = read_dma(t, base)
    per = t.get("dma_terms_per_decade", 3.0)
    if data["T"] is None:
        return Material.fit_prony(data["w"], data["e1"], data["e2"], terms_per_decade=per, nu=nu)
    table = _shift_table(t)
    given = None if table is None else set(table) - {"law", "reference_temperature"}
    if table is None or (given and given != SHIFT_KEYS[table["law"]] - {"law", "reference_temperature"}):
        raise InputError(
            "[material] a DMA table with a temperature column needs shift = { law = 'wlf' | 'arrhenius', "
            "reference_temperature = <K> } (the law's parameters are fitted to the sweeps) or the full law "
            "({ law = 'wlf', C1, C2, reference_temperature } or { law = 'arrhenius', activation_energy, "
            f"reference_temperature }}, imposed), got {table!r}"
        )
    material, _ = Material.fit_master_curve(
        data["w"],
        data["T"],
        data["e1"],
        data["e2"],
        reference_temperature=table["reference_temperature"],
        shift=_law_of(table) if given else table["law"],
        terms_per_decade=per,
        nu=nu,
    )
    return material


def shift_law(t, material):
    """The scene's shift law: given in ``[material] shift``, or fitted with the master curve."""
    if isinstance(material.fit_report, MasterCurveReport):
        return material.fit_report.law
    table = _shift_table(t)
    if table is None:
        return None
    missing = sorted(SHIFT_KEYS[table["law"]] - set(table))
    if missing:
        raise InputError(
            f"[material] shift: {', '.join(missing)} required for law = {table['law']!r} "
            "(or give a DMA table with a temperature column to fit them)"
        )
    return _law_of(table)


def loading_temperatures(t, law):
    """``[loading] temperatures`` (K) as a tuple; empty when not given."""
    if "temperatures" not in t:
        return ()
    values = t["temperatures"]
    if not (
        isinstance(values, list)
        and values
        and all(isinstance(v, (int, float)) and not isinstance(v, bool) and 0 < v < np.inf for v in values)
    ):
        raise InputError(
            f"[loading] temperatures must be a non-empty list of absolute temperatures > 0 K, got {values!r}"
        )
    check_kelvin("[loading] temperatures", values)
    if law is None:
        raise InputError(
            "[loading] temperatures need a shift law: [material] shift = { law = 'wlf', C1, C2, "
            "reference_temperature } or a DMA table with a temperature column"
        )
    for v in values:
        law(float(v))  # a WLF law names temperatures at or below T_ref - C2
    return tuple(float(v) for v in values)


def scene_fields(raw, material):
    """``{"shift": law or None, "temperatures": tuple, "superposition": bool}`` for the Scene, from the
    raw tables."""
    law = shift_law(raw["material"], material)
    temps = loading_temperatures(raw["loading"], law)
    superposed = raw["loading"].get("superposition", False)
    if not isinstance(superposed, bool):
        raise InputError(f"[loading] superposition must be true or false, got {superposed!r}")
    if superposed and not temps:
        raise InputError("[loading] superposition = true needs [loading] temperatures (K) to map")
    for T in temps:  # a shift beyond what floating point holds is named here, not in the run
        try:
            material.at_temperature(T, law)
        except InputError as err:
            raise InputError(f"[loading] temperatures: {err}") from None
    return {"shift": law, "temperatures": temps, "superposition": superposed}


def scene_at(scene, T):
    """The single-temperature study of ``scene`` at ``T`` (K): the material moved by the shift
    law, the same speeds, and ``xi`` with the time of that material (its longest creep time at
    ``T``, unless the scene gives ``xi_time``), so that ``xi`` and the listed creep times agree."""
    material = scene.material.at_temperature(T, scene.shift)
    tau, source = scene_values.xi_time(scene.raw.get("loading", {}), material)
    if "xi_time" not in scene.raw.get("loading", {}):
        source = f"{source}; at {T:g} K"
    return dataclasses.replace(
        scene,
        material=material,
        temperatures=(),
        xi_time=tau,
        xi_time_source=source,
        xi=scene.speeds * tau / scene.xi_length,
    )


def excited_band(scene):
    """``(w_low, w_high)`` (rad/s): the frequencies the scene's moving speeds load the material
    at (see the module docstring), or None when nothing moves."""
    moving = np.asarray(scene.speeds)[np.asarray(scene.speeds) > 0]
    if moving.size == 0:
        return None
    s = scene.surface
    q_low = 2 * np.pi / s.length
    nyquist = np.pi * s.n / s.length * max(abs(math.cos(d)) + abs(math.sin(d)) for d in scene.directions)
    spectrum = s.metadata.get("spectrum", {})
    q_high = nyquist
    if spectrum.get("cutoff_wavevector"):
        aniso = float(spectrum.get("anisotropy", 1.0))
        q_high = min(nyquist, float(spectrum["cutoff_wavevector"]) * max(aniso, 1.0 / aniso))
    return float(q_low * moving.min()), float(q_high * moving.max())


def material_warnings(scene):
    """What the material's data do not cover of the frequencies the scene excites, and a shift
    law used outside its range, as plain sentences (one list for the study: prefixed by the
    temperature when the scene has several)."""
    band = excited_band(scene)
    if not scene.temperatures:
        material = scene.material
        if band is None:
            return list(material.warnings)
        return list(material.extrapolation_warnings(*band))
    out = []
    for T in scene.temperatures:
        material = scene.material.at_temperature(T, scene.shift)
        found = material.extrapolation_warnings(*band) if band is not None else material.warnings
        out += [f"at {T:g} K: {text}" for text in found]
    return out


def with_material_warnings(scene):
    """``scene`` with :func:`material_warnings` added to its warnings."""
    return dataclasses.replace(scene, warnings=tuple(scene.warnings) + tuple(material_warnings(scene)))
