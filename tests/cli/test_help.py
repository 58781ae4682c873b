"""Help that lists what exists: the validation cases, every surface kind in the template, and the
friction plot's main axis in the units its user thinks in."""

import re

import pytest
from conftest import make_tiny_scene

from validation.cases import CASES
from viscobem_cli import scene as scenes
from viscobem_cli.catalog import scene_path
from viscobem_cli.main import main


def test_validate_list_and_help_name_every_case(capsys):
    assert main(["validate", "--list"]) == 0
    listed = capsys.readouterr().out
    with pytest.raises(SystemExit):
        main(["validate", "--help"])
    helped = capsys.readouterr().out
    for name, case in CASES.items():
        assert re.search(rf"^  {name} +{re.escape(case.title)}$", listed, re.MULTILINE), name
        assert name in helped and case.title in helped


def test_the_template_names_every_surface_kind():
    line = next(x for x in scene_path("seed").read_text().splitlines() if x.startswith("kind ="))
    named = re.findall(r'"(\w+)"', line)
    assert sorted(named) == sorted(scenes.SURFACE_KINDS), line


PRONY = """
[material]
E0 = 1e6
moduli = [2e6, 2e6, 2e6]
times = [1e-4, 1e-2, 1]
"""


@pytest.mark.parametrize("prony", [False, True])
def test_a_fitted_material_is_plotted_against_speed_with_xi_on_top(prony):
    from viscobem_cli.plots.style import pyplot, sweep_axis

    text = make_tiny_scene("plots = false", speeds="[0.001, 0.01, 0.1]")
    if prony:
        text = PRONY + text[text.index("[surface]") :]
    scene = scenes.parse(text)
    fig, ax = pyplot().subplots()
    x = sweep_axis(ax, scene)
    top = next(c for c in ax.child_axes)
    if prony:  # several times: xi's tau is only the longest one
        assert ax.get_xlabel() == "sliding speed v (m/s)" and top.get_xlabel().startswith(r"$\xi")
        assert list(x) == pytest.approx([0.001, 0.01, 0.1])
    else:  # one time: xi is the seed paper's axis
        assert ax.get_xlabel().startswith(r"$\xi") and top.get_xlabel() == "sliding speed v (m/s)"
        assert list(x) == pytest.approx(list(scene.xi))
    pyplot().close(fig)
