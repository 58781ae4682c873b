"""The rolling FEM called plainly (no mesh argument) against Hunter's exact solution, and the
uniform mesh's refusal of a mesh whose solve cannot fit.

The default mesh is squares graded toward the contact and its leading-edge layer in both
directions, so its cost follows the contact, not the modulus ratio or the block; the uniform core's element count grows like
``resolution^2 E_inf / E0``.
"""

import math

import pytest

from bem import InputError, Material
from fem_reference import rolling, rolling_cylinder
from validation.references import hunter


def _speed(m, radius, load, s):
    """Speed at which the retardation length ``V lambda`` is ``s`` relaxed Hertz half-widths."""
    a0 = math.sqrt(4 * load * radius * (1 - m.nu**2) / (math.pi * m.E0))
    return s * a0 / float(m.creep_times[0])


def test_default_call_is_the_quadtree_and_meets_hunter():
    # E_inf/E0 = 10 near the friction peak (V lambda = a0), R = 10 mm, 1000 N/m. Measured at the
    # defaults (resolution 6, 21,196 unknowns): -0.095 % (moment form), -0.011 % (dissipation form),
    # +0.17 % (peak pressure); limits 1 % (the target for friction): margin 10x over the
    # moment form
    m = Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01)
    V = _speed(m, 0.01, 1000.0, 1.0)
    r = rolling_cylinder(m, radius=0.01, load=1000.0, speed=V)
    h = hunter.rolling_cylinder(m, radius=0.01, load=1000.0, speed=V)
    assert r.mesh == "quadtree" and r.success, r.message
    assert abs(r.friction / h.friction - 1) < 0.01
    assert abs(r.friction_dissipation / h.friction - 1) < 0.01
    assert abs(r.peak_pressure / h.peak_pressure - 1) < 0.01


def test_uniform_mesh_that_cannot_fit_is_refused_before_assembly(monkeypatch):
    # E_inf/E0 = 1000 at resolution 6: a uniform core of about 2e6 unknowns, whose factor alone needs
    # more than 20 GiB; with 4 GiB available it is refused, naming the parameters, before any
    # operator is assembled
    def never(*args, **kwargs):
        raise AssertionError("assembled a mesh that cannot fit")

    monkeypatch.setattr(rolling, "available_memory", lambda: 4 * 2**30)
    monkeypatch.setattr(rolling, "quadrature_operators", never)
    m = Material.standard_linear_solid(E0=2e6, E_inf=2e9, relaxation_time=0.01, nu=0.5)
    with pytest.raises(InputError, match=r"mesh='uniform' needs at least .* GiB .* mesh='quadtree'.* resolution"):
        rolling_cylinder(m, radius=0.02, load=500.0, speed=3.7e-4, mesh="uniform")


def test_uniform_mesh_that_fits_is_not_refused(monkeypatch):
    # the same 4 GiB admit the small uniform mesh of a ratio-3 solid (1568 elements, 1.1 GiB
    # resident measured): the refusal is about the size, not the option
    monkeypatch.setattr(rolling, "available_memory", lambda: 4 * 2**30)
    m = Material.standard_linear_solid(E0=1e6, E_inf=3e6, relaxation_time=0.01, nu=0.5)
    r = rolling_cylinder(m, radius=0.01, load=100.0, speed=0.01, resolution=2, grading=2.0, mesh="uniform")
    assert r.mesh == "uniform" and r.success, r.message


@pytest.mark.slow
def test_default_call_at_modulus_ratio_1000():
    # The default call on a one-term solid at E_inf/E0 = 1000 other than the high-ratio test's: E0 =
    # 1 MPa, creep time 5 s, R = 15 mm, 800 N/m, at its friction peak (V lambda = 1.7 a0). A uniform
    # core there holds about 2e6 unknowns and runs out of memory; the default squares take 32,680
    # unknowns and 0.73 GiB. Measured: -0.117 % (moment), +0.891 % (dissipation, its estimate 3.8 %
    # warns), +0.151 % (peak pressure); limits 1 % and 2 % (the targets): margin 1.12x over
    # the dissipation form (the tensor mesh: +0.663 %)
    m = Material.standard_linear_solid(E0=1e6, E_inf=1e9, creep_time=5.0, nu=0.5)
    R, P = 0.015, 800.0
    V = _speed(m, R, P, 1.7)
    r = rolling_cylinder(m, radius=R, load=P, speed=V)
    h = hunter.rolling_cylinder(m, radius=R, load=P, speed=V)
    assert r.mesh == "quadtree" and r.success, r.message
    assert abs(r.friction / h.friction - 1) < 0.01
    assert abs(r.friction_dissipation / h.friction - 1) < 0.01
    assert abs(r.peak_pressure / h.peak_pressure - 1) < 0.02
