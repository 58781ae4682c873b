"""Scenes with a sliding direction: ``[loading] direction_deg`` (one angle, or a sweep)."""

import json

import numpy as np
import pytest

import bem
from viscobem_cli import scene as scenes
from viscobem_cli.main import main

SCENE = """
title = "directions"
[material]
E0 = 1.0e6
E_inf = 1.0e7
creep_time = 0.01
[surface]
kind = "self_affine"
length = 0.001
n = 32
hurst = 0.8
scales = 4
rms_slope = 0.3
anisotropy = 2.0
seed = 1
[loading]
load = 0.05
speeds = [0.03]
direction_deg = DIRS
[outputs]
fields = false
plots = PLOTS
"""


def _write(tmp_path, dirs, plots="false"):
    path = tmp_path / "s.toml"
    path.write_text(SCENE.replace("DIRS", dirs).replace("PLOTS", plots))
    return path


def test_direction_sweep_gives_mu_of_theta_and_a_polar_plot(tmp_path):
    path = _write(tmp_path, "[0, 90]", plots="true")
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--no-progress"]) == 0
    rec = json.loads((tmp_path / "out" / "results.json").read_text())
    table = rec["directions"]
    assert table["direction_deg"] == [0, 90]
    assert (tmp_path / "out" / "friction_polar.png").is_file()
    mu = np.array(table["friction"])[:, 0]
    # each direction is the solver's own answer for that direction
    scene = scenes.load(path)
    for deg, value in zip(table["direction_deg"], mu):
        ref = bem.solve(scene.surface, scene.material, speed=0.03, load=0.05, direction=np.radians(deg))
        assert value == pytest.approx(ref.friction, rel=1e-12)
    # the anisotropic surface: along y differs from along x
    assert abs(mu[1] / mu[0] - 1) > 0.05
    sub = json.loads((tmp_path / "out" / "direction_090.000" / "results.json").read_text())
    assert sub["direction_deg"] == 90


def test_single_direction_applies_to_every_point(tmp_path):
    path = _write(tmp_path, "45")
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    rec = json.loads((tmp_path / "o" / "results.json").read_text())
    assert rec["direction_deg"] == 45 and "directions" not in rec
    scene = scenes.load(path)
    ref = bem.solve(scene.surface, scene.material, speed=0.03, load=0.05, direction=np.pi / 4)
    assert rec["friction_curve"]["friction"][0] == pytest.approx(ref.friction, rel=1e-12)


@pytest.mark.parametrize("dirs, words", [('"east"', "direction_deg"), ("[0, 0]", "repeat"), ("[]", "non-empty")])
def test_bad_directions_are_named(tmp_path, dirs, words):
    with pytest.raises(bem.errors.InputError, match=words):
        scenes.load(_write(tmp_path, dirs))


def test_profile_directions_are_0_or_180(tmp_path):
    text = SCENE.replace("DIRS", "[0, 45]").replace("PLOTS", "false").replace("anisotropy = 2.0", "dim = 1")
    path = tmp_path / "p.toml"
    path.write_text(text)
    with pytest.raises(bem.errors.InputError, match="direction_deg = 45.*0 or pi"):
        scenes.load(path)


def test_direction_sweep_surfaces_every_directions_warnings(tmp_path, capsys):
    """Issue 25 item 6: the 30 and 90 degree points carried friction-form warnings while the
    sweep's top-level warnings were empty and the console printed none. Now every direction's
    warnings reach the top level, each prefixed with its direction, and the console prints them."""
    path = _write(tmp_path, "[0, 30, 90]")
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    out = capsys.readouterr().out
    rec = json.loads((tmp_path / "o" / "results.json").read_text())
    subs = {
        deg: json.loads((tmp_path / "o" / f"direction_{deg:07.3f}" / "results.json").read_text())["warnings"]
        for deg in (0, 30, 90)
    }
    assert subs[30]  # 32 cells, 4 scales, 30 % slopes: the oblique points do warn
    expected = [f"at direction {deg} deg: {w}" for deg in (0, 30, 90) for w in subs[deg]]
    assert rec["warnings"] == expected
    assert out.count("WARNING:") == len(expected)
