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


def check_inputs(material, radius, load, speed, resolution, contact_band, maxiter, grading, fold, mesh):
    """The validated inputs of :func:`fem_reference.rolling_cylinder`, each error naming its parameter."""
    if not isinstance(material, Material):
        raise InputError(f"material must be a bem.Material, got {type(material).__name__}")
    R = check_positive("radius", radius)
    P = check_positive("load", load)
    V = check_positive("speed", speed, allow_zero=True)
    n_res = check_int("resolution", resolution, 1, 200)
    band = check_positive("contact_band", contact_band)
    maxiter = check_int("maxiter", maxiter, 1)
    ratio = check_positive("grading", grading)
    if not 1.0 < ratio <= 2.0:
        raise InputError(f"grading must be in (1, 2], got {grading!r}")
    if band < 1.05:
        raise InputError(f"contact_band must be >= 1.05 relaxed half-widths, got {contact_band!r}")
    fold = check_positive("fold", fold, allow_zero=True)
    if fold >= 1:
        raise InputError(f"fold must be in [0, 1), got {fold!r}")
    if mesh not in ("uniform", "graded"):
        raise InputError(f"mesh must be 'uniform' or 'graded', got {mesh!r}")
    return R, P, V, n_res, band, maxiter, ratio, fold
