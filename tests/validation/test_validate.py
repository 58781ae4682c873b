"""The validation harness: metrics, the ``viscobem validate`` command, its reports, VTK files
(read back with pyvista and meshio), exit statuses and regression baselines.

The default tests run the cheap periodic cases (and one rolling-cylinder speed on a coarse
grid, for the FEM .vtu files) through the CLI in-process; the whole quick set against the
stored baselines is ``pytest -m slow`` (about two minutes).
"""

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from conftest import vtk_units

from bem.errors import InputError
from validation import baselines, metrics
from validation.cases import CASES, cylinder, periodic
from viscobem_cli.main import main

CHEAP = ["rubber", "full_contact_rough", "elastic_rough_dense"]  # registry order


# ------------------------------------------------------------------ metrics
def test_bin_average_is_exact_for_the_piecewise_linear_interpolant():
    x = np.linspace(0.0, 1.0, 11)
    edges = np.array([0.05, 0.33, 0.5, 0.97])
    got = metrics.bin_average(x, 2 * x + 1, edges)
    want = [(e1 + e0) + 1 for e0, e1 in zip(edges[:-1], edges[1:])]  # mean of 2x + 1 over [e0, e1]
    np.testing.assert_allclose(got, want, rtol=1e-14)
    # outside the samples the pressure is zero: half of the bin [0.9, 1.1] carries p = 1
    assert metrics.bin_average(x, np.ones_like(x), [0.9, 1.1])[0] == pytest.approx(0.5, rel=1e-14)


def test_sampled_edges_are_midway_and_edge_error_is_in_cells():
    x = np.arange(10) * 0.1
    p = np.array([0, 0, 1, 2, 3, 2, 1, 0, 0, 0], float)
    trail, lead = metrics.sampled_edges(x, p)
    assert trail == pytest.approx(0.15) and lead == pytest.approx(0.65)
    assert metrics.edge_error(lead, 0.6, 0.1) == pytest.approx(0.5)


def test_rel_l2_uses_the_trapezoid_rule_on_any_spacing():
    x = np.array([0.0, 0.1, 1.0])
    ref = np.array([1.0, 1.0, 1.0])
    # error 1 on [0, 0.1] only at x = 0: int e^2 = 0.05 (trapezoid), int ref^2 = 1
    assert metrics.rel_l2(x, ref + np.array([1.0, 0, 0]), ref) == pytest.approx(np.sqrt(0.05), rel=1e-14)
    assert metrics.rel_max(ref * 1.5, ref) == pytest.approx(0.5)


_MEASURE = """
import time, numpy as np
from validation.metrics import measure
def hold():
    a = np.ones(6_000_000)  # 46 MiB, touched
    time.sleep(0.15)  # several sampling intervals
    return a.sum()
value, cost = measure(hold)
print(value, cost.seconds, cost.peak_mib, 6_000_000 * 8 / 2**20)
"""


def test_measure_sees_memory_held_during_the_call():
    """In a fresh interpreter (the RSS growth of a long-lived process misses pages it already
    holds, as documented): the 46 MiB array shows up, sampled every 20 ms. The bounds are in
    units of the array itself (its pages are touched, so all of them are resident), not of
    any one machine's baseline."""
    import subprocess
    import sys

    root = Path(__file__).resolve().parents[2]
    out = subprocess.run(
        [sys.executable, "-c", _MEASURE],
        capture_output=True,
        text=True,
        check=True,
        cwd=root,
        env={"PYTHONPATH": str(root), "PATH": "/usr/bin:/bin"},
    ).stdout.split()
    value, seconds, peak, array = (float(v) for v in out)
    assert value == 6_000_000 and seconds >= 0.15
    assert 0.95 * array <= peak <= 2 * array


# ------------------------------------------------------------------ the command
@pytest.fixture(scope="module")
def cheap_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("validate")
    argv = ["validate", "--quick", "--no-progress", "--out", str(out)]
    for name in CHEAP:
        argv += ["--case", name]
    status = main(argv)
    return status, out, json.loads((out / "report.json").read_text())


def test_cheap_cases_pass_and_report_every_number(cheap_run):
    status, out, record = cheap_run
    assert status == 0
    assert list(record["cases"]) == CHEAP and record["summary"]["failed"] == []
    for name, case in record["cases"].items():
        assert case["status"] == "passed" and case["checks"] and case["runs"]
        for k in case["checks"]:
            assert set(k) >= {"metric", "solver", "label", "value", "tolerance", "passed", "why"}
            assert k["why"], f"{name} {k['metric']}: every tolerance says why"
        assert all(r["seconds"] > 0 for r in case["runs"])
    md = (out / "report.md").read_text()
    html = (out / "report.html").read_text()
    for name in CHEAP:
        assert f"`{name}`" in md and f"id='{name}'" in html
    plots = html.count("class='vb-zoom vb-plot'") + html.count("data:image/png;base64,")
    assert plots >= 3 * len(CHEAP) and f"data-plots='{plots}'" in html  # overlays, sweeps, timings
    assert html.count("<img") == html.count("data:image/png;base64,")
    assert len(list((out / "plots").glob("*.png"))) == plots  # each plot also as its own PNG
    assert "src='http" not in html  # self-contained


def _pvd_entries(path):
    return [(d.get("file"), float(d.get("timestep"))) for d in ET.parse(path).getroot().iter("DataSet")]


def every_file_states_its_units(folder):
    """Parse ``units`` from every VTK file under ``folder`` (each block of a .vtm); return the
    suffixes seen. BEM and FEM files carry the same JSON object."""
    import pyvista as pv

    files = sorted(p for p in Path(folder).rglob("*") if p.suffix in (".vti", ".vtu", ".vtp", ".vtm"))
    for f in files:
        data = pv.read(f)
        for ds in data if isinstance(data, pv.MultiBlock) else [data]:
            units = vtk_units(ds)
            assert units["displacement"] == "m" and units["speed"] == "m/s", f
            assert units.get("pressure", "Pa") == "Pa" and units.get("stress", "Pa") == "Pa", f
    return {f.suffix for f in files}


def paraview_snippet():
    """The Python block of docs/paraview.md that reads a file's provenance and units."""
    text = (Path(__file__).parents[2] / "docs" / "paraview.md").read_text()
    block = text[text.index("## What made a file") :].split("```python\n", 1)[1].split("```", 1)[0]
    assert 'pv.read("viscobem-out/vtk/point_000.vti")' in block
    return block


def run_paraview_snippet(path, capsys):
    exec(paraview_snippet().replace("viscobem-out/vtk/point_000.vti", str(path)), {})
    return capsys.readouterr().out


def test_every_vtk_file_reads_back(cheap_run):
    import pyvista as pv

    _, out, record = cheap_run
    assert every_file_states_its_units(out / "vtk") == {".vti", ".vtm", ".vtu", ".vtp"}  # BEM and FEM
    files = [f for c in record["cases"].values() for f in c["files"]]
    assert files and all((out / f).exists() for f in files)
    for f in files:
        if f.endswith(".pvd"):
            entries = _pvd_entries(out / f)
            assert entries and all((out / f).parent.joinpath(e).exists() for e, _ in entries)
            reader = pv.get_reader(out / f)  # ParaView's view: one time step per entry
            np.testing.assert_allclose(reader.time_values, sorted(t for _, t in entries))
            reader.set_active_time_point(len(entries) - 1)
            data = reader.read()[0]
            if isinstance(data, pv.MultiBlock):  # an FEM run: block and contact interface
                data = data["interface"]
            assert "pressure" in data.point_data
            continue
        if f.endswith(".vtm"):  # the FEM: its block and its contact interface
            blocks = pv.read(out / f)
            iface = blocks["interface"]
            p, g, c = (np.asarray(iface.point_data[k]) for k in ("pressure", "gap", "contact"))
            assert "stress" in blocks["volume"].cell_data and np.array_equal(c.astype(bool), p > 0)
            assert np.all(p >= 0) and np.all(g >= -1e-6 * np.ptp(g))
            continue
        grid = pv.read(out / f)
        p, g, c = (np.asarray(grid.point_data[k]) for k in ("pressure", "gap", "contact"))
        assert "displacement" in grid.point_data and p.size == grid.n_points
        assert np.array_equal(c.astype(bool), p > 0)
        assert np.all(p >= 0) and np.all(g >= -1e-9 * max(np.ptp(grid.point_data["heights"]), 1e-30))


def test_vti_holds_the_reported_pressure(cheap_run):
    """The dense case's 2-D grid: the VTK pressure along y = 0 is the plotted BEM profile."""
    import pyvista as pv

    _, out, record = cheap_run
    case = record["cases"]["elastic_rough_dense"]
    prof = case["profiles"][1]["curves"]["bem-periodic"][1]
    grid = pv.read(out / "vtk" / "elastic_rough_dense" / "bem" / "point_001.vti")
    n = grid.dimensions[0]
    p = np.asarray(grid.point_data["pressure"]).reshape((n, n), order="F")
    np.testing.assert_array_equal(p[:, 0], prof)


def test_fem_vtu_and_pvd_of_a_rolling_sweep(tmp_path, monkeypatch, capsys):
    """One coarse speed of the rolling cylinder through the CLI: BEM .vti (periodic and isolated),
    FEM .vtm (block and interface), a .pvd per solver; every file's ``units`` parses the same way,
    and the docs' snippet reads both kinds."""
    import pyvista as pv

    cfg = dict(cylinder.QUICK_SLS[3], s=[0.3], cells=10, resolution=2)
    monkeypatch.setitem(cylinder.QUICK_SLS, 3, cfg)
    main(
        [
            "validate",
            "--jobs",
            "1",  # in this process: the test patches the case
            "--quick",
            "--no-progress",
            "--no-baseline",
            "--no-plots",
            "--case",
            "cylinder_sls_r3",
            "--out",
            str(tmp_path),
        ]
    )
    record = json.loads((tmp_path / "report.json").read_text())
    case = record["cases"]["cylinder_sls_r3"]
    assert case["status"] in ("passed", "failed")  # coarser than the quick set: plumbing only
    assert {k["solver"] for k in case["checks"]} == set(cylinder.SOLVERS)
    blocks = pv.read(tmp_path / "vtk" / "cylinder_sls_r3" / "fem" / "point_000.vtm")
    vol, iface = blocks["volume"], blocks["interface"]
    assert {"stress", "strain", "dissipation", "von_mises", "hydrostatic_pressure"} <= set(vol.cell_data.keys())
    assert np.all(np.asarray(vol.cell_data["dissipation"]) >= -1e-9)
    fem = next(r for r in case["runs"] if r["solver"] == "fem")
    assert "unknowns" in fem["detail"] and "flexibility" in fem["detail"] and fem["peak_mib"] >= 0
    assert iface.field_data["speed"][0] == pytest.approx(record["cases"]["cylinder_sls_r3"]["numbers"]["speeds"][0])
    assert iface.field_data["load"][0] == cylinder.P and iface.field_data["radius"][0] == cylinder.R
    assert np.all(np.asarray(iface.point_data["pressure"]) >= 0)
    for sub in cylinder.SOLVERS:
        entries = _pvd_entries(tmp_path / "vtk" / "cylinder_sls_r3" / sub / "sweep.pvd")
        assert [t for _, t in entries] == [0.3]
        assert list(pv.get_reader(tmp_path / "vtk" / "cylinder_sls_r3" / sub / "sweep.pvd").time_values) == [0.3]
    bem = pv.read(tmp_path / "vtk" / "cylinder_sls_r3" / "bem-periodic" / "point_000.vti")
    x = np.asarray(bem.points[:, 0])
    p = np.asarray(bem.point_data["pressure"])
    assert abs(np.sum(p * x) / np.sum(p)) < 1e-3  # centred on the cylinder's axis (origin set)
    m = cylinder.sls(3)
    assert bem.field_data["E_inf"][0] == m.E_inf and bem.field_data["E0"][0] == pytest.approx(m.E0)
    np.testing.assert_allclose(bem.field_data["relaxation_times"], m.relaxation_times)
    assert bem.field_data["load"][0] == pytest.approx(cylinder.P) and "Pa" in str(bem.field_data["units"][0])
    assert every_file_states_its_units(tmp_path / "vtk") >= {".vti", ".vtm", ".vtu", ".vtp"}
    capsys.readouterr()
    case = tmp_path / "vtk" / "cylinder_sls_r3"
    printed = run_paraview_snippet(case / "bem-periodic" / "point_000.vti", capsys)
    assert "bem-periodic" in printed and "'pressure': 'Pa'" in printed
    printed = run_paraview_snippet(case / "fem" / "point_000.vtm", capsys)
    assert "rolling_cylinder" in printed and "'pressure': 'Pa'" in printed and "'stress_nodal': 'Pa'" in printed


# ------------------------------------------------------------------ checks that can fail
def test_a_failed_fem_solve_is_a_failed_check_not_a_pass(monkeypatch):
    """The FEM adapter passes the solver's own ``success`` on: a solve that says it failed is a
    failed check (the adapter used to report ``success=True`` whatever the solver said)."""
    from dataclasses import replace

    import fem_reference
    from validation.cases import solvers

    real = fem_reference.rolling_cylinder

    def failing(*args, **kwargs):
        return replace(real(*args, **kwargs), success=False, message="active set did not settle")

    monkeypatch.setattr(fem_reference, "rolling_cylinder", failing)
    m = cylinder.sls(3)
    sol = solvers.fem_cylinder(m, radius=cylinder.R, load=cylinder.P, speed=cylinder._speed(m, 3.0), resolution=1)
    assert sol["success"] is False
    from validation.cases.base import CaseOutput

    out = CaseOutput()
    assert not out.converged("fem", "s=3", sol)
    assert [c.passed for c in out.checks] == [False] and "did not settle" in out.checks[0].why
    with pytest.raises(KeyError):  # an adapter without ``success`` is an error, never a pass
        out.converged("fem", "s=3", {"residual": 0.0, "message": ""})


def test_fem_self_checks_catch_a_broken_energy_balance_and_contact():
    """The energy balance compares two computed numbers, the contact residual is recomputed from
    the field: both fail when their inputs disagree (a 5 % dissipation error, a wrong approach)."""
    from validation.cases.base import CaseOutput
    from validation.cases.fem_checks import CONTACT_TOL, fem_self_checks

    good = dict(power_fields=1.0, power_moment=1.002, contact_residual=1e-10, linear_residual=1e-13)
    out = CaseOutput()
    fem_self_checks(out, "x", good, 0.01, "why")
    assert all(c.passed for c in out.checks) and len(out.checks) == 3
    out = CaseOutput()
    fem_self_checks(
        out, "x", dict(good, power_fields=1.06, contact_residual=10 * CONTACT_TOL, linear_residual=1e-6), 0.01, "why"
    )
    assert [c.passed for c in out.checks] == [False, False, False]


def test_creep_peak_is_compared_with_the_exact_maximum_not_the_axis():
    """At E_inf/E0 = 10 and t = 0.3 lambda the Lee-Radok pressure peaks on a ring at r/a ~ 0.9,
    above the axis value: the case's reference is the maximum over r."""
    from validation.references import lee_radok

    m = cylinder.sls(10)
    t = 0.3 * float(m.creep_times[0])
    a = lee_radok.contact_radius(m, 0.01, 1.0, np.array([t]))[0]
    r = np.linspace(0.0, a, 801)
    p = lee_radok.pressure(m, 0.01, 1.0, t, r)
    assert 0.85 < r[np.argmax(p)] / a < 0.95 and p.max() > 1.05 * p[0]


# ------------------------------------------------------------------ sensitivity
def test_sensitivity_table_and_exit_status(tmp_path, monkeypatch, capsys):
    """--sensitivity reruns the cases with wrong inputs: every entry names the checks that caught it,
    the HTML shows the table, and a perturbation no check catches (a tolerance made useless) fails
    the run."""
    argv = [
        "validate",
        "--jobs",
        "1",  # in this process: the test patches the case
        "--quick",
        "--no-progress",
        "--no-vtk",
        "--no-plots",
        "--no-baseline",
        "--sensitivity",
        "--case",
        "westergaard",
        "--case",
        "elastic_rough_dense",
        "--out",
        str(tmp_path / "a"),
    ]
    assert main(argv) == 0
    record = json.loads((tmp_path / "a" / "report.json").read_text())
    entries = record["sensitivity"]
    assert {e["case"] for e in entries} == {"westergaard", "elastic_rough_dense"}
    for e in entries:
        assert set(e) >= {"case", "solver", "perturbation", "detected", "by"}
        # elastic and at rest: the relaxation times and the speed change nothing, everything else is caught
        changes = not (e["perturbation"].startswith("relaxation") or e["perturbation"].startswith("speed"))
        assert e["required"] == changes and e["detected"] == changes and bool(e["by"]) == changes
    html = (tmp_path / "a" / "report.html").read_text()
    assert "id='sensitivity'" in html and "caught by" in html
    loose = dict(periodic.QUICK_WEST, tol=dict(l2=1e9, max=1e9, peak=1e9, edge=1e9))
    monkeypatch.setattr(periodic, "QUICK_WEST", loose)
    argv[-1] = str(tmp_path / "b")
    capsys.readouterr()
    assert main(argv) == 1
    assert "UNDETECTED westergaard: bem-periodic with E_inf +2%" in capsys.readouterr().out


def test_perturbations_change_only_what_they_name():
    from validation.perturb import PERTURBATIONS, Tamper

    m = cylinder.prony()
    by_name = {p.name: p for p in PERTURBATIONS}
    up = by_name["E_inf +2%"].material(m)
    assert up.E_inf == pytest.approx(1.02 * m.E_inf) and up.E0 == m.E0
    np.testing.assert_array_equal(up.relaxation_times, m.relaxation_times)
    e0 = by_name["E0 -2%"].material(m)
    assert e0.E0 == pytest.approx(0.98 * m.E0) and e0.E_inf == pytest.approx(m.E_inf)
    np.testing.assert_allclose(by_name["relaxation times +5%"].material(m).relaxation_times, 1.05 * m.relaxation_times)
    t = Tamper(by_name["speed +5%"])
    assert t.inputs("a", m, 0.0, 1.0) == (m, 0.0, 1.0) and t.changed == set()
    assert t.inputs("b", m, 2.0, 1.0)[1] == pytest.approx(2.1) and t.changed == {"b"}


# ------------------------------------------------------------------ failures and baselines
def test_cases_in_two_processes_give_the_numbers_of_one(tmp_path):
    """--jobs 2 runs the cases in processes of their own: the same records, in registry order, as
    one after another in this process (to round-off: the processes run one thread each)."""
    from validation.runner import run_cases

    names = ["elastic_rough_dense", "westergaard"]
    runs = {
        jobs: run_cases(names, quick=True, out_dir=tmp_path / str(jobs), vtk=False, progress=False, jobs=jobs)
        for jobs in (1, 2)
    }
    assert list(runs[2]["cases"]) == ["westergaard", "elastic_rough_dense"] == list(runs[1]["cases"])
    for name, case in runs[1]["cases"].items():
        other = runs[2]["cases"][name]
        assert other["status"] == case["status"] == "passed"
        assert [c["label"] for c in other["checks"]] == [c["label"] for c in case["checks"]]
        for a, b in zip(case["checks"], other["checks"]):
            assert b["value"] == pytest.approx(a["value"], rel=1e-9, abs=1e-15)


def test_jobs_must_be_a_positive_integer(tmp_path, capsys):
    from validation.runner import run_cases

    for jobs in (0, -1, 1.5, True):
        with pytest.raises(InputError, match="jobs must be an integer >= 1"):
            run_cases(["westergaard"], quick=True, out_dir=tmp_path, jobs=jobs)
    assert main(["validate", "--jobs", "0", "--case", "westergaard", "--out", str(tmp_path)]) == 2
    assert "jobs must be an integer >= 1; got 0" in capsys.readouterr().err


def test_bad_case_name_is_an_input_error(tmp_path, capsys):
    assert main(["validate", "--case", "nope", "--out", str(tmp_path)]) == 2
    assert "case must be one of" in capsys.readouterr().err
    assert main(["validate", "--update-baselines", "--case", "westergaard", "--out", str(tmp_path)]) == 2


def test_a_crashing_case_is_reported_and_the_others_still_run(tmp_path, monkeypatch, capsys):
    from validation.cases import Case

    def boom(**_):
        raise RuntimeError("solver exploded")

    monkeypatch.setitem(CASES, "westergaard", Case("westergaard", "t", "d", ("exact",), "exact", boom))
    status = main(
        [
            "validate",
            "--jobs",
            "1",  # in this process: the test patches the case
            "--quick",
            "--no-baseline",
            "--no-progress",
            "--no-vtk",
            "--no-plots",
            "--case",
            "westergaard",
            "--case",
            "elastic_rough_dense",
            "--out",
            str(tmp_path),
        ]
    )
    assert status == 1 and "RuntimeError: solver exploded" in capsys.readouterr().out
    record = json.loads((tmp_path / "report.json").read_text())
    assert record["cases"]["westergaard"]["status"] == "error"
    assert record["cases"]["elastic_rough_dense"]["status"] == "passed"
    assert "solver exploded" in (tmp_path / "report.html").read_text()


def test_baselines_round_trip(cheap_run, tmp_path):
    _, _, record = cheap_run
    path = baselines.write(record, tmp_path / "b.json", command="test")
    stored = json.loads(path.read_text())
    assert (
        stored["provenance"]["commit"] == record["environment"]["commit"] and stored["provenance"]["command"] == "test"
    )
    assert baselines.compare(record, path)["ok"]


def test_missed_tolerance_and_changed_baseline_exit_non_zero_with_a_summary(tmp_path, monkeypatch, capsys):
    """One run of the Westergaard case with a tolerance it cannot meet and a baseline moved by 20 %
    (a real change of a discretisation error): both are listed, and the status is 1."""
    stored = json.loads(baselines.DEFAULT.read_text())
    key = "bem-periodic/pressure_rel_max/p/p*=0.5"
    stored["values"]["westergaard"][key] *= 1.2
    path = tmp_path / "b.json"
    path.write_text(json.dumps(stored))
    tight = dict(periodic.QUICK_WEST, tol=dict(periodic.QUICK_WEST["tol"], l2=1e-9))
    monkeypatch.setattr(periodic, "QUICK_WEST", tight)
    status = main(
        [
            "validate",
            "--jobs",
            "1",  # in this process: the test patches the case
            "--quick",
            "--no-progress",
            "--no-vtk",
            "--no-plots",
            "--case",
            "westergaard",
            "--baseline",
            str(path),
            "--out",
            str(tmp_path / "o"),
        ]
    )
    text = capsys.readouterr().out
    assert status == 1
    assert "FAIL westergaard: bem-periodic pressure_rel_l2" in text
    regressions = [line for line in text.splitlines() if "REGRESSION" in line]
    assert len(regressions) == 1 and key in regressions[0]  # nothing else moved
    report = json.loads((tmp_path / "o" / "report.json").read_text())
    assert report["summary"]["failed"] == ["westergaard"] and not report["baseline"]["ok"]


def test_stored_quick_baselines_cover_every_case_and_say_where_they_came_from():
    stored = json.loads(baselines.DEFAULT.read_text())
    assert set(stored["values"]) == set(CASES)
    prov = stored["provenance"]
    assert len(prov["commit"]) == 40 and prov["date"] and prov["machine"] and "--update-baselines" in prov["command"]


@pytest.mark.slow
def test_quick_set_matches_the_stored_baselines(tmp_path):
    """The CI regression set: every case at quick settings, every tolerance, every baseline."""
    assert main(["validate", "--quick", "--no-progress", "--out", str(tmp_path)]) == 0
    record = json.loads((tmp_path / "report.json").read_text())
    assert record["baseline"]["ok"] and record["summary"]["failed"] == []


@pytest.mark.slow
def test_rubber_fem_against_bem():
    """The full rubber case: every BEM solver against the isolated BEM on twice the cells at the
    friction peak and a decade below, and the FEM against that reference on its material."""
    out = CASES["rubber"](quick=False)
    failed = [c.key for c in out.checks if not c.passed]
    assert not failed, failed
    assert {c.solver for c in out.checks} >= {
        "fem vs bem-reference",
        "bem-periodic vs bem-reference",
        "bem-isolated-adaptive vs bem-reference",
    }


SCENE = """
title = "vtk metadata"
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
seed = 3
[loading]
load = 0.3
xi = { start = 1e-2, stop = 1e-1, num = 2 }
[outputs]
vtk = true
plots = false
"""


def test_cli_vti_carries_the_study_metadata(tmp_path):
    """``viscobem run`` with VTK: each .vti names its speed, load, material and units, and holds the
    pressure the results report."""
    import pyvista as pv

    path = tmp_path / "s.toml"
    path.write_text(SCENE)
    assert main(["run", str(path), "--out", str(tmp_path / "out"), "--no-progress"]) == 0
    rec = json.loads((tmp_path / "out" / "results.json").read_text())
    curve = rec["friction_curve"]
    for k in range(2):
        grid = pv.read(tmp_path / "out" / "vtk" / f"point_{k:03d}.vti")
        fd = grid.field_data
        assert fd["speed"][0] == pytest.approx(curve["speed"][k], rel=1e-12)
        assert fd["load"][0] == pytest.approx(0.3) and fd["cell_length"][0] == pytest.approx(0.01)
        assert fd["friction"][0] == pytest.approx(curve["friction"][k], rel=1e-12)
        assert fd["E0"][0] == pytest.approx(1e7 / 3) and fd["E_inf"][0] == pytest.approx(1e7)
        assert fd["creep_times"][0] == pytest.approx(0.01)
        assert fd["dimensionless_speed"][0] == pytest.approx(curve["xi"][k], rel=1e-9)
        assert "Pa" in str(fd["units"][0]) and "m/s" in str(fd["units"][0])
        p = np.asarray(grid.point_data["pressure"])
        assert p.mean() * 0.01**2 == pytest.approx(0.3, rel=1e-6)  # fields stored in float32
