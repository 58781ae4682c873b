"""Exact solutions of the periodic solver: Westergaard's sinusoid and full contact of rough surfaces.

Westergaard (validation.references.westergaard) is checked on its own first (mean pressure and the
contact condition under the plane-strain symbol ``2 / (E* |q|)``), then used as the reference
of the elastic solver. In full contact the steady-sliding problem is linear and its exact
solution is the Fourier one, ``p = p_mean + A^-1 (h - mean h)``, for any material and speed.
"""

import numpy as np
import pytest
from conftest import make_prony30, make_seed
from scipy import integrate

import bem
from bem import surfaces
from validation.references.westergaard import westergaard

E, NU, LAM, G0 = 1e7, 0.3, 1e-3, 1e-5  # nu != 0.5 so that the 1 - nu**2 factor is exercised
E_STAR = E / (1 - NU**2)
P_STAR = np.pi * E_STAR * G0 / LAM


# ------------------------------------------------------------ the reference itself
@pytest.mark.parametrize("frac", [0.1, 0.5, 0.9, 1.5])
def test_westergaard_mean_pressure_is_the_load(frac):
    sol = westergaard(G0, LAM, frac * P_STAR, E, NU)
    mean, _ = integrate.quad(sol.pressure, -LAM / 2, LAM / 2, points=[-sol.half_width, sol.half_width], limit=200)
    # quad on a smooth integrand (sqrt edges are endpoints): round-off level
    assert mean / LAM == pytest.approx(sol.mean_pressure, rel=1e-12)
    assert sol.full_contact == (frac >= 1)
    assert np.all(sol.pressure(np.linspace(-LAM, LAM, 1001)) >= 0)


@pytest.mark.parametrize("frac", [0.1, 0.5, 0.9])
def test_westergaard_closes_the_gap_in_contact_only(frac):
    """Under ``u_q = 2 p_q / (E* |q|)`` the exact pressure makes ``u - h`` constant in contact.

    Checked with numpy's FFT on 2**16 points, independent of bem. The sampled pressure has
    square-root edges, so the sampled displacement carries an aliasing error that falls
    like ``dx**1.5`` (measured 5e-7 g0 at 2**16, 5e-6 g0 at 2**14); 1e-5 g0 bounds it, while
    a wrong factor in ``p*`` or ``a`` leaves an O(g0) residual.
    """
    sol = westergaard(G0, LAM, frac * P_STAR, E, NU)
    n = 2**16
    x = np.arange(n) * LAM / n
    p = sol.pressure(x)
    q = 2 * np.pi * np.fft.rfftfreq(n, LAM / n)
    uq = np.zeros(q.size, complex)
    uq[1:] = 2 * np.fft.rfft(p)[1:] / (E_STAR * q[1:])
    gap = np.fft.irfft(uq, n) - G0 * np.cos(2 * np.pi * x / LAM)
    contact = p > 0
    gap -= gap[contact].mean()
    assert np.ptp(gap[contact]) < 1e-5 * G0
    assert gap[~contact].min() > -1e-5 * G0
    assert contact.mean() == pytest.approx(2 * sol.half_width / LAM, abs=2 / n)


def test_westergaard_full_contact_is_the_fourier_solution():
    sol = westergaard(G0, LAM, 2 * P_STAR, E, NU)
    x = np.linspace(0, LAM, 9)
    assert sol.half_width == LAM / 2
    np.testing.assert_allclose(sol.pressure(x), 2 * P_STAR + P_STAR * np.cos(2 * np.pi * x / LAM), rtol=1e-14)


# ------------------------------------------------------------ elastic solver vs Westergaard
def _westergaard_solve(n, frac, **kw):
    sol = westergaard(G0, LAM, frac * P_STAR, E, NU)
    surface = surfaces.sinusoid(n, LAM, amplitude=G0)
    res = bem.solve(surface, bem.Material.elastic(E, NU), speed=0.0, load=sol.load, rtol=1e-10, **kw)
    x = np.arange(n) * LAM / n
    return sol, res, sol.pressure(x)


def test_westergaard_full_contact_to_round_off():
    sol, res, exact = _westergaard_solve(256, 1.5)
    assert res.contact_fraction == 1.0
    np.testing.assert_allclose(res.pressure, exact, rtol=0, atol=1e-12 * sol.mean_pressure)


def test_westergaard_partial_contact_converges_at_first_order():
    """``a = lam / 4`` (``p_mean = p*/2``) sits on a grid point for every ``n`` here, so the
    edge is placed alike on every grid and the error sequence is clean. The sampled solution
    misses the square-root edge by O(dx): the relative L2 error falls like ``dx`` (measured
    slope -1.000, err * n = 0.86) and the maximum error like ``dx**0.5``."""
    ns = np.array([256, 512, 1024, 2048])
    l2, linf = [], []
    for n in ns:
        sol, res, exact = _westergaard_solve(n, 0.5)
        assert sol.half_width == pytest.approx(LAM / 4, rel=1e-14)
        assert res.load == pytest.approx(sol.load, rel=1e-12)
        width = np.count_nonzero(res.pressure > 0) * LAM / n
        assert abs(width - 2 * sol.half_width) <= 2 * LAM / n  # contact width within 2 cells
        l2.append(np.sqrt(np.mean((res.pressure - exact) ** 2) / np.mean(exact**2)))
        linf.append(np.max(np.abs(res.pressure - exact)) / exact.max())
    rate_l2 = np.polyfit(np.log(ns), np.log(l2), 1)[0]
    rate_linf = np.polyfit(np.log(ns), np.log(linf), 1)[0]
    assert -1.1 < rate_l2 < -0.9
    assert -0.6 < rate_linf < -0.4
    assert l2[-1] < 1e-3


@pytest.mark.parametrize("frac", [0.05, 0.3, 0.77])
def test_westergaard_half_width_within_two_cells(frac):
    """Any load: the edge falls anywhere in a cell, so the count of contact points is
    ``2 a / dx`` within the two edge cells; the L2 error stays at the O(dx) level."""
    n = 1024
    sol, res, exact = _westergaard_solve(n, frac)
    width = np.count_nonzero(res.pressure > 0) * LAM / n
    assert abs(width - 2 * sol.half_width) <= 2 * LAM / n
    assert np.sqrt(np.mean((res.pressure - exact) ** 2) / np.mean(exact**2)) < 3.0 / n


# ------------------------------------------------------------ full contact of rough surfaces
def _exact_full_contact(h, length, material, speed, mean_pressure):
    """``p = p_mean + A^-1 (h - mean h)`` with ``A`` built here from ``1 / E*(w)`` (the complex
    modulus, not the creep series the operator uses) and numpy's full-spectrum FFT; returns
    the pressure and eq. 6's friction ``-(1/p_mean) mean(p dh/dx)``."""
    hq = np.fft.fftn(h) / h.size
    q = np.meshgrid(*[2 * np.pi * np.fft.fftfreq(n, length / n) for n in h.shape], indexing="ij")
    qn = np.sqrt(sum(c**2 for c in q))
    qn[(0,) * h.ndim] = 1.0
    pq = hq * qn * material.complex_modulus(-q[0] * speed) / (2 * (1 - material.nu**2))
    pq[(0,) * h.ndim] = 0.0
    p = mean_pressure + np.real(np.fft.ifftn(pq) * h.size)
    dhdx = np.real(np.fft.ifftn(1j * q[0] * hq) * h.size)
    return p, (-np.mean(p * dhdx) / mean_pressure if mean_pressure > 0 else np.nan)


XIS = np.logspace(-4, 2, 7)


@pytest.mark.parametrize("material_name, tau", [("seed", 0.01), ("prony30", 1.0)])
@pytest.mark.parametrize("dim, n", [(1, 512), (2, 64)])
def test_full_contact_is_exact(material_name, tau, dim, n):
    """Pressure and friction equal the Fourier solution to round-off at every speed.

    ``scales = n / 4`` keeps the spectrum off the Nyquist modes. The load is twice what the
    most demanding speed needs for full contact. Tolerance 1e-10: the solve is one
    Fourier division (round-off 1e-15 relative); eq. 6 sums ``p dh/dx`` of both signs, which
    loses up to ``slope / mu`` ~ 1e3 of that (measured worst 3e-13).
    """
    material = make_seed() if material_name == "seed" else make_prony30()
    length = 1e-3
    s = surfaces.self_affine(n, length, hurst=0.8, scales=n // 4, rms_height=1e-6, seed=5, dim=dim)
    speeds = XIS * length / tau  # xi = v tau / L
    p_mean = -2 * min(_exact_full_contact(s.heights, length, material, v, 0.0)[0].min() for v in speeds)
    for v in speeds:
        p, mu = _exact_full_contact(s.heights, length, material, v, p_mean)
        res = bem.solve(s, material, speed=v, load=p_mean * length**dim)
        assert res.contact_fraction == 1.0 and res.iterations == 1
        np.testing.assert_allclose(res.pressure, p, rtol=0, atol=1e-10 * p_mean)
        assert mu > 0
        assert res.friction == pytest.approx(mu, rel=1e-10)
        assert res.friction_eq6 == pytest.approx(res.friction, rel=1e-10)
        assert res.dissipated_power == pytest.approx(mu * res.load * v, rel=1e-10)


@pytest.mark.parametrize("shape", [(64,), (65,), (32, 32), (33, 33)])
def test_full_contact_friction_forms_agree_with_nyquist_content(shape):
    """White-noise heights fill every mode, the Nyquist ones included (even n): the two
    friction forms still coincide to round-off (measured <= 1.1e-15; bound 1e-12), since the
    symbol is real there and neither form takes dissipation from those modes."""
    m = make_seed()
    h = np.random.default_rng(1).standard_normal(shape) * 1e-8
    p, _ = _exact_full_contact(h, LAM, m, 0.3 * LAM / 0.01, 0.0)
    res = bem.solve(surfaces.from_heights(h, LAM), m, speed=0.3 * LAM / 0.01, load=-2 * p.min() * LAM ** len(shape))
    assert res.contact_fraction == 1.0 and res.friction > 0
    assert res.friction_eq6 == pytest.approx(res.friction, rel=1e-12)


@pytest.mark.parametrize("xi", [0.0, 0.1])
def test_ridges_in_2d_are_the_plane_strain_profile(xi):
    """A 2-D surface invariant along y is the 1-D profile (plane strain): same symbol, since
    ``|q| = |q_x|`` on the ``q_y = 0`` column. Loads: ``p_mean L**2`` (N) and ``p_mean L`` (N/m).
    Both solves reach rtol 1e-12 on the same LCP: bound 1e-9 relative."""
    m, n = make_seed(), 128
    profile = surfaces.sinusoid(n, LAM, amplitude=G0)
    ridges = surfaces.sinusoid(n, LAM, amplitude=G0, dim=2, direction="x")
    p_mean = 0.3 * np.pi * m.E0 / (1 - m.nu**2) * G0 / LAM
    one = bem.solve(profile, m, speed=xi * LAM / 0.01, load=p_mean * LAM, rtol=1e-12)
    two = bem.solve(ridges, m, speed=xi * LAM / 0.01, load=p_mean * LAM**2, rtol=1e-12)
    np.testing.assert_allclose(two.pressure, one.pressure[:, None] * np.ones(n), rtol=0, atol=1e-9 * one.pressure.max())
    assert two.friction == pytest.approx(one.friction, rel=1e-9, abs=1e-15)
    assert two.approach == pytest.approx(one.approach, rel=1e-9)


@pytest.mark.slow
def test_westergaard_convergence_to_16k():
    """As the first-order test, over n = 256..16384: measured slope -1.000, err * n = 0.86."""
    ns = 2 ** np.arange(8, 15)
    l2 = []
    for n in ns:
        sol, res, exact = _westergaard_solve(int(n), 0.5)
        l2.append(np.sqrt(np.mean((res.pressure - exact) ** 2) / np.mean(exact**2)))
    assert -1.05 < np.polyfit(np.log(ns), np.log(l2), 1)[0] < -0.95
    assert l2[-1] * ns[-1] < 1.0


@pytest.mark.slow
def test_westergaard_16k_without_the_coarse_start_needs_the_ascent_damping():
    """From the full-contact start (``coarsen=False``) the plain Newton steps of 16384 points cycle
    (400 steps at residual ~800 measured); damped after ``CYCLING_STEPS`` rising residuals in a row
    (``bem.contact.newton``) they converge (66 steps measured). The coarse start takes 2 steps."""
    _, res, _ = _westergaard_solve(16384, 0.5, contact_options=bem.contact.ContactOptions(coarsen=False))
    assert res.success
