"""The benchmark suite's own logic (no solves): Pareto front, exponent fit, outputs only in --out."""

from pathlib import Path

import numpy as np
import pytest

from viscobem_bench import cases, report, scaling, suite


def test_pareto_front_keeps_only_undominated_points():
    pts = [
        {"time": 1.0, "error": 1e-2},
        {"time": 2.0, "error": 1e-3},
        {"time": 3.0, "error": 5e-3},
        {"time": 0.5, "error": 5e-2},
        {"time": 4.0, "error": None},
        {"time": 5.0, "error": 1e-4},
    ]
    assert report.pareto_front(pts) == [3, 0, 1, 5]  # sorted by time; 2 is dominated by 1


def test_fit_exponent_recovers_n_log_n():
    n = np.array([64, 128, 256, 512, 1024])
    N = n.astype(float) ** 2
    k, k_nlogn = scaling._fit_exponent(n, 3e-8 * N * np.log(N))
    assert k_nlogn == pytest.approx(0.0, abs=1e-12)  # exact N log N data
    assert 1.0 < k < 1.15  # log N adds ~0.1 to the apparent power over this range
    assert scaling._fit_exponent(n, 1e-9 * N**1.5)[0] == pytest.approx(1.5, abs=1e-12)


def test_suite_writes_only_in_its_output_folder(tmp_path, monkeypatch):
    """The driver (no solver selected, no scaling or skipping) writes bench.json and bench.md in
    ``out_dir`` and nothing in the working directory or the source checkout (its README)."""
    readme = Path(suite.__file__).resolve().parents[1] / "README.md"
    before = readme.read_bytes() if readme.is_file() else None
    cwd = tmp_path / "cwd"
    cwd.mkdir()
    monkeypatch.chdir(cwd)
    result = suite.run(
        quick=True, out_dir=tmp_path / "out", solvers=["none"], scaling=False, skip=False, echo=lambda *a: None
    )
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["bench.json", "bench.md"]
    assert result["files"] == ["bench.json", "bench.md"] and not any(cwd.iterdir())
    assert (readme.read_bytes() if readme.is_file() else None) == before


def test_rough_heights_are_one_surface_at_every_size():
    h64, h128 = cases.rough_heights(64), cases.rough_heights(128)
    assert np.allclose(h128[::2, ::2], h64, rtol=0, atol=1e-12 * np.abs(h64).max())  # exact resampling


def test_registry_entries_are_complete():
    assert {"periodic-westergaard", "periodic-rough-viscoelastic", "fem-hunter"} <= set(cases.REGISTRY)
    for entry in cases.REGISTRY.values():
        assert entry.knobs and callable(entry.measure)
        assert list(entry.groups(True))  # a quick run has work in every entry


def test_rubber_speeds_benchmark_runs_from_the_cli(tmp_path):
    """`viscobem bench rubber_speeds` writes its table; at a rubbery speed (symbol phase near 0)
    the rubber costs about what the elastic case does, at xi = 1e4 (1000x stiffness contrast
    between the q_x = 0 modes and the sliding ones) several times more (64²: 58 and 437
    products against 62)."""
    import json

    from viscobem_bench import rubber_speeds
    from viscobem_cli.main import main

    assert main(["bench", "rubber_speeds", "--quick", "--out", str(tmp_path)]) == 0
    result = json.loads((tmp_path / "rubber_speeds.json").read_text())
    assert "| case | xi |" in (tmp_path / "rubber_speeds.md").read_text()
    rows = {r["xi"]: r for r in result["rows"]}
    n = str(rubber_speeds.QUICK_SIZES[0])
    assert all(r["by_n"][m]["success"] for r in result["rows"] for m in r["by_n"])
    assert all(abs(r["by_n"][n]["contact_fraction"] - 0.1) < 0.01 for r in result["rows"])
    elastic = rows[None]["by_n"][n]["matvecs"]
    assert rows[1e-4]["max_phase_deg"] < 5 and rows[1e-4]["by_n"][n]["matvecs"] < 1.5 * elastic
    assert rows[1e4]["max_phase_deg"] < 45 and rows[1e4]["by_n"][n]["matvecs"] > 3 * elastic


def test_curve_benchmark_runs_from_the_cli(tmp_path):
    """`viscobem bench curve` writes its table: every curve converges at every speed, its loads
    give the targeted contact at the rubbery end, the contact shrinks as the rubber stiffens, and
    the costs are the ratios they claim to be."""
    import json

    from viscobem_bench import curve
    from viscobem_cli.main import main

    assert main(["bench", "curve", "--quick", "--out", str(tmp_path)]) == 0
    result = json.loads((tmp_path / "curve.json").read_text())
    assert "| seed | scales | contact |" in (tmp_path / "curve.md").read_text()
    curves = result["curves"]
    assert len(curves) == len(curve.QUICK_SURFACES) * len(curve.CONTACTS)
    for c in curves:
        assert c["all_converged"] and len(c["rows"]) == len(curve.XIS) == 13
        assert abs(c["rows"][0]["contact_fraction"] / c["target_contact"] - 1) < 0.05
        assert c["rows"][-1]["contact_fraction"] < 0.5 * c["rows"][0]["contact_fraction"]
        assert c["products"] == sum(r["matvecs"] for r in c["rows"])
        assert c["products_in_elastic_solves"] == pytest.approx(c["products"] / c["elastic"]["matvecs"])
        assert c["cpu_in_elastic_solves"] == pytest.approx(c["cpu_time"] / c["elastic"]["cpu_time"])
    assert result["worst"]["products"] == max(c["products_in_elastic_solves"] for c in curves)


def test_broadband_benchmark_runs_from_the_cli(tmp_path):
    """`viscobem bench broadband` writes its table: every size converges at about 60 % contact,
    and the products grow slowly with the band (128² -> 256², 32 -> 64 scales: 96 -> 157)."""
    import json

    from viscobem_bench import broadband
    from viscobem_cli.main import main

    assert main(["bench", "broadband", "--quick", "--out", str(tmp_path)]) == 0
    rows = json.loads((tmp_path / "broadband.json").read_text())["rows"]
    assert "| n | scales |" in (tmp_path / "broadband.md").read_text()
    assert [r["n"] for r in rows] == list(broadband.QUICK_SIZES) and all(r["success"] for r in rows)
    assert all(r["scales"] == r["n"] // 4 and abs(r["contact_fraction"] - 0.6) < 0.05 for r in rows)
    assert rows[1]["matvecs"] < 2 * rows[0]["matvecs"]
