"""Measured topographies (bem.surfaces.measured): files written here by
SurfaceTopography in four instrument formats (NetCDF, X3P, Gwyddion, plain text with a
header) and a bare matrix, read back in metres; detrending, square patch, boundary choice,
resampling and the PSD report."""

import contextlib
import subprocess
import sys
import warnings

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
    np.savetxt(path, heights)  # a bare matrix is h[ix, iy], one text row per x, as numpy writes it
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
    s = measured.to_surface(m, n, detrend="none")  # a periodic scan: solved as it is by default
    xg = np.arange(n) / n
    np.testing.assert_allclose(s.heights, f(xg, xg), rtol=0, atol=1e-20)
    assert s.length == side and not s.centered
    assert s.metadata["measured"]["boundary"] == "periodic" and s.metadata["measured"]["window"] == "none"
    rep = measured.psd_report(m, s)
    assert rep["variance_above_grid_nyquist"] < 1e-28  # both modes on the grid
    assert rep["q_grid_max"] == pytest.approx(np.pi * n / side)
    # the same scan on a grid that cannot hold mode 5: that variance is reported as lost
    coarse = measured.to_surface(m, 8, detrend="none")
    lost = measured.psd_report(m, coarse)["variance_above_grid_nyquist"]
    assert lost == pytest.approx(0.5 * 0.05**2 / (0.5 * 0.1**2 + 0.5 * 0.05**2), rel=1e-9)


def test_windows_and_mirror(heights):
    m = measured.Measurement(heights * 1e-8, (SX * 1e-6, SY * 1e-6))  # 10 nm rms: slopes below 1
    patch, side = measured.square_patch(m)
    assert side == pytest.approx(SY * 1e-6) and patch.shape == (NY, NY)
    with pytest.warns(UserWarning, match="only the square"):
        tukey = measured.to_surface(m, 16, window="tukey", alpha=0.5)
    assert tukey.metadata["measured"]["window"] == "tukey" and tukey.metadata["measured"]["alpha"] == 0.5
    with pytest.warns(UserWarning):
        mirror = measured.to_surface(m, 16, window="mirror")
    # n points per side of the patch: the mirrored cell has twice the side and the points
    assert mirror.length == pytest.approx(2 * side) and mirror.n == 32
    assert mirror.metadata["measured"]["load_factor"] == 4 and measured.cell_load(mirror, 0.5) == 2.0
    # mirror tiling at the scan's own resolution reproduces the patch in the first quadrant
    with pytest.warns(UserWarning):
        own = measured.to_surface(m, NY, window="mirror", detrend="none")
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
    with pytest.warns(UserWarning, match="finite rigid punch"):
        s = measured.to_surface(measured.read_topography(path), n, boundary="isolated", detrend="none")
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
    s = measured.to_surface(m, 64, window="periodic_component")
    assert s.shape == (64,) and s.length == pytest.approx(1e-4)
    rep = measured.psd_report(m, s)
    assert rep["q_grid_max"] == pytest.approx(np.pi * 64 / 1e-4)
    res = bem.solve(s, bem.Material.elastic(1e7), speed=0.0, load=1.0)
    assert res.success and 0 < res.contact_fraction < 1


# --- scans of part of a larger surface (issue 25) ------------------------------------------------


def _parent_patch(shape=(60, 40), n=128, seed=3, length=1e-3):
    """A non-periodic scan: the first ``shape`` points of a periodic self-affine surface."""
    parent = surfaces.self_affine(n, length, hurst=0.8, scales=n // 8, rolloff=4, rms_slope=0.2, seed=seed)
    return np.array(parent.heights)[: shape[0], : shape[1]], length / n


@pytest.mark.parametrize("shape", [(300, 200), (128, 128), (150, 400)])
def test_psd_report_matches_surface_topography(shape):
    """The PSD of a non-periodic scan (radial Hann window over mean(w**2)) in the report is
    SurfaceTopography's on the same data and bins, in viscobem's normalisation (theirs /
    (2 pi)**2): measured 1e-12 apart at worst (target 5 %; the window rescaled to the patch
    variance instead was 0.5-2.8x off)."""
    h, dx = _parent_patch(shape, n=512)
    m = measured.detrend(measured.Measurement(h, (shape[0] * dx, shape[1] * dx)), "plane")
    q_st, c_st = st.Topography(m.heights, m.physical_sizes, periodic=False).power_spectrum_from_area(window="hann")
    keep = ~np.ma.getmaskarray(c_st)
    q_st, c_st = np.ma.getdata(q_st)[keep], np.ma.getdata(c_st)[keep] / (2 * np.pi) ** 2
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # the cropped square: tested below
        s = measured.to_surface(m, 32, boundary="periodic")
    rep = measured.psd_report(m, s)
    c = np.exp(np.interp(np.log(q_st), np.log(rep["q"]), np.log(rep["C"])))
    np.testing.assert_allclose(c, c_st, rtol=1e-9)
    np.testing.assert_allclose(rep["q"], q_st, rtol=1e-12)


def test_line_scan_psd_matches_surface_topography():
    h, dx = _parent_patch((512, 1), n=512)
    m = measured.detrend(measured.Measurement(h[:, 0], (512 * dx,)), "plane")
    q_st, c_st = st.UniformLineScan(m.heights, m.physical_sizes, periodic=False).power_spectrum_from_profile(
        window="hann"
    )
    keep = ~np.ma.getmaskarray(c_st)
    q, c = measured.psd(m)
    np.testing.assert_allclose(q, np.ma.getdata(q_st)[keep], rtol=1e-12)
    np.testing.assert_allclose(c, np.ma.getdata(c_st)[keep] / (2 * np.pi), rtol=1e-9)


@contextlib.contextmanager
def _no_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error", UserWarning)
        yield


def test_tilted_scan_through_the_api_is_detrended():
    """A tilted scan through to_surface / from_scan gives the friction of the level scan (plane
    detrending by default, as the scene kind does), not a friction whose eq. 6 form turns negative."""
    h, dx = _parent_patch((64, 64))
    side = 64 * dx
    x = (np.arange(64) + 0.5) * dx
    tilt = 0.1 * x[:, None] + 0.03 * x[None, :]  # 0.1 along x: half the rms slope
    mat = bem.Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01)
    out = []
    for heights in (h, h + tilt):
        s = measured.to_surface(measured.Measurement(heights, (side, side)), 64)
        load = 3e4 * side**2  # on the patch: bem.solve gives a mirrored cell its share
        out.append(bem.solve(s, mat, speed=0.01, load=load, periodic=not s.centered))
    level, tilted = out
    assert tilted.friction == pytest.approx(level.friction, rel=1e-9)  # the same surface after detrending
    assert tilted.friction_eq6 == pytest.approx(tilted.friction, rel=0.1)  # measured 1.2 %
    assert s.metadata["measured"]["detrend"] == "plane"
    s = bem.surfaces.from_scan(h + tilt, physical_sizes=(side, side))
    assert s.metadata["measured"]["detrend"] == "plane"
    np.testing.assert_allclose(s.heights, measured.to_surface(measured.Measurement(h, (side, side)), 64).heights)


def test_non_square_scan_says_what_is_used():
    """A 60 x 40 scan: the default square is its centred 40 x 40, recorded and warned about;
    an explicit square is recorded without a warning; cover() lists squares covering all of it."""
    h, dx = _parent_patch((60, 40))
    m = measured.Measurement(h, (60 * dx, 40 * dx))
    with pytest.warns(UserWarning, match=r"60 x 40 points.*66.7 % of the scan"):
        s = bem.surfaces.from_scan(m)
    rec = s.metadata["measured"]
    assert rec["patch"]["points"] == [40, 40] and rec["patch"]["origin"] == pytest.approx([10 * dx, 0])
    assert rec["patch"]["fraction_of_scan"] == pytest.approx(40 / 60) and rec["warnings"]
    assert rec["n"] == 40 and s.n == 80 and s.length == pytest.approx(2 * 40 * dx)  # mirrored cell
    origins = measured.cover(m)
    assert len(origins) == 2 and origins[0] == (0.0, 0.0) and origins[1][0] == pytest.approx(20 * dx)
    covered = np.zeros(h.shape, bool)
    for origin in origins:
        with _no_warning():
            t = measured.to_surface(m, 20, patch=origin)
        starts = [round(o / dx) for o in t.metadata["measured"]["patch"]["origin"]]
        covered[starts[0] : starts[0] + 40, starts[1] : starts[1] + 40] = True
        assert not t.metadata["measured"]["warnings"]
    assert covered.all()
    with _no_warning():
        t = measured.to_surface(m, 16, patch=(5 * dx, 10 * dx, 20 * dx))
    assert t.metadata["measured"]["patch"]["points"] == [20, 20]
    np.testing.assert_array_equal(measured.square_patch(m, (5 * dx, 10 * dx, 20 * dx))[0], h[5:25, 10:30])
    with pytest.raises(InputError, match="inside the scan"):
        measured.to_surface(m, 16, patch=(30 * dx, 0.0, 35 * dx))
    with pytest.raises(InputError, match="patch must be"):
        measured.to_surface(m, 16, patch="middle")


def test_boundaries_that_misrepresent_a_patch_are_warned_about():
    h, dx = _parent_patch((40, 40))
    m = measured.Measurement(h, (40 * dx, 40 * dx))
    for kwargs, words in [
        (dict(boundary="isolated"), "finite rigid punch"),
        (dict(window="none"), "keeps the step between the scan's opposite edges"),
        (dict(window="hann"), "flattens the patch"),
    ]:
        with pytest.warns(UserWarning, match=words):
            s = measured.to_surface(m, 20, **kwargs)
        assert any(words in w for w in s.metadata["measured"]["warnings"])
    for window in ("mirror", "periodic_component", "tukey"):
        with _no_warning():
            measured.to_surface(m, 20, window=window)
    # a scan declared periodic is solved as it is, without a warning
    periodic = measured.Measurement(h, (40 * dx, 40 * dx), periodic=True)
    with _no_warning():
        s = measured.to_surface(periodic, 20)
    assert s.metadata["measured"]["window"] == "none" and s.n == 20


def test_periodic_component_is_moisans():
    """Moisan's periodic component: same mean, its periodic Laplacian is the scan's Laplacian with
    free (Neumann) edges (the defining equation, to round-off), and the edges' jump is gone."""
    h, _ = _parent_patch((48, 36))
    p = measured.periodic_component(h)
    assert p.mean() == pytest.approx(h.mean(), abs=1e-18)

    def periodic_laplacian(u):
        return sum(np.roll(u, 1, a) + np.roll(u, -1, a) - 2 * u for a in range(u.ndim))

    def free_laplacian(u):
        out = np.zeros_like(u)
        for a in range(u.ndim):
            d = np.diff(u, axis=a)
            pad = [(0, 0)] * u.ndim
            pad[a] = (1, 1)
            d = np.pad(d, pad)
            out += np.diff(d, axis=a)
        return out

    np.testing.assert_allclose(periodic_laplacian(p), free_laplacian(h), rtol=0, atol=1e-12 * np.abs(h).max())
    assert measured.edge_mismatch(h) > 0.5 and measured.edge_mismatch(p) < 0.2 * measured.edge_mismatch(h)
    line = measured.periodic_component(h[:, 0])
    np.testing.assert_allclose(periodic_laplacian(line), free_laplacian(h[:, 0]), atol=1e-12 * np.abs(h).max())


def test_from_scan_inputs():
    h, dx = _parent_patch((32, 32))
    with pytest.raises(InputError, match="physical_sizes .* is required"):
        bem.surfaces.from_scan(h)
    with pytest.raises(InputError, match="one size > 0 per axis"):
        bem.surfaces.from_scan(h, physical_sizes=(1e-3,))
    s = bem.surfaces.from_scan(h * 1e3, 16, physical_sizes=(32 * dx * 1e3, 32 * dx * 1e3), unit="mm")
    ref = bem.surfaces.from_scan(h, 16, physical_sizes=(32 * dx, 32 * dx))
    np.testing.assert_allclose(s.heights, ref.heights, rtol=1e-12, atol=1e-12 * np.abs(ref.heights).max())
    with pytest.raises(InputError, match="come with the Measurement"):
        bem.surfaces.from_scan(measured.Measurement(h, (1e-3, 1e-3)), unit="um")
    with pytest.raises(InputError, match="n must be"):
        bem.surfaces.from_scan(h, 2, physical_sizes=(1e-3, 1e-3))


def test_load_refuses_a_non_square_map_and_says_what_to_write(tmp_path):
    np.save(tmp_path / "scan.npy", np.zeros((30, 20)))
    with pytest.raises(InputError, match=r"30 x 20 map.*from_scan.*kind = \"measured\""):
        surfaces.load(tmp_path / "scan.npy", 1e-3)


def test_patches_cut_from_a_known_parent_give_its_friction():
    """The four quadrants of a periodic self-affine surface (each a quarter of its area, holding
    4 roll-off wavelengths), each solved as a non-periodic scan with the defaults at the parent's
    nominal pressure, against the parent's friction below and at its peak.

    Measured on parents with seeds 1-4: the quadrants' mean within 8.1 % of the parent (limit 15 %,
    the issue's target), every quadrant within 20 % (limit 25 %: a single patch differs from the
    whole surface by its content, 11 % rms in ``viscobem bench measured`` for every periodic
    treatment alike) and its two friction forms within 6.1 % (limit 10 %, the issue's target).
    The former default (isolated patch) is 22-39 % high on average, forms up to 185 % apart."""
    n, length, p0 = 128, 1e-3, 3e4
    parent = surfaces.self_affine(n, length, hurst=0.8, scales=n // 8, rolloff=8, rms_slope=0.2, seed=1)
    mat = bem.Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01)
    h, m, side = np.array(parent.heights), n // 2, length / 2
    for speed in (1e-3, 1e-2):
        ref = bem.solve(parent, mat, speed=speed, load=p0 * length**2)
        errors = []
        for i in (0, m):
            for j in (0, m):
                s = measured.to_surface(measured.Measurement(h[i : i + m, j : j + m], (side, side)), m)
                load = p0 * side**2  # on the patch
                res = bem.solve(s, mat, speed=speed, load=load, periodic=not s.centered)
                assert res.friction_eq6 == pytest.approx(res.friction, rel=0.10)
                errors.append(res.friction / ref.friction - 1)
        assert abs(np.mean(errors)) < 0.15 and max(map(abs, errors)) < 0.25, (speed, errors)


def test_speed_limit_is_where_the_patch_is_excited_beyond_the_loss_peak():
    """Standard linear solid: the loss tangent peaks at 1 / sqrt(tau lambda) (relaxation and creep
    times), so v* = side / (2 pi sqrt(tau lambda)); to the search grid's step (0.35 %)."""
    h, dx = _parent_patch((40, 40))
    s = measured.to_surface(measured.Measurement(h, (40 * dx, 40 * dx)), 20)
    sls = bem.Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01)
    expected = 40 * dx / (2 * np.pi * np.sqrt(sls.relaxation_times[0] * sls.creep_times[0]))
    assert measured.speed_limit(s, sls) == pytest.approx(expected, rel=4e-3)
    assert measured.speed_limit(s, bem.Material.elastic(1e7)) == np.inf
    with pytest.raises(InputError, match="from_scan"):
        measured.speed_limit(surfaces.sinusoid(8, 1e-3, amplitude=1e-6), sls)
