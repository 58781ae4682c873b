"""`viscobem bench measured`: the boundary treatments of a measured scan, scored on patches cut from
a known periodic parent, run from the CLI and write their table and JSON."""

import json

from bem.surfaces import measured
from viscobem_bench import measured as bench


def test_measured_benchmark_runs_from_the_cli(tmp_path):
    from viscobem_cli.main import main

    assert main(["bench", "measured", "--quick", "--out", str(tmp_path)]) == 0
    result = json.loads((tmp_path / "measured.json").read_text())
    solves = json.loads((tmp_path / "measured_solves.json").read_text())
    assert "| treatment | patch side / L |" in (tmp_path / "measured.md").read_text()
    cfg = bench.QUICK
    per_treatment = len(cfg["rolloffs"]) * len(cfg["seeds"]) * len(bench.FRACTIONS) * cfg["positions"]
    assert len(solves) == len(cfg["treatments"]) * per_treatment * len(cfg["speeds"])
    assert all(r["success"] for r in solves) and result["chosen"] == measured.DEFAULT_WINDOW
    assert len(result["by_seed"]) == len(cfg["treatments"]) * len(bench.FRACTIONS) * len(cfg["speeds"])
    for r in solves:  # the errors are against the parent at the same speed
        parent = next(p for p in result["parents"] if p["seed"] == r["seed"] and p["rolloff"] == r["rolloff"])
        ref = next(q["friction"] for q in parent["rows"] if q["speed"] == r["speed"])
        assert r["error"] == r["friction"] / ref - 1
    ranks = {(r["treatment"], r["fraction"]): r for r in result["ranking"]}
    assert len(ranks) == len(cfg["treatments"]) * len(bench.FRACTIONS)
    # the edges' step: the eq. 6 form runs away without a window, not with the mirror
    assert ranks[("none", 0.25)]["max_form_gap"] > 3 * ranks[("mirror", 0.25)]["max_form_gap"]
