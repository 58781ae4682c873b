"""Rigid surfaces: the :class:`Surface` type and every way to make one.

Conventions (docs/theory.md §4, §5). Heights ``h`` (m) are **positive toward the half-space**, so
contact starts at ``max(h)``. A surface is a 1-D profile ``h[ix]`` or a square 2-D map
``h[ix, iy]`` (axis 0 is x, the sliding direction) on a cell of side ``length`` (m) with
``n`` points per side, spacing ``length / n``. Periodic cells put point ``j`` at
``x_j = j * spacing`` (as :mod:`bem.fft`); ``centered`` surfaces (isolated indenters) put
it at the centre of element ``j`` of a domain centred on the indenter,
``x_j = (j + 1/2) * spacing - length / 2``.

Workflow:

1. make a surface: generated (:func:`self_affine`, :func:`profile` in :mod:`.rough`), analytic
   (:func:`sinusoid`, :func:`sphere`, :func:`cylinder` in :mod:`.shapes`), from an array
   (:func:`from_heights`) or measured (:func:`from_scan` for a scan of any shape and format,
   periodic or not; :func:`load` for a plain file holding one square periodic cell; the steps
   of ``from_scan`` are in :mod:`.measured`);
2. check what it holds (:mod:`.statistics`: rms height and slope, the PSD and its target);
3. hand it to :func:`bem.solve`.
"""

from .measured import from_scan, load
from .rough import profile, self_affine
from .shapes import cylinder, sinusoid, sphere
from .surface import Surface, from_heights

__all__ = ["Surface", "from_heights", "self_affine", "profile", "sinusoid", "load", "from_scan", "sphere", "cylinder"]
