"""`viscobem bench materials`: the Prony-fit and master-curve comparison with pyvisco runs from the
CLI, writes its table and JSON, and the numbers hold what the closing note claims."""

import json

import pytest


def test_materials_benchmark_runs_from_the_cli(tmp_path):
    pytest.importorskip("pyvisco")
    from viscobem_cli.main import main

    assert main(["bench", "materials", "--quick", "--out", str(tmp_path)]) == 0
    result = json.loads((tmp_path / "materials.json").read_text())
    assert "| method | terms |" in (tmp_path / "materials.md").read_text()
    ours, pyvisco = result["prony12"][0], result["prony12"][1]
    assert ours["method"].startswith("viscobem") and pyvisco["method"] == "pyvisco"
    assert ours["storage_max"] < 0.03 and ours["loss_max"] < 0.05  # the targets, 12 decades, 1 % noise
    assert all(ours["loss_max"] < r["loss_max"] for r in result["prony12"][1:])
    mc = result["master"][0]
    assert mc["C1_rel"] < 0.02 and mc["C2_rel"] < 0.02 and mc["log_aT_max"] < 0.1
    assert all(mc["log_aT_max"] < r["log_aT_max"] for r in result["master"][1:])
    # the temperature sets, noise-free: the joint fit is exact where the sweeps overlap or
    # leave narrow gaps (measured C1 within 5e-7, moduli within 3e-5), and says so where it is not
    cases = {}
    for row in result["cases"]:
        cases.setdefault(row["case"], []).append(row)
    for name in ("10 K, T_ref not measured", "5 K, -40..60 C", "0/23/50 C", "20 K, two gaps"):
        joint = cases[name][0]
        assert joint["method"] == "viscobem joint" and abs(joint["C1_rel"]) < 1e-5 and joint["warnings"] == 0
        assert max(joint["storage_max"], joint["loss_max"], joint["ref_storage_max"], joint["ref_loss_max"]) < 1e-4
        assert cases[name][3]["method"] == "pyvisco"
    wide = cases["no overlap"]
    assert wide[0]["warnings"] == 1 and wide[0]["law_sigma_max"] > 1.0 and "failed" in wide[1]
    assert wide[2]["method"] == "viscobem imposed law" and wide[2]["storage_max"] < 1e-6
    assert "| viscobem joint |" in (tmp_path / "materials.md").read_text()
