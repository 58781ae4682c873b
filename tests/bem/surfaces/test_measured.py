"""Measured topographies (bem.surfaces.measured): files written here by
SurfaceTopography in four instrument formats (NetCDF, X3P, Gwyddion, plain text with a
header) and a bare matrix, read back in metres; detrending, square patch, boundary choice,
resampling and the PSD report."""

import subprocess
import sys

import numpy as np
import pytest

import bem
from bem import surfaces
from bem.errors import InputError
from bem.surfaces import measured

st = pytest.importorskip("SurfaceTopography")

NX, NY, SX, SY = 24, 20, 3.0, 2.5  # micrometres


@pytest.fixture(scope="module")
def heights():
    return np.random.default_rng(7).normal(size=(NX, NY))  # micrometres


def _write(fmt, h, folder):
    topo = st.Topography(h, (SX, SY), unit="um", info={})
    path = folder / f"scan.{fmt}"
    {"nc": topo.to_netcdf, "x3p": topo.to_x3p, "gwy": topo.to_gwy, "txt": topo.to_matrix}[fmt](str(path))
    return path


@pytest.mark.parametrize("fmt", ["nc", "x3p", "gwy", "txt"])
def test_round_trip_heights_and_sizes_in_metres(fmt, heights, tmp_path):
    m = measured.read_topography(_write(fmt, heights, tmp_path))
    # X3P and Gwyddion store metres in floating point: a unit conversion's round-off
    np.testing.assert_allclose(m.heights, heights * 1e-6, rtol=1e-12, atol=1e-20)
    assert m.physical_sizes == pytest.approx((SX * 1e-6, SY * 1e-6), rel=1e-12)
    assert m.spacing == pytest.approx((SX * 1e-6 / NX, SY * 1e-6 / NY), rel=1e-12)
    assert m.source["unit_from_file"] and m.source["sizes_from_file"]
    # the file is the authority: a contradicting unit is refused
    with pytest.raises(InputError, match="unit 'nm' contradicts"):
        measured.read_topography(tmp_path / f"scan.{fmt}", unit="nm")


def test_bare_matrix_needs_unit_and_sizes(heights, tmp_path):
    path = tmp_path / "bare.txt"
    np.savetxt(path, heights.T)  # instrument text files (and SurfaceTopography) hold one row per y
    with pytest.raises(InputError, match="unit is required"):
        measured.read_topography(path)
    with pytest.raises(InputError, match="physical_sizes is required"):
        measured.read_topography(path, unit="nm")
    m = measured.read_topography(path, unit="nm", physical_sizes=(SX, SY))
    np.testing.assert_allclose(m.heights, heights * 1e-9, rtol=1e-12)
    assert m.physical_sizes == pytest.approx((SX * 1e-9, SY * 1e-9))
    with pytest.raises(InputError, match="unit must be one of"):
        measured.read_topography(path, unit="furlong", physical_sizes=(SX, SY))


def test_unreadable_file_is_a_clear_error(tmp_path):
    path = tmp_path / "junk.xyz123"
    path.write_bytes(b"\x00\x01 not a topography")
    with pytest.raises(InputError, match="could not be read"):
        measured.read_topography(path)
    with pytest.raises(InputError, match="no such file"):
        measured.read_topography(tmp_path / "missing.nc")


def test_missing_extra_names_it(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)
    with pytest.raises(ImportError, match=r"viscobem\[topography\]"):
        measured.read_topography(tmp_path / "x.nc")


def test_import_bem_does_not_import_surface_topography():
    code = "import sys, bem, bem.surfaces.measured; print('SurfaceTopography' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


@pytest.mark.parametrize("mode, degree", [("plane", 1), ("curvature", 2)])
def test_detrend_removes_exactly_its_polynomial(mode, degree, heights):
    x = np.linspace(-1, 1, NX)[:, None]
    y = np.linspace(-1, 1, NY)[None, :]
    trend = 3e-6 + 2e-6 * x - 1e-6 * y + (degree == 2) * (4e-6 * x**2 + 1e-6 * x * y - 2e-6 * y**2)
    base = measured.detrend(measured.Measurement(heights * 1e-8, (SX * 1e-6, SY * 1e-6)), mode)
    m = measured.detrend(measured.Measurement(base.heights + trend, (SX * 1e-6, SY * 1e-6)), mode)
    np.testing.assert_allclose(m.heights, base.heights, rtol=0, atol=1e-18)
    assert m.source["detrend"] == mode
    if mode == "plane":  # a plane cannot take out curvature
        curved = measured.Measurement(base.heights + 4e-6 * x**2 + 0 * y, (SX * 1e-6, SY * 1e-6))
        assert np.abs(measured.detrend(curved, "plane").heights - base.heights).max() > 1e-7
    with pytest.raises(InputError, match="detrend must be one of"):
        measured.detrend(m, "cubic")


def test_periodic_fourier_resampling_is_exact_for_resolved_modes():
    """A periodic scan of two modes below the grid's Nyquist comes back exactly on a coarser grid."""
    n_scan, n, side = 96, 32, 2e-5
    x = np.arange(n_scan) / n_scan
    f = lambda x, y: (
        1e-7 * np.cos(2 * np.pi * 3 * x)[:, None] + 5e-8 * np.sin(2 * np.pi * (5 * x[:, None] + 2 * y[None, :]))
    )
    m = measured.Measurement(f(x, x), (side, side), periodic=True)
    s = measured.to_surface(m, n, boundary="periodic", window="none")
    xg = np.arange(n) / n
    np.testing.assert_allclose(s.heights, f(xg, xg), rtol=0, atol=1e-20)
    assert s.length == side and not s.centered
    assert s.metadata["measured"]["boundary"] == "periodic" and s.metadata["measured"]["window"] == "none"
    rep = measured.psd_report(m, s)
    assert rep["variance_above_grid_nyquist"] < 1e-28
    assert rep["q_grid_max"] == pytest.approx(np.pi * n / side)
    # the same scan on a grid that cannot hold mode 5: that variance is reported as lost
    coarse = measured.to_surface(m, 8, boundary="periodic", window="none")
    lost = measured.psd_report(m, coarse)["variance_above_grid_nyquist"]
    assert lost == pytest.approx(0.5 * 0.05**2 / (0.5 * 0.1**2 + 0.5 * 0.05**2), rel=1e-9)


def test_windows_and_mirror(heights):
    m = measured.Measurement(heights * 1e-6, (SX * 1e-6, SY * 1e-6))
    patch, side = measured.square_patch(m)
    assert side == pytest.approx(SY * 1e-6) and patch.shape == (NY, NY)
    tukey = measured.to_surface(m, 16, boundary="periodic", window="tukey", alpha=0.5)
    assert tukey.metadata["measured"]["window"] == "tukey" and tukey.metadata["measured"]["alpha"] == 0.5
    mirror = measured.to_surface(m, 32, boundary="periodic", window="mirror")
    assert mirror.length == pytest.approx(2 * side)
    # mirror tiling at the scan's own resolution reproduces the patch in the first quadrant
    own = measured.to_surface(m, 2 * NY, boundary="periodic", window="mirror")
    np.testing.assert_allclose(own.heights[:NY, :NY], patch, rtol=0, atol=1e-18)
    np.testing.assert_allclose(own.heights[NY:, :NY], patch[::-1], rtol=0, atol=1e-18)
    with pytest.raises(InputError, match="window must be one of"):
        measured.to_surface(m, 16, boundary="periodic", window="kaiser")
    with pytest.raises(InputError, match="boundary must be one of"):
        measured.to_surface(m, 16, boundary="open")


def test_measured_sphere_solved_isolated_matches_the_synthetic_one(tmp_path):
    """A sphere written as an X3P scan (finer than the grid), read, and solved on the measured
    patch as an isolated contact, against the same sphere from bem.surfaces."""
    n, length, radius = 32, 2e-3, 0.01
    fine = 4 * n
    c = (np.arange(fine) + 0.5) / fine * length - length / 2
    h = -(c[:, None] ** 2 + c[None, :] ** 2) / (2 * radius)
    path = tmp_path / "sphere.x3p"
    st.Topography(h * 1e3, (length * 1e3, length * 1e3), unit="mm", info={}).to_x3p(str(path))
    s = measured.to_surface(measured.read_topography(path), n, boundary="isolated")
    ref = surfaces.sphere(radius=radius, n=n, length=length)
    # element means of a paraboloid are its centre values plus a constant (w**2 / 6 R), and the
    # cubic spline is exact for it: measured 4e-20 m apart (sag 9.4e-5 m)
    assert np.abs((s.heights - s.heights.max()) - (ref.heights - ref.heights.max())).max() < 1e-15
    mat = bem.Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01)
    a = bem.solve(s, mat, speed=0.01, load=0.05, periodic=False)
    b = bem.solve(ref, mat, speed=0.01, load=0.05, periodic=False)
    assert a.friction == pytest.approx(b.friction, rel=1e-7)  # measured 2e-10 (solver tolerance)
    assert a.contact_fraction == b.contact_fraction
    assert s.metadata["measured"]["boundary"] == "isolated" and s.centered


def test_line_scan_becomes_a_profile(tmp_path):
    h = np.random.default_rng(1).normal(size=200)  # micrometres over 100 um
    st.UniformLineScan(h, 100.0, unit="um", info={}).to_netcdf(str(tmp_path / "line.nc"))
    m = measured.read_topography(tmp_path / "line.nc")
    np.testing.assert_allclose(m.heights, h * 1e-6, rtol=1e-12)
    assert m.physical_sizes == pytest.approx((1e-4,))
    m = measured.detrend(m, "plane")
    assert abs(np.polyfit(np.arange(200), m.heights, 1)[0]) < 1e-20
    s = measured.to_surface(m, 64, boundary="periodic", window="hann")
    assert s.shape == (64,) and s.length == pytest.approx(1e-4)
    rep = measured.psd_report(m, s)
    assert rep["q_grid_max"] == pytest.approx(np.pi * 64 / 1e-4)
    res = bem.solve(s, bem.Material.elastic(1e7), speed=0.0, load=1.0)
    assert res.success and 0 < res.contact_fraction < 1
