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
        (
            ("temperatures = [290.0, 300.0, 312.5]", "temperatures = [200.2]"),
            ["[loading] temperatures", "log10 a_T = 4491"],
        ),
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


# ---------------------------------------------------------------- real DMA files, temperatures that make sense


def _sweep_rows(temps_c, m=None, law=None):
    """Rows (Hz, E' MPa, E'' MPa, T C) of sweeps from the 3-term series under WLF(8.86, 101.6, 296.15)."""
    law = law or WLF(8.86, 101.6, 296.15)
    m = m or bem.Material.from_prony(E0=2e6, moduli=[3e7, 4e7, 2e7, 1e7], times=[1e-6, 1e-4, 1e-2, 1.0])
    hz = np.logspace(-1, 2, 10)
    rows = []
    for t in temps_c:
        e = m.at_temperature(t + 273.15, law).complex_modulus(2 * np.pi * hz)
        rows.append(np.column_stack([hz, e.real / 1e6, e.imag / 1e6, np.full(hz.size, t)]))
    return np.vstack(rows), m, law


TEMPS_C = np.arange(-30.0, 41.0, 5.0)


def test_a_csv_with_named_columns_and_units_in_the_header(tmp_path):
    """A header row used to be rejected ("could not convert string 'frequency_Hz'"). Columns are
    found by name in any order, extra columns are ignored, units come from the header: the same
    material as the headerless table with the unit keys."""
    rows, m, law = _sweep_rows(TEMPS_C)
    tan = rows[:, 2] / rows[:, 1]
    table = np.column_stack([rows[:, 3], rows[:, 0], tan, rows[:, 2], rows[:, 1]])
    lines = ["temperature_C,frequency_Hz,tan_delta,E''_MPa,E'_MPa"] + [",".join(f"{x:.17g}" for x in r) for r in table]
    (tmp_path / "named.csv").write_text("\n".join(lines) + "\n")
    text = DMA_SCENE.replace("PLOTS", "false").replace('dma = "sweeps.csv"', 'dma = "named.csv"')
    for key in ("dma_frequency_unit", "dma_modulus_unit", "dma_temperature_unit"):
        text = "\n".join(line for line in text.splitlines() if not line.startswith(key))
    s = scenes.parse(text, base=tmp_path)
    assert s.dma["units"] == {"frequency": "Hz", "modulus": "MPa", "temperature": "C"}
    np.testing.assert_allclose(s.dma["T"], rows[:, 3] + 273.15)
    _write_sweeps(tmp_path / "sweeps.csv")
    plain = scenes.parse(DMA_SCENE.replace("PLOTS", "false"), base=tmp_path)
    assert s.shift.C1 == pytest.approx(plain.shift.C1, rel=1e-6)


def test_two_header_rows_and_named_columns(tmp_path):
    """pyvisco's layout: names, then units. And dma_columns for names nobody guesses."""
    rows, _, _ = _sweep_rows(TEMPS_C)
    body = "\n".join(",".join(f"{x:.17g}" for x in r) for r in rows)
    (tmp_path / "pyvisco.csv").write_text("f_set,E_stor,E_loss,T\nHz,MPa,MPa,C\n" + body + "\n")
    text = DMA_SCENE.replace("PLOTS", "false").replace('dma = "sweeps.csv"', 'dma = "pyvisco.csv"')
    s = scenes.parse(text, base=tmp_path)
    assert s.shift.C1 == pytest.approx(8.86, rel=1e-3) and s.dma["e1"].max() > 1e7
    (tmp_path / "odd.csv").write_text("a,b,c,d\n" + body + "\n")
    odd = text.replace('"pyvisco.csv"', '"odd.csv"')
    with pytest.raises(InputError, match="no column named for frequency, storage, loss.*dma_columns"):
        scenes.parse(odd, base=tmp_path)
    named = odd.replace(
        'dma = "odd.csv"',
        'dma = "odd.csv"\ndma_columns = { frequency = "a", storage = 2, loss = "c", temperature = 4 }',
    )
    assert scenes.parse(named, base=tmp_path).shift.C1 == pytest.approx(s.shift.C1, rel=1e-9)
    clash = text.replace('dma_modulus_unit = "MPa"', 'dma_modulus_unit = "kPa"')
    with pytest.raises(InputError, match="dma_modulus_unit = 'kPa' disagrees with the unit 'MPa'"):
        scenes.parse(clash, base=tmp_path)


def test_known_wlf_constants_are_imposed_from_a_scene(tmp_path):
    """All of C1, C2, reference_temperature with a temperature column: the law is used as given."""
    _write_sweeps(tmp_path / "sweeps.csv")
    text = DMA_SCENE.replace("PLOTS", "false").replace(
        'law = "wlf", reference_temperature = 296.15',
        'law = "wlf", C1 = 8.86, C2 = 101.6, reference_temperature = 296.15',
    )
    s = scenes.parse(text, base=tmp_path)
    assert s.shift == WLF(8.86, 101.6, 296.15) and s.material.fit_report.law_imposed
    partial = text.replace("C1 = 8.86, ", "")
    with pytest.raises(InputError, match="the full law"):
        scenes.parse(partial, base=tmp_path)


@pytest.mark.parametrize(
    "replace, words",
    [
        (
            ("temperatures = [296.15, 320.0]", "temperatures = [23.0, 50.0]"),
            ["[loading] temperatures", "degrees Celsius"],
        ),
        (("reference_temperature = 296.15", "reference_temperature = 23.0"), ["reference_temperature", "Celsius"]),
        (('dma_temperature_unit = "C"\n', ""), ['dma_temperature_unit = \\"C\\"', "degrees Celsius"]),
    ],
)
def test_temperatures_in_celsius_are_named(tmp_path, replace, words):
    _write_sweeps(tmp_path / "sweeps.csv")
    with pytest.raises(InputError) as err:
        scenes.parse(DMA_SCENE.replace("PLOTS", "false").replace(*replace), base=tmp_path)
    for word in words:
        assert word.replace("\\", "") in str(err.value)


DMA_RUN = DMA_SCENE.replace("PLOTS", "false").replace("speeds = [0.01, 0.1, 1.0]", "speeds = [1e-6, 0.01]")


def test_results_record_the_law_the_band_and_the_extrapolation(tmp_path, capsys):
    """results.json holds C1, C2 and the reference temperature, the fit report with the data's
    band, and the band the speeds excite; a speed below the data's band is a warning there and on
    the console. Each temperature's xi and xi_time come from the material at that temperature (at
    320 K xi used to be computed with the 296.15 K creep time while the 320 K one was listed)."""
    from viscobem_cli.main import main

    _write_sweeps(tmp_path / "sweeps.csv")
    (tmp_path / "scene.toml").write_text(DMA_RUN)
    assert main(["run", str(tmp_path / "scene.toml"), "--out", str(tmp_path / "out"), "--no-progress"]) == 0
    printed = capsys.readouterr().out
    rec = json.loads((tmp_path / "out" / "results.json").read_text())
    sub = json.loads((tmp_path / "out" / "T_320.00K" / "results.json").read_text())
    law = sub["material"]["shift"]
    assert law["law"] == "WLF" and law["reference_temperature"] == 296.15
    assert law["C1"] == pytest.approx(8.86, rel=1e-3) and law["C2"] == pytest.approx(101.6, rel=1e-3)
    fit = sub["material"]["fit"]
    assert fit["law"]["C1"] == law["C1"] and fit["terms"] > 0 and len(fit["worst_loss"]) == 3
    lo, hi = sub["material"]["data_band"]
    w_low, w_high = sub["material"]["excited_band"]
    assert w_low == pytest.approx(2 * np.pi / 0.01 * 1e-6) and w_low < lo  # 1e-6 m/s: below the data
    assert w_high == pytest.approx(np.pi * 64 / 0.01 * 0.01)
    creep = max(sub["material"]["creep_times"])
    assert sub["xi_time"] == pytest.approx(creep, rel=1e-12) and "at 320 K" in sub["xi_time_source"]
    assert sub["friction_curve"]["xi"] == pytest.approx([v * creep / 0.01 for v in (1e-6, 0.01)], rel=1e-12)
    below = [w for w in rec["warnings"] if "the material is extrapolated" in w]
    assert {w.split(":")[0] for w in below} == {"at 296.15 K", "at 320 K"}
    assert all("down to 0.000628 rad/s" in w for w in below)
    assert "WARNING: at 320 K: the material is extrapolated" in printed
    assert sub["warnings"] == rec["warnings"][: len(sub["warnings"])]  # the study's warnings, once


RUBBER_MAP = """
title = "map"
[material]
E0 = 1e6
moduli = [2.5e7, 2.5e7, 2.5e7, 2.5e7, 2.5e7, 2.5e7, 2.5e7, 2.5e7]
times = [1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0]
shift = { law = "wlf", C1 = 8.86, C2 = 101.6, reference_temperature = 296.15 }
[surface]
kind = "self_affine"
dim = 1
length = 0.01
n = 256
hurst = 0.8
scales = 16
rms_height = 2e-5
seed = 1
[loading]
load = 1e4
speeds = [1e-5, 1e-4, 1e-3, 1e-2, 1e-1]
temperatures = [273.15, 296.15, 323.15]
SUPERPOSITION
[outputs]
fields = false
plots = PLOTS
"""


def test_a_superposed_temperature_study_matches_the_direct_one(tmp_path, capsys):
    """``superposition = true``: one curve over the reduced speeds stands for every temperature,
    within 1 % of the study that sweeps each temperature; it writes the same table, with the
    reduced speeds and the estimate of each interpolated point, and the Grosch plot."""
    superposed = scenes.parse(RUBBER_MAP.replace("SUPERPOSITION", "superposition = true").replace("PLOTS", "true"))
    direct = scenes.parse(RUBBER_MAP.replace("SUPERPOSITION", "").replace("PLOTS", "false"))
    assert superposed.superposition and not direct.superposition
    rec = run_scene(superposed, tmp_path / "map", progress=False)
    ref = run_scene(direct, tmp_path / "direct", progress=False)
    table, sweep = rec["temperature_sweep"], rec["temperature_sweep"]["loads"][0]
    assert table["method"] == "superposition" and sweep["solves"] > 0
    mu, mu_direct = np.array(sweep["friction"]), np.array(ref["temperature_sweep"]["loads"][0]["friction"])
    np.testing.assert_allclose(mu, mu_direct, rtol=0.01)
    reduced = np.array(sweep["reduced_speed"])
    np.testing.assert_allclose(reduced, np.outer(10.0 ** np.array(table["log10_shift_factor"]), sweep["speed"]))
    est = np.array(sweep["interpolation_error"], dtype=float)
    assert np.all(est[np.array(sweep["interpolated"])] <= 0.005)
    assert {"friction_master_curve.png", "friction_speed_temperature.png"} <= set(rec["files"])
    assert (tmp_path / "map" / "friction_master_curve.png").stat().st_size > 10_000
    assert json.loads((tmp_path / "map" / "results.json").read_text())["temperature_sweep"]["method"] == "superposition"


@pytest.mark.parametrize(
    "change,match",
    [
        (("SUPERPOSITION", 'superposition = "yes"'), "superposition must be true or false"),
        (
            ("temperatures = [273.15, 296.15, 323.15]\nSUPERPOSITION", "superposition = true"),
            "needs \\[loading\\] temperatures",
        ),
    ],
)
def test_superposition_keys_are_checked(change, match):
    with pytest.raises(InputError, match=match):
        scenes.parse(RUBBER_MAP.replace(*change).replace("SUPERPOSITION", "").replace("PLOTS", "false"))


def test_superposition_needs_moving_speeds(tmp_path):
    text = RUBBER_MAP.replace("SUPERPOSITION", "superposition = true").replace("PLOTS", "false")
    s = scenes.parse(text.replace("speeds = [1e-5,", "speeds = [0.0, 1e-5,"))
    with pytest.raises(InputError, match="speeds > 0"):
        run_scene(s, tmp_path / "out", progress=False)
