"""Temperature in scenes: DMA tables with units, shift laws, and friction against speed and T.

Scene keys (temperatures are in kelvin wherever a scene gives one)::

    [material]
    dma = "sweeps.csv"            # columns: frequency, E', E'' [, temperature]
    dma_frequency_unit = "Hz"     # "rad/s" (default) | "Hz"
    dma_modulus_unit = "MPa"      # "Pa" (default) | "kPa" | "MPa" | "GPa"
    dma_temperature_unit = "C"    # "K" (default) | "C" (degrees Celsius)
    shift = { law = "wlf", C1 = 8.86, C2 = 101.6, reference_temperature = 296.15 }
         # or { law = "arrhenius", activation_energy = 1.5e5, reference_temperature = 296.15 } (J/mol, K)
         # with a 4-column DMA table: { law = "wlf" | "arrhenius", reference_temperature = ... }
         # and the law's parameters are fitted to the sweeps (bem.Material.fit_master_curve)
    [loading]
    temperatures = [273.15, 296.15, 323.15]   # K; needs a shift law

The material of the scene is the one at the law's reference temperature. With
``temperatures``, the speed sweep runs once per temperature on
``material.at_temperature(T, law)``, each in its own folder ``T_<value>K`` (resumable like any
sweep), and the study's ``results.json`` gains ``temperature_sweep``: friction and contact
fraction per temperature and speed. Plots: ``friction_speed_temperature.png`` (a heat map of
the friction coefficient over log10 speed and T) and ``friction_curves_temperatures.png``
(one curve per temperature); ``master_curve.png`` when the material was fitted to sweeps at
several temperatures (raw data, data shifted by the fitted law, and the fit).
"""

from pathlib import Path

import numpy as np

from bem import Material
from bem.errors import InputError
from bem.materials.master_curve import MasterCurveReport
from bem.materials.temperature import WLF, Arrhenius

FREQUENCY_UNITS = {"rad/s": 1.0, "Hz": 2 * np.pi}
MODULUS_UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9}
TEMPERATURE_OFFSETS = {"K": 0.0, "C": 273.15}
SHIFT_KEYS = {
    "wlf": {"law", "C1", "C2", "reference_temperature"},
    "arrhenius": {"law", "activation_energy", "reference_temperature"},
}


def _unit(t, key, table, default):
    unit = t.get(key, default)
    if unit not in table:
        raise InputError(f"[material] {key} must be one of {', '.join(map(repr, table))}, got {unit!r}")
    return table[unit]


def read_dma(t, base):
    """The DMA table of ``[material] dma`` in SI: ``w`` (rad/s), ``e1``, ``e2`` (Pa), ``T`` (K or None)."""
    if not isinstance(t["dma"], str):
        raise InputError(f"[material] dma must be a file path (string), got {t['dma']!r}")
    path = (Path(base) / t["dma"]).resolve()
    try:
        data = np.loadtxt(path, delimiter="," if path.suffix == ".csv" else None, comments="#", ndmin=2)
    except (OSError, ValueError) as err:
        raise InputError(f"[material] dma: cannot read {str(path)!r}: {err}") from None
    if data.shape[1] not in (3, 4):
        raise InputError(
            f"[material] dma: {str(path)!r} needs 3 columns (frequency, storage, loss) or 4 "
            f"(frequency, storage, loss, temperature), got {data.shape[1]}"
        )
    w = data[:, 0] * _unit(t, "dma_frequency_unit", FREQUENCY_UNITS, "rad/s")
    scale = _unit(t, "dma_modulus_unit", MODULUS_UNITS, "Pa")
    offset = _unit(t, "dma_temperature_unit", TEMPERATURE_OFFSETS, "K")
    temps = data[:, 3] + offset if data.shape[1] == 4 else None
    return {"w": w, "e1": data[:, 1] * scale, "e2": data[:, 2] * scale, "T": temps, "path": str(path)}


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
    return table


def dma_material(t, base, nu):
    """The material of a DMA table: a Prony fit (3 columns) or a master curve (4 columns)."""
    data = read_dma(t, base)
    per = t.get("dma_terms_per_decade", 3.0)
    if data["T"] is None:
        return Material.fit_prony(data["w"], data["e1"], data["e2"], terms_per_decade=per, nu=nu)
    table = _shift_table(t)
    if table is None or set(table) - {"law", "reference_temperature"}:
        raise InputError(
            "[material] a DMA table with a temperature column needs shift = { law = 'wlf' | "
            "'arrhenius', reference_temperature = <K> } (the law's parameters are fitted to "
            "the sweeps), got " + repr(table)
        )
    material, _ = Material.fit_master_curve(
        data["w"],
        data["T"],
        data["e1"],
        data["e2"],
        reference_temperature=table["reference_temperature"],
        shift=table["law"],
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
    args = {k: v for k, v in table.items() if k != "law"}
    for key, value in args.items():
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise InputError(f"[material] shift: {key} must be a number, got {value!r}")
    return WLF(**args) if table["law"] == "wlf" else Arrhenius(**args)


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
    if law is None:
        raise InputError(
            "[loading] temperatures need a shift law: [material] shift = { law = 'wlf', C1, C2, "
            "reference_temperature } or a DMA table with a temperature column"
        )
    for v in values:
        law(float(v))  # a WLF law names temperatures at or below T_ref - C2
    return tuple(float(v) for v in values)


def scene_fields(raw, material):
    """``{"shift": law or None, "temperatures": tuple}`` for the Scene, from the raw tables."""
    law = shift_law(raw["material"], material)
    return {"shift": law, "temperatures": loading_temperatures(raw["loading"], law)}
