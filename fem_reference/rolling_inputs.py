"""Inputs of the rolling-cylinder model: their checks and the size of the block that stands for the
half-space."""

import numpy as np

from bem.checks import check_int, check_positive
from bem.errors import InputError
from bem.materials.material import Material


def hertz_half_width(E, nu, radius, load):
    """Hertz half-width (m) of a cylinder of ``radius`` pressed by ``load`` (N/m) into a half-space of
    modulus ``E`` and Poisson ratio ``nu`` (plane strain)."""
    return float(np.sqrt(4.0 * load * radius * (1.0 - nu**2) / (np.pi * E)))


def domain_size(material, radius, load, speed, *, contact_factor=40.0, retardation_factor=30.0):
    """Half-width ``L`` = depth ``H`` of the block (m) standing for the half-space.

    ``L = max(contact_factor * a_0, retardation_factor * V * max(lambda_k))`` with ``a_0``
    the relaxed Hertz half-width and ``lambda_k`` the creep (retardation) times: the
    truncation error of the elastic problem scales as ``(a/H)^2`` and that of the
    viscoelastic one with ``V lambda / L`` (the retardation length must fit inside).
    """
    a0 = hertz_half_width(material.E0, material.nu, radius, load)
    ell_r = speed * float(np.max(material.creep_times)) if material.creep_times.size else 0.0
    return max(contact_factor * a0, retardation_factor * ell_r)


# default growth of the element size per unit distance, plus one. A standard solid (E_inf/E0 = 30) at
# its friction peak on the quadtree: the dissipation form 0.98 % from the BEM at 1.5, 0.08 % at 1.25
# and 0.05 % at 1.15 (the moment form -0.24, -0.13, -0.11 %), at 0.48, 1.2 and 2.5 thousand squares
TENSOR_GRADING = 1.5
QUADTREE_GRADING = 1.25


def check_inputs(material, radius, load, speed, resolution, contact_band, maxiter, grading, fold, mesh):
    """The validated inputs of :func:`fem_reference.rolling_cylinder`, each error naming its parameter."""
    if not isinstance(material, Material):
        raise InputError(f"material must be a bem.Material, got {type(material).__name__}")
    R = check_positive("radius", radius)
    P = check_positive("load", load)
    V = check_positive("speed", speed, allow_zero=True)
    n_res = check_int("resolution", resolution, 1, 200)
    band = check_positive("contact_band", contact_band)
    maxiter = None if maxiter is None else check_int("maxiter", maxiter, 1)
    if grading is None:
        # the quadtree's squares grow in both directions, the tensor meshes' rows and columns in one
        grading = QUADTREE_GRADING if mesh == "quadtree" else TENSOR_GRADING
    ratio = check_positive("grading", grading)
    if not 1.0 < ratio <= 2.0:
        raise InputError(f"grading must be in (1, 2], got {grading!r}")
    if band < 1.05:
        raise InputError(f"contact_band must be >= 1.05 relaxed half-widths, got {contact_band!r}")
    fold = check_positive("fold", fold, allow_zero=True)
    if fold >= 1:
        raise InputError(f"fold must be in [0, 1), got {fold!r}")
    if mesh not in ("uniform", "graded", "quadtree"):
        raise InputError(f"mesh must be 'uniform', 'graded' or 'quadtree', got {mesh!r}")
    return R, P, V, n_res, band, maxiter, ratio, fold


# Lower bounds of what the direct solve of a uniform-core mesh holds at once, per unknown ``N`` of its
# displacement and pressure: the factor's entries over ``N log2 N`` (nested-dissection orderings of a
# 2-D mesh fill in like that) and the assembled system's entries over ``N``. Measured on the uniform
# mesh (resolution 6, one condensed term, E_inf/E0 = 3, 10, 30): factor 81, 110, 120 (PARDISO) and
# 231, 241 (SuperLU); system 408, 481, 412. The smallest of each, so that a mesh refused is one whose
# solve cannot fit, whatever the solver: the estimate counts 8 bytes per factor entry (its value only)
# and 12 per system entry (value and column index).
FACTOR_FILL = 80.0
SYSTEM_FILL = 400.0


def check_uniform_fits(x, y, available):
    """Refuse a uniform-core mesh (element edges ``x``, ``y``) whose direct solve cannot fit in
    ``available`` bytes (None: not known, nothing is refused), before anything is assembled.

    The uniform core has ``h = a_inf / resolution`` over the relaxed contact band, so its element
    count grows like ``resolution^2 E_inf / E0``; the graded mesh's does not.
    """
    if available is None:
        return
    nx, ny = x.size - 1, y.size - 1
    n = 2.0 * (2 * nx + 1) * (2 * ny + 1) + 3.0 * nx * ny  # 9-node displacements and 3 pressures each
    need = 8.0 * FACTOR_FILL * n * np.log2(n) + 12.0 * SYSTEM_FILL * n
    if need > available:
        raise InputError(
            f"mesh='uniform' needs at least {need / 2**30:.3g} GiB for its {n:.3g} unknowns at this resolution "
            f"and modulus ratio, more than the {available / 2**30:.3g} GiB available: use "
            f"the default mesh='quadtree', whose cost does not grow with E_inf/E0, or a lower resolution"
        )
