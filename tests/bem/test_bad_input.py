"""Bad input raises bem.errors.InputError (a ValueError) whose message names the parameter."""

import numpy as np
import pytest

import bem
from bem import Material, surfaces
from bem.errors import InputError
from viscobem_cli.main import main

NAN = float("nan")
SLS = dict(E0=1e6, E_inf=1e7)


@pytest.mark.parametrize(
    "build, name",
    [
        (lambda: Material.elastic(0.0), "E"),
        (lambda: Material.elastic(-1e6), "E"),
        (lambda: Material.elastic(NAN), "E"),
        (lambda: Material.elastic(np.inf), "E"),
        (lambda: Material.elastic("stiff"), "E"),
        (lambda: Material.elastic(1e6, nu=0.6), "nu"),
        (lambda: Material.elastic(1e6, nu=-0.1), "nu"),
        (lambda: Material.elastic(1e6, nu=NAN), "nu"),
        (lambda: Material.standard_linear_solid(E0=1e7, E_inf=1e7, creep_time=1.0), "E_inf"),
        (lambda: Material.standard_linear_solid(E0=1e7, E_inf=1e6, creep_time=1.0), "E_inf"),
        (lambda: Material.standard_linear_solid(E0=0.0, E_inf=1e6, creep_time=1.0), "E0"),
        (lambda: Material.standard_linear_solid(E0=NAN, E_inf=1e6, creep_time=1.0), "E0"),
        (lambda: Material.standard_linear_solid(**SLS), "relaxation_time or creep_time"),
        (
            lambda: Material.standard_linear_solid(**SLS, creep_time=1.0, relaxation_time=0.1),
            "relaxation_time or creep_time",
        ),
        (lambda: Material.standard_linear_solid(**SLS, creep_time=0.0), "creep_time"),
        (lambda: Material.standard_linear_solid(**SLS, relaxation_time=-1.0), "relaxation_time"),
        (lambda: Material.standard_linear_solid(**SLS, relaxation_time=NAN), "relaxation_time"),
        (lambda: Material.standard_linear_solid(**SLS, creep_time=1.0, nu=0.7), "nu"),
        (lambda: Material.from_prony(E0=1e6, moduli=[1e6, 2e6], times=[1.0]), "moduli and times"),
        (lambda: Material.from_prony(E0=1e6, moduli=[1e6], times=[0.0]), "times"),
        (lambda: Material.from_prony(E0=1e6, moduli=[1e6], times=[-1.0]), "times"),
        (lambda: Material.from_prony(E0=1e6, moduli=[1e6], times=[NAN]), "times"),
        (lambda: Material.from_prony(E0=1e6, moduli=[-1e6], times=[1.0]), "moduli"),
        (lambda: Material.from_prony(E0=1e6, moduli=[NAN], times=[1.0]), "moduli"),
        (lambda: Material.from_prony(E0=1e6, moduli=[1e6, 1e6], times=[1.0, 1.0]), "times"),
        (lambda: Material.from_prony(E0=-1e6, moduli=[1e6], times=[1.0]), "E0"),
        (lambda: Material.from_prony(E0=1e6, moduli=[[1e6]], times=[[1.0]]), "moduli"),
        (lambda: Material.from_prony(E0=1e6, moduli=[1e6], times=[1.0], nu=0.51), "nu"),
        (lambda: Material.from_creep(E0=1e6, compliances=[1e-7, 1e-7], times=[1.0]), "compliances and times"),
        (lambda: Material.from_creep(E0=1e6, compliances=[-1e-7], times=[1.0]), "compliances"),
        (lambda: Material.from_creep(E0=1e6, compliances=[1e-6], times=[1.0]), "compliances"),  # E_inf = inf
        (lambda: Material.from_creep(E0=1e6, compliances=[1e-7], times=[0.0]), "times"),
        (lambda: Material.from_creep(E0=1e6, compliances=[NAN], times=[1.0]), "compliances"),
        (lambda: Material.fit_prony([1.0, 2.0], [1e6, 1e6], [1e5]), "frequencies, storage and loss"),
        (lambda: Material.fit_prony([1.0, 2.0], [1e6, 1e6], [1e5, -1e5]), "loss"),
        (lambda: Material.fit_prony([0.0, 2.0], [1e6, 1e6], [1e5, 1e5]), "frequencies"),
        (lambda: Material.fit_prony([1.0, 2.0], [1e6, NAN], [1e5, 1e5]), "storage"),
        (lambda: Material.fit_prony([1.0, 2.0], [1e6, 1e6], [1e5, 1e5], times=[-1.0]), "times"),
        (lambda: Material.fit_prony([1.0, 2.0], [1e6, 1e6], [1e5, 1e5], terms_per_decade=0), "terms_per_decade"),
        (lambda: Material.elastic(1e6).folded(-1.0, 1.0), "w_min"),
        (lambda: Material.elastic(1e6).folded(1.0, 0.0), "w_max"),
    ],
)
def test_material_rejects(build, name):
    with pytest.raises(InputError, match=name):
        build()


SURFACE = surfaces.sinusoid(64, 1e-3, amplitude=1e-6)
MAT = Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(speed=0.1, load=0.0), "load"),
        (dict(speed=0.1, load=-1.0), "load"),
        (dict(speed=0.1, load=NAN), "load"),
        (dict(speed=0.1, load=np.inf), "load"),
        (dict(speed=0.1), "load"),  # neither load nor approach
        (dict(speed=0.1, load=1.0, approach=1e-7), "load"),  # both
        (dict(speed=0.1, approach=-1e-7), "approach"),
        (dict(speed=0.1, approach=NAN), "approach"),
        (dict(speed=-0.1, load=1.0), "speed"),
        (dict(speed=NAN, load=1.0), "speed"),
        (dict(speed=np.inf, load=1.0), "speed"),
        (dict(speed="fast", load=1.0), "speed"),
        (dict(speed=0.1, load=1.0, rtol=0.0), "rtol"),
        (dict(speed=0.1, load=1.0, rtol=-1e-8), "rtol"),
        (dict(speed=0.1, load=1.0, rtol=1.0), "rtol"),
        (dict(speed=0.1, load=1.0, rtol=NAN), "rtol"),
        (dict(speed=0.1, load=1.0, initial=np.ones(63)), "initial"),
        (dict(speed=0.1, load=1.0, initial=np.ones((64, 64))), "initial"),
        (dict(speed=0.1, load=1.0, periodic="no"), "periodic"),  # False is valid: isolated contact
        (dict(speed=0.1, load=1.0, method="lemke"), "method"),
    ],
)
def test_solve_rejects(kwargs, name):
    with pytest.raises(InputError, match=name):
        bem.solve(SURFACE, MAT, **kwargs)


@pytest.mark.parametrize(
    "surface, material, name",
    [
        (np.zeros(64), MAT, "surface"),
        ("rough.npy", MAT, "surface"),
        (SURFACE, "rubber", "material"),
        (SURFACE, None, "material"),
    ],
)
def test_solve_rejects_wrong_types(surface, material, name):
    with pytest.raises(InputError, match=name):
        bem.solve(surface, material, speed=0.1, load=1.0)


@pytest.mark.parametrize("speeds", [[], [-1.0], [0.1, -0.1], [NAN], [np.inf], [[0.1, 0.2]]])
def test_friction_curve_rejects_speeds(speeds):
    with pytest.raises(InputError, match="speeds"):
        bem.friction_curve(SURFACE, MAT, speeds=speeds, load=1.0)


def test_friction_curve_rejects_load():
    with pytest.raises(InputError, match="load"):
        bem.friction_curve(SURFACE, MAT, speeds=[0.1], load=-1.0)


def test_input_error_is_a_value_error():
    assert issubclass(InputError, ValueError)


# ------------------------------------------------------------ gaps found in 25c6e16, fixed in 2c4d878
@pytest.mark.parametrize("maxiter", [0, -1, 2.5, True])
def test_solve_rejects_maxiter(maxiter):
    with pytest.raises(InputError, match="maxiter"):
        bem.solve(SURFACE, MAT, speed=0.1, load=1.0, maxiter=maxiter)


def test_solve_rejects_nan_initial():
    initial = np.ones(64)
    initial[3] = NAN
    with pytest.raises(InputError, match="initial"):
        bem.solve(SURFACE, MAT, speed=0.1, load=1.0, initial=initial)


def test_friction_curve_rejects_non_numeric_speeds():
    with pytest.raises(InputError, match="speeds"):
        bem.friction_curve(SURFACE, MAT, speeds="fast", load=1.0)


def test_folded_rejects_reversed_band():
    with pytest.raises(InputError, match="w_min"):
        Material.elastic(1e6).folded(10.0, 1.0)


@pytest.mark.parametrize("factor", [1.0, 1.5])
def test_solve_rejects_approach_at_or_beyond_full_contact(factor):
    """At ``max h - mean h`` the zero-mean displacement closes the whole gap: the load is
    unbounded, and beyond it there is no solution (it used to run maxiter iterations)."""
    full = SURFACE.heights.max() - SURFACE.heights.mean()  # 1e-6 m for this sinusoid
    with pytest.raises(InputError, match="approach"):
        bem.solve(SURFACE, MAT, speed=0.1, approach=factor * full, maxiter=10)


# ------------------------------------------------------------ issue 7: heights, files, scenes, CLI
@pytest.mark.parametrize(
    "heights, words",
    [
        ([0.0, NAN, 1e-6, 0.0], ["heights", "finite"]),
        ([0.0, np.inf, 1e-6, 0.0], ["heights", "finite"]),
        (np.zeros((4, 5)), ["heights", "square"]),
        (np.zeros((4, 4, 4)), ["heights", "dimension"]),
        (np.zeros(1), ["heights", "at least 2"]),
        ([["a", "b"], ["c", "d"]], ["heights", "real numbers"]),
    ],
)
def test_from_heights_rejects(heights, words):
    with pytest.raises(InputError) as err:
        surfaces.from_heights(heights, 1e-3)
    for w in words:
        assert w in str(err.value)


@pytest.mark.parametrize("length", [0.0, -1e-3, NAN, np.inf])
def test_from_heights_rejects_length(length):
    with pytest.raises(InputError, match="length"):
        surfaces.from_heights(np.zeros(8), length)


@pytest.mark.parametrize(
    "name, content, words",
    [
        ("missing.npy", None, ["could not be read"]),
        ("folder.txt", "DIR", ["could not be read"]),
        ("garbage.txt", "1 2 x\n3 4 5\n", ["could not be read"]),
        ("empty.csv", "", ["could not be read", "empty"]),
        ("ragged.csv", "1,2,3\n4,5\n", ["could not be read"]),
        ("nan.txt", "0 1\nnan 0\n", ["finite"]),
        ("rect.txt", "0 1 2\n3 4 5\n", ["square"]),
        ("heights.dat", "0 1\n", [".npy, .txt or .csv"]),
    ],
)
def test_surface_file_rejects(tmp_path, name, content, words):
    path = tmp_path / name
    if content == "DIR":
        path.mkdir()
    elif content is not None:
        path.write_text(content)
    with pytest.raises(InputError) as err:
        surfaces.load(path, 1e-3)
    assert "path" in str(err.value)
    for w in words:
        assert w in str(err.value)


GOOD_SCENE = """
[material]
E0 = 3.3e6
E_inf = 1.0e7
creep_time = 0.01
[surface]
kind = "sinusoid"
length = 0.01
n = 16
amplitude = 1e-6
[loading]
load = 0.01
speeds = [0.001]
[solver]
rtol = 1e-8
[outputs]
plots = false
"""

# (replace this, with that) in GOOD_SCENE -> words the one-line error must contain
SCENE_CASES = [
    (("E0 = 3.3e6", "E0 = -3.3e6"), ["E0", "> 0"]),
    (("E0 = 3.3e6", "E0 = 0.0"), ["E0", "> 0"]),
    (("E_inf = 1.0e7", "E_inf = 1.0e6"), ["E_inf", "> E0"]),
    (("creep_time = 0.01", "creep_time = -0.01"), ["creep_time", "> 0"]),
    (("creep_time = 0.01", "creep_time = 0.0"), ["creep_time", "> 0"]),
    (("creep_time = 0.01", "creep_time = 0.01\nnu = 0.6"), ["nu", "[0.0, 0.5]"]),
    (("creep_time = 0.01", "creep_time = 0.01\nnu = -0.1"), ["nu", "[0.0, 0.5]"]),
    (
        ("E0 = 3.3e6\nE_inf = 1.0e7\ncreep_time = 0.01", "E0 = 1e6\nmoduli = [1e6, 1e6]\ntimes = [1.0]"),
        ["moduli and times", "same length"],
    ),
    (("E0 = 3.3e6\nE_inf = 1.0e7\ncreep_time = 0.01", "E0 = 1e6\nmoduli = [1e6]\ntimes = [-1.0]"), ["times", "> 0"]),
    (("E0 = 3.3e6\nE_inf = 1.0e7\ncreep_time = 0.01", "E = -1e6"), ["E ", "> 0"]),
    (("load = 0.01", "load = 0.0"), ["load", "> 0"]),
    (("load = 0.01", "load = -0.01"), ["load", "> 0"]),
    (("load = 0.01", 'load = "heavy"'), ["load", "number"]),
    (("load = 0.01", "load = nan"), ["load"]),
    (("speeds = [0.001]", "speeds = [-0.001]"), ["speeds", ">= 0"]),
    (("speeds = [0.001]", 'speeds = ["fast"]'), ["speeds", "number"]),
    (("speeds = [0.001]", "speeds = []"), ["speeds", "non-empty"]),
    (("speeds = [0.001]", "xi = { start = 1e-2, stop = 1e-3, num = 3 }"), ["xi", "start <= stop"]),
    (("speeds = [0.001]", 'xi = { start = "a", stop = 1e-3, num = 3 }'), ["xi.start", "number"]),
    (("speeds = [0.001]", "xi = { start = 1e-3, stop = 1e-2, num = 2.5 }"), ["xi.num", "integer"]),
    (("speeds = [0.001]", "speeds = [0.001]\nxi_time = -1.0"), ["xi_time", "> 0"]),
    (("rtol = 1e-8", "rtol = 2.0"), ["rtol", "(0, 1)"]),
    (("rtol = 1e-8", 'rtol = "tight"'), ["rtol", "number"]),
    (("rtol = 1e-8", "maxiter = 2.5"), ["maxiter", "integer"]),
    (("rtol = 1e-8", 'warm_start = "yes"'), ["warm_start", "true or false"]),
    (("amplitude = 1e-6", "amplitude = -1e-6"), ["amplitude", "> 0"]),
    (("n = 16", "n = 16.5"), ["n ", "integer"]),
    (("n = 16", "n = 1"), ["n ", ">= 2"]),
    (("length = 0.01", "length = 0.0"), ["length", "> 0"]),
    (("length = 0.01", "lenght = 0.01"), ["'lenght'", "valid keys", "length"]),
    (("[outputs]", "[outputs]\nplot = true"), ["'plot'", "valid keys", "plots"]),
    (("[solver]", "[solvr]"), ["'solvr'", "valid keys", "solver"]),
    (("[outputs]\nplots = false", "", "outputs = 3"), ["[outputs]", "table"]),
    (('kind = "sinusoid"', 'kind = "file"\npath = "nowhere.npy"'), ["nowhere.npy", "could not be read"]),
    (('kind = "sinusoid"', 'kind = "file"\npath = 3'), ["path", "string"]),
    (("[material]", "[material]\ndma = 'nowhere.csv'\n[unused]"), ["'unused'", "valid keys"]),
    (("E0 = 3.3e6\nE_inf = 1.0e7\ncreep_time = 0.01", "dma = 'nowhere.csv'"), ["dma", "nowhere.csv"]),
    (("[loading]", "[loading"), ["not valid TOML"]),
]


def _scene_cli(tmp_path, capsys, text, out):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    code = main(["run", str(path), "--out", str(out), "--no-progress"])
    return code, capsys.readouterr().err


@pytest.mark.parametrize("edit, words", SCENE_CASES)
def test_bad_scene_is_one_clear_line_and_touches_no_output(tmp_path, capsys, edit, words):
    old, new, top = edit if len(edit) == 3 else edit + ("",)
    assert old in GOOD_SCENE
    out = tmp_path / "out"
    out.mkdir()
    previous = '{"previous": "results"}'
    (out / "results.json").write_text(previous)
    code, err = _scene_cli(tmp_path, capsys, top + GOOD_SCENE.replace(old, new), out)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("viscobem: error:") and "Traceback" not in err
    for w in words:
        assert w in lines[0], (w, lines[0])
    assert (out / "results.json").read_text() == previous  # nothing written over
    assert sorted(p.name for p in out.iterdir()) == ["results.json"]


@pytest.mark.parametrize("make", ["missing", "directory", "binary", "empty"])
def test_unreadable_scene_file(tmp_path, capsys, make):
    path = tmp_path / "scene.toml"
    if make == "directory":
        path.mkdir()
    elif make == "binary":
        path.write_bytes(b"\xff\xfe\x00\x81 not toml \x00")
    elif make == "empty":
        path.write_text("")
    code = main(["run", str(path), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and "scene" in err
    assert not (tmp_path / "out").exists()


def test_unwritable_output_is_one_clear_line(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    code, err = _scene_cli(tmp_path, capsys, GOOD_SCENE, blocker / "out")
    assert code == 2 and len(err.strip().splitlines()) == 1 and "cannot write" in err
    assert blocker.read_text() == "not a folder"


def test_failing_run_keeps_previous_results(tmp_path, capsys):
    """A good run, then a run that fails after parsing (the solver rejects its input): the
    first run's results.json is intact, byte for byte."""
    import json
    from dataclasses import replace

    from viscobem_cli import scene as scenes
    from viscobem_cli.run.study import run_scene

    out = tmp_path / "out"
    code, _ = _scene_cli(tmp_path, capsys, GOOD_SCENE, out)
    assert code == 0
    before = (out / "results.json").read_bytes()
    assert json.loads(before)["complete"]
    bad = replace(scenes.parse(GOOD_SCENE), load=-1.0, loads=(-1.0,))  # bypasses the scene check
    with pytest.raises(InputError, match="load"):
        run_scene(bad, out, progress=False)
    assert (out / "results.json").read_bytes() == before


def test_interrupted_sweep_leaves_valid_json_with_finished_points(tmp_path, monkeypatch):
    import json

    import viscobem_cli.run.study as study
    from viscobem_cli import scene as scenes

    scene = scenes.parse(GOOD_SCENE.replace("speeds = [0.001]", "speeds = [0.001, 0.002, 0.003]"))
    real = bem.sliding.solve  # the solve that bem.sweep calls
    calls = []

    def interrupted(*args, **kwargs):
        calls.append(1)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return real(*args, **kwargs)

    monkeypatch.setattr("bem.sliding.solve", interrupted)
    with pytest.raises(KeyboardInterrupt):
        study.run_scene(scene, tmp_path, progress=False)
    rec = json.loads((tmp_path / "results.json").read_text())
    assert not rec["complete"]
    assert rec["friction_curve"]["success"][:2] == [True, True] and rec["friction_curve"]["friction"][2] is None
    # the two finished points are on disk (for resuming), and no temporary files are left
    assert sorted(p.name for p in tmp_path.iterdir()) == ["points", "results.json"]
    assert len(list((tmp_path / "points").glob("*.json"))) == 2
    assert all(p.suffix in (".json", ".npz") for p in (tmp_path / "points").iterdir())


def test_write_atomic_failure_keeps_old_file(tmp_path):
    from viscobem_cli.files import write_atomic

    path = tmp_path / "results.json"
    path.write_text("old")
    with pytest.raises(TypeError):
        write_atomic(path, b"bytes into a text file")  # fails inside the write
    assert path.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["results.json"]
