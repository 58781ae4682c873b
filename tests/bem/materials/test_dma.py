"""The DMA reader is public API (issue: units pass silently): a table in MPa and Hz whose header
names no unit is not read silently as Pa and rad/s; header units are read; the CLI calls it."""

import numpy as np
import pytest

import bem
from bem.errors import InputError
from bem.materials import read_dma

TRUE = bem.Material.from_prony(E0=3.9e6, moduli=[2e7, 8e7, 3e8], times=[1.0, 1e-2, 1e-4])
HZ = np.logspace(-2, 3, 16)


def _rows(temperature=None):
    e = TRUE.complex_modulus(2 * np.pi * HZ)
    cols = [HZ, e.real / 1e6, e.imag / 1e6] + ([np.full(HZ.size, temperature)] if temperature is not None else [])
    return "\n".join(",".join(f"{v:.17g}" for v in row) for row in zip(*cols)) + "\n"


def test_a_table_in_mpa_and_hz_without_units_is_not_read_silently(tmp_path):
    path = tmp_path / "export.csv"
    path.write_text(_rows())
    with pytest.warns(UserWarning, match=r"names no unit for frequency, storage: read as frequency in rad/s"):
        with pytest.raises(InputError, match=r"got 3.9.* Pa \(looks like MPa: multiply by 1e\+06, or set modulus_unit"):
            read_dma(path)
    table = read_dma(path, frequency_unit="Hz", modulus_unit="MPa")
    assert not table.warnings and table.temperatures is None
    np.testing.assert_allclose(table.frequencies, 2 * np.pi * HZ, rtol=1e-15)
    fitted = bem.Material.fit_prony(table.frequencies, table.storage, table.loss)
    assert fitted.E0 == pytest.approx(TRUE.E0, rel=0.02)


def test_header_units_are_read_and_a_clash_is_named(tmp_path):
    path = tmp_path / "sweep.txt"
    path.write_text("f (Hz)\tE' [MPa]\tE'' [MPa]\tT (°C)\n" + _rows(25.0).replace(",", "\t"))
    table = read_dma(path)
    assert table.units == {"frequency": "Hz", "modulus": "MPa", "temperature": "C"} and not table.warnings
    np.testing.assert_allclose(table.temperatures, 298.15)
    np.testing.assert_allclose(table.storage, TRUE.complex_modulus(2 * np.pi * HZ).real, rtol=1e-14)
    with pytest.raises(InputError, match="modulus_unit = 'kPa' disagrees with the unit 'MPa'"):
        read_dma(path, modulus_unit="kPa")
    with pytest.raises(InputError, match="frequency_unit must be one of 'rad/s', 'Hz', got 'rpm'"):
        read_dma(path, frequency_unit="rpm")


def test_the_cli_reads_dma_through_the_api_and_reports_assumed_units(tmp_path):
    from viscobem_cli import scene as scenes

    (tmp_path / "d.csv").write_text(_rows())
    text = """
[material]
dma = "d.csv"
dma_modulus_unit = "MPa"
[surface]
kind = "sinusoid"
length = 1e-3
n = 16
amplitude = 1e-6
[loading]
load = 1.0
speeds = [0.001]
"""
    s = scenes.parse(text, base=tmp_path)
    api = read_dma(tmp_path / "d.csv", modulus_unit="MPa")
    np.testing.assert_array_equal(s.dma["e1"], api.storage)
    assert any("names no unit for frequency: read as frequency in rad/s" in w for w in s.warnings)
    with pytest.raises(InputError, match=r"^\[material\] .*looks like MPa.*dma_modulus_unit"):
        scenes.parse(text.replace('dma_modulus_unit = "MPa"\n', ""), base=tmp_path)
