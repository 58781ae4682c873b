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
