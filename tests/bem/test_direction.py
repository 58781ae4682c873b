"""Sliding in any direction (bem.direction): rotation checks, periodicity in the angle,
reversal, and an exact oblique case (a diagonal sinusoid is a 1-D profile in disguise)."""

import dataclasses

import numpy as np
import pytest

import bem
from bem import direction, surfaces
from bem.errors import InputError
from bem.halfspace.periodic import PeriodicHalfSpace

MAT = bem.Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01)
L = 1e-3
SPEED = 0.03  # xi = v tau / L = 0.3: strongly viscoelastic


@pytest.fixture(scope="module")
def rough():
    return surfaces.self_affine(64, L, hurst=0.8, scales=8, rms_slope=0.3, seed=1, anisotropy=2.0)


def _turned(surface, k):
    return dataclasses.replace(surface, heights=np.ascontiguousarray(np.rot90(surface.heights, k)))


def test_periodic_plus_y_is_the_turned_surface_along_plus_x(rough):
    """Along +y over h equals along +x over h turned by -90 degrees (np.rot90(h, -1))."""
    load = 0.05 * 1e6 * L * L
    along_y = bem.solve(rough, MAT, speed=SPEED, load=load, direction=np.pi / 2)
    along_x = bem.solve(_turned(rough, -1), MAT, speed=SPEED, load=load)
    # the same arithmetic on permuted arrays: round-off
    assert along_y.friction == pytest.approx(along_x.friction, rel=1e-12)
    assert along_y.contact_fraction == along_x.contact_fraction
    np.testing.assert_allclose(
        along_y.pressure, np.rot90(along_x.pressure, 1), rtol=0, atol=1e-9 * along_x.pressure.max()
    )
    # the surface is anisotropic: the two directions differ (else the check is empty)
    assert abs(along_y.friction / bem.solve(rough, MAT, speed=SPEED, load=load).friction - 1) > 0.05


def test_periodic_oblique_operator_at_90_degrees_matches_the_turn(rough):
    """The oblique operator (general path), forced at theta = pi/2, against the quarter turn."""
    op = direction.DirectedPeriodicHalfSpace(rough.shape, L, MAT, SPEED, np.pi / 2)
    assert not op.factors_along_x
    rng = np.random.default_rng(3)
    p = rng.random(rough.shape)
    opx = PeriodicHalfSpace(rough.shape, L, MAT, SPEED)
    u_turn = np.rot90(opx.displacement(np.rot90(p, -1)), 1)
    np.testing.assert_allclose(op.displacement(p), u_turn, rtol=0, atol=1e-13 * np.abs(u_turn).max())
    assert op.dissipation_integral(bem.fft.forward(p)) == pytest.approx(
        opx.dissipation_integral(bem.fft.forward(np.rot90(p, -1))), rel=1e-12
    )
    load = 0.05 * 1e6 * L * L
    sol = bem.contact.solve_contact(op, rough.heights, mean_pressure=load / op.area, rtol=1e-8)
    ref = bem.solve(rough, MAT, speed=SPEED, load=load, direction=np.pi / 2)
    # two solver paths, each to rtol = 1e-8: measured 4e-9 in friction, 1.2e-7 in pressure
    assert op.dissipation_integral(bem.fft.forward(sol.pressure)) / load == pytest.approx(ref.friction, rel=1e-7)
    assert np.abs(sol.pressure - ref.pressure).max() < 1e-6 * ref.pressure.max()


def test_oblique_is_continuous_at_a_lattice_direction(rough):
    """The oblique operator at 1e-6 rad from +x against the x-operator: a change linear in the
    angle while v lambda theta / L << 1 (measured 2.1e-7 in friction, 3.1e-7 in eq. 6)."""
    load = 0.05 * 1e6 * L * L
    ref = bem.solve(rough, MAT, speed=SPEED, load=load)
    near = bem.solve(rough, MAT, speed=SPEED, load=load, direction=1e-6)
    assert near.friction == pytest.approx(ref.friction, rel=2e-6)
    assert near.friction_eq6 == pytest.approx(ref.friction_eq6, rel=2e-6)
    assert near.contact_fraction == ref.contact_fraction


def test_direction_is_periodic_in_2pi_and_reversal_is_a_half_turn(rough):
    load = 0.05 * 1e6 * L * L
    theta = 0.3
    a = bem.solve(rough, MAT, speed=SPEED, load=load, direction=theta)
    b = bem.solve(rough, MAT, speed=SPEED, load=load, direction=theta + 2 * np.pi)
    assert a.friction == pytest.approx(b.friction, rel=1e-12)
    np.testing.assert_allclose(a.pressure, b.pressure, rtol=0, atol=1e-10 * a.pressure.max())
    # reversal: along theta + pi over h is along theta over h turned by a half turn
    back = bem.solve(rough, MAT, speed=SPEED, load=load, direction=theta + np.pi)
    half = bem.solve(_turned(rough, 2), MAT, speed=SPEED, load=load, direction=theta)
    assert back.friction == pytest.approx(half.friction, rel=1e-7)  # solver tolerance (rtol 1e-8)
    np.testing.assert_allclose(back.pressure, np.rot90(half.pressure, 2), rtol=0, atol=1e-6 * back.pressure.max())
    assert abs(back.friction / a.friction - 1) > 0.05  # not symmetric: the check has teeth
    assert a.friction > 0 and back.friction > 0


@pytest.mark.parametrize("frac", [0.3, 2.0])  # partial and full contact
def test_diagonal_sinusoid_is_the_profile_along_its_wavevector(frac):
    """h = g cos(2 pi (x + y) / L) slid along 45 degrees is the 1-D sinusoid of wavelength
    L / sqrt(2) slid along its axis, on the same n samples per period: exact to solver tolerance.
    n is odd: with even n the corner mode (-1)**(i + j) is also (-1)**(i - j), a pattern along
    both diagonals, so its symbol is an alias mean and the 2-D grid is not the profile there."""
    n, g = 33, 1e-5
    x = np.arange(n) * L / n
    h2 = g * np.cos(2 * np.pi * (x[:, None] + x[None, :]) / L)
    h1 = g * np.cos(2 * np.pi * np.arange(n) / n)
    lam = L / np.sqrt(2)
    p_star = np.pi * 1e6 / 0.75 * g / lam
    r1 = bem.solve(surfaces.from_heights(h1, lam), MAT, speed=SPEED, load=frac * p_star * lam)
    r2 = bem.solve(surfaces.from_heights(h2, L), MAT, speed=SPEED, load=frac * p_star * L * L, direction=np.pi / 4)
    assert r2.friction == pytest.approx(r1.friction, rel=1e-6)  # two solves to rtol 1e-8
    assert r2.friction_eq6 == pytest.approx(r1.friction_eq6, rel=1e-6)
    idx = (np.arange(n)[:, None] + np.arange(n)[None, :]) % n
    np.testing.assert_allclose(r2.pressure, r1.pressure[idx], rtol=0, atol=1e-6 * r1.pressure.max())
    # across the ridges nothing dissipates; backward the same friction (the profile is even)
    across = bem.solve(surfaces.from_heights(h2, L), MAT, speed=SPEED, load=frac * p_star * L * L, direction=-np.pi / 4)
    assert abs(across.friction) < 1e-10 * r1.friction
    assert r1.friction > 1e-3


def test_isolated_plus_y_is_the_turned_indenter_along_plus_x():
    """An elliptic paraboloid (radii 2:1) along +y against the same body turned, along +x."""
    n, length = 32, 4e-3
    c = (np.arange(n) - (n - 1) / 2) * length / n
    h = -(c[:, None] ** 2 / (2 * 0.02) + c[None, :] ** 2 / (2 * 0.01))
    s = surfaces.from_heights(h, length, centered=True)
    speed, load = 0.1, 0.5
    along_y = bem.solve(s, MAT, speed=speed, load=load, periodic=False, direction=np.pi / 2)
    along_x = bem.solve(_turned(s, -1), MAT, speed=speed, load=load, periodic=False)
    assert along_y.friction == pytest.approx(along_x.friction, rel=1e-12)
    assert along_y.contact_fraction == along_x.contact_fraction
    np.testing.assert_allclose(
        along_y.pressure, np.rot90(along_x.pressure, 1), rtol=0, atol=1e-9 * along_x.pressure.max()
    )
    plain = bem.solve(s, MAT, speed=speed, load=load, periodic=False)
    assert abs(along_y.friction / plain.friction - 1) > 0.02
    # reversal of an even body: the same friction, mirrored fields
    back = bem.solve(s, MAT, speed=speed, load=load, periodic=False, direction=np.pi)
    assert back.friction == pytest.approx(plain.friction, rel=1e-6)
    np.testing.assert_allclose(back.pressure, plain.pressure[::-1, ::-1], rtol=0, atol=1e-6 * plain.pressure.max())


def test_profile_reversed():
    prof = surfaces.profile(64, L, hurst=0.8, scales=16, rms_slope=0.2, seed=2)
    load = 0.05 * 1e6 * L
    back = bem.solve(prof, MAT, speed=SPEED, load=load, direction=np.pi)
    mirror = bem.solve(dataclasses.replace(prof, heights=prof.heights[::-1].copy()), MAT, speed=SPEED, load=load)
    assert back.friction == pytest.approx(mirror.friction, rel=1e-12)
    np.testing.assert_allclose(back.pressure, mirror.pressure[::-1], rtol=0, atol=1e-9 * back.pressure.max())


@pytest.mark.parametrize(
    "bad, kwargs, words", [(0.5, {}, "0 or pi"), (float("nan"), {}, "finite"), ("east", {}, "radians")]
)
def test_bad_directions_for_profiles(bad, kwargs, words):
    prof = surfaces.profile(32, L, hurst=0.8, scales=8, rms_slope=0.2, seed=2)
    with pytest.raises(InputError, match="direction") as err:
        bem.solve(prof, MAT, speed=SPEED, load=1.0, direction=bad, **kwargs)
    assert words in str(err.value)


def test_oblique_adaptive_is_refused():
    s = surfaces.sphere(radius=0.01, n=16, length=2e-3)
    with pytest.raises(InputError, match="direction.*adaptive"):
        bem.solve(s, MAT, speed=0.1, load=0.1, periodic=False, method="adaptive", direction=0.4)


def _ellipsoid():
    n, length = 32, 4e-3
    c = (np.arange(n) - (n - 1) / 2) * length / n
    return surfaces.from_heights(-(c[:, None] ** 2 / (2 * 0.02) + c[None, :] ** 2 / (2 * 0.01)), length, centered=True)


def test_isolated_oblique_kernels_against_the_x_quadrature():
    """The ray quadrature along +x and +y against bem.halfspace.influence's exact-shift x-quadrature."""
    from bem.halfspace import influence
    from bem.halfspace.directed import oblique_kernels

    n = 12
    for shift in (1e-5, 0.05, 0.7, 3.0, 50.0, 1e4):  # element widths
        ref = influence.square_creep_sum(n, 1.0, [shift], [1.0])[1:-1:2]  # y >= 0 half
        along_x, _ = oblique_kernels(n, 1.0, 0.0, [shift], [1.0])
        along_y, _ = oblique_kernels(n, 1.0, np.pi / 2, [shift], [1.0])
        scale = np.abs(ref).max()
        # measured at most 2.3e-11 (x) relative; 1e-9 leaves margin for other shifts
        assert np.abs(along_x[:, n - 1 :] - ref).max() < 1e-9 * scale, shift
        assert np.abs(along_y[n - 1 :, :].T - ref).max() < 1e-9 * scale, shift


@pytest.mark.parametrize("theta", [0.4, np.pi / 4])
def test_isolated_oblique_kernels_converged(theta):
    """Oblique rays against the same quadrature with 24 nodes per piece and the kink pieces on
    every ray (measured at most 2.8e-10 relative)."""
    from bem.halfspace.directed import oblique_kernels

    for shift in (0.05, 0.7, 3.0, 50.0):
        k, s = oblique_kernels(8, 1.0, theta, [shift], [1.0])
        kr, sr = oblique_kernels(8, 1.0, theta, [shift], [1.0], nodes=24, near=1e9)
        assert np.abs(k - kr).max() < 2e-9 * np.abs(kr).max(), shift
        assert np.abs(s - sr).max() < 2e-9 * np.abs(sr).max(), shift


def test_isolated_oblique_operator_at_90_degrees_matches_the_turn():
    from bem.halfspace.directed import DirectedIsolatedHalfSpace

    s = _ellipsoid()
    op = DirectedIsolatedHalfSpace(s.shape, s.length, MAT, 0.1, np.pi / 2)
    opx = bem.halfspace.isolated.IsolatedHalfSpace(s.shape, s.length, MAT, 0.1)
    # measured 1.6e-10 of the largest coefficient
    assert np.abs(op.kernel - opx.kernel.T).max() < 1e-8 * np.abs(opx.kernel).max()
    sol = bem.contact.solve_contact(op, s.heights, mean_pressure=0.5 / op.area, rtol=1e-8)
    ref = bem.solve(s, MAT, speed=0.1, load=0.5, periodic=False, direction=np.pi / 2)
    # measured 2e-9 in friction and 2.5e-7 of the peak in pressure (quadrature and solver tolerance)
    assert op.dissipation_integral(sol.pressure) / 0.5 == pytest.approx(ref.friction, rel=1e-7)
    assert np.abs(sol.pressure - ref.pressure).max() < 1e-5 * ref.pressure.max()


def test_isolated_oblique_periodic_in_2pi_reversal_and_isotropy():
    s = _ellipsoid()
    kw = {"speed": 0.1, "load": 0.5, "periodic": False}
    a = bem.solve(s, MAT, direction=0.3, **kw)
    b = bem.solve(s, MAT, direction=0.3 + 2 * np.pi, **kw)
    assert a.friction == pytest.approx(b.friction, rel=1e-12)
    back = bem.solve(s, MAT, direction=0.3 + np.pi, **kw)
    half = bem.solve(_turned(s, 2), MAT, direction=0.3, **kw)
    assert back.friction == pytest.approx(half.friction, rel=1e-7)
    np.testing.assert_allclose(back.pressure, np.rot90(half.pressure, 2), rtol=0, atol=1e-6 * back.pressure.max())
    # an elliptic body: friction between its two principal values, different from both
    along_x = bem.solve(s, MAT, direction=0.0, **kw).friction
    along_y = bem.solve(s, MAT, direction=np.pi / 2, **kw).friction
    assert min(along_x, along_y) < a.friction < max(along_x, along_y)
    # a sphere: the same friction in every direction up to the square grid's anisotropy
    # (measured 0.45 % at 45 degrees on 32 elements)
    sphere = surfaces.sphere(radius=0.01, n=32, length=2e-3)
    mu = [bem.solve(sphere, MAT, speed=0.01, load=0.05, periodic=False, direction=t).friction for t in (0.0, np.pi / 4)]
    assert mu[1] == pytest.approx(mu[0], rel=0.01)


def test_anisotropy_is_reported_from_the_sliding_direction(rough):
    """Moments and the contact-PSD ellipse of a solve along +y, measured from +y, equal those of
    the turned surface slid along +x, measured from +x (the seed's convention)."""
    from bem.analysis import anisotropy

    load = 0.05 * 1e6 * L * L
    along_y = bem.solve(rough, MAT, speed=SPEED, load=load, direction=np.pi / 2)
    along_x = bem.solve(_turned(rough, -1), MAT, speed=SPEED, load=load)
    my = anisotropy.spectral_moments(along_y.displacement, L, direction=np.pi / 2)
    mx = anisotropy.spectral_moments(along_x.displacement, L)
    for name in ("m20", "m02", "m11", "gamma"):
        assert getattr(my, name) == pytest.approx(getattr(mx, name), rel=1e-9, abs=1e-12 * mx.m20)
    assert np.cos(2 * (my.theta_max - mx.theta_max)) == pytest.approx(1.0, abs=1e-9)
    assert my.direction == np.pi / 2 and mx.direction == 0.0
    # measured from +x instead, the moments differ (the check has teeth)
    from_x = anisotropy.spectral_moments(along_y.displacement, L)
    assert np.cos(2 * (from_x.theta_max - mx.theta_max)) < 0.5 and from_x.m11 * mx.m11 < 0
    ey = anisotropy.psd_contour(
        anisotropy.contact_psd(along_y.pressure > 0, L, smoothing=2.0), 0.7, direction=np.pi / 2
    )
    ex = anisotropy.psd_contour(anisotropy.contact_psd(along_x.pressure > 0, L, smoothing=2.0), 0.7)
    # the contour's rays (multiples of pi / 180) map onto each other under a quarter turn
    assert ey.stretch_x == pytest.approx(ex.stretch_x, rel=1e-9)
    assert ey.orientation == pytest.approx(ex.orientation, abs=1e-9)
    assert ex.stretch_x > 1.5  # stretched along the sliding direction (measured 2.3)
    with pytest.raises(InputError, match="same sliding direction"):
        anisotropy.relative_moments(my, mx)


def test_friction_curve_along_a_direction():
    s = surfaces.self_affine(32, L, hurst=0.8, scales=4, rms_slope=0.3, seed=1, anisotropy=2.0)
    curve = bem.friction_curve(s, MAT, speeds=[0.003, 0.03], load=0.05, direction=0.5, warm_start=False)
    for v, mu in zip((0.003, 0.03), curve.friction):
        assert mu == pytest.approx(bem.solve(s, MAT, speed=v, load=0.05, direction=0.5).friction, rel=1e-12)
    assert curve.friction[0] != pytest.approx(
        bem.friction_curve(s, MAT, speeds=[0.003], load=0.05).friction[0], rel=1e-3
    )


def test_adaptive_mesh_along_plus_y_is_the_turned_indenter():
    s = _ellipsoid()
    kw = {"speed": 0.1, "load": 0.5, "periodic": False, "method": "adaptive", "levels": 2}
    along_y = bem.solve(s, MAT, direction=np.pi / 2, **kw)
    along_x = bem.solve(_turned(s, -1), MAT, **kw)
    assert along_y.friction == pytest.approx(along_x.friction, rel=1e-12)
    np.testing.assert_allclose(
        along_y.pressure, np.rot90(along_x.pressure, 1), rtol=0, atol=1e-9 * along_x.pressure.max()
    )
