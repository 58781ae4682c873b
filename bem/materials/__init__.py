"""Linear viscoelastic materials: the two series, fits to DMA data, and temperature.

Units SI (Pa, 1/Pa, s, rad/s, K). Workflow:

1. a :class:`Material` from a Prony (relaxation) or creep (retardation) series, or a standard
   linear solid (:mod:`.material`); the two series are converted exactly (:mod:`.interconversion`);
2. or fitted to DMA data (a table read in SI with its units by :func:`read_dma`, :mod:`.dma`):
   one isothermal sweep (``Material.fit_prony``, :mod:`.prony_fit`), or
   sweeps at several temperatures shifted onto a master curve (``Material.fit_master_curve``,
   :mod:`.master_curve`);
3. moved to another temperature through a shift law (:mod:`.temperature`: WLF, Arrhenius) with
   ``Material.at_temperature``.
"""

from .dma import DMATable, read_dma
from .material import Material
from .temperature import WLF, Arrhenius

__all__ = ["Arrhenius", "DMATable", "Material", "WLF", "read_dma"]
