"""A case that raises under a perturbation is its own outcome in the sensitivity run (``error``),
never a detection: whatever the solver's error was, no check measured it. Before, an exception
counted as ``detected`` by "error"."""

import json

from validation.cases import CASES, Case
from validation.perturb import NONE
from viscobem_cli.main import main


def test_an_exception_under_a_perturbation_is_not_a_detection(tmp_path, monkeypatch, capsys):
    real = CASES["westergaard"]

    def raising(*, quick, vtk_dir, root, tamper):
        out = real.run(quick=quick, vtk_dir=vtk_dir, root=root, tamper=tamper)
        if tamper.perturbation is not NONE and tamper.perturbation.name == "load +2%":
            raise RuntimeError("solver broke on the wrong load")
        return out

    monkeypatch.setitem(
        CASES, "westergaard", Case(real.name, real.title, real.description, real.solvers, real.reference, raising)
    )
    argv = ["validate", "--quick", "--no-progress", "--no-vtk", "--no-plots", "--no-baseline", "--sensitivity"]
    argv += ["--jobs", "1", "--case", "westergaard", "--out", str(tmp_path)]  # in this process: the case is patched
    capsys.readouterr()
    assert main(argv) == 1
    printed = capsys.readouterr().out
    assert "RAISED westergaard" in printed and "raised instead" in printed
    entries = json.loads((tmp_path / "report.json").read_text())["sensitivity"]
    raised = [e for e in entries if e["perturbation"] == "load +2%"]
    assert raised and all(e["outcome"] == "error" and not e["detected"] for e in raised)
    assert "solver broke" in raised[0]["by"][0]
    others = [e for e in entries if e["perturbation"] != "load +2%" and e["required"]]
    assert others and all(e["outcome"] == "detected" for e in others)
    html = (tmp_path / "report.html").read_text()
    assert "RAISED (not a detection)" in html
