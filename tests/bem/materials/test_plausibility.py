"""Numbers no solid or temperature has (issue: units pass silently) are refused or warned about,
naming the likely unit: MPa typed as Pa, a ratio no material has, a temperature far from the data."""

import numpy as np
import pytest

import bem
from bem.errors import InputError
from bem.materials import WLF

TIMES = np.logspace(-6, 0, 4)


def test_moduli_in_mpa_are_refused_naming_the_unit():
    with pytest.raises(InputError, match=r"E0 must be in \[1000, 1e\+12\] Pa .* got 2.4 Pa \(looks like MPa: multiply"):
        bem.Material.from_prony(E0=2.4, moduli=[10.0, 100.0, 500.0, 1000.0], times=TIMES)
    with pytest.raises(InputError, match="got 3.9 Pa .looks like MPa"):
        bem.Material.elastic(3.9)
    with pytest.raises(InputError, match=r"E_inf must be in .* got 2e\+13 Pa"):
        bem.Material.standard_linear_solid(E0=2e9, E_inf=2e13, relaxation_time=1.0)
    # the same numbers in Pa are a rubber
    m = bem.Material.from_prony(E0=2.4e6, moduli=np.array([10.0, 100.0, 500.0, 1000.0]) * 1e6, times=TIMES)
    assert m.E_inf == pytest.approx(1612.4e6)


def test_a_ratio_no_material_has_is_refused():
    with pytest.raises(InputError, match=r"E_inf / E0 must be at most 1e\+06 .* got 2e\+06"):
        bem.Material.standard_linear_solid(E0=1e3, E_inf=2e9, relaxation_time=1.0)


def test_a_fit_to_a_table_in_mpa_read_as_pa_is_refused():
    w = np.logspace(-2, 4, 25)
    true = bem.Material.from_prony(E0=3.9e6, moduli=[2e7, 8e7, 3e8], times=[1.0, 1e-2, 1e-4])
    e = true.complex_modulus(w)
    with pytest.raises(InputError, match="looks like MPa"):
        bem.Material.fit_prony(w, e.real / 1e6, e.imag / 1e6)


def test_temperatures_far_from_the_law_warn_and_impossible_ones_are_refused():
    m = bem.Material.standard_linear_solid(E0=1e6, E_inf=1e9, relaxation_time=1e-3)
    wlf = WLF(17.4, 51.6, 300.0)
    with pytest.raises(InputError, match=r"T .* must be an absolute temperature <= 1000 K .* got 1e\+06 K"):
        m.at_temperature(1e6, wlf)
    assert not m.at_temperature(330.0, wlf).warnings
    far = m.at_temperature(450.0, wlf).warnings
    assert any("150 K from the shift law's reference temperature 300 K" in w for w in far)


def test_a_fitted_material_warns_outside_its_data_temperatures():
    wlf = WLF(10.0, 80.0, 300.0)
    taus = np.logspace(-8, 2, 11)
    true = bem.Material.from_prony(E0=2e6, moduli=2e6 * 99 / 11 * np.ones(11), times=taus)
    w = np.logspace(-1, 2, 10)
    temps = np.repeat([280.0, 300.0, 320.0], w.size)
    ww = np.tile(w, 3)
    e = true.complex_modulus(ww * 10.0 ** wlf(temps))
    mat, law = bem.Material.fit_master_curve(ww, temps, e.real, e.imag, reference_temperature=300.0)
    assert not [x for x in mat.at_temperature(330.0, law).warnings if "fitted to" in x]
    warned = mat.at_temperature(370.0, law).warnings
    assert any("outside the temperatures the material was fitted to (280 to 320 K)" in x for x in warned)


def test_data_temperatures_no_polymer_has_are_refused():
    # moduli passed where the temperatures go (the argument order is frequencies, temperatures,
    # storage, loss): before this check the fit ran and blamed superposition
    w = np.tile(np.logspace(-1, 2, 8), 3)
    temps = np.repeat([263.15, 293.15, 323.15], 8)
    e = bem.Material.from_prony(E0=3e6, moduli=[3e7, 2e8], times=[1e-3, 1e-5]).complex_modulus(w)
    with pytest.raises(InputError, match=r"temperatures must be an absolute temperature <= 1000 K .* moduli"):
        bem.Material.fit_master_curve(w, e.real, temps, e.imag, reference_temperature=293.15)
