"""The command line and scenes: a small study end to end, and scene validation."""
import json
import subprocess
import sys

import numpy as np
import pytest

from viscobem_cli import scene as scenes
from viscobem_cli.main import main

SMALL = """
title = "small"
[material]
E0 = 3.3333333333333335e6
E_inf = 1.0e7
creep_time = 0.01
[surface]
kind = "self_affine"
length = 0.01
n = 64
hurst = 0.8
scales = 16
rms_height = 2.0e-5
seed = 3
[loading]
load = 0.3
xi = { start = 1e-3, stop = 1e-1, num = 3 }
[outputs]
vtk = true
"""


def test_default_scene_is_the_seed_study():
    s = scenes.load()
    assert s.material.E_inf == 1e7 and s.material.E_inf / s.material.E0 == pytest.approx(3.0)
    assert s.material.creep_times[0] == pytest.approx(0.01)
    assert s.surface.length == 0.01 and s.load == 0.30
    assert s.xi[0] == pytest.approx(1e-4) and s.xi[-1] == pytest.approx(1e2)
    # xi = v tau / L with tau the creep time
    assert np.allclose(s.speeds, s.xi * 0.01 / 0.01)


def test_small_study_writes_every_output(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SMALL)
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--no-progress"]) == 0
    rec = json.loads((tmp_path / "out" / "results.json").read_text())
    curve = rec["friction_curve"]
    assert rec["complete"] and rec["all_converged"]
    assert set(["xi", "speed", "friction", "contact_fraction"]) <= set(curve)
    assert len(curve["friction"]) == 3 and all(f > 0 for f in curve["friction"])
    assert all(r <= 1e-8 for r in curve["residual"])
    for name in ["fields.npz", "friction_curve.png", "pressure_map.png", "vtk/sweep.pvd"]:
        assert (tmp_path / "out" / name).is_file(), name
    fields = np.load(tmp_path / "out" / "fields.npz")
    assert fields["pressure"].shape == (3, 64, 64) and fields["pressure"].dtype == np.float32
    # the stored fields are the solution: mean pressure times area is the load (float32: 6e-8 rounding)
    assert np.allclose(fields["pressure"].astype(float).mean(axis=(1, 2)) * 0.01**2, 0.3, rtol=1e-6)
    import pyvista as pv

    grid = pv.read(tmp_path / "out" / "vtk" / "point_000.vti")
    assert np.allclose(np.asarray(grid.point_data["pressure"]).reshape(64, 64, order="F"), fields["pressure"][0])


def test_unrequested_outputs_are_not_written(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(SMALL.replace("vtk = true", "vtk = false\nplots = false\nfields = false"))
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    # points/ holds the per-point records a rerun resumes from (no fields asked for: json only)
    assert sorted(p.name for p in (tmp_path / "o").iterdir()) == ["points", "results.json"]
    assert all(p.suffix == ".json" for p in (tmp_path / "o" / "points").iterdir())
    rec = json.loads((tmp_path / "o" / "results.json").read_text())
    assert rec["stages_run"] == ["friction_curve"]
    assert set(rec["stages"]) == {"fold", "friction_curve", "point_solve", "total"}


@pytest.mark.parametrize("bad, words", [
    (SMALL.replace("hurst = 0.8", "hurts = 0.8"), ["'hurts'", "valid keys", "hurst"]),
    (SMALL.replace("[outputs]", "[outputz]"), ["'outputz'", "valid keys"]),
    (SMALL.replace("load = 0.3", "load = -0.3"), ["load"]),
    (SMALL.replace("E_inf = 1.0e7", "E_inf = 1.0e6"), ["E_inf"]),
    (SMALL.replace('kind = "self_affine"', 'kind = "fractal"'), ["kind", "self_affine"]),
])
def test_bad_scene_names_the_problem_without_traceback(tmp_path, bad, words):
    path = tmp_path / "bad.toml"
    path.write_text(bad)
    proc = subprocess.run([sys.executable, "-m", "viscobem_cli.main", "run", str(path), "--out",
                           str(tmp_path / "o")], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    for w in words:
        assert w in proc.stderr


def test_missing_scene_file_is_a_clear_error(tmp_path, capsys):
    assert main(["run", str(tmp_path / "nope.toml"), "--out", str(tmp_path / "o")]) == 2
    assert "cannot read" in capsys.readouterr().err
