"""Rough surfaces (bem.surfaces) and their statistics (bem.surfaces.statistics).

Spectral checks are exact (round-off): the generator gives every mode the deterministic
amplitude of the target PSD, so the realised PSD is compared with the target itself.
"""

import copy
import dataclasses
import pickle

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st_
from hypothesis.extra import numpy as hnp

from bem import fft
from bem.errors import InputError
from bem.surfaces import Surface, from_heights, load, profile, self_affine, sinusoid
from bem.surfaces.statistics import periodogram, psd, psd_target, rms_height, rms_slope

L = 2e-3  # cell side (m)
RTOL = 1e-10


def _moments(surface):
    """m20 = <(dh/dx)^2>, m02 = <(dh/dy)^2> over the full spectrum (independent of bem.surfaces.statistics)."""
    qx, qy = surface.wavevectors()
    hq2 = np.abs(fft.forward(surface.heights)) ** 2
    w = fft.full_spectrum_weights(surface.shape)
    return np.sum(w * qx**2 * hq2), np.sum(w * qy**2 * hq2)


def _assert_spectrum_equals_target(surface):
    c = periodogram(surface)
    target = psd_target(surface.wavevectors(), **surface.metadata["spectrum"])
    np.testing.assert_allclose(c, target, rtol=RTOL, atol=RTOL * target.max())
    return c, target


# --- generator: exact spectrum -------------------------------------------------------


@pytest.mark.parametrize(
    "n, scales, hurst, rolloff",
    [(64, 16, 0.8, 1.0), (64, 32, 0.3, 4.0), (63, 31, 0.5, 2.5), (32, 16, 1.0, 1.0), (32, 8, 0.0, 8.0)],
)
def test_realised_psd_equals_target_2d(n, scales, hurst, rolloff):
    s = self_affine(n, L, hurst=hurst, scales=scales, rolloff=rolloff, rms_height=1e-6, seed=7)
    c, target = _assert_spectrum_equals_target(s)
    # the target itself, checked independently of psd_target: plateau, power law, cut-off
    q_l = 2 * np.pi / L
    qx, qy = s.wavevectors()
    k = np.hypot(qx, qy) / q_l * np.ones_like(c)
    assert np.all(c[k > scales + 1e-9] < 1e-25 * c.max()) and c.flat[0] < 1e-25 * c.max()
    plateau = c[(k > 0.5) & (k <= rolloff)]
    np.testing.assert_allclose(plateau, plateau.max(), rtol=RTOL)
    law = (k >= rolloff) & (k <= scales + 1e-9)
    np.testing.assert_allclose(
        c[law] * k[law] ** (2 * (1 + hurst)), (c[law] * k[law] ** (2 * (1 + hurst))).max(), rtol=RTOL
    )


def test_nyquist_modes_are_exact_when_cutoff_reaches_them():
    """scales = n/2 includes the self-conjugate Nyquist modes; they keep the target amplitude."""
    s = self_affine(32, L, hurst=0.7, scales=16, rms_height=1e-6, seed=3)
    c, target = _assert_spectrum_equals_target(s)
    assert target[16, 0] > 0 and target[0, 16] > 0


def test_radial_psd_equals_target_exactly():
    s = self_affine(64, L, hurst=0.8, scales=24, rolloff=3.0, rms_height=1e-6, seed=1)
    q, c = psd(s)
    np.testing.assert_allclose(c, psd_target(q, **s.metadata["spectrum"]), rtol=RTOL, atol=RTOL * c.max())
    q_l = 2 * np.pi / L
    np.testing.assert_allclose(q[:4] / q_l, [1, np.sqrt(2), 2, np.sqrt(5)], rtol=1e-14)


def test_profile_spectrum_exact_with_1d_exponent():
    hurst, scales = 0.6, 40
    p = profile(128, L, hurst=hurst, scales=scales, rms_height=3e-7, seed=2)
    assert p.ndim == 1 and p.shape == (128,)
    c, _ = _assert_spectrum_equals_target(p)
    k = np.arange(c.size, dtype=float)
    law = (k >= 1) & (k <= scales)
    scaled = c[law] * k[law] ** (1 + 2 * hurst)
    np.testing.assert_allclose(scaled, scaled[0], rtol=RTOL)
    assert np.all(c[k > scales] < 1e-25 * c.max())


# --- normalisation, Parseval, reality ------------------------------------------------


@pytest.mark.parametrize("dim", [1, 2])
def test_rms_height_and_slope_normalisation_exact(dim):
    a = self_affine(64, L, hurst=0.8, scales=20, rms_height=2e-6, seed=4, dim=dim)
    b = self_affine(64, L, hurst=0.8, scales=20, rms_slope=0.15, seed=4, dim=dim)
    assert rms_height(a) == pytest.approx(2e-6, rel=1e-13)
    assert rms_slope(b) == pytest.approx(0.15, rel=1e-13)
    # same phases and shape: the two differ by a constant factor only
    np.testing.assert_allclose(b.heights * rms_height(a) / rms_height(b), a.heights, rtol=0, atol=1e-18)


@pytest.mark.parametrize("dim", [1, 2])
def test_parseval_height_and_slope(dim):
    s = self_affine(64, L, hurst=0.5, scales=24, rms_height=1e-6, seed=5, dim=dim)
    h = s.heights
    assert rms_height(s) == pytest.approx(np.sqrt(np.mean((h - h.mean()) ** 2)), rel=1e-12)
    q = s.wavevectors()
    hq = fft.forward(h)
    grad2 = sum(fft.inverse(1j * qi * hq, s.shape) ** 2 for qi in q)  # no Nyquist content
    assert rms_slope(s) == pytest.approx(np.sqrt(np.mean(grad2)), rel=1e-12)
    _, c = psd(s, bins=[0.5 * 2 * np.pi / L, 1e9])  # one bin holding every nonzero mode
    q_l = 2 * np.pi / L
    assert c[0] * q_l**dim * (s.n**dim - 1) == pytest.approx(rms_height(s) ** 2, rel=1e-12)


def test_heights_real_mean_zero_readonly():
    s = self_affine(64, L, hurst=0.8, scales=32, rms_height=1e-6, seed=9)
    assert s.heights.dtype == np.float64 and np.isrealobj(s.heights)
    assert abs(s.heights.mean()) < 1e-14 * rms_height(s)
    with pytest.raises(ValueError):
        s.heights[0, 0] = 1.0


def test_seeds_reproducible_and_distinct():
    kw = dict(hurst=0.8, scales=16, rms_height=1e-6)
    a, b, c = (self_affine(64, L, seed=seed, **kw) for seed in (11, 11, 12))
    np.testing.assert_array_equal(a.heights, b.heights)
    assert np.max(np.abs(a.heights - c.heights)) > 0.1 * rms_height(a)
    g = self_affine(64, L, seed=np.random.default_rng(11), **kw)
    np.testing.assert_array_equal(g.heights, a.heights)
    assert a.metadata["seed"] == 11 and g.metadata["seed"] is None


def test_cutoff_wavevector_equivalent_to_scales():
    q_l = 2 * np.pi / L
    a = self_affine(64, L, hurst=0.8, scales=16, rms_height=1e-6, seed=0)
    b = self_affine(64, L, hurst=0.8, cutoff_wavevector=16 * q_l, rms_height=1e-6, seed=0)
    np.testing.assert_allclose(a.heights, b.heights, rtol=0, atol=1e-20)


# --- anisotropy ----------------------------------------------------------------------


@pytest.mark.parametrize("s", [2.0, 0.5, 3.0, 1.3])
def test_anisotropy_moment_ratio_exact(s):
    surf = self_affine(128, L, hurst=0.8, scales=20, rms_slope=0.1, seed=6, anisotropy=s)
    m20, m02 = _moments(surf)
    assert m02 / m20 == pytest.approx(s**2, rel=1e-12)
    assert np.sqrt(m20 + m02) == pytest.approx(0.1, rel=1e-12)
    _assert_spectrum_equals_target(surf)
    assert 0.8 < surf.metadata["spectrum"]["directional_factor"] < 1.25


def test_anisotropy_definition_long_axis_keeps_isotropic_spectrum():
    """For s > 1 the x-axis spectrum is the isotropic one; the y-axis is compressed by s."""
    spec = dict(hurst=0.8, cutoff_wavevector=20.0, rolloff_wavevector=2.0, prefactor=1.0)
    q = np.linspace(0.5, 19.0, 7)
    iso = psd_target(q, **spec)
    zero = np.zeros_like(q)
    np.testing.assert_allclose(psd_target((q, zero), anisotropy=2.0, **spec), iso, rtol=1e-14)
    np.testing.assert_allclose(psd_target((zero, 2 * q), anisotropy=2.0, **spec), iso, rtol=1e-14)
    np.testing.assert_allclose(psd_target((zero, q), anisotropy=0.5, **spec), iso, rtol=1e-14)


def test_isotropic_surface_has_equal_moments():
    """A realisation's moments are equal only in expectation; the target's are equal exactly."""
    surf = self_affine(64, L, hurst=0.8, scales=32, rms_slope=0.1, seed=6)
    spec = surf.metadata["spectrum"]
    assert spec["directional_factor"] == 1.0 and spec["anisotropy"] == 1.0
    target = psd_target(surf.wavevectors(), **spec)
    qx, qy = surf.wavevectors()
    w = fft.full_spectrum_weights(surf.shape)
    assert np.sum(w * qy**2 * target) == pytest.approx(np.sum(w * qx**2 * target), rel=1e-12)


# --- sinusoids -----------------------------------------------------------------------


def test_sinusoid_profile():
    s = sinusoid(64, L, amplitude=1e-6, wavelength=L / 4)
    assert s.ndim == 1 and s.heights[0] == 1e-6 and np.argmax(s.heights) == 0
    assert rms_height(s) == pytest.approx(1e-6 / np.sqrt(2), rel=1e-13)
    assert rms_slope(s) == pytest.approx(1e-6 * (2 * np.pi * 4 / L) / np.sqrt(2), rel=1e-12)
    q, c = psd(s)  # a single mode pair at k = 4: C = (a/2)^2 L/(2 pi)
    assert q[np.argmax(c)] == pytest.approx(4 * 2 * np.pi / L)
    assert c.max() == pytest.approx((0.5e-6) ** 2 * L / (2 * np.pi), rel=1e-12)


@pytest.mark.parametrize("direction, rms", [("x", 1 / np.sqrt(2)), ("y", 1 / np.sqrt(2)), ("xy", 0.5)])
def test_sinusoid_surface(direction, rms):
    s = sinusoid(32, L, amplitude=2.0, dim=2, direction=direction)
    assert s.shape == (32, 32) and s.heights[0, 0] == 2.0 and s.heights.max() == 2.0
    assert rms_height(s) == pytest.approx(2.0 * rms, rel=1e-13)
    m20, m02 = _moments(s)
    assert {"x": m02, "y": m20, "xy": m02 - m20}[direction] == pytest.approx(0, abs=1e-9 * (m20 + m02))


# --- Surface and from_heights --------------------------------------------------------


def test_from_heights_copies_and_properties():
    raw = np.arange(16.0).reshape(4, 4)
    before = raw.copy()
    s = from_heights(raw, 2.0)
    raw[0, 0] = 99.0
    assert s.heights[0, 0] == 0.0 and not s.heights.flags.writeable
    raw[0, 0] = 0.0
    np.testing.assert_array_equal(raw, before)
    assert (s.ndim, s.n, s.shape, s.spacing) == (2, 4, (4, 4), 0.5)
    np.testing.assert_array_equal(s.x, [0.0, 0.5, 1.0, 1.5])
    x, y = s.coordinates()
    assert x.shape == (4, 4) and x[2, 0] == 1.0 and y[0, 3] == 1.5
    c = dataclasses.replace(s, centered=True)
    np.testing.assert_allclose(c.x, [-0.75, -0.25, 0.25, 0.75])
    assert from_heights([1.0, 2.0, 3.0], 3.0, centered=True).x.tolist() == [-1.0, 0.0, 1.0]
    assert from_heights([0.0, 1.0], 1.0).coordinates()[0].tolist() == [0.0, 0.5]


@pytest.mark.parametrize(
    "heights, length, name",
    [
        ([[0.0, 1.0, 2.0], [0.0, 1.0, 2.0]], 1.0, "heights"),
        ([0.0, np.nan, 1.0], 1.0, "heights"),
        ([1.0], 1.0, "heights"),
        (np.zeros((2, 2, 2)), 1.0, "heights"),
        ([0.0, 1.0], 0.0, "length"),
        ([0.0, 1.0], -1.0, "length"),
        ([0.0, 1.0], np.inf, "length"),
    ],
)
def test_surface_rejects_bad_input(heights, length, name):
    with pytest.raises(InputError, match=name):
        from_heights(heights, length)
    with pytest.raises(InputError, match=name):
        Surface(heights, length)


def test_surface_pickles_and_metadata_is_read_only():
    s = self_affine(32, L, hurst=0.8, scales=8, rms_height=1e-6, seed=1, anisotropy=1.5)
    for t in (pickle.loads(pickle.dumps(s)), copy.deepcopy(s)):
        np.testing.assert_array_equal(t.heights, s.heights)
        assert dict(t.metadata["spectrum"]) == dict(s.metadata["spectrum"])
        assert (t.length, t.name, t.centered) == (s.length, s.name, s.centered)
    with pytest.raises(TypeError):
        s.metadata["spectrum"]["prefactor"] = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.length = 1.0


# --- load ----------------------------------------------------------------------------


@pytest.mark.parametrize("suffix, delimiter", [(".npy", None), (".txt", " "), (".csv", ","), (".txt", "\t")])
@pytest.mark.parametrize("shape", [(8,), (8, 8)])
def test_load_round_trip(tmp_path, suffix, delimiter, shape):
    data = np.random.default_rng(0).standard_normal(shape)
    path = tmp_path / f"topo{suffix}"
    if suffix == ".npy":
        np.save(path, data)
    else:
        np.savetxt(path, data[None, :] if data.ndim == 1 else data, delimiter=delimiter, header="heights", fmt="%.17g")
    s = load(path, 1e-3)
    np.testing.assert_array_equal(s.heights, data)
    assert s.length == 1e-3 and s.name == "topo" and s.metadata["kind"] == "file"


@pytest.mark.parametrize("unit, factor", [("m", 1.0), ("mm", 1e-3), ("um", 1e-6), ("nm", 1e-9)])
def test_load_unit_conversion(tmp_path, unit, factor):
    path = tmp_path / "column.csv"
    path.write_text("# one column: a profile\n1.5\n-2.0\n0.25\n3.0\n")
    s = load(str(path), 1e-2, unit=unit)
    np.testing.assert_allclose(s.heights, np.array([1.5, -2.0, 0.25, 3.0]) * factor, rtol=1e-15)


@pytest.mark.parametrize(
    "content, suffix",
    [
        ("1 2 3\n4 5 6\n", ".txt"),
        ("1,2\n3,nan\n", ".csv"),
        ("a,b\nc,d\n", ".csv"),
        ("", ".txt"),
        ("1,2\n3\n", ".csv"),
        ("1 2\n3 4\n", ".dat"),
        ("7\n", ".txt"),
    ],
)
def test_load_rejects_bad_files(tmp_path, content, suffix):
    path = tmp_path / f"bad{suffix}"
    path.write_text(content)
    with pytest.raises(InputError, match="path"):
        load(path, 1e-3)


def test_load_rejects_missing_file_and_bad_unit(tmp_path):
    with pytest.raises(InputError, match="path"):
        load(tmp_path / "missing.npy", 1e-3)
    np.save(tmp_path / "ok.npy", np.zeros((4, 4)))
    with pytest.raises(InputError, match="unit"):
        load(tmp_path / "ok.npy", 1e-3, unit="inch")
    with pytest.raises(InputError, match="length"):
        load(tmp_path / "ok.npy", -1.0)


# --- bad input names the parameter ---------------------------------------------------

GOOD = dict(n=64, length=L, hurst=0.8, scales=16, rms_height=1e-6)


@pytest.mark.parametrize(
    "change, name",
    [
        (dict(n=1), "n"),
        (dict(n=64.0), "n"),
        (dict(length=0.0), "length"),
        (dict(hurst=1.5), "hurst"),
        (dict(hurst=np.nan), "hurst"),
        (dict(scales=33), "scales"),
        (dict(scales=0), "scales"),
        (dict(scales=None), "scales"),  # default 64 > n/2
        (dict(cutoff_wavevector=1e3), "cutoff_wavevector"),
        (dict(scales=None, cutoff_wavevector=1e6), "cutoff_wavevector"),
        (dict(scales=None, cutoff_wavevector=1.0), "cutoff_wavevector"),
        (dict(rolloff=0.5), "rolloff"),
        (dict(rolloff=17.0), "rolloff"),
        (dict(rms_slope=0.1), "rms_slope"),
        (dict(rms_height=None), "rms_height"),
        (dict(rms_height=-1e-6), "rms_height"),
        (dict(rms_height=None, rms_slope=0.0), "rms_slope"),
        (dict(seed=-1), "seed"),
        (dict(seed=1.5), "seed"),
        (dict(dim=3), "dim"),
        (dict(anisotropy=0.0), "anisotropy"),
        (dict(anisotropy=2.0, dim=1), "anisotropy"),
        (dict(anisotropy=4.0), "scales"),
        (dict(anisotropy=0.25), "scales"),
    ],
)
def test_self_affine_rejects_bad_input(change, name):
    kw = {**GOOD, **change}
    n, length = kw.pop("n"), kw.pop("length")
    with pytest.raises(InputError, match=name):
        self_affine(n, length, **kw)


@pytest.mark.parametrize(
    "change, name",
    [
        (dict(amplitude=0.0), "amplitude"),
        (dict(wavelength=L / 2.5), "wavelength"),
        (dict(wavelength=2 * L), "wavelength"),
        (dict(wavelength=L / 8), "wavelength"),
        (dict(dim=3), "dim"),
        (dict(dim=2, direction="z"), "direction"),
        (dict(direction="y"), "direction"),
        (dict(n=1), "n"),
    ],
)
def test_sinusoid_rejects_bad_input(change, name):
    kw = {"n": 16, "length": L, "amplitude": 1e-6, **change}
    with pytest.raises(InputError, match=name):
        sinusoid(kw.pop("n"), kw.pop("length"), **kw)


def test_statistics_reject_bad_input():
    s = sinusoid(16, L, amplitude=1e-6)
    with pytest.raises(InputError, match="length"):
        rms_slope(np.zeros(8))
    with pytest.raises(InputError, match="length"):
        psd(s, L)
    with pytest.raises(InputError, match="heights"):
        rms_height(np.zeros((4, 5)))
    with pytest.raises(InputError, match="bins"):
        psd(s, bins=[3.0, 1.0])
    with pytest.raises(InputError, match="bins"):
        psd(s, bins=0)
    with pytest.raises(InputError, match="q"):
        psd_target(np.ones(3), hurst=0.5, cutoff_wavevector=10.0, rolloff_wavevector=1.0, anisotropy=2.0)
    with pytest.raises(InputError, match="rolloff_wavevector"):
        psd_target(np.ones(3), hurst=0.5, cutoff_wavevector=1.0, rolloff_wavevector=2.0)


# --- statistics accept arrays and never modify them ----------------------------------


@settings(max_examples=30, deadline=None)
@given(
    hnp.arrays(np.float64, st_.sampled_from([(6,), (5, 5), (8, 8)]), elements=st_.floats(-1e3, 1e3, allow_nan=False))
)
def test_statistics_on_arrays_parseval_and_inputs_unmodified(h):
    before = h.copy()
    assert rms_height(h) == pytest.approx(np.std(h), rel=1e-9, abs=1e-9)
    c = periodogram(h, 1.0)
    w = fft.full_spectrum_weights(h.shape)
    assert np.sum(w * c) * (2 * np.pi) ** h.ndim == pytest.approx(np.mean(h**2), rel=1e-9, abs=1e-9)
    rms_slope(h, 1.0)
    psd(h, 1.0)
    psd(h, 1.0, bins=3)
    np.testing.assert_array_equal(h, before)
