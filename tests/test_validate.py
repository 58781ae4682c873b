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

from validation import baselines, metrics
from validation.cases import CASES, cylinder, periodic
from viscobem_cli.main import main

CHEAP = ["full_contact_rough", "elastic_rough_dense"]


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

    root = Path(__file__).resolve().parent.parent
    out = subprocess.run([sys.executable, "-c", _MEASURE], capture_output=True, text=True, check=True,
                         cwd=root, env={"PYTHONPATH": str(root), "PATH": "/usr/bin:/bin"}).stdout.split()
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
    assert html.count("data:image/png;base64,") >= 3 * len(CHEAP)  # overlays, sweeps, timings
    assert html.count("<img") == html.count("data:image/png;base64,")
    assert "src='http" not in html  # self-contained


def _pvd_entries(path):
    return [(d.get("file"), float(d.get("timestep"))) for d in ET.parse(path).getroot().iter("DataSet")]


def test_every_vtk_file_reads_back(cheap_run):
    import pyvista as pv

    _, out, record = cheap_run
    files = [f for c in record["cases"].values() for f in c["files"]]
    assert files and all((out / f).exists() for f in files)
    for f in files:
        if f.endswith(".pvd"):
            entries = _pvd_entries(out / f)
            assert entries and all((out / f).parent.joinpath(e).exists() for e, _ in entries)
            reader = pv.get_reader(out / f)  # ParaView's view: one time step per entry
            np.testing.assert_allclose(reader.time_values, sorted(t for _, t in entries))
            reader.set_active_time_point(len(entries) - 1)
            assert "pressure" in reader.read()[0].point_data
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


def test_fem_vtu_and_pvd_of_a_rolling_sweep(tmp_path, monkeypatch):
    """One coarse speed of the rolling cylinder through the CLI: BEM .vti (periodic and isolated),
    FEM .vtu, a .pvd per solver."""
    import meshio
    import pyvista as pv

    cfg = dict(cylinder.QUICK_SLS[3], s=[0.3], cells=10, resolution=2)
    monkeypatch.setitem(cylinder.QUICK_SLS, 3, cfg)
    main(["validate", "--quick", "--no-progress", "--no-baseline", "--no-plots", "--case", "cylinder_sls_r3",
          "--out", str(tmp_path)])
    record = json.loads((tmp_path / "report.json").read_text())
    case = record["cases"]["cylinder_sls_r3"]
    assert case["status"] in ("passed", "failed")  # coarser than the quick set: plumbing only
    assert {k["solver"] for k in case["checks"]} == set(cylinder.SOLVERS)
    vtu = meshio.read(tmp_path / "vtk" / "cylinder_sls_r3" / "fem" / "point_000.vtu")
    assert vtu.points.shape[1] == 3 and "displacement" in vtu.point_data
    assert {"stress", "strain", "dissipation"} <= set(vtu.cell_data)
    assert np.all(np.asarray(vtu.cell_data["dissipation"][0]) >= -1e-9)
    for sub in cylinder.SOLVERS:
        entries = _pvd_entries(tmp_path / "vtk" / "cylinder_sls_r3" / sub / "sweep.pvd")
        assert [t for _, t in entries] == [0.3]
        assert list(pv.get_reader(tmp_path / "vtk" / "cylinder_sls_r3" / sub / "sweep.pvd").time_values) == [0.3]
    bem = pv.read(tmp_path / "vtk" / "cylinder_sls_r3" / "bem-periodic" / "point_000.vti")
    x = np.asarray(bem.points[:, 0])
    p = np.asarray(bem.point_data["pressure"])
    assert abs(np.sum(p * x) / np.sum(p)) < 1e-3  # centred on the cylinder's axis (origin set)


# ------------------------------------------------------------------ failures and baselines
def test_bad_case_name_is_an_input_error(tmp_path, capsys):
    assert main(["validate", "--case", "nope", "--out", str(tmp_path)]) == 2
    assert "case must be one of" in capsys.readouterr().err
    assert main(["validate", "--update-baselines", "--case", "westergaard", "--out", str(tmp_path)]) == 2


def test_a_crashing_case_is_reported_and_the_others_still_run(tmp_path, monkeypatch, capsys):
    from validation.cases import Case

    def boom(**_):
        raise RuntimeError("solver exploded")

    monkeypatch.setitem(CASES, "westergaard", Case("westergaard", "t", "d", ("exact",), "exact", boom))
    status = main(["validate", "--quick", "--no-baseline", "--no-progress", "--no-vtk", "--no-plots",
                   "--case", "westergaard", "--case", "elastic_rough_dense", "--out", str(tmp_path)])
    assert status == 1 and "RuntimeError: solver exploded" in capsys.readouterr().out
    record = json.loads((tmp_path / "report.json").read_text())
    assert record["cases"]["westergaard"]["status"] == "error"
    assert record["cases"]["elastic_rough_dense"]["status"] == "passed"
    assert "solver exploded" in (tmp_path / "report.html").read_text()


def test_baselines_round_trip(cheap_run, tmp_path):
    _, _, record = cheap_run
    path = baselines.write(record, tmp_path / "b.json", command="test")
    stored = json.loads(path.read_text())
    assert stored["provenance"]["commit"] == record["environment"]["commit"] and stored["provenance"]["command"] == "test"
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
    status = main(["validate", "--quick", "--no-progress", "--no-vtk", "--no-plots", "--case", "westergaard",
                   "--baseline", str(path), "--out", str(tmp_path / "o")])
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
