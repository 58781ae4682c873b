"""Persson's theory: exact in full contact (equal to the BEM), continuous = discrete."""

import numpy as np
import pytest

import bem
from bem.analysis import persson
from bem.errors import InputError


@pytest.fixture(scope="module")
def smooth_surface():
    # 2 um rms on a 10 mm cell: 20 kPa nominal pressure keeps every point in contact
    return bem.surfaces.self_affine(64, 0.01, hurst=0.8, scales=16, rms_height=2e-6, seed=1)


@pytest.mark.parametrize("speed", [1e-3, 1.0, 100.0])
def test_discrete_full_contact_theory_is_the_bem(seed, smooth_surface, speed):
    load = 2e3
    res = bem.solve(smooth_surface, seed, speed=speed, load=load)
    assert res.contact_fraction == 1.0
    mu, area = persson.friction_discrete(
        smooth_surface, seed, speeds=[speed], pressure=load / 0.01**2, partial_contact=False
    )
    # the same sum over the same modes (E from the Prony series, the BEM's J from the creep
    # series: E J = 1 to round-off); measured agreement 3e-14
    assert mu[0] == pytest.approx(res.friction, rel=1e-10)
    assert area[0] == 1.0


def test_partial_contact_factor_tends_to_one_under_high_pressure(seed, smooth_surface):
    full, _ = persson.friction_discrete(smooth_surface, seed, speeds=[0.1], pressure=1e8, partial_contact=False)
    part, area = persson.friction_discrete(smooth_surface, seed, speeds=[0.1], pressure=1e8)
    # G ~ (E rms_slope / sigma0)^2 ~ 1e-4 here, so 1 - P = erfc(1/(2 sqrt G)) ~ 1e-20
    assert part[0] == pytest.approx(full[0], rel=1e-12)
    assert area[0] == 1.0


@pytest.mark.parametrize("partial", [False, True])
def test_continuous_integral_matches_the_lattice_sum(seed, partial):
    """The lattice sum approximates the integral with cells of area q_L^2: its error falls as
    the cell grows relative to the roll-off wavelength (fixed PSD, q_r = 2 pi / 10 mm)."""
    speeds = [0.01, 1.0]
    errors = []
    for n, scales, rolloff in [(128, 32, 2), (256, 64, 4)]:
        s = bem.surfaces.self_affine(
            n, 0.01 * rolloff, hurst=0.8, scales=scales, rolloff=rolloff, rms_height=2e-5, seed=1
        )
        mu_d, a_d = persson.friction_discrete(s, seed, speeds=speeds, pressure=3000, partial_contact=partial)
        mu_c, a_c = persson.friction_for_surface(s, seed, speeds=speeds, pressure=3000, partial_contact=partial)
        errors.append(np.abs(mu_c / mu_d - 1))
        # the contact area P(q1) sums G over every scale: lattice error measured 0.01 %
        assert a_c == pytest.approx(a_d, rel=2e-3)
    # measured: full contact 0.26 %, 0.02 % ; partial 1.8 %, 0.6 % (v = 0.01) and 20 %, 7 %
    # (v = 1 m/s, where the dissipation sits at the few lowest modes and P(q) is set there)
    assert np.all(errors[1] < (0.004 if not partial else 0.10))
    assert np.all(errors[1] < errors[0])
    # the quadrature itself is converged: doubling the nodes changes mu by < 1e-6
    fine, _ = persson.friction_for_surface(
        s, seed, speeds=speeds, pressure=3000, partial_contact=partial, points=801, angles=512
    )
    assert fine == pytest.approx(mu_c, rel=1e-6)


def test_friction_is_bell_shaped_and_positive(seed):
    s = bem.surfaces.self_affine(64, 0.01, hurst=0.8, scales=16, rms_height=2e-5, seed=1)
    v = np.logspace(-5, 3, 17)
    mu, area = persson.friction_for_surface(s, seed, speeds=v, pressure=3000)
    assert np.all(mu > 0) and np.all((area > 0) & (area < 1))
    k = int(np.argmax(mu))
    assert 0 < k < v.size - 1 and mu[0] < mu[k] / 10 and mu[-1] < mu[k] / 10


def test_bad_input(seed, smooth_surface):
    with pytest.raises(InputError, match="pressure"):
        persson.friction_discrete(smooth_surface, seed, speeds=[1.0], pressure=-1.0)
    with pytest.raises(InputError, match="q1"):
        persson.friction(seed, psd=lambda q: q**-3, q0=10.0, q1=1.0, speeds=[1.0], pressure=1.0)
    with pytest.raises(InputError, match="self_affine"):
        persson.friction_for_surface(
            bem.surfaces.sinusoid(16, 1.0, amplitude=1e-3, dim=2), seed, speeds=[1.0], pressure=1.0
        )
