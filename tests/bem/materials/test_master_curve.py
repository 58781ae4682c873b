"""Master curves: synthetic multi-temperature sweeps from a known series and shift law.

The truth is the 11-term series of ``test_prony_fit`` (``E_inf/E0 = 200``, times 1e-7 to
1e3 s at 296.15 K) under WLF ``C1 = 8.86, C2 = 101.6 K``. It is "measured" from 0.1 to
100 Hz (13 points) every 5 K from ``T_ref - 45`` to ``T_ref + 60`` K (22 sweeps, a master
curve of 13.3 decades), with 1 % Gaussian noise on each of ``E'`` and ``E''``.
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


def truth():
    return Material.from_prony(E0=2e6, moduli=np.full(11, 2e6 * 199 / 11), times=np.logspace(-7, 3, 11))


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


def test_noise_free_sweeps_give_the_law_and_the_series():
    """Measured: C1, C2 within 2.2e-4; every sweep reproduced within 4e-4 (bounds 2e-3 and 1e-2:
    the overlap shifts interpolate linearly between points 0.25 decades apart)."""
    m = truth()
    fit, law = Material.fit_master_curve(*sweeps(m, LAW, 0, noise=0.0), reference_temperature=TREF, hz=True)
    assert isinstance(law, WLF) and law.reference_temperature == TREF
    assert law.C1 == pytest.approx(LAW.C1, rel=2e-3) and law.C2 == pytest.approx(LAW.C2, rel=2e-3)
    assert max(data_errors(fit, law, m, LAW)) < 1e-2


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_recovery_from_noisy_sweeps(seed):
    """1 % noise. Measured over seeds 1-10: C1 within 0.94 %, C2 within 0.99 %; log a_T within
    0.062 decades at every measured temperature; each sweep reproduced by the material at its
    temperature with E' within 1.6 % and E'' within 3.6 % of the noise-free truth; law_rms
    <= 0.015 decades, fit residuals rms <= 1.05 % (the noise)."""
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


def test_a_mislabelled_sweep_shows_in_the_law_residual():
    """One sweep labelled 7.5 K colder than measured: the shifts leave the law by far more
    than with correct labels (measured law_rms 0.093 vs 0.012 decades)."""
    m = truth()
    f, T, e1, e2 = sweeps(m, LAW, 1)
    good = Material.fit_master_curve(f, T, e1, e2, reference_temperature=TREF, hz=True)[0].fit_report
    bad_T = T.copy()
    bad_T[T == TEMPS[14]] = TEMPS[14] - 7.5  # between the sweeps at TEMPS[12] and TEMPS[13]
    bad = Material.fit_master_curve(f, bad_T, e1, e2, reference_temperature=TREF, hz=True)[0].fit_report
    assert bad.law_rms > 3 * good.law_rms


def test_segments_group_by_temperature_within_tolerance():
    label, temps = segments([300.1, 280.0, 299.9, 280.2, 320.0], tolerance=0.5)
    np.testing.assert_array_equal(label, [1, 0, 1, 0, 2])
    np.testing.assert_allclose(temps, [280.1, 300.0, 320.0])


def test_bad_master_curve_input_is_named():
    m = truth()
    f, T, e1, e2 = sweeps(m, LAW, 1)
    kw = dict(reference_temperature=TREF, hz=True)
    with pytest.raises(InputError, match="reference_temperature"):
        Material.fit_master_curve(f, T, e1, e2, reference_temperature=400.0, hz=True)
    with pytest.raises(InputError, match="shift"):
        Material.fit_master_curve(f, T, e1, e2, shift="vft", **kw)
    with pytest.raises(InputError, match=">= 3 temperatures"):
        keep = T < TEMPS[2]
        Material.fit_master_curve(f[keep], T[keep], e1[keep], e2[keep], reference_temperature=TEMPS[0], hz=True)
    with pytest.raises(InputError, match="temperatures"):
        Material.fit_master_curve(f, T[:-1], e1, e2, **kw)
    sparse = np.isin(T, TEMPS[::4])
    with pytest.raises(InputError, match=r"do not overlay \(rms log10 mismatch 0.2"):  # 4 decades apart
        Material.fit_master_curve(f[sparse], T[sparse], e1[sparse], e2[sparse], **kw)
