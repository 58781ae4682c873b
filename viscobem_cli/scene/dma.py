"""DMA tables in scenes: columns found by position or by name, units from the scene or the header.

A table is a text file (``.csv``: commas; otherwise commas, semicolons, tabs or spaces) of
one measured point per row, with ``#`` comments. Its columns are frequency, storage modulus
``E'``, loss modulus ``E''`` and, for sweeps at several temperatures, temperature:

- **without a header**, in that order;
- **with header rows** (every leading row that is not all numbers), by name, in any order and
  beside other columns: the first header row names the columns (``frequency``, ``f``,
  ``omega``; ``storage``, ``E'``, ``E_stor``, ``storage modulus``; ``loss``, ``E''``,
  ``E_loss``, ``loss modulus``; ``temperature``, ``T``, ``temp``; case, spaces and
  underscores aside), or ``[material] dma_columns = {frequency = "...", storage = "...",
  loss = "...", temperature = "..."}`` names them (a header name, or a 1-based column
  number);
- a unit written in a header (``f (Hz)``, ``E' [MPa]``, ``T_C``, ``temperature (°C)``, or a
  row of units) is used unless the scene's ``dma_*_unit`` key gives one, which must then
  agree. Without either: rad/s, Pa and K.

A temperature column in kelvin below 100 K is taken for degrees Celsius and rejected with a
message that says to set ``dma_temperature_unit = "C"``.
"""

import re
from pathlib import Path

import numpy as np

from bem.errors import InputError
from bem.materials.temperature import MIN_KELVIN

__all__ = ["read_dma", "FREQUENCY_UNITS", "MODULUS_UNITS", "TEMPERATURE_OFFSETS", "QUANTITIES"]

FREQUENCY_UNITS = {"rad/s": 1.0, "Hz": 2 * np.pi}
MODULUS_UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9}
TEMPERATURE_OFFSETS = {"K": 0.0, "C": 273.15}
QUANTITIES = ("frequency", "storage", "loss", "temperature")
UNIT_KEYS = {"frequency": "dma_frequency_unit", "storage": "dma_modulus_unit", "temperature": "dma_temperature_unit"}
TABLES = {"frequency": FREQUENCY_UNITS, "storage": MODULUS_UNITS, "temperature": TEMPERATURE_OFFSETS}
ALIASES = {
    "frequency": {"frequency", "freq", "f", "fset", "omega", "w", "angularfrequency", "frequencyhz"},
    "storage": {"storage", "e'", "e′", "estor", "estorage", "storagemodulus", "e1", "eprime", "ep"},
    "loss": {"loss", "e''", "e″", "e′′", "eloss", "lossmodulus", "e2", "edoubleprime", "epp"},
    "temperature": {"temperature", "temp", "t"},
}
# unit spellings in headers -> the scene's unit names
HEADER_UNITS = {
    "hz": "Hz",
    "rad/s": "rad/s",
    "rads": "rad/s",
    "rad/sec": "rad/s",
    "pa": "Pa",
    "kpa": "kPa",
    "mpa": "MPa",
    "gpa": "GPa",
    "k": "K",
    "c": "C",
    "°c": "C",
    "degc": "C",
    "celsius": "C",
    "kelvin": "K",
}


def _unit(t, key, table, default):
    unit = t.get(key, default)
    if unit not in table:
        raise InputError(f"[material] {key} must be one of {', '.join(map(repr, table))}, got {unit!r}")
    return unit


def _split(line, delimiter):
    return [c.strip().strip('"').strip() for c in (line.split(delimiter) if delimiter else line.split())]


def _delimiter(lines, csv):
    if csv:
        return ","
    sample = lines[0] if lines else ""
    return next((d for d in (",", ";", "\t") if d in sample), None)


def _numeric(cells):
    try:
        [float(c) for c in cells]
    except ValueError:
        return False
    return bool(cells)


def _name_and_unit(text):
    """``("storage", "MPa")`` from ``"E' (MPa)"``; the unit is None when there is none."""
    raw = text.strip().lower()
    unit = None
    bracket = re.search(r"[\(\[]\s*([^\)\]]+?)\s*[\)\]]", raw)
    if bracket:
        unit = HEADER_UNITS.get(bracket.group(1).replace(" ", ""))
        raw = (raw[: bracket.start()] + raw[bracket.end() :]).strip()
    else:
        parts = re.split(r"[_\s]+", raw)
        if len(parts) > 1 and parts[-1] in HEADER_UNITS:
            unit = HEADER_UNITS[parts[-1]]
            raw = " ".join(parts[:-1])
    return re.sub(r"[\s_\-]+", "", raw), unit


def _columns(t, names):
    """Column index of each quantity present, from ``dma_columns`` or the header names."""
    given = t.get("dma_columns")
    if given is not None:
        if not isinstance(given, dict) or set(given) - set(QUANTITIES):
            raise InputError(
                f"[material] dma_columns must be a table with keys among {', '.join(QUANTITIES)}, got {given!r}"
            )
        found = {}
        for q, ref in given.items():
            if isinstance(ref, int) and not isinstance(ref, bool) and 1 <= ref <= len(names):
                found[q] = ref - 1
            elif isinstance(ref, str) and ref in names:
                found[q] = names.index(ref)
            else:
                raise InputError(
                    f"[material] dma_columns.{q} must be a header name ({', '.join(map(repr, names))}) or a "
                    f"column number 1..{len(names)}, got {ref!r}"
                )
        return found
    found = {}
    for k, name in enumerate(names):
        base, _ = _name_and_unit(name)
        for q, aliases in ALIASES.items():
            if base in aliases and q not in found:
                found[q] = k
    return found


def _header_units(header_rows, columns):
    """The unit each quantity's header gives (names row or a units row), or None."""
    units = {}
    for q, k in columns.items():
        for i, row in enumerate(header_rows):
            if k < len(row):
                whole = HEADER_UNITS.get(row[k].strip().lower().replace(" ", "")) if i > 0 else None  # a units row
                unit = _name_and_unit(row[k])[1] or whole
                if unit is not None:
                    units[q] = unit
                    break
    return units


def _read_rows(path, csv):
    try:
        text = path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as err:
        raise InputError(f"[material] dma: cannot read {str(path)!r}: {err}") from None
    lines = [ln.split("#", 1)[0].strip() for ln in text.splitlines()]
    lines = [ln for ln in lines if ln]
    delimiter = _delimiter(lines, csv)
    rows = [_split(ln, delimiter) for ln in lines]
    header = []
    while rows and not _numeric(rows[0]):
        header.append(rows.pop(0))
    if not rows:
        raise InputError(f"[material] dma: {str(path)!r} holds no rows of numbers")
    width = len(rows[0])
    for i, row in enumerate(rows):
        if len(row) != width or not _numeric(row):
            raise InputError(
                f"[material] dma: {str(path)!r}: data row {i + 1} ({', '.join(row)!s}) is not {width} numbers "
                "like the first"
            )
    return header, np.array([[float(c) for c in row] for row in rows])


def read_dma(t, base):
    """The DMA table of ``[material] dma`` in SI: ``w`` (rad/s), ``e1``, ``e2`` (Pa), ``T`` (K or
    None), and the ``path`` and ``units`` read."""
    if not isinstance(t["dma"], str):
        raise InputError(f"[material] dma must be a file path (string), got {t['dma']!r}")
    path = (Path(base) / t["dma"]).resolve()
    header, data = _read_rows(path, path.suffix.lower() == ".csv")
    if header:
        names = header[0]
        columns = _columns(t, names)
        missing = [q for q in QUANTITIES[:3] if q not in columns]
        if missing:
            raise InputError(
                f"[material] dma: {str(path)!r}: no column named for {', '.join(missing)} among "
                f"{', '.join(map(repr, names))}; name them frequency, storage, loss [, temperature] (or E', E'') "
                "or set [material] dma_columns = {frequency = ..., storage = ..., loss = ..., temperature = ...}"
            )
        from_header = _header_units(header, columns)
    else:
        if data.shape[1] not in (3, 4):
            raise InputError(
                f"[material] dma: {str(path)!r} needs 3 columns (frequency, storage, loss) or 4 "
                f"(frequency, storage, loss, temperature), or a header row naming them; got {data.shape[1]}"
            )
        columns, from_header = dict(zip(QUANTITIES, range(data.shape[1]))), {}
    units = {}
    for q in ("frequency", "storage", "temperature"):
        key, table = UNIT_KEYS[q], TABLES[q]
        default = {"frequency": "rad/s", "storage": "Pa", "temperature": "K"}[q]
        header_unit = from_header.get(q) if q != "storage" else from_header.get("storage", from_header.get("loss"))
        if key in t and header_unit is not None and t[key] != header_unit:
            raise InputError(
                f"[material] {key} = {t[key]!r} disagrees with the unit {header_unit!r} in the header of {str(path)!r}"
            )
        units[q] = _unit(t, key, table, header_unit or default)
    if "storage" in from_header and "loss" in from_header and from_header["storage"] != from_header["loss"]:
        raise InputError(f"[material] dma: {str(path)!r} gives E' and E'' in different units; use one")
    w = data[:, columns["frequency"]] * FREQUENCY_UNITS[units["frequency"]]
    scale = MODULUS_UNITS[units["storage"]]
    temps = None
    if "temperature" in columns:
        temps = data[:, columns["temperature"]] + TEMPERATURE_OFFSETS[units["temperature"]]
        if np.any(temps < MIN_KELVIN):
            raise InputError(
                f"[material] dma: the temperature column of {str(path)!r} goes down to {temps.min():g} K, below "
                f'{MIN_KELVIN:g} K: that looks like degrees Celsius; set dma_temperature_unit = "C" (or write the '
                "unit in the header)"
            )
    return {
        "w": w,
        "e1": data[:, columns["storage"]] * scale,
        "e2": data[:, columns["loss"]] * scale,
        "T": temps,
        "path": str(path),
        "units": {"frequency": units["frequency"], "modulus": units["storage"], "temperature": units["temperature"]},
    }
