"""Every time and size the README and docs state comes from the record of measured runs.

``docs/timings.json`` is written by ``python docs/timings.py`` (see its docstring); a stated
figure is a link to its entry, ``[75 s on 2 cores](timings.md#validate_quick)``. These tests
fail when a stated figure and the recorded one differ by more than a factor of 2, when a page
states a time or size without such a link, when a required run is missing from the record or
failed, and when the page of the record is out of date.
"""

import importlib.util
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("viscobem_docs_timings", ROOT / "docs" / "timings.py")
timings = importlib.util.module_from_spec(spec)
spec.loader.exec_module(timings)

RECORD = json.loads(timings.RECORD.read_text(encoding="utf-8"))
# the runs the README and the docs must be able to state: the test suite, both validation sets,
# `viscobem run` and every built-in scene
REQUIRED = ["tests", "validate_quick", "validate_full"]
# pages whose times are physics (theory), history (changelog) or benchmark records of their own
NOT_CLAIMS = {"timings.md", "theory.md", "changelog.md", "benchmarks.md"}
UNLINKED = [
    re.compile(
        r"(?:~|\babout|\bunder|\bover|\bwithin|\btakes?|\bonly|\bin)\s+(?:a|an|\d+(?:\.\d+)?)\s*"
        r"(?:s|sec|seconds?|min|minutes?|h|hours?)\b",
        re.IGNORECASE,
    ),
    re.compile(r"\d+(?:\.\d+)?\s*(?:minutes?|hours?|seconds?)\b", re.IGNORECASE),
    re.compile(r"\b(?:a|an|one)\s+(?:minute|hour)\b", re.IGNORECASE),
    re.compile(r"\d+(?:\.\d+)?\s*(?:kB|MB|GB|MiB|GiB)\b"),
]


def pages():
    return [ROOT / "README.md"] + sorted(p for p in (ROOT / "docs").glob("*.md") if p.name not in NOT_CLAIMS)


def claims():
    for path in pages():
        for match in timings.CLAIM.finditer(path.read_text(encoding="utf-8")):
            yield path.name, match.group(1), match.group(3)


def drift(text, entry):
    """Stated over recorded (>= 1 both ways: the factor they differ by); for a run CI recorded
    (``"upper"``), only how far it took longer than stated (a faster machine keeps the promise)."""
    value, kind = timings.stated(text)
    assert kind is not None, f"no figure in {text!r}"
    recorded = timings.recorded(entry, kind)
    assert recorded, f"the record has no {kind} for this run"
    if entry.get("upper"):
        return max(1.0, recorded / value)
    return max(value / recorded, recorded / value)


def required_runs():
    from viscobem_cli.catalog import builtin_scenes

    return REQUIRED + [f"run_{name}" for name in builtin_scenes()]


def test_record_has_the_machine_and_every_required_run():
    machine = RECORD["machine"]
    assert machine["cores"] and machine["cpu"] and machine["memory_gib"]
    for key in required_runs():
        assert key in RECORD["runs"], f"no recorded run {key!r}: measure it with python docs/timings.py {key}"
        e = RECORD["runs"][key]
        assert e["exit_status"] == 0, f"{key} failed when measured: {e['last_line']}"
        assert e["date"] and e["wall_s"] > 0
        if e.get("source"):  # measured elsewhere: it must say where
            assert len(e["source"]) > 20
        else:
            assert e["cpu_s"] > 0 and e["load_average"]["during_mean_1min"] is not None


def test_every_stated_figure_is_within_2x_of_the_record():
    found = list(claims())
    assert len(found) >= 8, f"expected the README and docs to state their run times, found {found}"
    for page, text, key in found:
        assert key in RECORD["runs"], f"{page}: [{text}] links to {key!r}, which the record does not hold"
        factor = drift(text, RECORD["runs"][key])
        assert factor <= 2.0, (
            f"{page}: [{text}] is {factor:.1f}x off the recorded run {key!r}; restate with python docs/timings.py --render"
        )


def test_the_required_runs_are_stated():
    stated = {key for _, _, key in claims()}
    for key in REQUIRED + ["run_seed"]:
        assert key in stated, f"the README and docs state no time for {key!r}"


def test_no_figure_without_its_record():
    for path in pages():
        text = timings.CLAIM.sub("", path.read_text(encoding="utf-8"))
        for pattern in UNLINKED:
            match = pattern.search(text)
            assert match is None, (
                f"{path.name} states {match.group(0)!r} with no link to its recorded run (docs/timings.md#KEY)"
            )


def test_the_drift_check_can_fail():
    entry = RECORD["runs"]["run_seed"]
    assert drift(timings.time_text(entry["wall_s"]), entry) < 1.1
    assert drift(timings.time_text(2.5 * entry["wall_s"]), entry) > 2.0
    assert drift(timings.time_text(entry["wall_s"] / 2.5), entry) > 2.0


def test_the_page_is_the_record():
    assert timings.PAGE.read_text(encoding="utf-8") == timings.page(RECORD), "rerun python docs/timings.py --render"


@pytest.mark.parametrize(
    "seconds,text", [(4.04, "4 s"), (75.2, "75 s"), (200, "3.3 min"), (1800, "30 min"), (7200, "2.0 h")]
)
def test_time_text(seconds, text):
    assert timings.time_text(seconds) == text
    value, kind = timings.stated(text)
    assert kind == "time" and abs(value / seconds - 1) < 0.06


def test_a_ci_run_slower_than_stated_fails_the_drift_check_and_a_faster_one_does_not(tmp_path, monkeypatch):
    """CI records the runs it makes (``--record``) and keeps the stated figures: a run that took
    3x the stated time fails ``test_every_stated_figure_is_within_2x_of_the_record``; one that took a
    third of it does not (the stated time is an upper figure, kept by a faster machine)."""
    record_path, page_path = tmp_path / "timings.json", tmp_path / "timings.md"
    record_path.write_text(timings.RECORD.read_text(encoding="utf-8"), encoding="utf-8")
    monkeypatch.setattr(timings, "RECORD", record_path)
    monkeypatch.setattr(timings, "PAGE", page_path)
    stated = next(text for _, text, key in claims() if key == "validate_quick")
    value, _ = timings.stated(stated)
    for factor, off in [(3.0, True), (1 / 3, False)]:
        timings.main(["--record", "validate_quick", str(factor * value), "CI: the wall clock of .ci/run step 4"])
        new = json.loads(record_path.read_text(encoding="utf-8"))["runs"]["validate_quick"]
        assert new["wall_s"] == pytest.approx(factor * value) and new["upper"]
        assert (drift(stated, new) > 2.0) is off
    assert page_path.read_text(encoding="utf-8") == timings.page(json.loads(record_path.read_text(encoding="utf-8")))
