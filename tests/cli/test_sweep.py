"""Sweeps: resume after an interruption, process pool and Dask give the same points,
ensembles (mean, standard error), only requested stages run, folding, scene checks."""

import json

import numpy as np
import pytest

import bem.sliding
from bem.errors import InputError
from viscobem_cli import scene as scenes
from viscobem_cli.run.study import fold_material, run_scene

BASE = """
title = "sweep test"
[material]
E0 = 3.3333333333333335e6
E_inf = 1.0e7
creep_time = 0.01
[surface]
kind = "self_affine"
length = 0.01
n = 32
hurst = 0.8
scales = 8
rms_height = 2.0e-5
seed = 5
realisations = 2
[loading]
load = 0.3
xi = { start = 1e-3, stop = 1e-1, num = 4 }
[solver]
rtol = 1e-9
[outputs]
fields = false
plots = false
"""


def _scene(text=BASE, **replace):
    for old, new in replace.items():
        text = text.replace(old, new)
    return scenes.parse(text)


def _numbers(rec):
    return {(p["r"], p["l"], p["i"]): (p["friction"], p["contact_fraction"]) for p in rec["points"]}


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    return run_scene(_scene(), tmp_path_factory.mktemp("ref"), progress=False)


def test_ensemble_reports_mean_and_standard_error(reference):
    curve = reference["friction_curve"]
    pts = reference["points"]
    assert len(pts) == 8 and reference["seeds"] == [5, 6]
    for i in range(4):
        mu = [p["friction"] for p in pts if p["i"] == i]
        assert curve["friction"][i] == pytest.approx(np.mean(mu), rel=1e-14)
        assert curve["friction_se"][i] == pytest.approx(np.std(mu, ddof=1) / np.sqrt(2), rel=1e-12)
    # the realisations are different surfaces: their friction differs
    assert all(se > 0 for se in curve["friction_se"])


def test_interrupted_sweep_resumes_where_it_stopped(tmp_path, monkeypatch, reference):
    real_solve, calls = bem.sliding.solve, []  # the solve that bem.sweep calls

    def interrupted(*args, **kw):
        if len(calls) == 5:
            raise KeyboardInterrupt  # the user presses Ctrl-C during the 6th solve
        calls.append(kw["speed"])
        return real_solve(*args, **kw)

    monkeypatch.setattr(bem.sliding, "solve", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_scene(_scene(), tmp_path, progress=False)
    partial = json.loads((tmp_path / "results.json").read_text())
    assert not partial["complete"] and len(partial["points"]) == 5  # every finished point is on disk
    assert len(list((tmp_path / "points").glob("*.json"))) == 5
    calls.clear()
    monkeypatch.setattr(bem.sliding, "solve", lambda *a, **kw: (calls.append(kw["speed"]), real_solve(*a, **kw))[1])
    rec = run_scene(_scene(), tmp_path, progress=False)
    assert rec["resumed_points"] == 5 and len(calls) == 3  # only the 3 missing points were solved
    assert rec["complete"] and rec["all_converged"]
    # same answers as an uninterrupted run, to the solver tolerance (different warm starts)
    for key, (mu, a) in _numbers(reference).items():
        assert _numbers(rec)[key][0] == pytest.approx(mu, rel=1e-6)
        assert _numbers(rec)[key][1] == pytest.approx(a, abs=1e-12)
        assert _numbers(rec)[key][1] == pytest.approx(a, abs=1e-12)
    # a changed study in the same folder does not reuse the old points
    rec2 = run_scene(_scene(**{"load = 0.3": "load = 0.35"}), tmp_path, progress=False)
    assert rec2["resumed_points"] == 0


def test_process_pool_gives_the_same_points(tmp_path, reference):
    rec = run_scene(_scene(), tmp_path, progress=False, workers=2)
    assert rec["solver"]["workers"] == 2 and rec["all_converged"]
    for key, (mu, a) in _numbers(reference).items():
        # warm starts differ between chunks: equal to the complementarity tolerance
        assert _numbers(rec)[key][0] == pytest.approx(mu, rel=1e-6)
        assert _numbers(rec)[key][1] == pytest.approx(a, abs=1e-12)


def test_dask_local_cluster_gives_the_same_points(tmp_path, reference):
    distributed = pytest.importorskip(
        "dask.distributed", reason="dask[distributed] is not installed (pip install '.[dask]')"
    )
    with distributed.LocalCluster(
        processes=False, n_workers=1, threads_per_worker=1, dashboard_address=None
    ) as cluster:
        text = BASE.replace("rtol = 1e-9", f'rtol = 1e-9\nscheduler = "{cluster.scheduler_address}"')
        rec = run_scene(scenes.parse(text), tmp_path, progress=False)
    assert rec["solver"]["scheduler"] == cluster.scheduler_address and rec["all_converged"]
    for key, (mu, a) in _numbers(reference).items():
        assert _numbers(rec)[key][0] == pytest.approx(mu, rel=1e-6)
        assert _numbers(rec)[key][1] == pytest.approx(a, abs=1e-12)


def test_scene_without_anisotropy_does_not_compute_it(tmp_path, monkeypatch):
    from bem.analysis import anisotropy, persson

    def forbidden(*a, **k):
        raise AssertionError("computed although the scene did not ask for it")

    for mod, names in [
        (anisotropy, ["spectral_moments", "contact_psd", "psd_contour", "relative_moments"]),
        (persson, ["friction", "friction_discrete", "friction_for_surface"]),
    ]:
        for name in names:
            monkeypatch.setattr(mod, name, forbidden)
    rec = run_scene(_scene(), tmp_path, progress=False)
    assert rec["stages_run"] == ["friction_curve"]
    assert "anisotropy" not in rec and "contact_psd" not in rec and "persson" not in rec
    assert not list((tmp_path / "points").glob("*.npz"))  # no fields stored either


def test_requested_stages_run_and_are_timed(tmp_path):
    text = BASE.replace("plots = false", "plots = false\nanisotropy = true\ncontact_psd = true\npersson = true")
    rec = run_scene(scenes.parse(text), tmp_path, progress=False)
    assert rec["stages_run"] == ["friction_curve", "anisotropy", "contact_psd", "persson"]
    for stage in ("contact_psd", "persson", "point_anisotropy"):
        assert rec["stages"][stage] >= 0
    a = rec["anisotropy"][0]
    assert a["gamma_relative"][0] == pytest.approx(1.0, rel=1e-12)  # lowest speed is the reference
    assert all(0 < g <= 1 for g in a["gamma"])
    c = rec["contact_psd"][0]
    assert all(x is not None and x > 0 for x in c["aspect_ratio"])
    assert len(rec["persson"][0]["friction"]) == 4


@pytest.mark.parametrize("dim", [1, 2])
def test_prony_terms_outside_the_band_are_folded(dim):
    """Terms at 1e-12 s (relaxed at every speed) and 1e9 s (glassy for every moving mode)
    around the active one. The relaxed term is always folded; the glassy one only on a 1-D
    profile: the q_x = 0 modes of a 2-D cell are static and respond with E0. The invariant is
    the operator: its symbol is unchanged to ~tol at every speed of the sweep."""
    from bem.halfspace.periodic import PeriodicHalfSpace

    text = BASE.replace("E_inf = 1.0e7\ncreep_time = 0.01", "moduli = [1e6, 5e6, 2e6]\ntimes = [1e-12, 3e-3, 1e9]")
    text = text.replace("xi = { start = 1e-3, stop = 1e-1, num = 4 }", "speeds = [1e-3, 1e-2, 1e-1, 1.0]")
    text = text.replace("seed = 5", f"seed = 5\ndim = {dim}")
    s = scenes.parse(text)
    m = fold_material(s)
    assert 3e-3 in m.relaxation_times and 1e-12 not in m.relaxation_times
    if dim == 1:
        assert m.moduli.size == 1 and m.E0 == pytest.approx(s.material.E0 + 2e6)
    else:
        assert m.moduli.size == 2 and m.E0 == s.material.E0
    for v in s.speeds:
        a = PeriodicHalfSpace(s.surface.shape, s.surface.length, s.material, v).symbol
        b = PeriodicHalfSpace(s.surface.shape, s.surface.length, m, v).symbol
        assert np.max(np.abs(a - b)) <= 1e-5 * np.max(np.abs(a))


@pytest.mark.parametrize(
    "old, new, word",
    [
        ("realisations = 2", "realisations = 0", "realisations"),
        ("realisations = 2", "realisations = 2\nworkers = 1", "workers"),
        ("rtol = 1e-9", "rtol = 1e-9\nworkers = 0", "workers"),
        ("rtol = 1e-9", "rtol = 1e-9\nscheduler = 3", "scheduler"),
        ("load = 0.3", "load = [0.3, -1]", "load"),
        ("[outputs]", "[analysis]\ncontact_level = 1.5\n[outputs]", "contact_level"),
    ],
)
def test_bad_scene_values_name_the_key(old, new, word):
    with pytest.raises(InputError, match=word):
        _scene(**{old: new})


def test_load_list_sweeps_loads(tmp_path):
    rec = run_scene(
        _scene(**{"load = 0.3": "load = [0.2, 0.4]", "realisations = 2": "realisations = 1", "num = 4": "num = 2"}),
        tmp_path,
        progress=False,
    )
    assert [c["load"] for c in rec["curves"]] == [0.2, 0.4]
    # more load, more contact at every speed
    assert all(b > a for a, b in zip(rec["curves"][0]["contact_fraction"], rec["curves"][1]["contact_fraction"]))


def test_material_from_a_dma_table(tmp_path):
    # a DMA master curve sampled from a known 3-term Prony series, fitted back by the scene
    true = bem.Material.from_prony(E0=2e6, moduli=[3e6, 4e6, 1e6], times=[1e-1, 1e-3, 1e-5])
    w = np.logspace(-2, 7, 60)
    e = true.complex_modulus(w)
    np.savetxt(
        tmp_path / "dma.csv", np.column_stack([w, e.real, e.imag]), delimiter=",", header="w (rad/s), E' (Pa), E'' (Pa)"
    )
    text = BASE.replace("E0 = 3.3333333333333335e6\nE_inf = 1.0e7\ncreep_time = 0.01", 'dma = "dma.csv"')
    s = scenes.parse(text, base=tmp_path)
    fitted = s.material.complex_modulus(w)
    # the true times lie on the fit's grid (2 per decade from 1/w_max = 1e-7 s to 1/w_min = 1e2 s),
    # so the non-negative least squares recovers the series: measured misfit 4e-16
    assert np.max(np.abs(fitted - e) / np.abs(e)) < 1e-9
    assert s.material.E_inf == pytest.approx(true.E_inf, rel=1e-9)


def test_built_in_scenes_load_by_name():
    assert {"seed", "seed_figures"} <= set(scenes.builtin_scenes())
    s = scenes.load("seed_figures")
    assert len(s.realisations) == 8 and s.seeds == tuple(range(1, 9))
    assert s.outputs["anisotropy"] and s.outputs["contact_psd"] and s.outputs["persson"]
    assert 1.17e-2 in s.xi.tolist() and s.plot_xi == 1.17e-2


def test_requested_plots_are_written(tmp_path):
    text = BASE.replace("plots = false", "plots = true\nanisotropy = true\ncontact_psd = true\npersson = true")
    text = text.replace("fields = false", "fields = true")
    rec = run_scene(scenes.parse(text), tmp_path, progress=False)
    for name in [
        "friction_curve.png",
        "contact_area.png",
        "pressure_map.png",
        "contact_map.png",
        "deformed_surface.png",
        "polar_m2.png",
        "contact_psd.png",
        "anisotropy.png",
    ]:
        assert name in rec["files"] and (tmp_path / name).stat().st_size > 1000, name


def test_command_line_workers_must_be_positive(tmp_path, capsys):
    from viscobem_cli.main import main

    path = tmp_path / "s.toml"
    path.write_text(BASE)
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--workers", "0"]) == 2
    assert "--workers" in capsys.readouterr().err


# ----------------------------------------------------------------------------- one sweep
def test_cli_points_are_the_friction_curve_of_the_api(tmp_path):
    """The command line's chunks and bem.friction_curve run the same warm-started loop: the
    same surface, material and speeds give the same numbers to round-off."""
    s = _scene(**{"realisations = 2": "realisations = 1"})
    rec = run_scene(s, tmp_path, progress=False)
    curve = bem.friction_curve(s.surface, s.material, speeds=s.speeds, load=0.3, rtol=1e-9)
    assert np.allclose(rec["friction_curve"]["friction"], curve.friction, rtol=1e-12, atol=0)
    assert rec["friction_curve"]["iterations"] == curve.iterations.astype(int).tolist()


def test_friction_curve_over_several_loads():
    s = _scene(**{"realisations = 2": "realisations = 1"})
    speeds = s.speeds[:3]
    seen = []
    curves = bem.friction_curve(
        s.surface, s.material, speeds=speeds, load=[0.2, 0.4], rtol=1e-9, callback=lambda k, v, res, msg: seen.append(k)
    )
    assert [c.load for c in curves] == [0.2, 0.4] and sorted(seen) == list(range(6))
    for c, load in zip(curves, (0.2, 0.4)):
        single = bem.friction_curve(s.surface, s.material, speeds=speeds, load=load, rtol=1e-9)
        assert np.array_equal(c.friction, single.friction) and c.all_converged
    assert np.all(curves[1].contact_fraction > curves[0].contact_fraction)
    assert "FrictionCurve(load=0.2, 3 speeds" in repr(curves[0])
    with pytest.raises(InputError, match="load"):
        bem.friction_curve(s.surface, s.material, speeds=speeds, load=[0.2, -1.0])


# ----------------------------------------------------------------------------- kill -9 and resume
def test_killed_sweep_resumes_with_identical_results(tmp_path):
    """``kill -9`` in the middle of ``viscobem run``: the folder keeps whole point files only,
    and a rerun solves just the missing points, giving the uninterrupted run's numbers."""
    import os
    import signal
    import subprocess
    import sys
    import time

    from viscobem_cli.main import main

    text = (
        BASE.replace("n = 32", "n = 64")
        .replace("scales = 8", "scales = 16")
        .replace("realisations = 2", "realisations = 1")
        .replace("num = 4", "num = 12")
        .replace("fields = false", "fields = true")
    )
    path = tmp_path / "s.toml"
    path.write_text(text)
    out = tmp_path / "killed"
    proc = subprocess.Popen(
        [sys.executable, "-m", "viscobem_cli.main", "run", str(path), "--out", str(out), "--no-progress"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    deadline = time.monotonic() + 120
    while len(list((out / "points").glob("*.json"))) < 3 and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.02)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    done = len(list((out / "points").glob("*.json")))
    assert 3 <= done < 12, f"{done} points written before the kill"
    partial = json.loads((out / "results.json").read_text())  # written at the start: valid JSON
    assert not partial["complete"]
    assert main(["run", str(path), "--out", str(out), "--no-progress"]) == 0
    resumed = json.loads((out / "results.json").read_text())
    assert resumed["complete"] and resumed["resumed_points"] >= done
    assert not list(out.rglob(".*.tmp"))
    assert main(["run", str(path), "--out", str(tmp_path / "whole"), "--no-progress"]) == 0
    whole = json.loads((tmp_path / "whole" / "results.json").read_text())
    for a, b in zip(resumed["points"], whole["points"]):
        # a resumed point may start cold instead of warm: equal to the solver tolerance
        assert a["friction"] == pytest.approx(b["friction"], rel=1e-6)
        assert a["contact_fraction"] == pytest.approx(b["contact_fraction"], abs=1e-12)
    with np.load(out / "fields.npz") as f, np.load(tmp_path / "whole" / "fields.npz") as g:
        assert f["pressure"].shape == g["pressure"].shape == (12, 64, 64)
        assert np.allclose(f["pressure"], g["pressure"], rtol=0, atol=1e-5 * g["pressure"].max())


@pytest.mark.parametrize("speeds", ["0.01", ["0.01", "0.1"], [True, False], [-1.0, 0.1], [[0.1, 0.2]]])
def test_friction_curve_wants_speeds_as_numbers(speeds):
    s = _scene(**{"realisations = 2": "realisations = 1"})
    with pytest.raises(InputError, match="speeds must be") as err:
        bem.friction_curve(s.surface, s.material, speeds=speeds, load=0.3)
    assert "np.float64" not in str(err.value)
