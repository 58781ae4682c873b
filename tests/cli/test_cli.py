"""The command line and scenes: a small study end to end, and scene validation."""

import inspect
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from bem.errors import InputError
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


@pytest.mark.parametrize(
    "bad, words",
    [
        (SMALL.replace("hurst = 0.8", "hurts = 0.8"), ["'hurts'", "valid keys", "hurst"]),
        (SMALL.replace("[outputs]", "[outputz]"), ["'outputz'", "valid keys"]),
        (SMALL.replace("load = 0.3", "load = -0.3"), ["load"]),
        (SMALL.replace("E_inf = 1.0e7", "E_inf = 1.0e6"), ["E_inf"]),
        (SMALL.replace('kind = "self_affine"', 'kind = "fractal"'), ["kind", "self_affine"]),
    ],
)
def test_bad_scene_names_the_problem_without_traceback(tmp_path, bad, words):
    path = tmp_path / "bad.toml"
    path.write_text(bad)
    proc = subprocess.run(
        [sys.executable, "-m", "viscobem_cli.main", "run", str(path), "--out", str(tmp_path / "o")],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    for w in words:
        assert w in proc.stderr


def test_missing_scene_file_is_a_clear_error(tmp_path, capsys):
    assert main(["run", str(tmp_path / "nope.toml"), "--out", str(tmp_path / "o")]) == 2
    assert "cannot read" in capsys.readouterr().err


# ----------------------------------------------------------------------------- a CLI that guides
def _cli(*args, env=None, **kw):
    """``viscobem ARGS`` in a fresh interpreter: (exit status, stdout, stderr)."""
    proc = subprocess.run(
        [sys.executable, "-m", "viscobem_cli.main", *args], capture_output=True, text=True, env=env, **kw
    )
    return proc.returncode, proc.stdout, proc.stderr


def test_version_and_help_list_every_built_in_scene():
    code, out, _ = _cli("--version")
    assert code == 0 and out.startswith("viscobem ") and out.split()[1][0].isdigit()
    names = scenes.builtin_scenes()
    assert {"seed", "seed_figures", "sphere"} <= set(names)
    for args in (["--help"], ["run", "--help"], ["scene", "--help"]):
        code, out, _ = _cli(*args)
        assert code == 0
        assert all(name in out for name in names), (args, out)
    assert "viscoelastic" in _cli("--help")[1]  # the description says what viscobem is


def test_mistyped_scene_name_lists_the_built_in_scenes():
    code, out, err = _cli("run", "sphrere")
    assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert "'sphrere'" in err and "Did you mean 'sphere'" in err
    assert all(name in err for name in scenes.builtin_scenes())


@pytest.mark.parametrize("name", scenes.builtin_scenes())
def test_scene_command_prints_every_built_in_scene(name, capsys):
    assert main(["scene", name]) == 0
    assert capsys.readouterr().out == (scenes.SCENE_DIR / f"{name}.toml").read_text()


# small sizes by the documented override mechanism (viscobem run --set)
TINY = ["--set", "surface.n=32", "--set", "surface.scales=8", "--set", "loading.xi.num=3"]


def test_template_runs_as_printed(tmp_path, capsys):
    """``viscobem scene`` prints the template; it runs as printed (shrunk with --set); its
    optional lines are comments, and each of them is a valid key once uncommented."""
    assert main(["scene"]) == 0
    template = capsys.readouterr().out
    for line in template.splitlines():  # no active placeholder (e.g. a cluster address)
        assert not line.lstrip().startswith("scheduler"), line
    path = tmp_path / "my.toml"
    path.write_text(template)
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--no-progress", *TINY]) == 0
    rec = json.loads((tmp_path / "out" / "results.json").read_text())
    assert rec["complete"] and rec["surface"]["n"] == 32 and len(rec["friction_curve"]["xi"]) == 3
    # every optional line "# key = value" is a valid key with a valid example value
    lines = template.splitlines()
    body = next(i for i, line in enumerate(lines) if line and not line.startswith("#"))  # after the header
    optional = [
        i
        for i, line in enumerate(lines)
        if i > body
        and line.startswith("# ")
        and line[2:3].isalpha()
        and "=" in line.split("#")[1]
        and not line.startswith("# other forms")
    ]
    assert len(optional) >= 10
    for i in optional:
        if "scheduler" not in lines[i]:
            lines[i] = lines[i][2:]
    scenes.parse("\n".join(lines), overrides=[s for s in TINY if s != "--set"])


def test_overrides_are_checked_like_the_scene():
    text = (scenes.SCENE_DIR / "seed.toml").read_text()
    assert scenes.parse(text, overrides=["surface.n=64", "surface.scales=16", "loading.xi.num=2"]).surface.n == 64
    with pytest.raises(InputError, match="'nn'.*valid keys"):
        scenes.parse(text, overrides=["surface.nn=64"])
    with pytest.raises(InputError, match="section.key=value"):
        scenes.parse(text, overrides=["surface.n"])


def test_missing_optional_dependency_names_the_extra(tmp_path):
    """dask and pyvista blocked (as if not installed): a command asked for one stops with one line
    naming the extra, exit 2 (viscobem validate runs without pyvista: tests/cli/test_extras.py)."""
    path = tmp_path / "s.toml"
    path.write_text(SMALL)
    block = "import sys; sys.modules['dask'] = sys.modules['distributed'] = sys.modules['pyvista'] = None; "
    for args, extra in [
        (["run", str(path), "--out", str(tmp_path / "o")], "vtk"),
        (["run", str(path), "--out", str(tmp_path / "o"), "--scheduler", "tcp://127.0.0.1:1"], "dask"),
    ]:
        code = f"{block}from viscobem_cli.main import main; sys.exit(main({args!r}))"
        proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        assert proc.returncode == 2, proc.stderr
        assert "Traceback" not in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
        assert f'pip install "viscobem[{extra}]"' in proc.stderr
    assert not (tmp_path / "o").exists()  # nothing was started


def test_console_states_tau_and_the_speed_range(tmp_path, capsys):
    path = tmp_path / "s.toml"
    path.write_text(SMALL.replace("vtk = true", "vtk = false\nplots = false"))
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "tau = 0.01 s (the material's longest creep time; set [loading] xi_time" in out
    assert "l = 10 mm (the cell length L)" in out
    assert "xi = 0.001 .. 0.1 is v = 0.001 .. 0.1 m/s" in out
    path.write_text(SMALL.replace("[outputs]", "xi_time = 0.1\n[outputs]").replace("vtk = true", "plots = false"))
    assert main(["run", str(path), "--out", str(tmp_path / "o2"), "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "tau = 0.1 s ([loading] xi_time)" in out and "v = 0.0001 .. 0.01 m/s" in out


def test_under_resolved_grid_warns_with_what_to_change(tmp_path, capsys):
    """n / scales = 2 points per shortest wavelength: the resolution warning at once; after the run
    every point's own warnings (bem.accuracy), gathered one sentence per kind with the speeds they
    come from; each printed, and each point's error estimate in results.json."""
    path = tmp_path / "coarse.toml"
    path.write_text(
        SMALL.replace("n = 64", "n = 32")
        .replace("vtk = true", "plots = false\nfields = false")
        .replace("start = 1e-3, stop = 1e-1", "start = 1e-2, stop = 1e-1")
    )
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    out = capsys.readouterr().out
    rec = json.loads((tmp_path / "o" / "results.json").read_text())
    warnings = rec["warnings"]
    assert "2 points per shortest wavelength" in warnings[0] and "Raise [surface] n to at least 64" in warnings[0]
    kinds = {p["kind"] for point in rec["points"] for p in point["warnings"]}
    assert {"contact_fraction", "friction_forms"} <= kinds, kinds
    gathered = [w for w in warnings[1:] if "friction_eq6" in w]
    assert len(gathered) == 1 and gathered[0].startswith("at 2 of 3 speeds (xi = 0.01, xi = 0.1; worst at xi = 0.01): ")
    assert out.count("WARNING:") == len(warnings)
    curve = rec["friction_curve"]
    assert all(e > 0.05 for e in curve["contact_fraction_error"])  # the estimate behind the warning
    assert all(p["error_estimate"]["method"] == "indicators" for p in rec["points"])
    # 4 points per wavelength (16 scales at 64²) gives no warning before the run
    assert scenes.parse(SMALL).warnings == ()


def test_output_files_are_readable_by_group_and_others(tmp_path):
    import os
    import stat

    path = tmp_path / "s.toml"
    path.write_text(SMALL.replace("vtk = true", "vtk = false"))
    old = os.umask(0o022)
    try:
        assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    finally:
        os.umask(old)
    files = [p for p in (tmp_path / "o").rglob("*") if p.is_file()]
    assert {"results.json", "fields.npz", "friction_curve.png"} <= {p.name for p in files}
    for p in files:
        assert stat.S_IMODE(p.stat().st_mode) == 0o644, p


@pytest.mark.parametrize("name, n", [("sphere", 48), ("cylinder", 128)])
def test_indenter_xi_is_on_the_relaxed_contact_radius(tmp_path, name, n):
    """Sphere and cylinder: xi = v tau / a0 (relaxed Hertz radius or half-width), contact
    radius and area per speed, a/a0 -> 1 at low speed, no roughness statistics."""
    s = scenes.load(name, overrides=[f"surface.n={n}", "loading.xi.num=3", "outputs.plots=false"])
    f_n, radius, e_star = s.load, 0.01, s.material.E0 / (1 - s.material.nu**2)
    if name == "sphere":
        a0 = (3 * f_n * radius / (4 * e_star)) ** (1 / 3)
    else:
        a0 = np.sqrt(4 * f_n * radius / (np.pi * e_star))
    assert s.xi_length == pytest.approx(a0, rel=1e-12)
    assert np.allclose(s.speeds, s.xi * a0 / 0.01, rtol=1e-12)
    from viscobem_cli.run.study import run_scene

    rec = run_scene(s, tmp_path, progress=False)
    assert "rms_height" not in rec["surface"] and "rms_slope" not in rec["surface"]
    assert rec["surface"]["hertz_radius_relaxed"] == [pytest.approx(a0)]
    a = np.array(rec["friction_curve"]["contact_radius"])
    # the contact radius (of equal area, or half the width) is within one element of Hertz's
    assert abs(a[0] - a0) < s.surface.spacing
    assert a[-1] < a[0]  # glassy at high speed: a smaller contact
    area = np.array(rec["friction_curve"]["contact_area"])
    assert np.allclose(area, np.pi * a**2 if name == "sphere" else 2 * a, rtol=1e-12)


def test_import_benchmark_prints_its_ratio_to_numpy_and_scipy(tmp_path, capsys):
    assert main(["bench", "import", "--quick", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    rec = json.loads((tmp_path / "import_bench.json").read_text())
    rows = {r["what"]: r for r in rec["rows"]}
    assert rows["reference (numpy + scipy.fft + scipy.sparse.linalg)"]["ratio_to_reference"] == 1.0
    assert rows["import bem"]["statement"] == "import bem" and "import bem" in out
    assert sorted(p.name for p in tmp_path.iterdir()) == ["import_bench.json"]  # only under --out


def test_scene_keys_table_documents_every_key():
    """viscobem_cli.scene.schema.KEYS is the table the scenes reference is generated from: every key
    the parser accepts is in it, with a type, a valid range and a meaning."""
    from viscobem_cli.scene.schema import KEYS, SECTIONS, keys_of

    for key in KEYS:
        assert key.type and key.valid and key.help and key.section in ("",) + SECTIONS, key
    names = {k.name for k in KEYS}
    assert len({(k.section, k.name) for k in KEYS}) == len(KEYS)  # no row twice
    # every key the parser reads from a table is a row of the table
    import re

    source = Path(inspect.getsourcefile(scenes.parse)).read_text()
    read = set(re.findall(r'\bt\.get\("(\w+)"', source)) | set(re.findall(r'\bt\["(\w+)"\]', source))
    assert read and read <= names, read - names
    for section in ("",) + SECTIONS:  # every key the parser accepts has a row
        rows = {k.name for k in keys_of(section)} | (set(SECTIONS) if section == "" else set())
        assert scenes.SCHEMA[section] <= rows, (
            f"add rows to viscobem_cli.scene.schema.KEYS: {scenes.SCHEMA[section] - rows}"
        )


def test_a_sweep_that_misses_the_friction_peak_says_so(tmp_path):
    """xi from 1e-4 to 1e-3 on the seed material: friction still rising at the end."""
    from viscobem_cli.guidance import peak_warnings

    path = tmp_path / "s.toml"
    path.write_text(
        SMALL.replace("start = 1e-3, stop = 1e-1", "start = 1e-4, stop = 1e-3").replace(
            "vtk = true", "plots = false\nfields = false"
        )
    )
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    warnings = json.loads((tmp_path / "o" / "results.json").read_text())["warnings"]
    assert any("largest at the highest speed" in w and "xi.stop" in w for w in warnings), warnings
    bell = {"load": 1.0, "xi": [1e-3, 1e-2, 1e-1], "friction": [0.1, 0.3, 0.2]}
    assert peak_warnings([bell], "x") == []
    falling = dict(bell, friction=[0.3, 0.2, 0.1])
    assert "lowest speed" in peak_warnings([falling], "x")[0] and "xi.start" in peak_warnings([falling], "x")[0]


def test_fields_in_float64_on_request(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(SMALL.replace("vtk = true", 'vtk = false\nplots = false\nfields_precision = "float64"'))
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-progress"]) == 0
    with np.load(tmp_path / "o" / "fields.npz") as f:
        assert f["pressure"].dtype == np.float64 and f["displacement"].dtype == np.float64
        assert np.allclose(f["pressure"].mean(axis=(1, 2)) * 0.01**2, 0.3, rtol=1e-12)  # exact to round-off
    # the point field files are folded into fields.npz; the numbers stay per point
    assert sorted(p.suffix for p in (tmp_path / "o" / "points").iterdir()) == [".json"] * 3
    with pytest.raises(InputError, match="fields_precision"):
        scenes.parse(SMALL.replace("[outputs]", '[outputs]\nfields_precision = "float16"'))
