"""The periodic benchmark: the FFT BEM on one rough surface from 256² up, against tamaas.

The problem, the cases and what is measured are stated in :mod:`.benchmark`. Workflow:

1. the problem (:mod:`.problem`): one band-limited surface resampled to every size, three
   materials (elastic, the seed's solid, a 20-term rubber) and the loads that give ~10 % contact;
2. a run (:mod:`.benchmark`, ``viscobem bench periodic`` or ``python -m viscobem_bench.periodic``)
   keeps its state in a :class:`~.session.Session` and runs every case in a fresh process
   (:mod:`.workers`), tamaas on the identical elastic problem when it is installed;
3. tables, targets and the published record (:mod:`.report`).
"""

from .benchmark import main, profile, run

__all__ = ["main", "profile", "run"]
