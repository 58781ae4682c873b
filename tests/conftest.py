"""Shared fixtures of the core-solver tests: reference materials and a dense LCP solver.

Materials
---------
- ``seed``: the seed paper's standard linear solid, ``E_inf = 1e7 Pa``, ``E_inf/E0 = 3``,
  creep (retardation) time 0.01 s.
- ``prony30``: a rubber-like series of 30 relaxation terms with times log-spaced over
  12 decades (1e-6 to 1e6 s) and ``E_inf/E0 = 1e4`` (``E0 = 1e6 Pa``).
"""

import contextlib
import dataclasses
import os

import numpy as np
import pytest

try:
    from threadpoolctl import threadpool_limits
except ImportError:  # only a speed-up: single-threaded BLAS for many small dense solves

    def threadpool_limits(**_):
        return contextlib.nullcontext()


import bem
from bem import Material
from validation.references.periodic_exact import murty_lcp  # the dense reference's LCP solver (Murty)


def vtk_units(dataset):
    """The parsed ``units`` field data of a VTK dataset (BEM or FEM: one format), checked to name
    every point, cell and field array the dataset holds."""
    import json

    units = json.loads(dataset.field_data["units"][0])
    arrays = {*dataset.point_data.keys(), *dataset.cell_data.keys(), *dataset.field_data.keys()}
    missing = arrays - {"units", "conventions"} - set(units)
    assert not missing, f"arrays without a unit: {sorted(missing)}"
    assert all(isinstance(u, str) and u for u in units.values()), units
    return units


def make_seed():
    return Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)


def make_prony30(ratio=1e4, terms=30):
    times = np.logspace(-6, 6, terms)
    moduli = np.full(terms, 1e6 * (ratio - 1.0) / terms)
    return Material.from_prony(E0=1e6, moduli=moduli, times=times)


@pytest.fixture(scope="session")
def seed():
    return make_seed()


@pytest.fixture(scope="session")
def prony30():
    return make_prony30()


def dense_operator(op):
    """Dense matrix of ``op.displacement`` (m/Pa), column ``j`` = response to a unit ``p_j``."""
    n = op.size
    eye = np.zeros(op.shape)
    cols = np.empty((n, n))
    for j in range(n):
        eye.flat[j] = 1.0
        cols[:, j] = op.displacement(eye).ravel()
        eye.flat[j] = 0.0
    return cols


def dense_contact(op, heights, shifted_approach):
    """Dense reference of the contact problem at one rigid position.

    The periodic operator has no ``q = 0`` response (``A 1 = 0``), so ``A`` itself is singular;
    ``M = A + c 11^T / N`` (``c`` = the self-influence) is a P-matrix (its symmetric part is
    positive definite) and ``M p = A p + c mean(p)``. Solving the LCP with gap
    ``M p - (h - max h) - d`` therefore solves the original problem with the approach
    ``delta = d - c mean(p)`` (the approach unknown carries the mean). Returns
    ``(pressure, delta, pivots)``.
    """
    A = dense_operator(op)
    c = op.self_influence()
    M = A + c / A.shape[0]
    ht = (heights - heights.max()).ravel()
    with threadpool_limits(limits=1, user_api="blas"):  # small dense solves: threads only hurt
        z, pivots = murty_lcp(M, -(ht + shifted_approach))
    return z.reshape(op.shape), shifted_approach - c * z.mean(), pivots


def make_tiny_scene(outputs, speeds="[0.01, 0.1]", seed=1, solver=""):
    """TOML of a 16² rough-surface study on the seed's material (seconds to run), with the
    ``[outputs]`` lines ``outputs`` (and ``[solver]`` lines ``solver``): for the tests of what
    ``viscobem run`` writes."""
    return f"""
[material]
E0 = 3.3e6
E_inf = 1.0e7
creep_time = 0.01
nu = 0.5
[surface]
kind = "self_affine"
length = 0.01
n = 16
hurst = 0.8
scales = 4
rms_height = 2e-5
seed = {seed}
[loading]
load = 0.3
speeds = {speeds}
[solver]
{solver}
[outputs]
{outputs}
"""


# ---------------------------------------------------------------- another machine's round-off
PERTURB_ENV, PERTURB_SEED_ENV = "VISCOBEM_PERTURB_HEIGHTS", "VISCOBEM_PERTURB_SEED"


def perturbed(surface, eps, seed=0):
    """``surface`` with its heights multiplied by ``1 + eps z``, ``z`` standard normal (seeded):
    a change in the last bits, the size of another processor's FFT round-off."""
    rng = np.random.default_rng(seed)
    h = surface.heights * (1.0 + eps * rng.standard_normal(surface.heights.shape))
    return dataclasses.replace(surface, heights=h)


@pytest.fixture(scope="session", autouse=True)
def _another_machine():
    """With ``VISCOBEM_PERTURB_HEIGHTS=eps`` set, every surface a test hands to :func:`bem.solve` or
    :func:`bem.friction_curve` is perturbed by ``eps`` relative (:func:`perturbed`, seeded by
    ``VISCOBEM_PERTURB_SEED``, default 0: the same perturbation for the same surface), so that a
    run stands for another machine whose round-off sends path-sensitive solves another way. The stress suite and the tests that bound operator
    products must pass so (``1e-12``); tests that compare with exact solutions to round-off are
    not meant to."""
    eps = float(os.environ.get(PERTURB_ENV) or 0.0)
    if not eps:
        yield
        return
    seed = int(os.environ.get(PERTURB_SEED_ENV) or 0)
    solve, curve = bem.solve, bem.friction_curve
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(bem, "solve", lambda surface, *a, **kw: solve(perturbed(surface, eps, seed), *a, **kw))
        mp.setattr(bem, "friction_curve", lambda surface, *a, **kw: curve(perturbed(surface, eps, seed), *a, **kw))
        yield
