"""What a solution says beyond friction and contact area, and a theory to compare with.

Workflow:

1. solve (:func:`bem.solve`, :func:`bem.friction_curve`);
2. the anisotropy that sliding imprints (:mod:`.anisotropy`): spectral moments of the deformed
   surface, and the PSD of the contact indicator with its fitted iso-contour ellipse;
3. Persson's theory of rubber friction on the same surface and material (:mod:`.persson`), an
   independent estimate of the friction curve.
"""

from . import anisotropy, persson

__all__ = ["anisotropy", "persson"]
