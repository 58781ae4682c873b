"""What ``rtol`` guarantees (bem.contact): the pressure's relative L2 error against a tight
solve is at most 10 x rtol, across 1-D and 2-D, periodic and isolated, smooth and rough, load
and displacement control, symmetric and strongly non-symmetric operators. The tight solve
stops at rtol 1e-11 (1e-12 reaches the round-off floor of some non-symmetric cases), so its
own error, below 1e-9, is far under the 1e-5 tested.

Measured ratios ``error / rtol`` at rtol = 1e-6 (and 1e-8) with the default options, the
largest 0.29 (isolated rolling cylinder 16 half-widths wide, at 1e-8), so the bound 10 has a
margin of 30; against them, the gap scaled by the peak-to-valley height instead:

========================  =========  ==========  ==================================
case                      1e-6       1e-8        gap scaled by peak-to-valley
========================  =========  ==========  ==================================
1-D rough elastic         0.00       0.00        34
1-D rough SLS             0.00       0.00        98
1-D rough SLS, approach   0.00       0.00
2-D rough elastic         0.00       0.00        4.6
2-D rough SLS             0.00       0.00        21
2-D rough elastic, appr.  0.00       0.00
2-D rough rubber          0.00       0.00        11
1-D sinusoid elastic      0.00       0.00        14
2-D sinusoid SLS          0.04       0.05        5.0
isolated cylinder 4096    0.00       0.02        13
 ... rolling              0.01       0.00        103
 ... 16 half-widths wide  0.09       0.02        281
 ... rolling              0.04       0.29        352
isolated sphere 64²       0.00       0.02        3.4
 ... rolling              0.01       0.01        22
========================  =========  ==========  ==================================

The gap scale is ``GAP_SCALE`` = 0.3 cells for every operator (held at 1e-4 of the height range:
``GAP_FLOOR_SHARE``; constants of :mod:`bem.contact.newton`), set by strongly non-symmetric
operators, which can have the larger pressure error per gap error. On the isolated rolling
cylinder with ``E_inf/E0 = 100`` (4096 cells), whose inner solves are preconditioned, 10 cells
would meet the bound too.
"""

import numpy as np
import pytest

import bem
from bem.contact import newton
from validation.references.hertz import line_contact, point_contact

SLS = bem.Material.standard_linear_solid(E0=1e7 / 3, E_inf=1e7, creep_time=0.01)
SLS100 = bem.Material.standard_linear_solid(E0=1e5, E_inf=1e7, creep_time=0.01)
ELASTIC = bem.Material.elastic(1e7)
RUBBER = bem.Material.from_prony(E0=1e6, moduli=np.full(20, (1e9 - 1e6) / 20), times=np.logspace(-10, 2, 20))
R = 0.01


def _cylinder(material, load, n, width):
    a = line_contact(material.E0, material.nu, R, load).a
    x = (np.arange(n) + 0.5) * width * a / n - width * a / 2
    return bem.surfaces.from_heights(-(x**2) / (2 * R), width * a, centered=True), a


def _sphere(material, load, n, width):
    a = point_contact(material.E0, material.nu, R, load).a
    x = (np.arange(n) + 0.5) * width * a / n - width * a / 2
    X, Y = np.meshgrid(x, x, indexing="ij")
    return bem.surfaces.from_heights(-(X**2 + Y**2) / (2 * R), width * a, centered=True), a


def _case(name):
    profile = bem.surfaces.profile(4096, 0.01, hurst=0.8, scales=512, rms_slope=0.1, seed=2)
    rough = bem.surfaces.self_affine(128, 0.01, hurst=0.8, scales=32, rms_slope=0.1, seed=1)
    isolated = {"load": 1000.0, "periodic": False, "method": "uniform"}
    if name == "1d-rough-elastic":
        return profile, ELASTIC, {"speed": 0.0, "load": 300.0}
    if name == "1d-rough-sls":
        return profile, SLS, {"speed": 0.01, "load": 300.0}
    if name == "1d-rough-sls-approach":
        return profile, SLS, {"speed": 0.01, "approach": bem.solve(profile, SLS, speed=0.01, load=300.0).approach}
    if name == "2d-rough-elastic":
        return rough, ELASTIC, {"speed": 0.0, "load": 3.0}
    if name == "2d-rough-sls":
        return rough, SLS, {"speed": 0.01, "load": 1.5}
    if name == "2d-rough-elastic-approach":
        return rough, ELASTIC, {"speed": 0.0, "approach": bem.solve(rough, ELASTIC, speed=0.0, load=3.0).approach}
    if name == "2d-rough-rubber":
        return rough, RUBBER, {"speed": 1e-6, "load": 0.9, "maxiter": 1000}
    if name == "1d-sinusoid-elastic":
        return bem.surfaces.sinusoid(1024, 0.01, amplitude=1e-5), ELASTIC, {"speed": 0.0, "load": 200.0}
    if name == "2d-sinusoid-sls":
        return bem.surfaces.sinusoid(64, 0.01, amplitude=1e-5, dim=2), SLS, {"speed": 0.01, "load": 0.5}
    if name.startswith("isolated-cylinder"):
        width = 16.0 if "wide" in name else 4.0
        s, a = _cylinder(SLS, 1000.0, 4096, width)
        return s, SLS, dict(speed=0.3 * a / 0.01 if "rolling" in name else 0.0, **isolated)
    s, a = _sphere(SLS, 1.0, 64, 3.0)
    return s, SLS, dict(speed=0.3 * a / 0.01 if "rolling" in name else 0.0, **dict(isolated, load=1.0))


CASES = [
    "1d-rough-elastic",
    "1d-rough-sls",
    "1d-rough-sls-approach",
    "2d-rough-elastic",
    "2d-rough-sls",
    "2d-rough-elastic-approach",
    "2d-rough-rubber",
    "1d-sinusoid-elastic",
    "2d-sinusoid-sls",
    "isolated-cylinder",
    "isolated-cylinder-rolling",
    "isolated-cylinder-wide",
    "isolated-cylinder-wide-rolling",
    "isolated-sphere",
    "isolated-sphere-rolling",
]


def _ratio(surface, material, kw, rtol, monkeypatch=None, **constants):
    """Relative L2 pressure error of a solve at ``rtol`` over ``rtol``, against a tight solve;
    ``constants`` replace those of :mod:`bem.contact.newton` for the loose solve."""
    tight = bem.solve(surface, material, rtol=1e-11, **kw)
    for name, value in constants.items():
        monkeypatch.setattr(newton, name, value)
    loose = bem.solve(surface, material, rtol=rtol, **kw)
    return np.linalg.norm(loose.pressure - tight.pressure) / np.linalg.norm(tight.pressure) / rtol


@pytest.mark.parametrize("name", CASES)
def test_rtol_bounds_the_relative_pressure_error(name):
    surface, material, kw = _case(name)
    assert _ratio(surface, material, kw, 1e-6) <= 10.0


def test_gap_scale_is_what_bounds_it(monkeypatch):
    """The guarantee comes from the gap scale: measured against the peak-to-valley height
    (about 3000 cells' displacements under the mean pressure here), the rolling cylinder's
    error is above the guarantee: with ``GAP_SCALE`` = 3000 it measures 19.6 x rtol, against 10
    guaranteed and at most 0.29 measured with the default."""
    surface, material, kw = _case("isolated-cylinder-rolling")
    assert _ratio(surface, material, kw, 1e-6, monkeypatch, GAP_SCALE=3000.0) > 10.0


def test_strongly_nonsymmetric_isolated_meets_the_bound(monkeypatch):
    """The strongly non-symmetric rolling cylinder meets the bound with ``GAP_SCALE``, and, its
    inner solves preconditioned by the padded cell's inverse, with a gap scale of 10 cells too
    (measured 1.4 x rtol); the periodic strongly non-symmetric cases of ``viscobem bench contact``
    do not (ablation row "gap scale 0.3 vs 10")."""
    s, a = _cylinder(SLS100, 1000.0, 4096, 4.0)
    kw = {"speed": 0.3 * a / 0.01, "load": 1000.0, "periodic": False, "method": "uniform"}
    assert _ratio(s, SLS100, kw, 1e-6) <= 10.0
    assert _ratio(s, SLS100, kw, 1e-6, monkeypatch, GAP_SCALE=10.0) <= 10.0
