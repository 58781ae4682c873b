"""Adaptive non-uniform mesh BEM for isolated contacts (the seed's method).

Putignano, Afferrante, Carbone & Demelio, IJSS 49 (2012) 338-343,
doi:10.1016/j.ijsolstr.2011.10.009, and IJSS 49 (2012) 2300 (viscoelastic sliding). The
half-space is loaded by piecewise-constant pressure on elements of several sizes: squares
(2-D surfaces, 3-D half-space) or strips (1-D profiles, plane strain). The solve starts on a
coarse uniform mesh; elements in contact, near the contact edge (``buffer``) or across a
steep pressure jump (``gradient``) are split in 2 (strips) or 4 (squares), and the problem is
solved again, ``levels`` times, until the refined elements are the cells of the fine grid.

Modules: :mod:`~bem.adaptive.mesh` (elements, refinement rules, sampling of the indenter),
:mod:`~bem.adaptive.square` and :mod:`~bem.adaptive.strip` (influence coefficients of square
and strip elements), :mod:`~bem.adaptive.assembly` (the dense matrices and the contact
operator), :mod:`~bem.adaptive.solver` (the refinement loop, :func:`solve_adaptive`).

Response (docs/theory.md §3), indenter moving in ``+x``, displacement positive into the solid::

    u(x) = (1/E_inf) (G * p)(x) + sum_k C_k integral_0^inf exp(-z) (G * p)(x + v lambda_k z) dz.

Cost and when to use it: the dense system makes assembly and products ``O(N_e**2)``; with
elements refined wherever there is contact, ``N_e`` is at least the number of fine cells in
contact. ``viscobem_bench/isolated.py`` (results in ``viscobem_bench/results/``) finds the uniform
DC-FFT grid (:mod:`bem.halfspace.isolated`) faster at equal error on cylinders and spheres, and about
as fast only when the contact covers ~1% of a wide domain; ``method="auto"`` therefore picks
the uniform grid. The adaptive solver remains an independent check of it (same collocation
inside the contact, independent kernels) and the seed's method.
"""

from .assembly import influence_matrix
from .mesh import AdaptiveMesh, marked_elements, refine, uniform_mesh
from .solver import AdaptiveResult, solve_adaptive
from .square import cell_creep_table

__all__ = [
    "AdaptiveMesh",
    "AdaptiveResult",
    "solve_adaptive",
    "influence_matrix",
    "uniform_mesh",
    "marked_elements",
    "refine",
    "cell_creep_table",
]
