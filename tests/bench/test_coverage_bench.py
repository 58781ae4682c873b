"""``viscobem bench coverage``: the default error estimate against the twice-finer solve over seeded
cases (docs/theory.md §13.5). The full statistics are the benchmark's; here a few held-out cases,
whose envelope must hold on every one of them, and the record the benchmark writes."""

import json

import pytest

from bem.accuracy import QUANTITIES
from viscobem_bench import coverage

SEEDS = list(coverage.HELD_OUT)[:8]  # 2 cylinders, 2 spheres, 2 profiles, 2 rough cells


@pytest.fixture(scope="module")
def records():
    return [coverage.measure(seed) for seed in SEEDS]


def test_no_estimate_says_below_one_per_cent_where_the_finer_grid_moves_more_than_five(records):
    for r in records:
        assert r["success"], r["name"]
        for q in QUANTITIES:
            e, m = r["estimate"][q], r["measured"][q]
            assert not (e is not None and e < 0.01 and m is not None and m > 0.05), (r["name"], q, e, m)


def test_friction_and_contact_estimates_cover_the_finer_grid_on_most_cases(records):
    """Share within a factor 3 (errors below the measurement's resolution count when the estimate is
    below three times it). Over the 120 held-out cases: friction 77 %, contact fraction 89 % (the
    target is 90 %: friction misses it). On these 8: contact 8, friction 4 (a profile whose friction
    moved 25 % where 6 % was estimated, and three over-estimates of errors below 1 %)."""
    st = coverage.statistics(records)
    assert st["cases"] == len(SEEDS)
    assert st["contact_fraction_within_3x"] >= 7 / 8 and st["friction_within_3x"] >= 4 / 8, st


def test_an_unresolved_peak_always_comes_with_its_warning(records):
    unresolved = [r for r in records if r["estimate"]["peak_pressure"] is None]
    assert unresolved, "the set should hold at least one unresolved peak (seeds 1002 and 1006)"
    for r in unresolved:
        assert r["reasons"]["peak_pressure"].startswith("unresolved") and "peak_unresolved" in r["warned"]


def test_statistics_count_misses_and_false_alarms():
    def rec(name, est, meas, warned=()):
        full = {q: None for q in QUANTITIES}
        return dict(
            name=name,
            success=True,
            estimate={**full, **est},
            measured={**full, **meas},
            warned=list(warned),
            ndim=1,
            contact_cells=100,
        )

    st = coverage.statistics(
        [
            rec("a", {"friction": 0.02}, {"friction": 0.05}),  # within 3x
            rec("b", {"friction": 0.005}, {"friction": 0.06}),  # below 1 % where above 5 %
            rec("c", {"friction": 0.08}, {"friction": 0.01}, ["friction"]),  # a false alarm
            rec("d", {"contact_fraction": 0.004}, {"contact_fraction": 0.0}),  # 0 is below one cell: 1/200
        ]
    )
    assert st["friction_within_3x"] == pytest.approx(1 / 3) and st["contact_fraction_within_3x"] == 1.0
    assert st["below_1pct_where_above_5pct"] == [("b", "friction")]
    assert st["warnings"] == 1 and st["false_alarms"] == 1


@pytest.mark.slow
def test_coverage_benchmark_writes_both_sets(tmp_path):
    coverage.run(quick=True, out_dir=tmp_path, echo=lambda *a: None)
    rec = json.loads((tmp_path / "coverage.json").read_text())
    assert set(rec["sets"]) == {"tuning", "held_out"}
    for s in rec["sets"].values():
        assert len(s["records"]) == coverage.QUICK and s["statistics"]["cases"] <= coverage.QUICK
    assert "within 3x" in (tmp_path / "coverage.md").read_text()
