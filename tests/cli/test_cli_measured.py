"""Scene kind ``measured``: an instrument file (written here by SurfaceTopography) solved on
the measured patch (isolated) or as a windowed periodic cell; the choice and the PSD report
in results.json."""

import json

import numpy as np
import pytest

import bem
from bem.surfaces import measured
from viscobem_cli import scene as scenes
from viscobem_cli.main import main

st = pytest.importorskip("SurfaceTopography")

SCENE = """
[material]
E0 = 1.0e6
E_inf = 1.0e7
creep_time = 0.01
[surface]
kind = "measured"
path = "scan.nc"
n = 32
detrend = "curvature"
BOUNDARY
[loading]
load = LOAD
speeds = [0.01]
[outputs]
fields = false
plots = PLOTS
"""


@pytest.fixture()
def folder(tmp_path):
    rng = np.random.default_rng(11)
    x = np.linspace(-1, 1, 80)
    # a rough patch on a tilted, curved form, in micrometres over 400 x 380 um
    h = 0.3 * rng.normal(size=(80, 76)) + 2.0 * x[:, None] + 5.0 * x[:, None] ** 2
    from scipy import ndimage

    h = ndimage.gaussian_filter(h, 2.0, mode="wrap")
    st.Topography(h, (400.0, 380.0), unit="um", info={}).to_netcdf(str(tmp_path / "scan.nc"))
    return tmp_path


def _scene(folder, boundary, load, plots="false"):
    path = folder / "s.toml"
    path.write_text(SCENE.replace("BOUNDARY", boundary).replace("LOAD", load).replace("PLOTS", plots))
    return path


def test_isolated_patch(folder):
    path = _scene(folder, 'boundary = "isolated"', "0.02", plots="true")
    assert main(["run", str(path), "--out", str(folder / "out"), "--no-progress"]) == 0
    rec = json.loads((folder / "out" / "results.json").read_text())
    meas = rec["measured"]
    assert meas["boundary"] == "isolated" and rec["solver"]["periodic"] is False
    assert meas["source"]["format"] == "nc" and meas["source"]["detrend"] == "curvature"
    assert meas["patch_side"] == pytest.approx(380e-6, rel=0.02)
    assert meas["psd"]["q_grid_max"] == pytest.approx(np.pi * 32 / meas["cell_side"])
    assert 0 < meas["psd"]["variance_above_grid_nyquist"] < 1
    assert (folder / "out" / "measured_psd.png").is_file()
    # the same numbers through the API
    m = measured.detrend(measured.read_topography(folder / "scan.nc"), "curvature")
    s = measured.to_surface(m, 32, boundary="isolated")
    scene = scenes.load(path)
    ref = bem.solve(s, scene.material, speed=0.01, load=0.02, periodic=False)
    assert rec["friction_curve"]["friction"][0] == pytest.approx(ref.friction, rel=1e-12)


def test_periodic_with_a_window(folder):
    path = _scene(folder, 'boundary = "periodic"\nwindow = "hann"', "0.01")
    assert main(["run", str(path), "--out", str(folder / "o"), "--no-progress"]) == 0
    rec = json.loads((folder / "o" / "results.json").read_text())
    assert rec["measured"]["boundary"] == "periodic" and rec["measured"]["window"] == "hann"
    assert rec["solver"]["periodic"] is True and rec["all_converged"]


@pytest.mark.parametrize(
    "extra, words",
    [
        ('boundary = "isolated"\n[solver]\nperiodic = true', "contradicts"),
        ('boundary = "periodic"\nwindow = "blackman"', "window must be one of"),
        ('boundary = "isolated"\nradius = 0.1', "do not apply"),
    ],
)
def test_bad_measured_scenes(folder, extra, words):
    with pytest.raises(bem.errors.InputError, match=words):
        scenes.load(_scene(folder, extra, "0.01"))
