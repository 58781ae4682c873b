"""``viscobem bench accuracy`` runs and writes its record (numbers are read, not asserted: timing
is the benchmark's business, not a test's)."""

import json

import pytest

from viscobem_bench import accuracy


@pytest.mark.slow
def test_accuracy_benchmark_writes_cost_and_agreement(tmp_path):
    accuracy.run(quick=True, out_dir=tmp_path, echo=lambda *a: None)
    rec = json.loads((tmp_path / "accuracy.json").read_text())
    assert [r["case"] for r in rec["cost"]] == list(accuracy.cases(True))
    for row in rec["cost"]:
        assert row["estimate_s"] > 0 and row["solve_s"] > 0 and row["overhead"] == row["estimate_s"] / row["solve_s"]
    assert len(rec["agreement"]) == 3 * len(rec["cost"])
    assert {r["quantity"] for r in rec["agreement"]} == {"friction", "contact_fraction", "peak_pressure"}
    assert "share" in (tmp_path / "accuracy.md").read_text()
