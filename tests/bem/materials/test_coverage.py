"""What DMA data cover: the band a fitted material is measured over, whether the data reach the
plateaus, and the warnings when a computation uses the material outside them.

The truth is the 11-term series of ``test_prony_fit`` (``E0 = 2 MPa``, ``E_inf/E0 = 200``, times
1e-7 to 1e3 s), sampled 10 points per decade from ``w_lo`` to 1e8 rad/s. With ``w_lo = 10``
rad/s (1 % noise) the data end on a steep ``E'``: the fit's relaxed modulus comes out 106 MPa
against the true 2 MPa (the issue's "51.7 MPa against 2 MPa", silently, before). With
``w_lo = 1e-5`` rad/s (two decades below the slowest term) the data reach the plateau.
"""

import numpy as np
import pytest

from bem import Material
from bem.errors import InputError
from bem.materials.coverage import PLATEAU_SLOPE
from bem.materials.temperature import WLF


def truth():
    return Material.from_prony(E0=2e6, moduli=np.full(11, 2e6 * 199 / 11), times=np.logspace(-7, 3, 11))


def fitted(w_lo, w_hi=1e8, seed=1, noise=0.01):
    w = np.logspace(np.log10(w_lo), np.log10(w_hi), int(10 * np.log10(w_hi / w_lo)) + 1)
    e = truth().complex_modulus(w)
    rng = np.random.default_rng(seed)
    return Material.fit_prony(
        w, e.real * (1 + noise * rng.standard_normal(w.size)), e.imag * (1 + noise * rng.standard_normal(w.size))
    )


def test_data_that_stop_short_of_the_rubbery_plateau_are_flagged():
    """Measured: E0 = 106 MPa (true 2 MPa), low-end log-slope 0.114 > 0.05; the warning for speeds
    below the band names the band, E0 and the slope."""
    fit = fitted(10.0)
    r = fit.fit_report
    assert fit.E0 > 20 * truth().E0  # the extrapolation is far off ...
    assert not r.relaxed_reached and r.end_slopes[0] > PLATEAU_SLOPE and r.glassy_reached  # ... and now known
    assert fit.extrapolation_warnings(10.0, 1e8) == ()  # inside the band: measured
    (text,) = fit.extrapolation_warnings(1e-3, 1e6)
    assert "down to 0.001 rad/s, 4 decades beyond" in text and "do not reach the relaxed (rubbery) plateau" in text
    assert f"E0 = {fit.E0:.4g} Pa is not measured" in text and "higher temperatures or lower frequencies" in text


def test_data_that_reach_both_plateaus():
    """Measured log-slopes 0.004 (low end) and 0.0018 (high end)."""
    fit = fitted(1e-5)
    r = fit.fit_report
    assert r.relaxed_reached and r.glassy_reached and fit.E0 == pytest.approx(2e6, rel=0.01)
    low, high = fit.extrapolation_warnings(1e-8, 1e10)
    assert "reach the relaxed (rubbery) plateau there" in low and "E0 = " in low
    assert "up to 1e+10 rad/s" in high and "reach the glassy plateau there" in high and "E_inf = " in high


def test_the_plateau_test_can_fail_on_the_glassy_side():
    """Data that stop 3 decades below the fastest term's rate: E' still rising at the top
    (measured log-slope 0.083)."""
    r = fitted(1e-5, 1e4).fit_report
    assert r.relaxed_reached and not r.glassy_reached and r.end_slopes[1] > PLATEAU_SLOPE


def test_the_band_moves_with_the_temperature():
    """At T the data's band is the reference band divided by a_T; so are the warnings' numbers."""
    law = WLF(8.86, 101.6, 296.15)
    fit = fitted(1e-5)
    hot = fit.at_temperature(330.0, law)
    a = 10.0 ** law(330.0)
    assert hot.data_band == pytest.approx((fit.data_band[0] / a, fit.data_band[1] / a), rel=1e-12)
    assert hot.extrapolation_warnings(fit.data_band[0] / a, fit.data_band[1] / a) == ()
    assert len(hot.extrapolation_warnings(fit.data_band[0], fit.data_band[1])) == 1  # beyond the top at 330 K


def test_a_material_as_given_has_nothing_to_say():
    m = truth()
    assert m.fit_report is None and m.data_band is None and m.extrapolation_warnings(1e-12, 1e12) == ()
    assert m.folded(1e-3, 1e3).extrapolation_warnings(1e-12, 1e12) == ()


def test_folding_keeps_the_fit_report():
    fit = fitted(10.0)
    folded = fit.folded(1e3, 1e5)
    assert folded.fit_report is fit.fit_report and len(folded.extrapolation_warnings(1e-3, 1e6)) == 1


def test_a_shift_law_used_outside_its_range_is_in_the_warnings():
    """WLF's pole is at T_ref - C2 = 194.55 K: 200 K is within 10 K of it (and 65 decades of shift)."""
    law = WLF(8.86, 101.6, 296.15)
    cold = truth().at_temperature(200.0, law)
    texts = cold.extrapolation_warnings(1.0, 10.0)
    assert any("below the WLF law's range" in t and "204.55 K" in t for t in texts)
    assert any("more than 15 decades" in t for t in texts)
    assert truth().at_temperature(296.15, law).warnings == ()


def test_bad_bands_are_named():
    fit = fitted(10.0)
    with pytest.raises(InputError, match="w_high"):
        fit.extrapolation_warnings(1.0, -1.0)
    with pytest.raises(InputError, match="w_low must be <= w_high"):
        fit.extrapolation_warnings(10.0, 1.0)
