"""Scene kind ``measured``: an instrument file (written here by SurfaceTopography) solved as a
mirrored periodic cell (the default), a windowed one or an isolated patch; the choice, the patch,
the warnings and the PSD report in results.json; the same numbers as the Python entry."""

import json
import sys

import numpy as np
import pytest

import bem
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


def test_default_patch_is_the_python_entry(folder):
    """Defaults (plane detrending, mirrored periodic cell, load on the patch) as bem.surfaces.from_scan:
    the same friction to round-off."""
    path = _scene(folder, "", "0.02", plots="true")
    assert main(["run", str(path), "--out", str(folder / "out"), "--no-progress"]) == 0
    rec = json.loads((folder / "out" / "results.json").read_text())
    meas = rec["measured"]
    assert meas["boundary"] == "periodic" and meas["window"] == "mirror" and rec["solver"]["periodic"] is True
    assert meas["source"]["format"] == "nc" and meas["detrend"] == "curvature"
    assert meas["patch_side"] == pytest.approx(380e-6, rel=0.02) and meas["cell_side"] == 2 * meas["patch_side"]
    assert meas["patch_loads"] == [0.02] and rec["loads"] == [0.02] and meas["load_factor"] == 4
    assert meas["cell_loads"] == [0.08]
    assert meas["patch"]["fraction_of_scan"] == pytest.approx(76 / 80)
    assert any("only the square" in w for w in rec["warnings"])  # 80 x 76 points: the centred 76 x 76
    assert meas["psd"]["q_grid_max"] == pytest.approx(np.pi * 32 / meas["patch_side"])
    assert 0 < meas["psd"]["variance_above_grid_nyquist"] < 1
    assert (folder / "out" / "measured_psd.png").is_file()
    scene = scenes.load(path)
    with pytest.warns(UserWarning, match="only the square"):
        s = bem.surfaces.from_scan(folder / "scan.nc", 32, detrend="curvature")
    ref = bem.solve(s, scene.material, speed=0.01, load=0.02)  # the load on the patch, as the scene's
    assert rec["friction_curve"]["friction"][0] == pytest.approx(ref.friction, rel=1e-12)


def test_isolated_patch_is_warned_about(folder):
    path = _scene(folder, 'boundary = "isolated"', "0.02")
    assert main(["run", str(path), "--out", str(folder / "out"), "--no-progress"]) == 0
    rec = json.loads((folder / "out" / "results.json").read_text())
    assert rec["measured"]["boundary"] == "isolated" and rec["solver"]["periodic"] is False
    assert rec["measured"]["load_factor"] == 1 and rec["loads"] == [0.02]
    assert any("finite rigid punch" in w for w in rec["warnings"])


def test_periodic_with_a_window(folder):
    path = _scene(folder, 'boundary = "periodic"\nwindow = "hann"', "0.01")
    assert main(["run", str(path), "--out", str(folder / "o"), "--no-progress"]) == 0
    rec = json.loads((folder / "o" / "results.json").read_text())
    assert rec["measured"]["boundary"] == "periodic" and rec["measured"]["window"] == "hann"
    assert rec["solver"]["periodic"] is True and rec["all_converged"]
    assert any("flattens the patch" in w for w in rec["warnings"])


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


def test_cover_solves_every_square_of_the_scan(folder):
    path = _scene(folder, 'patch = "cover"', "0.02")
    scene = scenes.load(path)
    assert len(scene.realisations) == 2 and not any("only the square" in w for w in scene.warnings)
    assert main(["run", str(path), "--out", str(folder / "c"), "--no-progress"]) == 0
    rec = json.loads((folder / "c" / "results.json").read_text())
    origins = [p["origin"][0] for p in rec["measured"]["patches"]]
    assert origins[0] == 0 and origins[1] == pytest.approx(4 * 400e-6 / 80)  # 80 x 76 points: squares at 0 and 4
    assert rec["friction_curve"]["realisations"] == 2 and rec["friction_curve"]["friction_se"][0] is not None


def test_edges_that_carry_load_get_advice_for_a_scan(folder):
    """window = "none" on a scan that is not periodic: the friction forms differ, and the advice
    speaks of the scan's boundary, not of the scales a scan does not have."""
    path = _scene(folder, 'window = "none"', "0.02")
    assert main(["run", str(path), "--out", str(folder / "w"), "--no-progress"]) == 0
    rec = json.loads((folder / "w" / "results.json").read_text())
    forms = [w for w in rec["warnings"] if "friction_eq6" in w and "differs from friction" in w]
    assert forms and not any("scales" in w for w in rec["warnings"])
    step = [w for w in rec["warnings"] if "keeps the step between the scan's opposite edges" in w]
    assert step and "Use window 'mirror'" in step[0]


def test_file_kind_refuses_a_non_square_map_and_names_the_kind(tmp_path, capsys):
    np.save(tmp_path / "scan.npy", np.zeros((30, 20)))
    path = tmp_path / "f.toml"
    path.write_text(
        SCENE.replace('kind = "measured"\npath = "scan.nc"\nn = 32\ndetrend = "curvature"\nBOUNDARY', "")
        .replace("[surface]", '[surface]\nkind = "file"\npath = "scan.npy"\nlength = 1e-3')
        .replace("LOAD", "0.01")
        .replace("PLOTS", "false")
    )
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and 'kind = "measured"' in err and "30 x 20" in err


def test_missing_surface_topography_is_one_line(folder, monkeypatch, capsys):
    """Without the topography extra: one line naming it and exit status 2 (no traceback)."""
    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)
    assert main(["run", str(_scene(folder, "", "0.01")), "--out", str(folder / "m"), "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "viscobem[topography]" in err and "Traceback" not in err


def test_speeds_beyond_what_the_scan_holds_are_warned_about(folder):
    """The loss peak of the solid (317 rad/s) excites the 0.38 mm patch's longest wavelength at
    0.019 m/s: of 0.001 and 0.1 m/s, the second is warned about."""
    path = _scene(folder, "", "0.02")
    path.write_text(path.read_text().replace("speeds = [0.01]", "speeds = [0.001, 0.1]"))
    assert main(["run", str(path), "--out", str(folder / "v"), "--no-progress"]) == 0
    rec = json.loads((folder / "v" / "results.json").read_text())
    assert rec["measured"]["speed_limit"] == pytest.approx(317 * 380e-6 / (2 * np.pi), rel=0.02)
    assert sum("is above" in w and "longer than the scanned patch" in w for w in rec["warnings"]) == 1
    assert any(w.startswith("at xi = 1.32:") and "longer than the scanned patch" in w for w in rec["warnings"])


def test_nominal_pressure_is_the_load_it_puts_on_the_patch(folder):
    """[loading] nominal_pressure (Pa) instead of load: the scene solves the patch load that pressure
    puts on the scanned patch, the same friction to round-off; giving both is one line."""
    by_load = json.loads(_run(folder, "load = 0.02"))
    side = by_load["measured"]["patch_side"]
    by_pressure = json.loads(_run(folder, f"nominal_pressure = {0.02 / side**2!r}"))
    assert by_pressure["loads"] == pytest.approx([0.02], rel=1e-12)
    assert by_pressure["friction_curve"]["friction"][0] == pytest.approx(
        by_load["friction_curve"]["friction"][0], rel=1e-12
    )
    path = folder / "both.toml"
    path.write_text(
        SCENE.replace("BOUNDARY", "").replace("LOAD", "0.02\nnominal_pressure = 1e5").replace("PLOTS", "false")
    )
    with pytest.raises(
        bem.InputError, match=r"exactly one of load .* and nominal_pressure .*, got load and nominal_pressure"
    ):
        scenes.load(path)


def _run(folder, loading):
    path = folder / "p.toml"
    text = SCENE.replace("BOUNDARY", "").replace("load = LOAD", loading).replace("PLOTS", "false")
    path.write_text(text)
    out = folder / ("out-" + loading.split()[0])
    assert main(["run", str(path), "--out", str(out), "--no-progress"]) == 0
    return (out / "results.json").read_text()
