"""docs/outputs.md against what ``viscobem run`` really writes, both ways.

One small scene asks for every output; each table of the page is read (first column: the
names, *when*: the scenes that have them) and compared with the run: a name the page promises
for this scene must be in the output, and everything the run writes must be on the page. The
``fields.npz`` and VTK tables must match the files' arrays exactly.
"""

import json
import re
from pathlib import Path

import numpy as np
import pytest

from conftest import make_tiny_scene
from viscobem_cli.main import main

ROOT = Path(__file__).resolve().parents[2]
PAGE = (ROOT / "docs" / "outputs.md").read_text(encoding="utf-8")
OUTPUTS = "friction_curve = true\nfields = true\nplots = true\nvtk = {vtk}\nanisotropy = true\ncontact_psd = true\npersson = true"
# the conditions of the page's "when" column that hold for SCENE; any other condition: not this scene
HOLDS = {"always", "`plots`", "`anisotropy = true`", "`contact_psd = true`", "`persson = true`", "a periodic cell"}


def tables(section):
    """Rows (lists of cells) of the tables under the ``## `` heading that starts with ``section``."""
    body = PAGE.split("\n## " + section, 1)[1].split("\n## ", 1)[0]
    rows = []
    for line in body.splitlines():
        if line.startswith("|") and not line.startswith("|---"):
            rows.append([c.strip() for c in line.strip("|").split(" | ")])
    return rows[1:] if rows else rows  # without the header


def names(cell):
    return re.findall(r"`([^`]+)`", cell)


def applies(row):
    return all(cond.strip() in HOLDS for cond in row[1].split(", "))


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    vtk = True
    try:
        import pyvista  # noqa: F401
    except ImportError:
        vtk = False
    folder = tmp_path_factory.mktemp("outputs")
    scene = folder / "scene.toml"
    scene.write_text(make_tiny_scene(OUTPUTS.format(vtk="true" if vtk else "false")))
    assert main([ "run", str(scene), "--out", str(folder / "out"), "--no-progress"]) == 0
    return folder / "out", vtk


def test_results_json_keys(run):
    out, _ = run
    record = json.loads((out / "results.json").read_text())
    listed = set()
    for row in tables("`results.json`"):
        keys = names(row[0])
        listed.update(keys)
        if applies(row):
            missing = [k for k in keys if k not in record]
            assert not missing, f"outputs.md promises results.json keys {missing} ({row[1]}); the run has none"
    unlisted = sorted(set(record) - listed)
    assert not unlisted, f"results.json keys missing from docs/outputs.md: {unlisted}"


def test_friction_curve_lists(run):
    out, _ = run
    curve = json.loads((out / "results.json").read_text())["friction_curve"]
    row = next(r for r in tables("`results.json`") if names(r[0]) == ["friction_curve"])
    promised = [n for n in names(row[2]) if not n.startswith("*")]
    assert not [n for n in promised if n not in curve], f"friction_curve lacks {promised}"
    plain = {k for k in curve if not k.endswith("_se")}
    assert not plain - set(promised), f"friction_curve keys missing from outputs.md: {sorted(plain - set(promised))}"


def test_fields_npz_arrays_exactly(run):
    out, _ = run
    with np.load(out / "fields.npz") as f:
        written = set(f.files)
    promised = {names(r[0])[0] for r in tables("`fields.npz`")}
    assert promised == written, f"outputs.md lists {sorted(promised)}, fields.npz holds {sorted(written)}"


def test_plots(run):
    out, _ = run
    written = {p.name for p in out.glob("*.png")}
    listed = set()
    for row in tables("Plots"):
        files = names(row[0])
        listed.update(files)
        if applies(row):
            assert set(files) <= written, f"outputs.md promises {files} ({row[1]}); the run wrote {sorted(written)}"
    assert written <= listed, f"plots missing from outputs.md: {sorted(written - listed)}"


def test_vtk_arrays_exactly(run):
    out, vtk = run
    if not vtk:
        pytest.skip("pyvista (the vtk extra) is not installed")
    import pyvista as pv

    grid = pv.read(out / "vtk" / "point_000.vti")
    promised = {names(r[0])[0] for r in tables("VTK") if r[1] == "point"}
    assert promised == set(grid.point_data.keys()), f"outputs.md lists {sorted(promised)}, VTK holds {sorted(grid.point_data.keys())}"
    assert (out / "vtk" / "sweep.pvd").is_file()


def test_gap_recipe_matches_the_vtk_gap(run):
    """The page's snippet for the gap gives the gap the solver wrote to VTK (float32 fields)."""
    out, vtk = run
    code = re.search(r"```python\n(.*?)```", PAGE.split("## `fields.npz`")[1], re.DOTALL).group(1)
    space = {}
    exec(code.replace('"viscobem-out/fields.npz"', repr(str(out / "fields.npz"))), space)  # noqa: S102
    gap = space["gap"]
    assert gap.shape == space["f"]["pressure"].shape
    scale = np.abs(space["h"]).max()
    assert np.min(gap) > -1e-5 * scale  # float32 fields: the gap is >= 0 to their rounding
    if vtk:
        import pyvista as pv

        grid = pv.read(out / "vtk" / "point_000.vti")
        exact = np.asarray(grid.point_data["gap"]).reshape(gap.shape[1:], order="F")
        assert np.max(np.abs(gap[0] - exact)) < 1e-5 * scale
