"""Running a scene: the study, its resumable points, and the record of ``results.json``.

Workflow (:func:`run_scene`, :mod:`.study`):

1. the points (realisation, load, speed) are solved in chunks, in this process, a pool or a Dask
   cluster, each written as it finishes so that a rerun resumes (:mod:`.points`);
2. what the scene asks for beyond friction is computed from them (:mod:`.analysis`: anisotropy,
   contact PSD, Persson's theory);
3. the numbers are gathered (:mod:`.records`), with the guidance a user should read
   (:mod:`viscobem_cli.guidance`), into ``results.json``, beside ``fields.npz``, the plots
   (:mod:`viscobem_cli.plots`) and VTK;
4. sweeps over temperatures (:mod:`.temperatures`) and sliding directions (:mod:`.directions`)
   run the study once per value, each in its own folder; measured surfaces add their record
   (:mod:`.measured`).
"""

from .study import fold_material, run_scene

__all__ = ["fold_material", "run_scene"]
