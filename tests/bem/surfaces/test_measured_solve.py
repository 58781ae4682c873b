"""A measured surface is solved as the user means it (issue: the measured patch): bem.solve takes
the load on the scanned patch, reports it, and warns above the patch's speed limit as the CLI does."""

import numpy as np
import pytest

import bem
from bem.accuracy.findings import Finding, gather
from bem.surfaces import measured

SLS = bem.Material.standard_linear_solid(E0=1e6, E_inf=1e7, creep_time=0.01)


@pytest.fixture(scope="module")
def scan():
    parent = bem.surfaces.self_affine(64, 1e-3, hurst=0.8, scales=8, rolloff=2, rms_slope=0.1, seed=2)
    h = np.array(parent.heights)[:40, :40]  # a non-periodic 0.625 mm square
    return bem.surfaces.from_scan(h, 16, physical_sizes=(0.625e-3, 0.625e-3))


def test_solve_takes_the_load_on_the_patch(scan):
    assert measured.load_factor(scan) == 4  # the mirrored cell holds the patch four times
    res = bem.solve(scan, SLS, speed=1e-3, load=0.02)
    cell = bem.surfaces.from_heights(scan.heights, scan.length)  # the same cell, not known as a patch
    ref = bem.solve(cell, SLS, speed=1e-3, load=0.08)
    assert res.friction == pytest.approx(ref.friction, rel=1e-12)
    assert res.load == pytest.approx(0.02, rel=1e-12)  # what was asked
    assert res.dissipated_power == pytest.approx(ref.dissipated_power / 4, rel=1e-12)
    # the same nominal pressure as the patch's: 0.02 N over the patch's area
    assert res.pressure.mean() == pytest.approx(0.02 / (0.625e-3) ** 2, rel=1e-9)


def test_solve_takes_a_nominal_pressure_instead_of_the_patch_load(scan):
    """20 kPa on the scanned patch is 20 kPa on its mirrored cell: the same solve as the patch load
    that pressure puts on the patch's area (0.625 mm square)."""
    by_pressure = bem.solve(scan, SLS, speed=1e-3, nominal_pressure=2e4)
    by_load = bem.solve(scan, SLS, speed=1e-3, load=2e4 * (0.625e-3) ** 2)
    assert by_pressure.friction == pytest.approx(by_load.friction, rel=1e-12)
    assert by_pressure.load == pytest.approx(by_load.load, rel=1e-12)
    assert by_pressure.pressure.mean() == pytest.approx(2e4, rel=1e-9)
    # the same keyword on any surface: the pressure times the cell's area (its length for a profile)
    profile = bem.surfaces.sinusoid(64, 1e-3, amplitude=1e-6)
    r = bem.solve(profile, SLS, speed=1e-3, nominal_pressure=1e5)
    assert r.load == pytest.approx(1e5 * 1e-3, rel=1e-12)
    for given in (dict(load=0.02, nominal_pressure=2e4), dict(nominal_pressure=2e4, approach=1e-7), {}):
        with pytest.raises(bem.InputError, match="give exactly one of load .*, nominal_pressure .* or approach"):
            bem.solve(scan, SLS, speed=1e-3, **given)
    with pytest.raises(bem.InputError, match="nominal_pressure"):
        bem.solve(scan, SLS, speed=1e-3, nominal_pressure=-1.0)


def test_solve_and_curve_warn_above_the_patch_speed_limit(scan):
    limit = measured.speed_limit(scan, SLS)
    slow = bem.solve(scan, SLS, speed=limit / 10, load=0.02)
    fast = bem.solve(scan, SLS, speed=limit * 10, load=0.02)
    assert not any("longer than the scanned patch" in w for w in slow.warnings)
    assert sum("longer than the scanned patch" in w for w in fast.warnings) == 1
    curve = bem.friction_curve(scan, SLS, speeds=[limit / 10, limit * 10], load=0.02)
    said = [w for w in curve.warnings if "longer than the scanned patch" in w]
    assert len(said) == 1 and said[0].startswith(f"at v = {limit * 10:.3g} m/s")


def test_curve_warnings_keep_each_distinct_finding_with_its_own_speeds():
    low = "the material is extrapolated: the sliding excites frequencies below 0.01 rad/s, 2 decades beyond"
    high = "the material is extrapolated: the sliding excites frequencies above 1e+05 rad/s, 1 decades beyond"
    points = [
        ("v = 0.001 m/s", [Finding(low, "material_data")]),
        ("v = 0.01 m/s", [Finding(low.replace("0.01 rad", "0.1 rad"), "material_data")]),
        ("v = 10 m/s", [Finding(high, "material_data")]),
    ]
    out = gather(points, noun="speeds")
    assert len(out) == 2
    assert out[0].startswith("at 2 of 3 speeds (v = 0.001 m/s, v = 0.01 m/s") and "below" in out[0]
    assert out[1].startswith("at v = 10 m/s:") and "above" in out[1]


def test_curve_takes_a_nominal_pressure_per_curve(scan):
    """friction_curve takes nominal_pressure (Pa) as solve does: each curve is the one of the patch
    load that pressure puts on the patch, and a list gives one curve per pressure."""
    patch_area = (0.625e-3) ** 2
    by_pressure = bem.friction_curve(scan, SLS, speeds=[1e-4, 1e-2], nominal_pressure=2e4)
    by_load = bem.friction_curve(scan, SLS, speeds=[1e-4, 1e-2], load=2e4 * patch_area)
    np.testing.assert_allclose(by_pressure.friction, by_load.friction, rtol=1e-12)
    assert by_pressure.load == pytest.approx(2e4 * patch_area, rel=1e-12)
    curves = bem.friction_curve(scan, SLS, speeds=[1e-4], nominal_pressure=[1e4, 2e4])
    assert [c.results[0].pressure.mean() for c in curves] == pytest.approx([1e4, 2e4], rel=1e-9)
    for given in ({}, dict(load=0.01, nominal_pressure=2e4)):
        with pytest.raises(bem.InputError, match="exactly one of load .* and nominal_pressure"):
            bem.friction_curve(scan, SLS, speeds=[1e-4], **given)
    with pytest.raises(bem.InputError, match="nominal_pressure must be"):
        bem.friction_curve(scan, SLS, speeds=[1e-4], nominal_pressure=[])
    with pytest.raises(bem.InputError, match="nominal_pressure"):
        bem.friction_curve(scan, SLS, speeds=[1e-4], nominal_pressure=[2e4, -1.0])
