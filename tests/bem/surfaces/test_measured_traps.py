"""Traps of one's own data (issue: units, scan files, missing points): one height-map convention
in every reader, one unit table, one missing-point policy, steps, and heights in the wrong unit."""

import warnings

import numpy as np
import pytest

import bem
from bem.errors import InputError
from bem.surfaces import measured

NX, NY = 40, 60  # a non-square map, pixels 5 um square: 200 x 300 um
SIZES = (200.0, 300.0)  # um


@pytest.fixture(scope="module")
def heights():
    """A smooth rough map in micrometres, ``h[ix, iy]``."""
    from scipy import ndimage

    return ndimage.gaussian_filter(np.random.default_rng(5).normal(size=(NX, NY)), 2.0)


def _quiet(call, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the right reading of a clean map warns about nothing
        return call(*args, **kwargs)


def _writers(h, folder):
    """The same map ``h[ix, iy]`` written as a user would, one file per supported layout."""
    out = {}
    np.save(folder / "map.npy", h)
    out["npy"] = folder / "map.npy"
    for name, sep in (("space.txt", " "), ("comma.csv", ","), ("semicolon.csv", ";"), ("tab.tsv", "\t")):
        np.savetxt(folder / name, h, delimiter=sep)
        out[name] = folder / name
    text = "\n".join(";".join(f"{v:.17g}".replace(".", ",") for v in row) for row in h)  # decimal commas
    (folder / "decimal_comma.csv").write_text("# exported by a spreadsheet\n" + text + "\n")
    out["decimal_comma.csv"] = folder / "decimal_comma.csv"
    return out


def test_the_same_map_reads_to_identical_heights_from_every_plain_format(heights, tmp_path):
    for name, path in _writers(heights, tmp_path).items():
        m = _quiet(measured.read_topography, path, unit="um", physical_sizes=SIZES)
        np.testing.assert_allclose(m.heights, heights * 1e-6, rtol=1e-13, err_msg=name)
        assert m.physical_sizes == pytest.approx((2e-4, 3e-4))


def test_instrument_formats_read_to_the_same_heights(heights, tmp_path):
    st = pytest.importorskip("SurfaceTopography")
    topo = st.Topography(heights, SIZES, unit="um", info={})
    for fmt, write in (("nc", topo.to_netcdf), ("x3p", topo.to_x3p), ("txt", topo.to_matrix)):
        path = tmp_path / f"instrument.{fmt}"
        write(str(path))  # its text export has a header and one row per y
        m = _quiet(measured.read_topography, path)
        np.testing.assert_allclose(m.heights, heights * 1e-6, rtol=1e-12, atol=1e-20, err_msg=fmt)


def test_a_transposed_map_warns_and_transpose_reads_it(heights, tmp_path):
    np.savetxt(tmp_path / "image.txt", heights.T)  # one row per y, as an image
    with pytest.warns(UserWarning, match=r"pixels are .* \(2.25 : 1\).*transpose=True"):
        measured.read_topography(tmp_path / "image.txt", unit="um", physical_sizes=SIZES[::-1][::-1])
    m = _quiet(measured.read_topography, tmp_path / "image.txt", unit="um", physical_sizes=SIZES[::-1], transpose=True)
    np.testing.assert_allclose(m.heights, heights * 1e-6, rtol=1e-13)
    with pytest.warns(UserWarning, match="transpose=True"):
        bem.surfaces.from_scan(heights.T, 16, physical_sizes=SIZES, unit="um")


@pytest.mark.parametrize("unit", ["um", "\u00b5m", "\u03bcm", "micron"])
def test_one_unit_table_takes_every_micrometre_spelling(unit, heights, tmp_path):
    np.save(tmp_path / "h.npy", heights[:NX, :NX])
    m = measured.read_topography(tmp_path / "h.npy", unit=unit, physical_sizes=(200.0, 200.0))
    assert m.heights.max() == pytest.approx(heights[:NX, :NX].max() * 1e-6)
    assert measured.load(tmp_path / "h.npy", 2e-4, unit=unit).heights.max() == pytest.approx(m.heights.max())


def test_missing_points_are_filled_the_same_way_in_arrays_and_files(heights, tmp_path):
    h = heights.copy()
    h[10:13, 20:24] = np.nan  # 12 of 2400 points
    with pytest.warns(UserWarning, match=r"12 of 2400 points .* \(0.5 %\) were missing .* harmonic"):
        from_array = measured.reading.from_array(h, SIZES, "um")
    text = "\n".join(",".join("" if np.isnan(v) else f"{v:.17g}" for v in row) for row in h)
    (tmp_path / "holes.csv").write_text(text)
    with pytest.warns(UserWarning, match="were missing"):
        from_file = measured.read_topography(tmp_path / "holes.csv", unit="um", physical_sizes=SIZES)
    np.testing.assert_allclose(from_file.heights, from_array.heights, rtol=1e-12)
    assert from_array.source["filled_points"] == 12
    # the fill is harmonic: each filled point is the mean of its four neighbours
    f = from_array.heights
    np.testing.assert_allclose(f[11, 21], (f[10, 21] + f[12, 21] + f[11, 20] + f[11, 22]) / 4, rtol=1e-10)
    # and it stays within the surrounding heights
    assert np.nanmin(h) <= f[10:13, 20:24].min() and f[10:13, 20:24].max() <= np.nanmax(h)


def test_too_many_missing_points_are_refused(heights):
    h = heights.copy()
    h[:, :7] = np.nan  # 11.7 %
    with pytest.raises(InputError, match=r"280 of 2400 points missing \(11.7 %\), more than 10 %"):
        bem.surfaces.from_scan(h, 16, physical_sizes=SIZES, unit="um")


def test_a_step_is_warned_about(heights):
    h = heights * 0.2  # rms about 0.03 um
    h[:, NY // 2 :] += 0.3  # a terrace 0.3 um high across y = 150 um
    with pytest.warns(UserWarning, match=r"jump by 0.29.* um .* across y = 0.15 mm"):
        bem.surfaces.from_scan(h, 16, physical_sizes=SIZES, unit="um", patch=(0, 0, 200.0 * 1e-6))
    with warnings.catch_warnings():
        warnings.simplefilter("error", UserWarning)
        bem.surfaces.from_scan(h[:, : NY // 2], 16, physical_sizes=(200.0, 150.0), unit="um", patch=(0, 0))


def test_micrometres_given_as_metres_are_refused(heights):
    with pytest.raises(InputError, match=r"taller than wide.*micrometres given as metres.*unit='um'"):
        bem.surfaces.from_scan(heights * 5, 16, physical_sizes=(4e-3, 6e-3))  # "5 m" rms on a 4 mm cell
    with pytest.raises(InputError, match="micrometres given as metres"):
        bem.solve(bem.surfaces.from_heights(heights[:NX, :NX] * 5, 4e-3), bem.Material.elastic(1e7), speed=0, load=1)


def test_sizes_in_metres_with_heights_in_micrometres_are_refused_naming_physical_sizes(heights):
    """unit names the heights' and the sizes' unit alike: sizes in metres beside unit='um' make the
    scan 4 nm wide, and the message says that physical_sizes are read in that unit."""
    with pytest.raises(InputError, match=r"physical_sizes are both read in unit \('um'\).*the scan 4e-09 x 4e-09 m"):
        bem.surfaces.from_scan(heights, 16, physical_sizes=(4e-3, 6e-3), unit="um")


def test_comma_separated_matrix_is_read_by_from_scan(heights, tmp_path):
    np.savetxt(tmp_path / "export.csv", heights, delimiter=",", header="heights in um", comments="# ")
    s = _quiet(bem.surfaces.from_scan, tmp_path / "export.csv", 16, physical_sizes=SIZES, unit="um", patch=(0, 0))
    assert s.metadata["measured"]["source"]["format"] == "matrix"


def test_a_text_row_that_is_not_numbers_is_named(tmp_path):
    (tmp_path / "bad.csv").write_text("1,2,3\n4,x,6\n7,8,9\n")
    with pytest.raises(InputError, match=r"line 2 \('4,x,6'\) is not a row of numbers"):
        measured.read_topography(tmp_path / "bad.csv", unit="um", physical_sizes=(3, 3))
