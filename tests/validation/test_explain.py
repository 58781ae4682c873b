"""The report's words: plain metric names, the basis of each tolerance, the worst check of a case
and the checks each plot is captioned with."""

import json
from pathlib import Path

from validation import explain, report
from validation.cases.base import Check

BASELINES = Path(__file__).parents[2] / "validation" / "baselines" / "quick.json"


def check(metric="pressure_rel_l2", solver="bem", label="s=0.3", value=0.01, tolerance=0.02, why=""):
    return Check(metric, solver, label, value, tolerance, why).as_dict()


def test_every_metric_of_the_quick_set_has_a_plain_name():
    values = json.loads(BASELINES.read_text())["values"]
    metrics = {key.split("/")[1] for case in values.values() for key in case}
    unnamed = sorted(m for m in metrics if explain.metric_name(m) == m)
    assert not unnamed, f"metrics without a plain name in validation/explain.py: {unnamed}"
    assert explain.metric_name("something_new") == "something_new"  # shown as is, never hidden


def test_the_basis_of_a_tolerance_is_read_from_its_reason():
    assert explain.basis(check(why="measured 1.0 % (20 cells, s = 0.3); margin 2x")) == "margin"
    assert explain.basis(check(why="measured <= 1 % at 20 cells; bound 2x")) == "margin"
    assert explain.margin_factor(check(why="moment form: measured 3.7e-3; margin >= 1.8x")) == 1.8
    assert explain.basis(check(why="sampling error 1/2 cell plus the solver's; one cell")) == "bound"
    assert explain.basis(check(why="first order in dx; bound 3/n")) == "bound"
    assert explain.basis(check(tolerance=None, why="not judged: the layer spans < 5 cells")) == "info"
    record = {
        "cases": {
            "a": {"checks": [check(why="margin 2x"), check(why="margin 3x"), check(why="one cell")]},
            "b": {"checks": [check(tolerance=None, why="not judged")]},
        }
    }
    text = explain.basis_sentence(record)
    assert text.startswith("2 of the 3 judged checks use a regression margin") and "2-3x (median 2.5x)" in text
    assert "1 use a bound" in text and "1 rows are info" in text
    bounds_only = {"cases": {"a": {"checks": [check(why="one cell"), check(why="round-off")]}}}
    assert explain.basis_sentence(bounds_only).startswith("None of the 2 judged checks uses a regression margin: all 2")


def test_the_worst_check_is_a_failure_first_then_the_closest_to_its_tolerance():
    close, far = check(value=0.019), check(metric="friction_rel_error", value=0.001, tolerance=0.002)
    failed = check(metric="approach_rel_error", value=0.3, tolerance=0.001, why="")
    assert explain.worst_check([far, close]) is close
    assert explain.worst_check([close, failed, far]) is failed
    failed_solve = check(metric="solver_success", value=1.0, tolerance=0.0)
    assert explain.worst_check([close, failed_solve]) is failed_solve
    assert explain.worst_check([check(tolerance=None)]) is None


def test_a_plot_is_captioned_with_the_checks_of_its_point_and_quantity():
    case = {
        "checks": [
            check(label="s=0.3", value=0.011),
            check(label="s=3", value=0.015),
            check(metric="friction_rel_error", label="s=3", value=1e-3, tolerance=3e-3),
            check(metric="friction_rel_diff", solver="bem vs fem", label="s=3", value=2e-3, tolerance=3e-3),
        ]
    }
    at = explain.illustrated(case, "s=0.3, V = 0.05 m/s", ["exact", "bem"], "overlay")
    assert [(k["metric"], k["label"]) for k in at] == [("pressure_rel_l2", "s=0.3")]  # not s=3
    sweep = explain.illustrated(case, "friction against speed", ["bem", "fem"], "sweep")
    assert [k["solver"] for k in sweep] == ["bem", "bem vs fem"]
    assert explain.illustrated(case, "friction against speed", ["bem"], "sweep")[0]["solver"] == "bem"
    caption = report._plot_caption(case, "s=3", ["bem"], "overlay")
    assert caption == "Checks shown (worst value / tolerance): pressure error, relative L2: bem 0.015 / 0.02."
