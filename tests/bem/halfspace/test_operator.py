"""Properties of the periodic steady-sliding operator (bem.halfspace.periodic.PeriodicHalfSpace).

Every check here is exact up to round-off (FFTs of size <= 64**2: a few 1e-15 relative),
so the bounds are 1e-12 unless stated.
"""

import numpy as np
import pytest
from conftest import dense_operator, make_prony30, make_seed

from bem import Material
from bem.halfspace.periodic import PeriodicHalfSpace

L = 1e-3
SHAPES = [(64,), (63,), (16, 16), (15, 15)]  # even and odd n: with and without Nyquist modes
RNG = np.random.default_rng(20261121)


def _op(shape, material=None, xi=1.0):
    material = make_seed() if material is None else material
    return PeriodicHalfSpace(shape, L, material, speed=xi * L / 0.01)


def _rel(a, b):
    return np.max(np.abs(a - b)) / np.max(np.abs(b))


@pytest.mark.parametrize("shape", SHAPES)
def test_linearity(shape):
    op = _op(shape)
    p, r = RNG.random(shape), RNG.random(shape)
    combo = op.displacement(2.5 * p - 0.7 * r)
    assert _rel(combo, 2.5 * op.displacement(p) - 0.7 * op.displacement(r)) < 1e-12
    assert np.isrealobj(combo) and combo.shape == shape
    assert abs(combo.mean()) < 1e-12 * np.abs(combo).max()  # zero mean: the approach carries it


@pytest.mark.parametrize("shape", [(32,), (12, 12)])
def test_symmetric_only_in_the_elastic_limit(shape):
    elastic = dense_operator(_op(shape, Material.elastic(1e7)))
    at_rest = dense_operator(_op(shape, xi=0.0))
    sliding = _op(shape, xi=1.0)
    dense = dense_operator(sliding)
    assert _rel(elastic, elastic.T) < 1e-14 and _rel(at_rest, at_rest.T) < 1e-14
    # seed material at xi = 1: the loss tangent is O(1), so the skew part is O(1) of the whole
    assert np.linalg.norm(dense - dense.T) > 0.1 * np.linalg.norm(dense)
    assert not sliding.is_symmetric
    sym = dense_operator(sliding.symmetric_part())
    assert _rel(sym, 0.5 * (dense + dense.T)) < 1e-12
    assert np.linalg.eigvalsh(sym + np.ones_like(sym)).min() > 0  # positive definite but for q = 0


@pytest.mark.parametrize("shape", [(32,), (33,), (12, 12), (11, 11)])
def test_reflection_in_x_transposes_and_in_y_commutes(shape):
    """Mirroring x is sliding the other way, and the operator of ``-v`` is the transpose:
    ``R_x A R_x = A^T``; mirroring y changes nothing, ``R_y A R_y = A``."""
    op = _op(shape, make_prony30(), xi=1e-3)
    A = dense_operator(op)
    idx = np.arange(op.size).reshape(shape)
    rx = np.roll(idx[::-1], 1, axis=0).ravel()  # j -> -j mod n along x
    assert _rel(A[np.ix_(rx, rx)], A.T) < 1e-12
    if len(shape) == 2:
        ry = np.roll(idx[:, ::-1], 1, axis=1).ravel()
        assert _rel(A[np.ix_(ry, ry)], A) < 1e-12


@pytest.mark.parametrize("shape", SHAPES)
def test_matches_the_full_spectrum_symbol(shape):
    """Against ``2 (1 - nu**2) / |q| / E*(w = -q_x v)`` on numpy's full spectrum: for odd n the
    complex result is real; for even n the x-Nyquist mode makes it complex and the operator
    keeps its real part (docs/theory.md §12: the symbol is not Hermitian there)."""
    m = make_prony30()
    op = _op(shape, m, xi=1e-2)
    p = RNG.random(shape)
    q = np.meshgrid(*[2 * np.pi * np.fft.fftfreq(n, L / n) for n in shape], indexing="ij")
    qn = np.sqrt(sum(c**2 for c in q))
    qn[(0,) * len(shape)] = np.inf
    u = np.fft.ifftn(np.fft.fftn(p) * 2 * (1 - m.nu**2) / qn / m.complex_modulus(-q[0] * op.speed))
    assert _rel(op.displacement(p), u.real) < 1e-12
    if shape[0] % 2:
        assert np.abs(u.imag).max() < 1e-12 * np.abs(u.real).max()
    else:
        assert np.abs(u.imag).max() > 1e-6 * np.abs(u.real).max()  # the Nyquist mode did matter
        assert np.all(op.symbol[shape[0] // 2].imag == 0)


def test_single_mode_lags_behind():
    """``p = cos(k x)`` gives ``u = |a| cos(k x + phi)`` with ``phi = arg J(-k v) in (0, pi/2)``:
    the deformation trails the load (material points travel in ``-x``)."""
    m, n, k = make_seed(), 256, 3
    op = _op((n,), m, xi=0.2)
    x = np.arange(n) * L / n
    kq = 2 * np.pi * k / L
    u = op.displacement(np.cos(kq * x))
    a = 2 * (1 - m.nu**2) / kq * m.complex_compliance(-kq * op.speed)
    assert 0 < np.angle(a) < np.pi / 2
    assert _rel(u, np.abs(a) * np.cos(kq * x + np.angle(a))) < 1e-12


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("xi", [0.0, 1e-3, 1.0, 1e3])
def test_dissipation_of_one_wave_is_its_loss(shape, xi):
    """A pressure wave ``cos(k x)`` (uniform in y) dissipates ``(A/2) k Im(a)`` per unit speed,
    ``a = 2 (1 - nu^2) / k J(-k v)`` from the material's own compliance, ``A`` the cell area:
    positive when sliding, zero at rest, and proportional to the loss compliance (a wrong sign
    of the frequency, or a wrong modulus, changes the number)."""
    m = make_prony30()
    op = _op(shape, m, xi=xi)
    n, k = shape[0], 3
    kq = 2 * np.pi * k / L
    x = np.arange(n) * L / n
    p = np.cos(kq * x) if len(shape) == 1 else np.cos(kq * x)[:, None] * np.ones(shape)
    a = 2 * (1 - m.nu**2) / kq * m.complex_compliance(-kq * op.speed)
    want = 0.5 * L ** len(shape) * kq * np.imag(a)
    d = op.dissipation_integral(np.fft.rfftn(p, norm="forward"))
    if xi == 0:
        assert d == 0 and want == 0
    else:
        assert want > 0 and d == pytest.approx(want, rel=1e-12)


@pytest.mark.parametrize("shape", SHAPES)
def test_dissipation_integral_is_minus_p_dudx(shape):
    """Parseval: the spectral sum equals ``-∫ p du/dx dA`` evaluated in real space with a
    spectral derivative (numpy FFT; the Nyquist derivative vanishes for real fields)."""
    op = _op(shape, make_seed(), xi=0.3)
    p = RNG.random(shape) * 1e5
    u = op.displacement(p)
    qx = 2 * np.pi * np.fft.fftfreq(shape[0], L / shape[0])
    qx = qx.reshape((-1,) + (1,) * (len(shape) - 1))
    if shape[0] % 2 == 0:
        qx[shape[0] // 2] = 0.0
    dudx = np.real(np.fft.ifftn(1j * qx * np.fft.fftn(u)))
    direct = -np.mean(p * dudx) * L ** len(shape)
    assert direct > 0
    assert op.dissipation_integral(np.fft.rfftn(p, norm="forward")) == pytest.approx(direct, rel=1e-12)


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("xi", [0.0, 1.0])
def test_pressure_from_displacement_inverts(shape, xi):
    """Exact on zero-mean fields up to round-off times the symbol's condition number
    ``max|a_q| / min|a_q|`` (up to ~1e5 here: ``E_inf/E0 = 1e4`` times the q range)."""
    op = _op(shape, make_prony30(), xi=xi)
    mag = np.abs(op.symbol.ravel()[1:])
    bound = 100 * np.finfo(float).eps * mag.max() / mag.min()
    p = RNG.standard_normal(shape)
    p -= p.mean()
    assert _rel(op.pressure_from_displacement(op.displacement(p)), p) < bound
    u = RNG.standard_normal(shape) * 1e-6
    u -= u.mean()
    assert _rel(op.displacement(op.pressure_from_displacement(u)), u) < bound


@pytest.mark.parametrize("shape", [(64,), (16, 16)])
def test_self_influence_is_the_diagonal(shape):
    op = _op(shape)
    np.testing.assert_allclose(np.diag(dense_operator(op)), op.self_influence(), rtol=1e-12)


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("xi", [0.0, 1.0])
def test_single_precision_twin_is_the_same_operator_in_float32(shape, xi):
    """The products the inner solves use (``bem.contact.ContactOptions.single_precision``): float32
    fields, within float32 round-off of the float64 products. Measured 2e-7 to 3.4e-7 of the
    largest value here (8e-7 at 1024²; float32's epsilon is 1.2e-7), so the bound is 1e-6.
    The inverse (full-contact) product amplifies that by the symbol's spread: 6e-7 for the
    seed material, up to 8e-4 for the 30-term Prony series (E_inf/E0 = 1e4) in 2-D; it only
    preconditions."""
    op = _op(shape, xi=xi)
    single = op.single_precision()
    assert single is op.single_precision() and single.dtype == np.float32
    p = RNG.random(shape)
    u = single.displacement(p)
    assert u.dtype == np.float32
    assert _rel(u, op.displacement(p)) < 1e-6
    assert _rel(single.pressure_from_displacement(op.displacement(p)), p - p.mean()) < 1e-5
    sym = op.symmetric_part()  # a twin of its own, not the parent's
    assert sym.single_precision().is_symmetric
    assert _rel(sym.single_precision().displacement(p), sym.displacement(p)) < 1e-6
