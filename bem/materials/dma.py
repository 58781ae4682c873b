"""DMA tables: a text file of measured points read into SI units, with the units named by its
header or by the caller.

Units SI on return: angular frequency in rad/s, moduli in Pa, temperature in K.

A table is a text file (``.csv``: commas; otherwise commas, semicolons, tabs or spaces) of one
measured point per row, with ``#`` comments. Its columns are frequency, storage modulus ``E'``,
loss modulus ``E''`` and, for sweeps at several temperatures, temperature:

- **without a header**, in that order;
- **with header rows** (every leading row that is not all numbers), by name, in any order and
  beside other columns: the first header row names the columns (``frequency``, ``f``,
  ``omega``; ``storage``, ``E'``, ``E_stor``, ``storage modulus``; ``loss``, ``E''``,
  ``E_loss``, ``loss modulus``; ``temperature``, ``T``, ``temp``; case, spaces and
  underscores aside), or ``columns = {"frequency": ..., "storage": ..., "loss": ...,
  "temperature": ...}`` names them (a header name, or a 1-based column number).

**Units.** A unit written in a header (``f (Hz)``, ``E' [MPa]``, ``T_C``, ``temperature (°C)``,
or a row of units) is used unless the caller gives one (``frequency_unit``, ``modulus_unit``,
``temperature_unit``; in a scene ``dma_frequency_unit``, ...), which must then agree. A unit
named by neither is **assumed** (rad/s, Pa, K) **and warned about**, naming the assumption and
how to set it: a factor of 2 pi in frequency cannot be told from the data. Moduli are then
checked against what solids have (:mod:`bem.plausibility`): a table in MPa read as Pa is refused,
naming the unit. A temperature column in kelvin below 100 K is taken for degrees Celsius and
refused with a message that says to set ``temperature_unit = "C"``.
"""

import re
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..plausibility import MODULUS_UNITS, check_moduli
from .temperature import MIN_KELVIN

__all__ = ["DMATable", "FREQUENCY_UNITS", "MODULUS_UNITS", "TEMPERATURE_OFFSETS", "QUANTITIES", "read_dma"]

FREQUENCY_UNITS = {"rad/s": 1.0, "Hz": 2 * np.pi}
TEMPERATURE_OFFSETS = {"K": 0.0, "C": 273.15}
QUANTITIES = ("frequency", "storage", "loss", "temperature")
ASSUMED = {"frequency": "rad/s", "storage": "Pa", "temperature": "K"}
ARGUMENTS = {"frequency": "frequency_unit", "storage": "modulus_unit", "temperature": "temperature_unit"}
TABLES = {"frequency": FREQUENCY_UNITS, "storage": MODULUS_UNITS, "temperature": TEMPERATURE_OFFSETS}
ALIASES = {
    "frequency": {"frequency", "freq", "f", "fset", "omega", "w", "angularfrequency", "frequencyhz"},
    "storage": {"storage", "e'", "e\u2032", "estor", "estorage", "storagemodulus", "e1", "eprime", "ep"},
    "loss": {"loss", "e''", "e\u2033", "e\u2032\u2032", "eloss", "lossmodulus", "e2", "edoubleprime", "epp"},
    "temperature": {"temperature", "temp", "t"},
}
# unit spellings in headers -> the unit names above
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
    "\u00b0c": "C",
    "degc": "C",
    "celsius": "C",
    "kelvin": "K",
}


@dataclass(frozen=True, eq=False)
class DMATable:
    """A DMA table in SI units.

    Attributes
    ----------
    frequencies : ndarray
        Angular frequencies (rad/s), as measured (not reduced).
    storage, loss : ndarray
        ``E'`` and ``E''`` (Pa).
    temperatures : ndarray or None
        Temperature of each point (K), None for a table without a temperature column.
    units : dict
        The units the file was read in: ``frequency``, ``modulus``, ``temperature``.
    path : str
        The file.
    warnings : tuple of str
        Units assumed because neither the header nor the caller named them.
    """

    frequencies: np.ndarray
    storage: np.ndarray
    loss: np.ndarray
    temperatures: object
    units: dict
    path: str
    warnings: tuple = ()


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


def _columns(given, names):
    """Column index of each quantity present, from ``columns`` or the header names."""
    if given is not None:
        if not isinstance(given, dict) or set(given) - set(QUANTITIES):
            raise InputError(f"columns must be a mapping with keys among {', '.join(QUANTITIES)}, got {given!r}")
        found = {}
        for q, ref in given.items():
            if isinstance(ref, int) and not isinstance(ref, bool) and 1 <= ref <= len(names):
                found[q] = ref - 1
            elif isinstance(ref, str) and ref in names:
                found[q] = names.index(ref)
            else:
                raise InputError(
                    f"columns.{q} must be a header name ({', '.join(map(repr, names))}) or a "
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
        raise InputError(f"path {str(path)!r} could not be read as a DMA table: {err}") from None
    lines = [ln.split("#", 1)[0].strip() for ln in text.splitlines()]
    lines = [ln for ln in lines if ln]
    delimiter = _delimiter(lines, csv)
    rows = [_split(ln, delimiter) for ln in lines]
    header = []
    while rows and not _numeric(rows[0]):
        header.append(rows.pop(0))
    if not rows:
        raise InputError(f"path {str(path)!r} holds no rows of numbers")
    width = len(rows[0])
    for i, row in enumerate(rows):
        if len(row) != width or not _numeric(row):
            raise InputError(
                f"path {str(path)!r}: data row {i + 1} ({', '.join(row)!s}) is not {width} numbers like the first"
            )
    return header, np.array([[float(c) for c in row] for row in rows])


def _unit(q, given, header_unit, path):
    """The unit of quantity ``q``: the caller's (which must agree with the header's), the header's,
    or None (assumed by the caller of this function)."""
    name, table = ARGUMENTS[q], TABLES[q]
    if given is not None and given not in table:
        raise InputError(f"{name} must be one of {', '.join(map(repr, table))}, got {given!r}")
    if given is not None and header_unit is not None and given != header_unit:
        raise InputError(f"{name} = {given!r} disagrees with the unit {header_unit!r} in the header of {str(path)!r}")
    return given or header_unit


def read_dma(path, *, frequency_unit=None, modulus_unit=None, temperature_unit=None, columns=None):
    """Read a DMA table (module docstring) into SI units.

    Parameters
    ----------
    path : str or os.PathLike
        The text file.
    frequency_unit : {"rad/s", "Hz"}, optional
        Unit of the frequency column, when the header does not name it (else it must agree).
    modulus_unit : {"Pa", "kPa", "MPa", "GPa"}, optional
        Unit of ``E'`` and ``E''``, likewise.
    temperature_unit : {"K", "C"}, optional
        Unit of the temperature column, likewise.
    columns : dict, optional
        ``{"frequency": ..., "storage": ..., "loss": ..., "temperature": ...}``: a header name or a
        1-based column number each, for headers that name them otherwise.

    Returns
    -------
    DMATable
        For :meth:`bem.Material.fit_prony` (``frequencies, storage, loss``) or, with
        temperatures, :meth:`bem.Material.fit_master_curve`. A unit assumed because nothing named
        it is in ``warnings`` and issued as a ``UserWarning``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "sweep.csv"
    >>> _ = path.write_text("f (Hz), E' (MPa), E'' (MPa)\\n1, 2.0, 0.5\\n10, 3.0, 1.0\\n")
    >>> table = read_dma(path)
    >>> table.frequencies.round(4).tolist(), table.storage.tolist()
    ([6.2832, 62.8319], [2000000.0, 3000000.0])
    """
    path = Path(path)
    header, data = _read_rows(path, path.suffix.lower() == ".csv")
    if header:
        names = header[0]
        found = _columns(columns, names)
        missing = [q for q in QUANTITIES[:3] if q not in found]
        if missing:
            raise InputError(
                f"path {str(path)!r}: no column named for {', '.join(missing)} among "
                f"{', '.join(map(repr, names))}; name them frequency, storage, loss [, temperature] (or E', E'') "
                "or give columns = {frequency = ..., storage = ..., loss = ..., temperature = ...}"
            )
        from_header = _header_units(header, found)
    else:
        if data.shape[1] not in (3, 4):
            raise InputError(
                f"path {str(path)!r} needs 3 columns (frequency, storage, loss) or 4 "
                f"(frequency, storage, loss, temperature), or a header row naming them; got {data.shape[1]}"
            )
        found, from_header = dict(zip(QUANTITIES, range(data.shape[1]))), {}
    if "storage" in from_header and "loss" in from_header and from_header["storage"] != from_header["loss"]:
        raise InputError(f"path {str(path)!r} gives E' and E'' in different units; use one")
    given = {"frequency": frequency_unit, "storage": modulus_unit, "temperature": temperature_unit}
    units, assumed = {}, []
    for q in ("frequency", "storage", "temperature"):
        header_unit = from_header.get(q) if q != "storage" else from_header.get("storage", from_header.get("loss"))
        units[q] = _unit(q, given[q], header_unit, path)
        if units[q] is None:
            units[q] = ASSUMED[q]
            if q != "temperature" or "temperature" in found:
                assumed.append(q)
    notes = ()
    if assumed:
        said = ", ".join(f"{q} in {ASSUMED[q]}" for q in assumed)
        keys = ", ".join(f"{ARGUMENTS[q]} (scene: dma_{ARGUMENTS[q]})" for q in assumed)
        notes = (
            f"the DMA table {str(path)!r} names no unit for {', '.join(assumed)}: read as {said}. If it is "
            f'in other units (Hz, MPa, C), set {keys} or write the unit in the header, e.g. "f (Hz)"',
        )
        for text in notes:
            warnings.warn(text, UserWarning, stacklevel=2)
    w = data[:, found["frequency"]] * FREQUENCY_UNITS[units["frequency"]]
    scale = MODULUS_UNITS[units["storage"]]
    e1, e2 = data[:, found["storage"]] * scale, data[:, found["loss"]] * scale
    if np.all(e1 > 0):
        check_moduli(
            float(e1.min()),
            float(e1.max()),
            names=("the smallest storage modulus", "the largest storage modulus"),
            hint=f"or set modulus_unit (scene: dma_modulus_unit); the table was read in {units['storage']}",
        )
    temps = None
    if "temperature" in found:
        temps = data[:, found["temperature"]] + TEMPERATURE_OFFSETS[units["temperature"]]
        if np.any(temps < MIN_KELVIN):
            raise InputError(
                f"the temperature column of {str(path)!r} goes down to {temps.min():g} K, below "
                f'{MIN_KELVIN:g} K: that looks like degrees Celsius; set temperature_unit = "C" (or write the '
                "unit in the header)"
            )
    units = {"frequency": units["frequency"], "modulus": units["storage"], "temperature": units["temperature"]}
    return DMATable(w, e1, e2, temps, units, str(path), notes)
