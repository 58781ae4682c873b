"""PNG plots of a study (matplotlib on the Agg backend, imported only when a plot is drawn).

Workflow:

1. :func:`write_all` (:mod:`.study`) draws what the scene's outputs ask for: the friction curve,
   contact area, pressure and deformed-surface maps, contact outlines of indenters;
2. the anisotropy plots (:mod:`.anisotropy`), temperature plots (:mod:`.temperatures`), the polar
   plot of a direction sweep (:mod:`.directions`) and a measured surface's PSD (:mod:`.measured`);
3. every plot shares :mod:`.style`: the xi axis with its speed twin, the sliding arrow, and atomic
   PNG writes.
"""

from .study import write_all

__all__ = ["write_all"]
