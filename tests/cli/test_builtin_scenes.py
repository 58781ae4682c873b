"""Every built-in scene runs without a quality warning, or its description names the warning and
why it is the point (issue 27 item 4).

A scene's description declares an expected warning on a line ``# Expected warning (KIND): why``,
``KIND`` one of the findings of :mod:`bem.accuracy.findings` or ``friction_peak`` (the friction peak
lies outside the sweep). Each scene runs at its own resolution on a sample of its speeds (the whole
sweeps take minutes), without plots.
"""

import json
import re
from pathlib import Path

import pytest

from viscobem_cli import scene as scenes
from viscobem_cli.catalog import scene_path
from viscobem_cli.run.study import run_scene

SAMPLES = {
    "seed": ["loading.xi=[1e-4, 1e-2, 1.0, 100.0]"],
    "seed_figures": [
        "loading.xi=[1e-4, 1.17e-2, 1.0, 100.0]",
        "surface.realisations=1",
        "solver.workers=1",
        "outputs.anisotropy=false",
        "outputs.contact_psd=false",
        "outputs.persson=false",
    ],
    "sphere": ["loading.xi={start = 1e-3, stop = 1e2, num = 4}"],
    "cylinder": ["loading.xi={start = 1e-3, stop = 1e2, num = 6}"],
    "temperature": [],
}
DECLARED = re.compile(r"^# Expected warning \((\w+)\): \S", re.M)


def _kinds(folder):
    """Kinds of every warning under ``folder``: each point's findings, and the curve-level ones."""
    kinds = set()
    for path in Path(folder).rglob("results.json"):
        rec = json.loads(path.read_text())
        kinds |= {w["kind"] for p in rec.get("points", []) for w in p.get("warnings", [])}
        kinds |= {"friction_peak" for w in rec["warnings"] if "the friction peak lies outside" in w}
        kinds |= {"resolution" for w in rec["warnings"] if "points per shortest wavelength of the surface" in w}
    return kinds


def test_every_builtin_scene_has_a_sample():
    assert set(SAMPLES) == set(scenes.builtin_scenes())


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(SAMPLES))
def test_builtin_scene_warns_only_as_its_description_says(name, tmp_path):
    declared = set(DECLARED.findall(scene_path(name).read_text()))
    scene = scenes.load(name, overrides=SAMPLES[name] + ["outputs.plots=false", "outputs.fields=false"])
    run_scene(scene, tmp_path, progress=False)
    assert _kinds(tmp_path) <= declared, (name, _kinds(tmp_path), declared)
