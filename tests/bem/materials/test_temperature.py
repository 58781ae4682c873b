"""Shift laws and ``Material.at_temperature``: time-temperature superposition, exactly.

``E*(w)`` at ``T`` must equal ``E*(a_T w)`` at the reference, for both series: the times
scale by ``a_T`` with one rounding each, so the bound is a few ulps of the products
``w tau`` (measured worst 4e-16 relative; bound 1e-14).
"""

import numpy as np
import pytest
from conftest import make_prony30, make_seed
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from bem import Material
from bem.errors import InputError
from bem.materials import temperature
from bem.materials.temperature import GAS_CONSTANT, WLF, Arrhenius, fit_arrhenius, fit_wlf

W = np.logspace(-10, 10, 801)
LAWS = {"wlf": WLF(8.86, 101.6, 296.15), "arrhenius": Arrhenius(120e3, 296.15)}


def test_wlf_formula_values_and_sign():
    law = WLF(C1=17.44, C2=51.6, reference_temperature=250.0)
    assert law(250.0) == 0.0
    assert law(260.0) == pytest.approx(-17.44 * 10 / 61.6, rel=1e-15)
    assert law(240.0) == pytest.approx(17.44 * 10 / 41.6, rel=1e-15)
    T = np.array([230.0, 250.0, 300.0])
    np.testing.assert_allclose(law(T), -17.44 * (T - 250) / (51.6 + T - 250), rtol=1e-15)
    assert law.shift_factor(300.0) < 1 < law.shift_factor(240.0)  # faster when hotter


def test_arrhenius_formula_values_and_sign():
    law = Arrhenius(activation_energy=100e3, reference_temperature=300.0)
    assert law(300.0) == 0.0
    expected = 100e3 / (GAS_CONSTANT * np.log(10)) * (1 / 330 - 1 / 300)
    assert law(330.0) == pytest.approx(expected, rel=1e-15) and law(330.0) < 0
    assert np.log(law.shift_factor(280.0)) == pytest.approx(100e3 / GAS_CONSTANT * (1 / 280 - 1 / 300), rel=1e-13)


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("make", [make_seed, make_prony30])
@pytest.mark.parametrize("T", [250.0, 296.15, 340.0])
def test_at_temperature_is_exact_superposition(law, make, T):
    m, shift = make(), LAWS[law]
    hot = m.at_temperature(T, shift)
    a = 10.0 ** shift(T)
    np.testing.assert_allclose(hot.complex_modulus(W), m.complex_modulus(a * W), rtol=1e-14, atol=0)
    np.testing.assert_allclose(hot.complex_compliance(W), m.complex_compliance(a * W), rtol=1e-14, atol=0)
    np.testing.assert_allclose(hot.creep_times, a * m.creep_times, rtol=2e-16)
    np.testing.assert_allclose(hot.compliances, m.compliances, rtol=0)
    assert hot.E0 == m.E0 and hot.E_inf == m.E_inf and hot.nu == m.nu
    t = np.logspace(-8, 8, 50)
    np.testing.assert_allclose(hot.relaxation_modulus(a * t), m.relaxation_modulus(t), rtol=1e-14)


def test_at_temperature_detects_a_wrong_factor():
    """The check above fails for a law 0.1 % off in a_T (guards against a vacuous test)."""
    m, shift = make_prony30(), LAWS["wlf"]
    hot = m.at_temperature(320.0, shift)
    a = 10.0 ** shift(320.0) * 1.001
    with pytest.raises(AssertionError):
        np.testing.assert_allclose(hot.complex_modulus(W), m.complex_modulus(a * W), rtol=1e-6)


def test_hotter_is_softer_and_less_lossy_at_a_fixed_frequency():
    m = make_prony30(1e3)
    e_cold = m.at_temperature(280.0, LAWS["wlf"]).complex_modulus(1.0)
    e_hot = m.at_temperature(320.0, LAWS["wlf"]).complex_modulus(1.0)
    assert e_hot.real < m.complex_modulus(1.0).real < e_cold.real


@pytest.mark.parametrize(
    "args, name",
    [
        ((0.0, 50.0, 300.0), "C1"),
        ((8.0, -1.0, 300.0), "C2"),
        ((8.0, 50.0, 0.0), "reference_temperature"),
        ((8.0, 50.0, float("nan")), "reference_temperature"),
    ],
)
def test_wlf_rejects_bad_parameters(args, name):
    with pytest.raises(InputError, match=name):
        WLF(*args)


def test_bad_temperatures_and_laws_are_named():
    with pytest.raises(InputError, match="activation_energy"):
        Arrhenius(-1.0, 300.0)
    with pytest.raises(InputError, match=r"T must be > reference_temperature - C2 = 250 K"):
        WLF(8.0, 50.0, 300.0)(240.0)
    with pytest.raises(InputError, match="kelvin|K"):
        Arrhenius(1e5, 300.0)(-20.0)
    with pytest.raises(InputError, match="shift"):
        make_seed().at_temperature(300.0, 2.0)
    with pytest.raises(dataclass_error()):
        LAWS["wlf"].C1 = 3.0


def dataclass_error():
    import dataclasses

    return dataclasses.FrozenInstanceError


def test_laws_fitted_to_their_own_values_come_back():
    """Noise-free shift factors: WLF by nonlinear least squares, Arrhenius linear; measured
    relative errors below 1e-9, bound 1e-6."""
    T = np.linspace(250.0, 360.0, 12)
    law = LAWS["wlf"]
    back = fit_wlf(T, law(T), law.reference_temperature)
    assert back.C1 == pytest.approx(law.C1, rel=1e-6) and back.C2 == pytest.approx(law.C2, rel=1e-6)
    arr = LAWS["arrhenius"]
    back = fit_arrhenius(T, arr(T), arr.reference_temperature)
    assert back.activation_energy == pytest.approx(arr.activation_energy, rel=1e-12)


def test_module_is_reachable_from_the_package():
    import bem

    assert bem.materials.temperature is temperature and isinstance(LAWS["wlf"], bem.materials.temperature.WLF)


@settings(derandomize=True, max_examples=40, deadline=None)
@given(
    c1=st.floats(1.0, 30.0),
    c2=st.floats(20.0, 300.0),
    dt=st.floats(-0.9, 3.0),
    log_times=st.lists(st.floats(-6, 6), min_size=1, max_size=8, unique=True),
)
def test_any_law_and_series_superpose_exactly(c1, c2, dt, log_times):
    """Random WLF laws, temperatures from T_ref - 0.9 C2 to T_ref + 3 C2, random series: the
    shifted material is the reference at a_T w to round-off (bound 1e-13)."""
    times = np.sort(10.0 ** np.array(log_times))
    assume(times.size == 1 or np.min(np.diff(np.log10(times))) >= 1e-3)
    m = Material.from_prony(E0=1e6, moduli=np.geomspace(1e6, 1e8, times.size), times=times)
    law = WLF(c1, c2, 300.0)
    T = 300.0 + dt * c2
    a = 10.0 ** law(T)
    hot = m.at_temperature(T, law)
    w = np.logspace(-8, 8, 65)
    np.testing.assert_allclose(hot.complex_modulus(w), m.complex_modulus(a * w), rtol=1e-13, atol=0)
    np.testing.assert_allclose(hot.complex_compliance(w), m.complex_compliance(a * w), rtol=1e-13, atol=0)


# ---------------------------------------------------------------- temperatures that make sense


@pytest.mark.parametrize(
    "make",
    [
        lambda: WLF(8.86, 101.6, 23.0),
        lambda: Arrhenius(1e5, 23.0),
        lambda: LAWS["wlf"](23.0),
        lambda: make_seed().at_temperature(60.0, LAWS["wlf"]),
    ],
)
def test_a_temperature_in_celsius_is_rejected(make):
    """``WLF(..., 23)`` (degrees Celsius typed as kelvin) used to be accepted silently."""
    with pytest.raises(InputError, match=r"looks like degrees Celsius \(use \d+(\.\d+)? K\)"):
        make()


def test_the_rejection_names_the_parameter():
    with pytest.raises(InputError, match="reference_temperature"):
        WLF(8.86, 101.6, 23.0)
    with pytest.raises(InputError, match="^T "):
        make_seed().at_temperature(50.0, LAWS["wlf"])
    assert temperature.check_kelvin("T", 100.0) == 100.0


def test_wlf_below_its_range_is_warned_about():
    """WLF(8.86, 101.6 K, 296.15 K) at -60 C: 8.9 K above its pole, log a_T = 39.5 (a_T = 3e39),
    used to pass silently."""
    law = LAWS["wlf"]
    assert law.lowest_believed == pytest.approx(296.15 - 101.6 + 10.0)
    texts = law.range_warnings(213.15)
    assert len(texts) == 1 and "log10 a_T = 39.5 at 213.15 K" in texts[0] and "15 decades" in texts[0]
    below = law.range_warnings(200.0)
    assert len(below) == 2 and "below the WLF law's range" in below[0] and "204.55 K" in below[0]
    assert law.range_warnings(250.0) == () and law.range_warnings(400.0) == ()
    assert law.range_warnings(250.0, max_log_shift=3.0) != ()  # log a_T = 6.4 at 250 K
    hot = LAWS["arrhenius"].range_warnings(200.0)  # 120 kJ/mol: 10.3 decades
    assert hot == () and Arrhenius(300e3, 296.15).range_warnings(200.0) != ()
    m = make_seed().at_temperature(213.15, law)
    assert m.warnings == texts and m.extrapolation_warnings(1.0, 2.0) == texts


@pytest.mark.parametrize("log_a", [306.0, 309.0, -330.0])
def test_shifts_beyond_floating_point_are_input_errors(log_a):
    """log a_T above 308 used to raise a raw OverflowError, and between 305 and 308 the material got
    infinite creep times (the seed's creep time is 0.01 s x 3: 1e306 of it overflows)."""
    with pytest.raises(
        InputError, match=f"T = 300 K is outside the shift law's range: it gives log10 a_T = {log_a:.4g}"
    ):
        make_seed().at_temperature(300.0, lambda T: log_a)


def test_wlf_close_to_its_pole_is_an_input_error_not_an_overflow():
    law = LAWS["wlf"]
    with pytest.raises(InputError, match="outside the shift law's range"):
        make_seed().at_temperature(law.reference_temperature - law.C2 + 0.5, law)


def test_a_law_referred_to_another_temperature_gives_the_same_shifts():
    law = LAWS["wlf"]
    moved = law.referenced_to(273.15)
    T = np.linspace(250.0, 360.0, 12)
    np.testing.assert_allclose(moved(T), law(T) - law(273.15), rtol=1e-13, atol=1e-13)
    arr = LAWS["arrhenius"].referenced_to(273.15)
    np.testing.assert_allclose(arr(T), LAWS["arrhenius"](T) - LAWS["arrhenius"](273.15), rtol=1e-13, atol=1e-13)
    with pytest.raises(InputError, match="WLF pole"):
        law.referenced_to(190.0)


@pytest.mark.parametrize("kind", ["wlf", "arrhenius"])
def test_a_law_through_shifts_known_up_to_a_constant(kind):
    """Shifts of two chains, each relative to its own first sweep (unknown offsets 3.1 and -7.4
    decades), the reference temperature between sweeps: the law with a free constant per chain
    comes back to 1e-9, zero at the reference by its form."""
    from bem.materials.temperature import fit_law

    law = LAWS[kind]
    T = np.linspace(255.0, 355.0, 11)
    groups = np.array([0] * 5 + [1] * 6)
    y = law(T) + np.where(groups == 0, 3.1, -7.4)
    back, offsets = fit_law(kind, T, y, law.reference_temperature, groups=groups)
    np.testing.assert_allclose(back.parameters, law.parameters, rtol=1e-9)
    np.testing.assert_allclose(offsets, [3.1, -7.4], rtol=1e-9)
    with pytest.raises(InputError, match="more temperature"):
        fit_law(kind, T[:2], y[:2], law.reference_temperature, groups=[0, 1])
