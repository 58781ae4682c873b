"""FEM (graded mesh, default settings) against Hunter's exact solution at E_inf/E0 = 1000.

Standard linear solid E0 = 2 MPa, E_inf = 2 GPa, relaxation time 10 ms, nu = 0.5; R = 20 mm,
P = 500 N/m, at Hunter's friction peak (V = 3.71e-4 m/s, V lambda / a0 = 1.70). A memory that
takes the strain as linear between neighbouring quadrature points puts the contact 27-36 um
downstream on the graded mesh, with errors of -2.62 % (moment form), -1.70 % (dissipation form)
and -4.2 % (peak pressure): this test fails on it.
"""

import math

import pytest

from bem import Material
from fem_reference import rolling_cylinder
from validation.references.hunter import rolling_cylinder as hunter

R, P, V = 0.02, 500.0, 3.7074e-4


@pytest.mark.slow
def test_fem_against_hunter_at_modulus_ratio_1000():
    m = Material.standard_linear_solid(E0=2e6, E_inf=2e9, relaxation_time=0.01, nu=0.5)
    r = rolling_cylinder(m, radius=R, load=P, speed=V)
    h = hunter(m, radius=R, load=P, speed=V)
    assert r.success, r.message
    # the trailing edge's estimate alternated between two meshes half an edge element apart; the
    # passes stop once it comes back (they had run into their limit of 8)
    assert r.passes < 8 and not [w for w in r.warnings if "did not settle" in w], r.warnings
    # measured (resolution 6, grading 1.5): -0.115 % (moment), +0.68 % (dissipation); limit 1 %:
    # margin 1.47x over the larger
    assert abs(r.friction / h.friction - 1) < 0.01
    assert abs(r.friction_dissipation / h.friction - 1) < 0.01
    # measured +0.46 % with the layer V tau = 3.7 um over 4 of the smallest elements, and -0.46 to
    # +0.50 % at 0.85, 1.15 and 10 times this speed; limit 2 % (the target): margin 4x. Over 2 elements
    # it was +3.5 % here and +3.8 % at 0.85 times the speed, and this assertion fails
    assert abs(r.peak_pressure / h.peak_pressure - 1) < 0.02
    # leading edge measured 1.3 um = 0.08 % of the contact width (was 27 um = 1.7 %); limit 0.5 %
    # of the width: margin 6x. The trailing edge (35 um = 2.2 %, where Hunter's pressure is 1 % of
    # its peak at 36 um from the edge) is located from pressures of that size and is not asserted.
    assert abs(r.leading_edge - h.leading_edge) < 0.005 * 2 * h.half_width


@pytest.mark.slow
def test_fem_resolves_the_layer_of_a_standard_solid_below_the_floor():
    # V lambda / a0 = 0.3: the layer V tau = 0.66 um is 0.18 % of an edge element, under layer_floor
    # (1 %). As the single term its layer is resolved all the same. Measured: peak pressure +0.12 %
    # (limit 2 %, the target: margin 16x; at the floor it was 18 % low and reported unresolved, and
    # this assertion fails there), friction -0.04 % (moment) and +0.66 % (dissipation), limit 1 %
    m = Material.standard_linear_solid(E0=2e6, E_inf=2e9, relaxation_time=0.01, nu=0.5)
    a0 = (4 * P * R * 0.75 / (math.pi * 2e6)) ** 0.5
    V = 0.3 * a0 / 10.0  # creep time lambda = 10 ms * 1000
    r = rolling_cylinder(m, radius=R, load=P, speed=V)
    h = hunter(m, radius=R, load=P, speed=V)
    assert r.success, r.message
    assert r.peak_resolved and r.thinnest_layer == pytest.approx(6.56e-7, rel=0.01), r.warnings
    assert abs(r.peak_pressure / h.peak_pressure - 1) < 0.02
    assert abs(r.friction / h.friction - 1) < 0.01
    assert abs(r.friction_dissipation / h.friction - 1) < 0.01


@pytest.mark.slow
@pytest.mark.parametrize("ratio", [10.0, 1000.0])
def test_fem_two_decades_below_the_friction_peak(ratio):
    # the friction is small there (the pressure centroid about 1 % of the contact width ahead of its
    # centre) and where the trailing edge falls among the nodes sets its error. With the trailing edge
    # meshed like the rest of the contact the forms were +0.86 / +2.12 % (ratio 10) and +0.49 / +2.82 %
    # (ratio 1000) from Hunter, and this test fails; with its zone of LAYER_ELEMENTS elements measured
    # -0.45 / +0.19 % and -0.38 / +0.59 %. Limit 1 % (the target): margin 1.7x over the larger
    from viscobem_bench.fem import high_ratio_peak_speed

    m = Material.standard_linear_solid(E0=2e6, E_inf=2e6 * ratio, relaxation_time=0.01, nu=0.5)
    speed = 0.01 * high_ratio_peak_speed(ratio)
    r = rolling_cylinder(m, radius=R, load=P, speed=speed)
    h = hunter(m, radius=R, load=P, speed=speed)
    assert r.success, r.message
    assert abs(r.friction / h.friction - 1) < 0.01
    assert abs(r.friction_dissipation / h.friction - 1) < 0.01
