"""Friction over speed and temperature by time-temperature superposition: one curve on the
reference material stands for every temperature of a thermorheologically simple rubber."""

import dataclasses

import numpy as np
import pytest

import bem
from bem import superposition as fm
from bem.errors import InputError

LAW = bem.temperature.WLF(8.86, 101.6, 296.15)
SPEEDS = np.logspace(-5, 0, 11)
TEMPERATURES = np.array([273.15, 283.15, 296.15, 313.15, 333.15])  # log10 a_T from 2.6 to -2.4
LOAD = 1e4


@pytest.fixture(scope="module")
def rubber():
    material = bem.Material.from_prony(E0=1e6, moduli=np.full(8, 2.5e7), times=np.logspace(-7, 0, 8))
    heights = bem.surfaces.self_affine(256, 0.01, hurst=0.8, scales=16, rms_height=2e-5, seed=1).heights
    return material, bem.surfaces.from_heights(heights[:, 0], 0.01)


@pytest.fixture(scope="module")
def mapped(rubber):
    material, profile = rubber
    return bem.friction_map(profile, material, speeds=SPEEDS, temperatures=TEMPERATURES, shift=LAW, load=LOAD)


def test_sliding_at_v_and_T_is_sliding_at_v_aT_on_the_reference(rubber):
    material, profile = rubber
    T, v = 273.15, 1e-3
    warm = bem.solve(profile, material.at_temperature(T, LAW), speed=v, load=LOAD, rtol=1e-10)
    reduced = bem.solve(profile, material, speed=v * LAW.shift_factor(T), load=LOAD, rtol=1e-10)
    assert warm.friction == pytest.approx(reduced.friction, rel=1e-7)
    np.testing.assert_allclose(warm.pressure, reduced.pressure, rtol=0, atol=1e-7 * warm.pressure.max())


def test_the_map_matches_direct_solves_at_several_temperatures(rubber, mapped):
    material, profile = rubber
    assert mapped.method == "superposition" and mapped.friction.shape == (TEMPERATURES.size, SPEEDS.size)
    assert mapped.contact_fraction.shape == mapped.friction.shape and np.all(np.isfinite(mapped.friction))
    for i in (0, 2, 4):
        direct = bem.friction_curve(profile, material.at_temperature(TEMPERATURES[i], LAW), speeds=SPEEDS, load=LOAD)
        np.testing.assert_allclose(mapped.friction[i], direct.friction, rtol=0.01)
        # the contact fraction moves in steps of one point (1/n): interpolated, it is within a few
        np.testing.assert_allclose(mapped.contact_fraction[i], direct.contact_fraction, rtol=0, atol=3 / profile.n)
    # every interpolated point carries its estimate, within the target; nodes are exact
    est = mapped.interpolation_error
    assert np.all(est[mapped.interpolated] <= fm.RTOL_MAP) and np.all(est[~mapped.interpolated] == 0)
    np.testing.assert_allclose(mapped.reduced_speeds, SPEEDS[None, :] * 10.0 ** LAW(TEMPERATURES)[:, None])
    assert all(r is not None for r in mapped.results) and set(mapped.error_estimate) >= {"friction"}


def test_one_curve_costs_less_than_a_curve_per_temperature(rubber, mapped):
    """The map over five temperatures whose shifts span as many decades as the speeds costs at most
    2.5 curves, not five: its cost grows with the span of the reduced speeds, not with the number
    of temperatures (the benchmark, viscobem bench friction_map, measures 13 x 25)."""
    material, profile = rubber
    one = bem.friction_curve(profile, material, speeds=SPEEDS, load=LOAD)
    products = sum(r.matvecs for r in one.results)
    assert mapped.matvecs < 2.5 * products < TEMPERATURES.size * products


def test_a_coarse_curve_says_so(rubber, monkeypatch):
    """Too few nodes and no refinement: the map is off by more than 1 % and its warnings say the
    estimate is above the target (or missing). (Below two nodes a period of the material's ripple
    the estimate aliases it too, which is why the start is three nodes a decade: NODES_PER_DECADE.)"""
    material, profile = rubber
    direct = bem.friction_curve(profile, material.at_temperature(TEMPERATURES[0], LAW), speeds=SPEEDS, load=LOAD)
    monkeypatch.setattr(fm, "NODES_PER_DECADE", 0.8)
    monkeypatch.setattr(fm, "MAX_REFINEMENTS", 0)
    args = dict(speeds=SPEEDS, temperatures=TEMPERATURES[:2], shift=LAW, load=LOAD)
    coarse = bem.friction_map(profile, material, **args)
    assert np.max(np.abs(coarse.friction[0] / direct.friction - 1)) > 0.01  # too coarse to be right...
    assert any("worse than rtol_map" in w for w in coarse.warnings)  # ...and it says so


def test_not_thermorheologically_simple_falls_back_to_direct_solves(rubber):
    """A material whose modulus moves with temperature (a vertical shift) is not simple: the map is
    then made of direct solves, and says so."""
    material, profile = rubber

    def stiffening(T):
        shifted = material.at_temperature(T, LAW)
        return bem.Material.from_prony(
            E0=shifted.E0 * (1 + 0.002 * (T - 296.15)), moduli=shifted.moduli, times=shifted.relaxation_times
        )

    speeds, temps = SPEEDS[::5], TEMPERATURES[:2]
    direct = bem.friction_map(profile, stiffening, speeds=speeds, temperatures=temps, shift=LAW, load=LOAD)
    assert direct.method == "direct" and direct.curve is None and len(direct.curves) == 2
    assert "not thermorheologically simple" in direct.warnings[0]
    check = bem.friction_curve(profile, stiffening(temps[0]), speeds=speeds, load=LOAD)
    np.testing.assert_array_equal(direct.friction[0], check.friction)
    simple = bem.friction_map(
        profile, lambda T: material.at_temperature(T, LAW), speeds=speeds, temperatures=temps, shift=LAW, load=LOAD
    )
    assert simple.method == "superposition"


def test_bad_input_names_the_argument(rubber):
    material, profile = rubber
    args = dict(speeds=SPEEDS, temperatures=TEMPERATURES, shift=LAW, load=LOAD)
    for key, value, match in (
        ("speeds", [0.0, 1.0], "speeds"),
        ("temperatures", [20.0], "temperatures"),
        ("shift", 3.0, "shift"),
        ("rtol_map", 2.0, "rtol_map"),
    ):
        with pytest.raises(InputError, match=match):
            bem.friction_map(profile, material, **dict(args, **{key: value}))
    assert dataclasses.is_dataclass(bem.FrictionMap)
