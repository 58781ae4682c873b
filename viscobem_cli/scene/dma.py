"""DMA tables in scenes: ``[material] dma`` read by :func:`bem.materials.read_dma`, with the
scene's ``dma_frequency_unit``, ``dma_modulus_unit``, ``dma_temperature_unit`` and
``dma_columns`` as its arguments (the file format, the units and what is assumed are documented
there). Its messages name the scene's keys.
"""

import re
import warnings
from pathlib import Path

from bem.errors import InputError
from bem.materials import dma

__all__ = ["read_dma", "FREQUENCY_UNITS", "MODULUS_UNITS", "TEMPERATURE_OFFSETS", "QUANTITIES"]

FREQUENCY_UNITS = dma.FREQUENCY_UNITS
MODULUS_UNITS = dma.MODULUS_UNITS
TEMPERATURE_OFFSETS = dma.TEMPERATURE_OFFSETS
QUANTITIES = dma.QUANTITIES
KEYS = {"frequency_unit": "dma_frequency_unit", "modulus_unit": "dma_modulus_unit"}
KEYS.update(temperature_unit="dma_temperature_unit", columns="dma_columns")
_ARGUMENT = re.compile(r"(?<![\w.])(frequency_unit|modulus_unit|temperature_unit|columns)\b(?! \(scene)")


def read_dma(t, base):
    """The DMA table of ``[material] dma`` in SI: ``w`` (rad/s), ``e1``, ``e2`` (Pa), ``T`` (K or
    None), and the ``path`` and ``units`` read."""
    if not isinstance(t["dma"], str):
        raise InputError(f"[material] dma must be a file path (string), got {t['dma']!r}")
    path = (Path(base) / t["dma"]).resolve()
    try:
        with warnings.catch_warnings():  # an assumed unit is reported with the scene's warnings
            warnings.simplefilter("ignore", UserWarning)
            table = dma.read_dma(path, **{arg: t.get(key) for arg, key in KEYS.items()})
    except InputError as err:  # the same line, in the scene's words
        raise InputError(f"[material] dma: {_ARGUMENT.sub(lambda m: KEYS[m.group(1)], str(err))}") from None
    return {
        "w": table.frequencies,
        "e1": table.storage,
        "e2": table.loss,
        "T": table.temperatures,
        "path": table.path,
        "units": table.units,
        "warnings": list(table.warnings),
    }
