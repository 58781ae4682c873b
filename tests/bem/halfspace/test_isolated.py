"""Isolated contacts (docs/theory.md §8): kernels, operator properties, Hunter, Hertz, low-speed friction.

References: Hunter's exact rolling cylinder (:mod:`validation.references.hunter`), Hertz
(:mod:`validation.references.hertz`), brute-force quadrature (scipy.integrate.quad) of the kernels, and
the independent dense strip kernel of :mod:`validation.references.bruteforce_line`.
"""

import numpy as np
import pytest
from scipy import integrate

import bem
from bem.errors import InputError
from bem.halfspace import influence
from bem.halfspace.isolated import IsolatedHalfSpace
from validation.references.bruteforce_line import strip_kernel
from validation.references.hertz import line_contact, point_contact
from validation.references.hunter import low_speed_friction, rolling_cylinder

R = 0.01  # indenter radius, m


def sls(ratio=3.0):
    """Standard linear solid, E_inf = 10 MPa, creep (retardation) time 0.01 s."""
    return bem.Material.standard_linear_solid(E0=1e7 / ratio, E_inf=1e7, creep_time=0.01)


def dense(op):
    n = op.size
    cols = np.empty((n, n))
    e = np.zeros(op.shape)
    for j in range(n):
        e.flat[j] = 1.0
        cols[:, j] = op.displacement(e).ravel()
        e.flat[j] = 0.0
    return cols


# ----------------------------------------------------------------------------- kernels
def _quad_creep(g, x, shift, kinks):
    """``∫_0^inf exp(-z) g(x + shift z) dz`` by adaptive quadrature split at the kinks."""
    f = lambda z: np.exp(-z) * g(x + shift * z)  # noqa: E731
    pts = sorted(p for p in ((k - x) / shift for k in kinks) if 0 < p < 60)
    edges = [0.0, *pts, 60.0]
    val = sum(integrate.quad(f, a, b, epsabs=0, epsrel=1e-13, limit=400)[0] for a, b in zip(edges, edges[1:]))
    return val + integrate.quad(f, 60.0, np.inf)[0]


def test_love_formula_against_quadrature_in_all_quadrants():
    w = 1.0
    # centre: (1/pi) 4 w ln(1 + sqrt 2) exactly
    assert influence.square_elastic(0.0, 0.0, w) == pytest.approx(4 * w * np.log(1 + np.sqrt(2)) / np.pi, rel=1e-14)
    for x, y in [(0.2, 0.1), (-0.3, 0.45), (-1.7, 0.4), (2.3, -3.1), (-0.6, -2.2), (5.0, 0.0), (80.0, -30.0)]:
        # split the square at the field point, so that 1/r is singular only at sub-rectangle corners
        xs = sorted({-w / 2, w / 2, *([x] if abs(x) < w / 2 else [])})
        ys = sorted({-w / 2, w / 2, *([y] if abs(y) < w / 2 else [])})
        ref = (
            sum(
                integrate.dblquad(
                    lambda t, s, x=x, y=y: 1.0 / np.hypot(x - s, y - t), s0, s1, t0, t1, epsabs=0, epsrel=1e-11
                )[0]
                for s0, s1 in zip(xs, xs[1:])
                for t0, t1 in zip(ys, ys[1:])
            )
            / np.pi
        )
        # 1e-9: adaptive quadrature of the corner singularities reaches ~1e-11
        assert influence.square_elastic(x, y, w) == pytest.approx(ref, rel=1e-9)


@pytest.mark.parametrize("shift", [1e-3, 0.3, 1.0, 7.3, 1e3])
def test_square_creep_kernel_against_brute_force_quadrature(shift):
    n, w = 12, 1.0
    table = influence.square_creep(n, w, shift)
    m = np.arange(-(2 * n - 1), 2 * n)
    for mi, j in [(0, 0), (1, 0), (-1, 0), (2, 0), (-2, 0), (-6, 1), (5, 2), (-20, 3), (23, 11), (-23, 0)]:
        ref = _quad_creep(lambda s, j=j: influence.square_elastic(s, j * w, w), mi * w / 2, shift, (-w / 2, w / 2))
        # measured <= 5e-11 (Gauss–Legendre on graded half elements); quad itself ~1e-13
        assert table[m == mi, j][0] == pytest.approx(ref, rel=1e-9)


def test_square_creep_sum_shares_work_exactly():
    shifts, weights = [0.004, 0.3, 2.0, 50.0], [1.0, 2.0, 3.0, 4.0]
    total = influence.square_creep_sum(10, 1.0, shifts, weights)
    single = sum(c * influence.square_creep(10, 1.0, s) for s, c in zip(shifts, weights))
    assert np.allclose(total, single, rtol=1e-13, atol=0)  # same arithmetic, summed in another order


@pytest.mark.parametrize("shift", [1e-4, 0.2, 13.0, 1e3])
def test_strip_creep_kernel_against_brute_force_quadrature(shift):
    w, ell = 1.0, 37.0
    const = -(2 / np.pi) * w * (np.log(shift / ell) - np.euler_gamma)  # the dropped constant
    for x in [0.0, 0.5, -0.5, 1.0, -3.0, 7.0, -30.0]:
        ref = _quad_creep(lambda s: influence.strip_elastic(s, w, ell), x, shift, (-w / 2, w / 2))
        # closed form to ~1e-13; quad of the log kink and the 1e3 tail limits the check to ~1e-9
        assert influence.strip_creep(x, w, shift) + const == pytest.approx(ref, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("dim", [1, 2])
def test_creep_kernels_reach_both_elastic_limits_without_cancellation(dim):
    """A creep term of shift L = v lambda tends to G (L -> 0) and to a constant (L -> inf). At
    L = 1e13 d a kernel that cancels catastrophically (docs/theory.md §12) would be off by ~eps L/d = 1e-3."""
    n, d = 16, 1.0
    m = np.arange(-(2 * n - 1), 2 * n)
    if dim == 1:

        def creep(shift):
            k = influence.strip_creep(m * d / 2, d, shift)
            return k - k[2 * n - 1]  # plane strain: only differences are defined

        el = influence.strip_elastic(m * d / 2, d, n * d)
        el = el - el[2 * n - 1]
    else:
        creep = lambda shift: influence.square_creep(n, d, shift)  # noqa: E731
        el = influence.square_elastic(m[:, None] * d / 2, d * np.arange(n)[None, :], d)
    scale = np.max(np.abs(el))
    # physical remainders: O((d/L) ln(L/d)) ~ 3e-12 at L = 1e13 d; O(L/d ln(d/L)) ~ 2e-9 at
    # L = 1e-10 d (log-singular slope of G at the element edges)
    assert np.max(np.abs(creep(1e13 * d))) <= 1e-10 * scale
    assert np.max(np.abs(creep(1e-10 * d) - el)) <= 1e-8 * scale
    # and in between the creep term is genuinely different from both limits
    assert np.max(np.abs(creep(3.0 * d) - el)) > 0.1 * scale and np.max(np.abs(creep(3.0 * d))) > 0.1 * scale


def test_inactive_creep_terms_are_folded():
    """Terms with v lambda < 1e-6 d act as relaxed, > 1e6 length as glassy (docs/theory.md §11)."""
    mat = bem.Material.from_creep(E0=1e6, compliances=[3e-7, 4e-7, 2e-7], times=[1e8, 1.0, 1e-7])
    n, length, v = 16, 1e-2, 1e-3  # v lambda: 1e5 m (glassy), 1e-3 m (active), 1e-10 m (relaxed)
    op = IsolatedHalfSpace((n, n), length, mat, v)
    active = bem.Material.from_creep(E0=1.0 / (1.0 / mat.E_inf + 6e-7), compliances=[4e-7], times=[1.0])
    ref = IsolatedHalfSpace((n, n), length, active, v)
    # folding errors O(v lambda / d) = 1.6e-7 and O(length / v lambda) = 1e-7 relative
    assert np.allclose(op.kernel, ref.kernel, rtol=2e-6, atol=0)


def test_strip_kernel_matches_independent_dense_reference():
    mat, n, length, v = sls(), 40, 0.004, 0.05
    op = IsolatedHalfSpace((n,), length, mat, v)
    d = length / n
    ref = strip_kernel(d * np.arange(-(n - 1), n), d, mat, v)
    # same physics, constants differ: compare up to a constant (round-off level agreement)
    diff = (op.kernel - op.kernel[n - 1]) - (ref - ref[n - 1])
    assert np.max(np.abs(diff)) <= 1e-10 * np.max(np.abs(ref - ref[n - 1]))


# ----------------------------------------------------------------------------- operator
@pytest.mark.parametrize("dim,n", [(1, 30), (2, 7)])
def test_operator_is_the_toeplitz_product_and_dissipates(dim, n):
    mat = sls(10.0)
    op = IsolatedHalfSpace((n,) * dim, 1e-3, mat, 0.02)
    a = dense(op)
    rng = np.random.default_rng(3)
    # DC-FFT = direct Toeplitz sum (no periodic images): column j is the kernel shifted to j
    k = op.kernel
    j = n // 3 if dim == 1 else (n // 3) * n + 2
    e = np.zeros(op.shape)
    e.flat[j] = 1.0
    if dim == 1:
        expect = k[np.arange(n) - j + n - 1]
    else:
        ix, iy = np.unravel_index(j, op.shape)
        expect = k[np.arange(n)[:, None] - ix + n - 1, np.arange(n)[None, :] - iy + n - 1].ravel()
    assert np.allclose(a[:, j], expect, rtol=1e-12, atol=1e-12 * np.abs(k).max())
    assert not np.allclose(a, a.T, rtol=1e-3, atol=0)  # steady sliding is not symmetric
    sym = dense(op.symmetric_part())
    assert np.allclose(sym, 0.5 * (a + a.T), rtol=1e-12, atol=1e-12 * np.abs(a).max())
    # positive dissipation for random (even sign-changing) pressures; zero for the symmetric part
    for _ in range(5):
        p = rng.standard_normal(op.shape)
        assert op.dissipation_integral(p) > 0
        assert abs(op.symmetric_part().dissipation_integral(p)) < 1e-12 * abs(op.dissipation_integral(p))
    # symmetric part positive definite on zero-mean pressures (what the contact solver needs)
    if dim == 2:
        assert np.linalg.eigvalsh(0.5 * (a + a.T)).min() > 0
    else:
        q = np.eye(n) - 1.0 / n
        assert np.linalg.eigvalsh(q @ (0.5 * (a + a.T)) @ q)[1:].min() > 0


# ----------------------------------------------------------------------------- Hunter (plane strain)
@pytest.mark.parametrize("ratio", [3.0, 100.0])
def test_rolling_cylinder_matches_hunter(ratio):
    """2000 cells over 3 relaxed contact widths; speeds V lam / a0 = 0.03 .. 30."""
    mat, load = sls(ratio), 1000.0
    a0 = line_contact(mat.E0, mat.nu, R, load).a
    cyl = bem.surfaces.cylinder(radius=R, n=2000, length=6 * a0)
    d = cyl.spacing
    for xi in (0.03, 0.3, 3.0, 30.0):
        v = xi * a0 / mat.creep_times[0]
        ref = rolling_cylinder(mat, radius=R, load=load, speed=v)
        res = bem.solve(cyl, mat, speed=v, load=load, periodic=False, rtol=1e-10)
        inside = np.flatnonzero(res.pressure > 0)
        lead, trail = cyl.x[inside[-1]] + d / 2, cyl.x[inside[0]] - d / 2
        # measured <= 1.6e-3 (ratio 100, xi 0.03: leading-edge layer V tau ~ 0.1 cell); issue: 0.5 %
        assert res.friction == pytest.approx(ref.friction, rel=5e-3)
        assert res.friction_eq6 == pytest.approx(ref.friction, rel=5e-3)
        # edges are resolved to the cell (measured <= 0.7 cells); issue: two cells
        assert abs(lead - ref.leading_edge) <= 2 * d and abs(trail - ref.trailing_edge) <= 2 * d
        assert res.load == pytest.approx(load, rel=1e-12)


def test_cylinder_low_speed_friction_for_a_creep_series():
    """mu -> (V/R) E0 sum_k C_k lam_k for two creep terms (Hunter covers one term only)."""
    mat = bem.Material.from_creep(E0=1e6, compliances=[3e-7, 4e-7], times=[0.01, 0.1])
    load = 1000.0
    a0 = line_contact(mat.E0, mat.nu, R, load).a
    cyl = bem.surfaces.cylinder(radius=R, n=1500, length=4 * a0)
    v = 0.003 * a0 / mat.creep_times.max()
    res = bem.solve(cyl, mat, speed=v, load=load, periodic=False)
    # next order is O(V lam / a) (Hunter: -0.67 V lam / a = -0.2 % here); the grid adds < 0.2 %
    assert res.friction == pytest.approx(low_speed_friction(mat, radius=R, speed=v), rel=1e-2)


def test_friction_curve_isolated_is_bell_shaped_and_matches_single_solves():
    mat, load = sls(), 1000.0
    a0 = line_contact(mat.E0, mat.nu, R, load).a
    cyl = bem.surfaces.cylinder(radius=R, n=600, length=6 * a0)
    speeds = np.array([0.03, 1.0, 30.0]) * a0 / mat.creep_times[0]
    curve = bem.friction_curve(cyl, mat, speeds=speeds, load=load, periodic=False)
    assert curve.all_converged
    assert curve.friction[1] > curve.friction[0] and curve.friction[1] > curve.friction[2]
    single = bem.solve(cyl, mat, speed=speeds[1], load=load, periodic=False)
    # warm start changes only the path: both meet rtol = 1e-8
    assert curve.friction[1] == pytest.approx(single.friction, rel=1e-6)


# ----------------------------------------------------------------------------- sphere (3-D)
def _hertz_errors(res, sphere, ref):
    area = np.count_nonzero(res.pressure > 0) * sphere.spacing**2
    return np.sqrt(area / np.pi) / ref.a - 1, res.pressure.max() / ref.p0 - 1


def test_sphere_elastic_limits_match_hertz_coarse():
    """64² over 4 relaxed contact radii (a0 = 16 cells): both elastic limits."""
    mat, load = sls(), 1.0
    a0 = point_contact(mat.E0, mat.nu, R, load).a
    sph = bem.surfaces.sphere(radius=R, n=64, length=4 * a0)
    for speed, modulus in ((0.0, mat.E0), (1e3 * a0 / mat.creep_times[0], mat.E_inf)):
        ref = point_contact(modulus, mat.nu, R, load)
        res = bem.solve(sph, mat, speed=speed, load=load, periodic=False)
        da, dp = _hertz_errors(res, sph, ref)
        # radius from the contact area: one ring of cells is d / (2a) = 3 % (5.4 % glassy); measured 0.7 %.
        # peak: measured 0.2 %; the glassy limit keeps a creep remainder O(a / V lam) = 0.1 %
        assert abs(da) < (0.03 if speed == 0 else 0.054) and abs(dp) < 0.01
        if speed == 0:
            assert res.approach == pytest.approx(ref.delta, rel=3e-3)  # measured 6e-4 (second order)
            assert abs(res.friction) < 1e-12
        else:
            assert 0 < res.friction < 1e-3 * low_speed_friction(mat, radius=R, speed=speed)


@pytest.mark.slow
def test_sphere_elastic_limits_match_hertz_256():
    mat, load = sls(), 1.0
    a0 = point_contact(mat.E0, mat.nu, R, load).a
    sph = bem.surfaces.sphere(radius=R, n=256, length=4 * a0)
    for speed, modulus in ((0.0, mat.E0), (1e3 * a0 / mat.creep_times[0], mat.E_inf)):
        ref = point_contact(modulus, mat.nu, R, load)
        res = bem.solve(sph, mat, speed=speed, load=load, periodic=False)
        da, dp = _hertz_errors(res, sph, ref)
        assert abs(da) < 0.02 and abs(dp) < 0.02  # issue's bar; measured 0.1 % and 0.02 %


def test_sphere_low_speed_friction_asymptote():
    """V lam / a0 = 0.01 on 96²: mu -> (V lam / R)(1 - E0/E_inf)."""
    mat, load = sls(), 1.0
    a0 = point_contact(mat.E0, mat.nu, R, load).a
    sph = bem.surfaces.sphere(radius=R, n=96, length=3 * a0)
    v = 0.01 * a0 / mat.creep_times[0]
    res = bem.solve(sph, mat, speed=v, load=load, periodic=False)
    lin = low_speed_friction(mat, radius=R, speed=v)
    assert lin == pytest.approx(v * mat.creep_times[0] / R * (1 - mat.E0 / mat.E_inf), rel=1e-12)
    # next order ~ -0.7 V lam / a (Hunter's line contact: -0.67 %); grid error measured 0.2-1.4 %
    # on 64²-128² (the leading-edge layer V tau = 0.1 cell is unresolved): 2 %
    assert res.friction == pytest.approx(lin, rel=0.02)
    assert res.friction_eq6 == pytest.approx(lin, rel=0.03)  # eq. 6: measured -2.1 %


@pytest.mark.parametrize("dim", [1, 2])
def test_low_speed_friction_on_a_coarse_grid_has_no_sub_cell_log_error(dim):
    """Shifts v lambda far below a cell: friction still on the asymptote (V lam / R)(1 - E0/E_inf).

    The exact dissipation of the piecewise-constant pressure (the friction before the fix) adds
    the dissipation of its steps between elements, ~ L ln(d / L) per step, which a smooth pressure
    does not have: on these grids it was +29 % / +15 % / +1.4 % (sphere, 64 cells on 3 a0) and
    +20 % / +10 % / +0.2 % (cylinder, 60 cells) at s = V lam / a0 = 1e-4 / 1e-3 / 1e-2, and grew
    without bound as s -> 0. The collocated slope measures -1.3 % / -1.2 % / +1.2 % and
    -1.7 % / -1.7 % / -0.1 % (collocation error ~ d / a, falling with the grid; next order of the
    asymptote ~ -0.67 s): 3 %. Between s = 1e-4 and 1e-3 (both far below a cell, L/d = 2e-3 and
    2e-2) the relative error must not move (old: by 15 % / 10 %; now 0.06 % / 0.03 %, the next
    order -0.67 s accounts for 0.06 %): 0.5 %.
    """
    mat = sls()
    if dim == 2:
        load = 1.0
        a0 = point_contact(mat.E0, mat.nu, R, load).a
        surface = bem.surfaces.sphere(radius=R, n=64, length=3 * a0)
    else:
        load = 1000.0
        a0 = line_contact(mat.E0, mat.nu, R, load).a
        surface = bem.surfaces.cylinder(radius=R, n=60, length=3 * a0)
    errors = []
    for s in (1e-4, 1e-3, 1e-2):
        v = s * a0 / mat.creep_times[0]
        res = bem.solve(surface, mat, speed=v, load=load, periodic=False, rtol=1e-10)
        errors.append(res.friction / low_speed_friction(mat, radius=R, speed=v) - 1)
    assert max(abs(e) for e in errors) < 0.03, errors
    assert abs(errors[0] - errors[1]) < 0.005, errors


def test_sliding_sphere_signs():
    """Pressure peak and centroid ahead (+x), trailing side shrinks, friction positive."""
    mat, load = sls(), 1.0
    a0 = point_contact(mat.E0, mat.nu, R, load).a
    sph = bem.surfaces.sphere(radius=R, n=48, length=3 * a0)
    res = bem.solve(sph, mat, speed=0.3 * a0 / mat.creep_times[0], load=load, periodic=False)
    px = res.pressure.sum(axis=1)
    x = sph.x
    assert np.sum(px * x) / px.sum() > 2 * sph.spacing
    assert x[np.argmax(px)] > 0
    inside = np.flatnonzero(px > 0)
    assert x[inside[-1]] > -x[inside[0]]  # leading edge farther out than the trailing one
    assert res.friction > 0 and res.friction_eq6 > 0 and res.dissipated_power > 0
    assert res.dissipated_power == pytest.approx(res.friction * load * res.speed)
    assert np.all(res.gap >= -1e-8 * np.ptp(sph.heights)) and np.all(res.pressure >= 0)


def test_grid_convergence_rate():
    """Second order: approach of the elastic sphere against Hertz, and of the sliding sphere
    against its finer grid (n = 24, 48, 96, 192; 3 relaxed contact radii)."""
    mat, load = sls(), 1.0
    ref = point_contact(mat.E0, mat.nu, R, load)
    v = 0.3 * ref.a / mat.creep_times[0]
    ns = np.array([24, 48, 96, 192])
    elastic, sliding = [], []
    for n in ns:
        sph = bem.surfaces.sphere(radius=R, n=int(n), length=3 * ref.a)
        if n < 192:
            elastic.append(abs(bem.solve(sph, mat, speed=0.0, load=load, periodic=False).approach / ref.delta - 1))
        sliding.append(bem.solve(sph, mat, speed=v, load=load, periodic=False).approach)
    rate_el = -np.polyfit(np.log(ns[:3]), np.log(elastic), 1)[0]
    rate_sl = -np.polyfit(np.log(ns[:3]), np.log(np.abs(np.diff(sliding))), 1)[0]
    # measured 2.05 and 2.03: piecewise-constant collocation of a smooth field is second order
    assert 1.8 < rate_el < 2.3 and 1.7 < rate_sl < 2.4


def test_displacement_control_matches_hertz_load():
    mat = bem.Material.elastic(1e7)
    ref = point_contact(1e7, 0.5, R, 1.0)
    sph = bem.surfaces.sphere(radius=R, n=64, length=4 * ref.a)
    res = bem.solve(sph, mat, speed=0.0, approach=ref.delta, periodic=False)
    assert res.load == pytest.approx(1.0, rel=5e-3)  # measured 1.8e-3 (second order in d)


# ----------------------------------------------------------------------------- surfaces and input
def test_indenter_geometry():
    s = bem.surfaces.sphere(radius=2.0, n=4, length=4.0)
    assert s.centered and s.shape == (4, 4)
    assert s.x.tolist() == [-1.5, -0.5, 0.5, 1.5]
    assert s.heights[1, 2] == pytest.approx(-(0.25 + 0.25) / 4.0)
    c = bem.surfaces.cylinder(radius=2.0, n=5, length=2.0, exact=True)
    assert c.heights[2] == 0.0 and c.heights[0] == pytest.approx(np.sqrt(4.0 - 0.64) - 2.0)


def test_bad_input():
    with pytest.raises(InputError, match="radius"):
        bem.surfaces.sphere(radius=-1.0, n=8, length=1.0)
    with pytest.raises(InputError, match="length must be <"):
        bem.surfaces.sphere(radius=1.0, n=8, length=1.5, exact=True)
    with pytest.raises(InputError, match="length must be <"):
        bem.surfaces.cylinder(radius=1.0, n=8, length=2.0, exact=True)
    with pytest.raises(InputError, match="n must be"):
        bem.surfaces.cylinder(radius=1.0, n=1, length=1.0)
    s = bem.surfaces.cylinder(radius=1.0, n=8, length=1.0)
    with pytest.raises(InputError, match="periodic"):
        bem.solve(s, sls(), speed=1.0, load=1.0, periodic="no")
    with pytest.raises(InputError, match="method"):
        bem.solve(s, sls(), speed=1.0, load=1.0, periodic=False, method="active-set")
    with pytest.raises(InputError, match="method"):
        bem.solve(s, sls(), speed=1.0, load=1.0, periodic=True, method="uniform")
    with pytest.raises(InputError, match="'levels' is an option of method='adaptive'"):
        bem.solve(s, sls(), speed=1.0, load=1.0, periodic=False, levels=3)


# ----------------------------------------------------------------------------- built-in scene
def test_sphere_scene_runs_small(tmp_path):
    """The built-in sphere scene (``viscobem run sphere``), shrunk to 24² and 3 speeds."""
    import json

    from viscobem_cli import scene as scenes
    from viscobem_cli.run.study import run_scene

    full = scenes.load("sphere")
    assert full.surface.centered and not full.periodic and full.surface.shape == (128, 128)
    text = (scenes.SCENE_DIR / "sphere.toml").read_text()
    small = scenes.parse(text.replace("n = 128", "n = 24").replace("num = 16", "num = 3"), source="small")
    record = run_scene(small, tmp_path, progress=False)
    assert record["all_converged"] and record["solver"]["periodic"] is False
    mu = record["friction_curve"]["friction"]
    assert mu[1] > mu[0] > 0 and mu[1] > mu[2] > 0  # the bell: xi = 1e-3, 0.32, 100
    for name in ("results.json", "fields.npz", "friction_curve.png", "pressure_maps.png", "contact_outlines.png"):
        assert (tmp_path / name).stat().st_size > 0
    assert json.loads((tmp_path / "results.json").read_text())["complete"]


def test_scene_rejects_bad_indenter_settings():
    from viscobem_cli import scene as scenes

    text = (scenes.SCENE_DIR / "sphere.toml").read_text()
    with pytest.raises(InputError, match="radius"):
        scenes.parse(text.replace("radius = 0.01", ""), source="x")
    with pytest.raises(InputError, match="method"):
        scenes.parse(text.replace("periodic = false", 'periodic = false\nmethod = "active-set"'), source="x")
    with pytest.raises(InputError, match="periodic"):
        scenes.parse(text.replace("periodic = false", 'periodic = "no"'), source="x")
