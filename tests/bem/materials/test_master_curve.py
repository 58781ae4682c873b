"""Master curves: synthetic multi-temperature sweeps from a known series and shift law.

Two truths, both under WLF ``C1 = 8.86, C2 = 101.6 K`` at ``T_ref = 296.15 K`` (23 C),
"measured" from 0.1 to 100 Hz (13 points per sweep):

- :func:`truth`: the 11-term series of ``test_prony_fit`` (``E_inf/E0 = 200``, times 1e-7 to
  1e3 s), every 5 K from ``T_ref - 45`` to ``T_ref + 60`` K (22 sweeps, 13.3 decades), with 1 %
  Gaussian noise on each of ``E'`` and ``E''``;
- :func:`truth12`: the issue's 12-term series (``E_inf/E0 = 200``, times 10^-9.2 to 10^1.8 s,
  off the fit's grid of times), noise-free, on the temperature sets a DMA user measures.

Noise-free data have an exact answer, so the bounds there are round-off-sized: the joint fit of
law and series recovers the truth to 1e-11 or better wherever the data are.
"""

import numpy as np
import pytest

from bem import Material
from bem.errors import InputError
from bem.materials.master_curve import MasterCurveReport, segments
from bem.materials.temperature import WLF, Arrhenius

TREF = 296.15
LAW = WLF(8.86, 101.6, TREF)
TEMPS = TREF + np.arange(-45.0, 61.0, 5.0)
HZ = np.logspace(-1, 2, 13)
C = 273.15  # K at 0 C


def truth():
    return Material.from_prony(E0=2e6, moduli=np.full(11, 2e6 * 199 / 11), times=np.logspace(-7, 3, 11))


def truth12():
    return Material.from_prony(E0=2e6, moduli=np.full(12, 2e6 * 199 / 12), times=np.logspace(-9.2, 1.8, 12))


def sweeps(material, law, seed, noise=0.01, temps=TEMPS):
    """Stacked columns (Hz, K, E' Pa, E'' Pa) of isothermal sweeps with multiplicative noise."""
    rng = np.random.default_rng(seed)
    cols = [[], [], [], []]
    for t in temps:
        e = material.at_temperature(t, law).complex_modulus(2 * np.pi * HZ)
        for c, v in zip(
            cols,
            (
                HZ,
                np.full(HZ.size, t),
                e.real * (1 + noise * rng.standard_normal(HZ.size)),
                e.imag * (1 + noise * rng.standard_normal(HZ.size)),
            ),
        ):
            c.append(v)
    return [np.concatenate(c) for c in cols]


def data_errors(fit, law, m, true_law, temps=TEMPS):
    """Max relative errors of E', E'' of ``fit`` under ``law`` at every measured (T, f),
    against the noise-free truth."""
    w = 2 * np.pi * HZ
    d1 = d2 = 0.0
    for t in temps:
        e = m.at_temperature(t, true_law).complex_modulus(w)
        f = fit.at_temperature(t, law).complex_modulus(w)
        d1, d2 = (max(d1, np.max(np.abs(f.real / e.real - 1))), max(d2, np.max(np.abs(f.imag / e.imag - 1))))
    return d1, d2


def reference_errors(fit, m, temps):
    """Max relative errors of E', E'' of the reference curve over the reduced band the sweeps cover."""
    lo, hi = 2 * np.pi * HZ[0] * 10.0 ** LAW(temps.max()), 2 * np.pi * HZ[-1] * 10.0 ** LAW(temps.min())
    w = np.logspace(np.log10(lo), np.log10(hi), 300)
    f, e = fit.complex_modulus(w), m.complex_modulus(w)
    return np.max(np.abs(f.real / e.real - 1)), np.max(np.abs(f.imag / e.imag - 1))


# ---------------------------------------------------------------- the reproducers (noise-free)


def test_reference_temperature_not_measured():
    """Sweeps every 10 K from -20 to 60 C, so 23 C is not one of them. Linear interpolation of the
    shifts to the reference (the old anchoring) gave C1 = 9.20, E' 7.7 % and E'' 14 % off over the
    band. Anchored through the law's free constant and fitted jointly: measured C1, C2 within 1e-12,
    E', E'' within 3e-12 (bound 1e-9)."""
    temps = C + np.arange(-20.0, 61.0, 10.0)
    m = truth12()
    fit, law = Material.fit_master_curve(*sweeps(m, LAW, 0, 0.0, temps), reference_temperature=TREF, hz=True)
    assert law.reference_temperature == TREF and TREF not in temps
    assert law.C1 == pytest.approx(LAW.C1, rel=1e-9) and law.C2 == pytest.approx(LAW.C2, rel=1e-9)
    assert max(reference_errors(fit, m, temps)) < 1e-9 and max(data_errors(fit, law, m, LAW, temps)) < 1e-9
    # the overlap shifts, anchored by the law's constant, are the true shifts to the overlay's accuracy
    # (measured 0.0057 decades: cubic splines through points 0.25 decades apart)
    assert np.max(np.abs(np.array(fit.fit_report.log_shift) - LAW(temps))) < 0.02


def test_sweeps_every_5_kelvin_overlap_by_a_third_of_a_decade():
    """-40 to 60 C every 5 K, the usual DMA practice: near -40 C neighbouring sweeps shift by 2.7
    decades and share 0.3 decade of their 3. The old search (0.9 decade of overlap required) refused
    ("do not overlay, rms 0.406"); measured now C1 within 4e-16, moduli within 7e-15 (bound 1e-9)."""
    temps = C + np.arange(-40.0, 61.0, 5.0)
    assert LAW(temps[0]) - LAW(temps[1]) == pytest.approx(2.674, abs=1e-3)  # 0.33 decade in common
    m = truth12()
    fit, law = Material.fit_master_curve(*sweeps(m, LAW, 0, 0.0, temps), reference_temperature=TREF, hz=True)
    assert law.C1 == pytest.approx(LAW.C1, rel=1e-9) and law.C2 == pytest.approx(LAW.C2, rel=1e-9)
    assert max(reference_errors(fit, m, temps)) < 1e-9
    assert fit.fit_report.gaps == ()  # every neighbour overlapped


def test_three_sweeps_at_0_23_and_50_celsius():
    """The old fit put the 0 C sweep 2.10 decades from 23 C against the true 2.59. Measured now: the
    law's shift within 1e-6 decades, the overlay's anchored shift within 0.0043 (bound 0.02), moduli
    at the measured points within 7e-6 (bound 1e-4: three sweeps leave the series less determined)."""
    temps = C + np.array([0.0, 23.0, 50.0])
    m = truth12()
    fit, law = Material.fit_master_curve(*sweeps(m, LAW, 0, 0.0, temps), reference_temperature=TREF, hz=True)
    assert law(C) == pytest.approx(LAW(C), abs=1e-4)
    assert fit.fit_report.log_shift[0] == pytest.approx(LAW(C), abs=0.02)
    assert max(data_errors(fit, law, m, LAW, temps)) < 1e-4


NO_OVERLAP = C + np.array([-35.0, -15.0, 15.0, 60.0])  # shifts 6.5, 4.5, 3.1 decades apart: 3 gaps


def test_sweeps_with_no_overlap_under_an_imposed_law():
    """Sweeps at -35, -15, 15 and 60 C: 0.1-3.5 decades of reduced frequency between neighbouring
    sweeps, nothing to overlay. With the law imposed the master curve still comes: noise-free,
    measured data errors 1.1e-9 (bound 1e-7). The gaps are reported: there the curve is
    interpolated, not measured."""
    m = truth12()
    f, T, e1, e2 = sweeps(m, LAW, 0, 0.0, NO_OVERLAP)
    fit, law = Material.fit_master_curve(f, T, e1, e2, shift=LAW, hz=True)
    assert law == LAW and fit.fit_report.law_imposed and fit.fit_report.law_sigma == ()
    assert max(data_errors(fit, law, m, LAW, NO_OVERLAP)) < 1e-7
    r = fit.fit_report
    assert len(r.gaps) == 3 and len(r.band_gaps) == 3
    assert max(b / a for a, b, _, _ in r.band_gaps) > 1e3  # 3.5 decades
    assert all(t1 > t2 for _, _, t1, t2 in r.band_gaps)  # the hotter sweep ends where a gap starts
    with pytest.raises(InputError, match="need.* every sweep to overlap"):
        Material.fit_master_curve(f, T, e1, e2, reference_temperature=TREF, hz=True, joint=False)


def test_sweeps_with_no_overlap_under_a_jointly_fitted_law():
    """Every 20 K from -30 to 50 C: two of the four gaps between neighbours leave no overlap.
    Fitted jointly with the series (the law's form and the series' E'-E'' consistency place the
    sweeps), noise-free: measured C1, C2 within 1e-10, sigma of log a_T 0.010 decades (bound
    1e-6 and no warning). Where the gaps are wide (the four sweeps above: 3.5 decades) the data
    do not pin the law down: every sweep is still reproduced (measured 0.43 %), but log a_T is
    12.6 decades off at -35 C, and the material's warnings say the law is weakly determined
    (linearised sigma 43 decades there)."""
    m = truth12()
    temps = C + np.arange(-30.0, 51.0, 20.0)
    fit, law = Material.fit_master_curve(*sweeps(m, LAW, 0, 0.0, temps), reference_temperature=TREF, hz=True)
    assert len(fit.fit_report.gaps) == 2 and fit.warnings == ()
    assert law.C1 == pytest.approx(LAW.C1, rel=1e-6) and law.C2 == pytest.approx(LAW.C2, rel=1e-6)
    assert max(fit.fit_report.law_sigma) < 0.05
    fit, law = Material.fit_master_curve(*sweeps(m, LAW, 0, 0.0, NO_OVERLAP), reference_temperature=TREF, hz=True)
    assert max(data_errors(fit, law, m, LAW, NO_OVERLAP)) < 0.01
    assert max(fit.fit_report.law_sigma) > 1.0
    assert any("weakly determined" in w for w in fit.warnings)


def test_an_imposed_law_at_another_reference_temperature_is_referred_to_it():
    """WLF referred to T' gives the same shifts relative to T'; the fit is the same material moved."""
    m = truth12()
    f, T, e1, e2 = sweeps(m, LAW, 0, 0.0, NO_OVERLAP)
    fit, law = Material.fit_master_curve(f, T, e1, e2, shift=LAW, reference_temperature=C, hz=True)
    assert law.reference_temperature == C
    np.testing.assert_allclose(law(T), LAW(T) - LAW(C), rtol=1e-12, atol=1e-12)
    w = 2 * np.pi * HZ * 10.0 ** law(NO_OVERLAP[1])  # the -15 C sweep's band at 0 C (measured 1e-11)
    np.testing.assert_allclose(fit.complex_modulus(w), m.at_temperature(C, LAW).complex_modulus(w), rtol=1e-9)


def test_imposed_law_needs_no_more_than_one_sweep():
    """One sweep of a material that reaches its relaxed plateau in it; one still relaxing steeply
    at its low end gives no relaxed modulus at all (E0 <= 0), and says so."""
    m = Material.from_prony(E0=5e6, moduli=[2e7, 6e7, 3e7], times=[1e-5, 1e-4, 1e-3])
    f, T, e1, e2 = sweeps(m, LAW, 0, 0.0, [TREF])
    fit, law = Material.fit_master_curve(f, T, e1, e2, shift=LAW, hz=True)
    assert fit.fit_report.frequency_band == pytest.approx((2 * np.pi * HZ[0], 2 * np.pi * HZ[-1]))
    assert fit.fit_report.relaxed_reached and fit.E0 == pytest.approx(5e6, rel=1e-3)  # measured 8e-5
    with pytest.raises(InputError, match="relaxed modulus E0 <= 0"):
        Material.fit_master_curve(*sweeps(truth12(), LAW, 0, 0.0, [TREF]), shift=LAW, hz=True)


# ---------------------------------------------------------------- noisy data


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_recovery_from_noisy_sweeps(seed):
    """1 % noise. Measured over seeds 1-10: C1 within 0.45 %, C2 within 0.21 %; log a_T within 0.019
    decades at every measured temperature; each sweep reproduced by the material at its temperature
    with E' within 1.9 % and E'' within 1.1 % of the noise-free truth; law_rms <= 0.020 decades, fit
    residuals rms <= 1.01 % (the noise), the law's sigma <= 0.0072 decades, no warnings. Bounds: 2 %,
    0.1 decade, 3 % and 5 % (the targets)."""
    m = truth()
    f, T, e1, e2 = sweeps(m, LAW, seed)
    fit, law = Material.fit_master_curve(f, T, e1, e2, reference_temperature=TREF, hz=True)
    assert law.C1 == pytest.approx(LAW.C1, rel=0.02) and law.C2 == pytest.approx(LAW.C2, rel=0.02)
    assert np.max(np.abs(law(TEMPS) - LAW(TEMPS))) < 0.1
    d1, d2 = data_errors(fit, law, m, LAW)
    assert d1 < 0.03 and d2 < 0.05
    r = fit.fit_report
    assert isinstance(r, MasterCurveReport) and r.temperatures == pytest.approx(tuple(TEMPS))
    assert r.law_rms < 0.03 and r.loss_rms < 0.015 and r.storage_rms < 0.015
    assert fit.warnings == () and max(r.law_sigma) < 0.05


def test_arrhenius_law_and_a_reference_between_sweeps():
    """Arrhenius truth (300 kJ/mol: 11 decades of shift), reference 2.5 K off any sweep."""
    m, true = truth(), Arrhenius(300e3, 300.0)
    temps = 300.0 + np.arange(-27.5, 40.0, 5.0)
    f, T, e1, e2 = sweeps(m, true, 4, temps=temps)
    fit, law = Material.fit_master_curve(f, T, e1, e2, reference_temperature=300.0, shift="arrhenius", hz=True)
    assert isinstance(law, Arrhenius)
    assert law.activation_energy == pytest.approx(300e3, rel=0.02)
    d1, d2 = data_errors(fit, law, m, true, temps)
    assert d1 < 0.03 and d2 < 0.05


def test_worst_points_name_the_sweep_and_frequency():
    m = truth()
    f, T, e1, e2 = sweeps(m, LAW, 1)
    e2[40] *= 1.3  # one bad loss point: sweep 3 (TREF - 30 K), 2nd frequency
    fit, law = Material.fit_master_curve(f, T, e1, e2, reference_temperature=TREF, hz=True)
    worst = fit.fit_report.worst_loss[0]
    assert worst["temperature"] == pytest.approx(T[40]) and worst["frequency"] == pytest.approx(2 * np.pi * f[40])
    assert worst["error"] == pytest.approx(fit.fit_report.loss_max) and worst["measured"] == e2[40]
    assert worst["reduced_frequency"] == pytest.approx(2 * np.pi * f[40] * 10.0 ** law(T[40]))


def test_a_mislabelled_sweep_is_named():
    """One sweep labelled 7.5 K colder than measured: no law puts it on the master curve (measured
    rms misfit 0.048 decades against 0.004-0.007 for the others), so the material's warnings name
    it; its overlap shifts leave the law by far more than with correct labels (law_rms 0.094
    against 0.011 decades)."""
    m = truth()
    f, T, e1, e2 = sweeps(m, LAW, 1)
    good, _ = Material.fit_master_curve(f, T, e1, e2, reference_temperature=TREF, hz=True)
    assert good.warnings == () and good.fit_report.notes == ()
    bad_T = T.copy()
    bad_T[T == TEMPS[14]] = TEMPS[14] - 7.5  # between the sweeps at TEMPS[12] and TEMPS[13]
    bad, law = Material.fit_master_curve(f, bad_T, e1, e2, reference_temperature=TREF, hz=True)
    assert len(bad.warnings) == 1 and f"sweep at {TEMPS[14] - 7.5:g} K is off the master curve" in bad.warnings[0]
    assert bad.fit_report.law_rms > 3 * good.fit_report.law_rms
    assert bad.at_temperature(300.0, law).warnings == bad.warnings  # it stays with the material


def test_sweeps_of_two_materials_do_not_superpose():
    """Every other sweep 1.5 times stiffer (a vertical shift no time-temperature law gives)."""
    m = truth()
    f, T, e1, e2 = sweeps(m, LAW, 1, noise=0.0)
    stiff = np.isin(T, TEMPS[1::2])
    e1, e2 = np.where(stiff, 1.5 * e1, e1), np.where(stiff, 1.5 * e2, e2)
    with pytest.raises(InputError, match="do not superpose"):
        Material.fit_master_curve(f, T, e1, e2, reference_temperature=TREF, hz=True)


def test_the_vectorised_overlap_search_is_the_scalar_mismatch():
    from bem.materials import master_curve as mc

    m = truth()
    f, T, e1, e2 = sweeps(m, LAW, 1)
    lw, l1, l2 = np.log10(2 * np.pi * f), np.log10(e1), np.log10(e2)
    a, b = (mc._Segment(lw[T == t], l1[T == t], l2[T == t]) for t in TEMPS[3:5])
    grid = np.linspace(-4.0, 4.0, 161)
    np.testing.assert_allclose(
        mc._mismatch_grid(a, b, grid, 0.25), [mc._mismatch(a, b, d, 0.25) for d in grid], rtol=1e-12
    )


def test_segments_group_by_temperature_within_tolerance():
    label, temps = segments([300.1, 280.0, 299.9, 280.2, 320.0], tolerance=0.5)
    np.testing.assert_array_equal(label, [1, 0, 1, 0, 2])
    np.testing.assert_allclose(temps, [280.1, 300.0, 320.0])


def test_bad_master_curve_input_is_named():
    m = truth()
    f, T, e1, e2 = sweeps(m, LAW, 1)
    kw = dict(reference_temperature=TREF, hz=True)
    with pytest.raises(InputError, match="shift"):
        Material.fit_master_curve(f, T, e1, e2, shift="vft", **kw)
    with pytest.raises(InputError, match="reference_temperature"):
        Material.fit_master_curve(f, T, e1, e2, hz=True)  # a fitted law needs it
    with pytest.raises(InputError, match="reference_temperature.*looks like degrees Celsius"):
        Material.fit_master_curve(f, T, e1, e2, reference_temperature=23.0, hz=True)
    with pytest.raises(InputError, match="temperatures.*looks like degrees Celsius"):
        Material.fit_master_curve(f, T - C, e1, e2, **kw)
    with pytest.raises(InputError, match=">= 3 temperatures"):
        keep = T < TEMPS[2]
        Material.fit_master_curve(f[keep], T[keep], e1[keep], e2[keep], reference_temperature=TEMPS[0], hz=True)
    with pytest.raises(InputError, match="temperatures"):
        Material.fit_master_curve(f, T[:-1], e1, e2, **kw)
    with pytest.raises(InputError, match="min_overlap"):
        Material.fit_master_curve(f, T, e1, e2, min_overlap=-1.0, **kw)
