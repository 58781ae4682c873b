"""Scenes with temperature: a shift law, a sweep per temperature, DMA tables with units.

Exact check: a material at ``T`` is the reference material with every time scaled by
``a_T``, and sliding at speed ``v`` probes frequencies proportional to ``v``, so the friction
obeys time-temperature superposition itself: ``mu(v, T) = mu(a_T v, T_ref)``. With
``C1 = 9, C2 = 100 K`` the law gives ``log10 a_T = +1`` at ``T_ref - 10 K`` and ``-1`` at
``T_ref + 12.5 K`` exactly, so the three temperatures share speeds a decade apart.
"""

import json

import numpy as np
import pytest

import bem
from bem.errors import InputError
from bem.materials.temperature import WLF, Arrhenius
from viscobem_cli import scene as scenes
from viscobem_cli.run.study import run_scene

TREF = 300.0
SCENE = """
title = "temperature test"
[material]
E0 = 3.3333333333333335e6
E_inf = 1.0e7
creep_time = 0.01
shift = { law = "wlf", C1 = 9.0, C2 = 100.0, reference_temperature = 300.0 }
[surface]
kind = "sinusoid"
length = 0.01
n = 64
amplitude = 1.0e-5
wavelength = 0.01
dim = 1
[loading]
load = 20.0
speeds = [0.01, 0.1, 1.0]
temperatures = [290.0, 300.0, 312.5]
[solver]
rtol = 1e-10
[outputs]
fields = false
plots = PLOTS
"""


def test_scene_reads_the_shift_law_and_temperatures():
    s = scenes.parse(SCENE.replace("PLOTS", "false"))
    assert s.shift == WLF(9.0, 100.0, 300.0) and s.temperatures == (290.0, 300.0, 312.5)
    assert s.shift(290.0) == pytest.approx(1.0, rel=1e-15) and s.shift(312.5) == pytest.approx(-1.0, rel=1e-15)
    arr = scenes.parse(
        SCENE.replace("PLOTS", "false").replace(
            'law = "wlf", C1 = 9.0, C2 = 100.0', 'law = "arrhenius", activation_energy = 1.5e5'
        )
    )
    assert arr.shift == Arrhenius(1.5e5, 300.0)


def test_friction_obeys_time_temperature_superposition(tmp_path, capsys):
    """``mu(v, 290 K) = mu(10 v, 300 K)`` and ``mu(v, 312.5 K) = mu(v / 10, 300 K)``: measured
    agreement 4e-16 relative (solver rtol 1e-10; bound 1e-8). A second ``viscobem run`` in the
    same folder resumes every point and prints the table of mu(v, T)."""
    (tmp_path / "scene.toml").write_text(SCENE.replace("PLOTS", "true"))
    s = scenes.load(tmp_path / "scene.toml")
    rec = run_scene(s, tmp_path / "out", progress=False)
    tmp_path = tmp_path / "out"
    table = rec["temperature_sweep"]
    assert table["temperature"] == [290.0, 300.0, 312.5] and table["units"]["temperature"] == "K"
    mu = np.array(table["loads"][0]["friction"])  # [temperature, speed]
    assert mu.shape == (3, 3) and np.all(mu > 0)
    np.testing.assert_allclose(mu[0, :2], mu[1, 1:], rtol=1e-8)  # cold: 10x faster at the reference
    np.testing.assert_allclose(mu[2, 1:], mu[1, :2], rtol=1e-8)  # hot: 10x slower
    assert not np.allclose(mu[0], mu[1], rtol=1e-3)  # temperature matters here
    on_disk = json.loads((tmp_path / "results.json").read_text())
    assert on_disk["temperature_sweep"]["loads"][0]["friction"] == table["loads"][0]["friction"]
    for name in ("friction_speed_temperature.png", "friction_curves_temperatures.png"):
        assert (tmp_path / name).stat().st_size > 1000 and name in rec["files"]
    assert (tmp_path / "T_290.00K" / "results.json").is_file()
    assert rec["friction_curve_temperature"] == 300.0 and rec["all_converged"]
    from viscobem_cli.main import main

    assert main(["run", str(tmp_path.parent / "scene.toml"), "--out", str(tmp_path), "--no-progress"]) == 0
    printed = capsys.readouterr().out
    assert "290.00    300.00    312.50" in printed and "resumed: 9 finished point(s)" in printed


def _write_sweeps(path, unit_c=True):
    """Sweeps in Hz, MPa, degrees C from a 3-term series under WLF(8.86, 101.6, 296.15)."""
    law = WLF(8.86, 101.6, 296.15)
    m = bem.Material.from_prony(E0=2e6, moduli=[3e7, 4e7, 2e7, 1e7], times=[1e-6, 1e-4, 1e-2, 1.0])
    hz = np.logspace(-1, 2, 10)
    rows = []
    for T in 296.15 + np.arange(-30.0, 41.0, 5.0):
        e = m.at_temperature(T, law).complex_modulus(2 * np.pi * hz)
        rows.append(np.column_stack([hz, e.real / 1e6, e.imag / 1e6, np.full(hz.size, T - 273.15)]))
    np.savetxt(path, np.vstack(rows), delimiter=",", header="f (Hz), E' (MPa), E'' (MPa), T (C)")
    return m, law


DMA_SCENE = SCENE.replace(
    """E0 = 3.3333333333333335e6
E_inf = 1.0e7
creep_time = 0.01
shift = { law = "wlf", C1 = 9.0, C2 = 100.0, reference_temperature = 300.0 }""",
    """dma = "sweeps.csv"
dma_frequency_unit = "Hz"
dma_modulus_unit = "MPa"
dma_temperature_unit = "C"
shift = { law = "wlf", reference_temperature = 296.15 }""",
).replace("[290.0, 300.0, 312.5]", "[296.15, 320.0]")


def test_a_dma_table_with_temperatures_gives_a_master_curve_and_its_law(tmp_path):
    """Noise-free sweeps, 10 points over 3 decades each: measured C1, C2 within 1.0e-3 relative
    (the overlap shifts interpolate linearly between points; bound 5e-3), moduli within 7e-4
    over the band (bound 1e-2)."""
    m, law = _write_sweeps(tmp_path / "sweeps.csv")
    s = scenes.parse(DMA_SCENE.replace("PLOTS", "true"), base=tmp_path)
    assert isinstance(s.shift, WLF) and s.shift.reference_temperature == 296.15
    assert s.shift.C1 == pytest.approx(8.86, rel=5e-3) and s.shift.C2 == pytest.approx(101.6, rel=5e-3)
    w = np.logspace(-1, 7, 50)
    np.testing.assert_allclose(s.material.complex_modulus(w), m.complex_modulus(w), rtol=1e-2)
    assert s.dma["T"].min() == pytest.approx(266.15) and s.dma["e1"].max() > 1e7  # units applied
    from viscobem_cli.run.temperatures import write_master_curve

    assert write_master_curve(s, tmp_path) == ["master_curve.png"]
    assert (tmp_path / "master_curve.png").stat().st_size > 1000


@pytest.mark.parametrize(
    "replace, words",
    [
        (("temperatures = [290.0, 300.0, 312.5]", "temperatures = [290.0, -3.0]"), ["temperatures", "> 0 K"]),
        (("temperatures = [290.0, 300.0, 312.5]", "temperatures = [150.0]"), ["reference_temperature - C2", "200"]),
        (('shift = { law = "wlf", C1 = 9.0, C2 = 100.0, reference_temperature = 300.0 }\n', ""), ["shift law"]),
        (('law = "wlf", C1 = 9.0', 'law = "vft", C1 = 9.0'), ["shift", "wlf", "arrhenius"]),
        (("C2 = 100.0,", "C2 = 100.0, Tg = 200.0,"), ["'Tg'", "valid keys"]),
        (("C1 = 9.0, ", ""), ["C1", "required"]),
        (("C1 = 9.0", "C1 = -9.0"), ["C1", "> 0"]),
    ],
)
def test_bad_temperature_scenes_are_named(replace, words):
    text = SCENE.replace("PLOTS", "false").replace(*replace)
    with pytest.raises(InputError) as err:
        scenes.parse(text)
    for word in words:
        assert word in str(err.value)


def test_bad_dma_units_and_missing_reference_are_named(tmp_path):
    _write_sweeps(tmp_path / "sweeps.csv")
    text = DMA_SCENE.replace("PLOTS", "false")
    with pytest.raises(InputError, match="dma_modulus_unit must be one of"):
        scenes.parse(text.replace('"MPa"', '"psi"'), base=tmp_path)
    with pytest.raises(InputError, match="dma_temperature_unit"):
        scenes.parse(text.replace('dma_temperature_unit = "C"', 'dma_temperature_unit = "F"'), base=tmp_path)
    with pytest.raises(InputError, match="reference_temperature"):
        scenes.parse(text.replace('law = "wlf", reference_temperature = 296.15', 'law = "wlf"'), base=tmp_path)


def test_built_in_temperature_scene_parses():
    s = scenes.load("temperature")
    assert len(s.temperatures) == 5 and isinstance(s.shift, WLF) and s.shift.reference_temperature == 296.15
    assert s.material.E_inf / s.material.E0 == pytest.approx(200, rel=1e-3) and s.speeds.size == 9
