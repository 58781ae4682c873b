"""``viscobem bench friction_map`` runs from the CLI and writes its record: the 13 x 25 map by
superposition against direct solves (within 1 % at every point compared, a ratio measured in the
same run) and its operator products against one 25-speed curve's (recorded, not asserted)."""

import json

import pytest

from viscobem_cli.main import main


@pytest.mark.slow
def test_friction_map_benchmark_runs_from_the_cli(tmp_path):
    assert main(["bench", "friction_map", "--quick", "--out", str(tmp_path)]) == 0
    rec = json.loads((tmp_path / "friction_map.json").read_text())
    assert rec["temperatures"] == 13 and rec["speeds"] == 25 and len(rec["rows"]) == 4
    assert rec["worst_difference"] <= rec["targets"]["difference"]
    assert rec["products_ratio"] == rec["map_products"] / rec["curve_products"] > 0
    for row in rec["rows"]:
        assert row["max_estimate"] <= 0.005 and row["interpolated_points"] > 0
    assert "operator products" in (tmp_path / "friction_map.md").read_text()
