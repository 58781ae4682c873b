"""``viscobem bench contact``: the switch that turns a mechanism off patches the constant wherever
the solver reads it and restores it after; the quick ablation runs from the CLI and records, per
variant, products, time, failures and the pressure error against the tight reference."""

import json

import pytest

from bem.contact import forcing, inner, newton
from viscobem_bench import contact as bench
from viscobem_cli.main import main


def test_the_switch_patches_every_copy_and_restores_it():
    tighten, gap = forcing.TIGHTEN, newton.GAP_SCALE
    with bench.switched_off({"forcing:TIGHTEN": 0.5, "newton:GAP_SCALE": 10.0}):
        assert forcing.TIGHTEN == inner.TIGHTEN == 0.5  # inner imported it by name
        assert newton.GAP_SCALE == 10.0
    assert forcing.TIGHTEN == inner.TIGHTEN == tighten and newton.GAP_SCALE == gap


def test_the_switch_restores_after_an_error():
    with pytest.raises(RuntimeError), bench.switched_off({"newton:CYCLING_STEPS": 10**9}):
        raise RuntimeError
    assert newton.CYCLING_STEPS < 10**9


def test_every_mechanism_names_what_it_switches():
    """Each patched name exists (a renamed constant would otherwise be switched off silently)."""
    import importlib

    names = [m[0] for m in bench.MECHANISMS]
    assert len(names) == len(set(names)) and names[0] == "all on"
    for _, _, options, patches in bench.MECHANISMS:
        bench.ContactOptions(**options)
        for key in patches:
            if key != "warm":
                module, name = key.split(":")
                assert hasattr(importlib.import_module(f"bem.contact.{module}"), name), key


@pytest.mark.slow
def test_the_quick_ablation_runs_from_the_cli(tmp_path, monkeypatch):
    """One mechanism against everything on, over the quick set: every case converges with the
    pressure within 10 rtol of the reference, and switching the coarse start off changes the path
    of the cases it applies to (the switch works)."""
    monkeypatch.setattr(bench, "MECHANISMS", bench.MECHANISMS[:2])
    assert main(["bench", "contact", "--quick", "--out", str(tmp_path)]) == 0
    rec = json.loads((tmp_path / "contact.json").read_text())
    on, off = rec["variants"]
    assert on["mechanism"] == "all on" and off["mechanism"] == "coarse start"
    assert on["failed"] == [] and on["max_error_in_rtol"] <= 10
    assert on["per_case"] != off["per_case"]
    assert all(c["elastic_products"] > 0 for c in rec["cases"])
    assert "pays" in (tmp_path / "contact.md").read_text()
