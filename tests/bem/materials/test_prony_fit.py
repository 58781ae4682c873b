"""Prony fits in relative error: both moduli hold over 12 decades, including the glassy tail.

The synthetic truth (:func:`dma_truth`) is DMA-like: 11 terms, one per decade from 1e-7 s to
1e3 s, ``E_inf/E0 = 200``, sampled at 121 frequencies over 12 decades (1e-4 to 1e8 rad/s)
with 1 % Gaussian noise on each of ``E'`` and ``E''``. In the top decade ``tan delta`` is
0.01-0.05. Errors are against the noise-free truth.
"""

import numpy as np
import pytest

from bem import Material
from bem.errors import InputError
from bem.materials.prony_fit import FitReport, default_times, fit_prony_series

W = np.logspace(-4, 8, 121)


def dma_truth():
    return Material.from_prony(E0=2e6, moduli=np.full(11, 2e6 * 199 / 11), times=np.logspace(-7, 3, 11))


def noisy(m, seed, level=0.01):
    rng = np.random.default_rng(seed)
    e = m.complex_modulus(W)
    return e.real * (1 + level * rng.standard_normal(W.size)), e.imag * (1 + level * rng.standard_normal(W.size))


def errors(fit, m):
    f, e = fit.complex_modulus(W), m.complex_modulus(W)
    return np.max(np.abs(f.real / e.real - 1)), np.max(np.abs(f.imag / e.imag - 1))


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_both_moduli_hold_over_12_decades_with_1_percent_noise(seed):
    """Targets E' 3 %, E'' 5 %. Measured (seeds 1-3): E' 0.46-0.54 %, E'' 0.82-1.02 %."""
    m = dma_truth()
    e = m.complex_modulus(W)
    assert 0.005 < np.min(e.imag[-10:] / e.real[-10:]) < 0.06  # a glassy tail with a small tan delta
    fit = Material.fit_prony(W, *noisy(m, seed))
    d1, d2 = errors(fit, m)
    assert d1 < 0.03 and d2 < 0.05


def test_weighting_by_the_modulus_magnitude_misses_the_glassy_tail():
    """The same NNLS weighted by |E*| for both moduli (the weighting this fit replaces) leaves
    E'' 14 % off (seed 1): the test above can fail."""
    from scipy.optimize import nnls

    m = dma_truth()
    e1, e2 = noisy(m, 1)
    taus = np.logspace(-9, 5, 43)
    wt = W[:, None] * taus
    mag = np.hypot(e1, e2)[:, None]
    a = np.vstack(
        [
            np.hstack([np.ones((W.size, 1)), wt**2 / (1 + wt**2)]) / mag,
            np.hstack([np.zeros((W.size, 1)), wt / (1 + wt**2)]) / mag,
        ]
    )
    cn = np.linalg.norm(a, axis=0)
    x = nnls(a / cn, np.concatenate([e1, e2]) / np.concatenate([mag[:, 0], mag[:, 0]]), maxiter=5000)[0] / cn
    keep = x[1:] > 0
    d1, d2 = errors(Material.from_prony(E0=x[0], moduli=x[1:][keep], times=taus[keep]), m)
    assert d2 > 0.05


def test_fit_report_gives_the_residuals_against_the_data():
    m = dma_truth()
    e1, e2 = noisy(m, 1)
    fit = Material.fit_prony(W, e1, e2)
    r = fit.fit_report
    assert isinstance(r, FitReport) and r.terms == fit.moduli.size and r.smoothing == 0.0
    f = fit.complex_modulus(W)
    assert r.storage_max == pytest.approx(np.max(np.abs(f.real / e1 - 1)), rel=1e-9)
    assert r.loss_rms == pytest.approx(np.sqrt(np.mean((f.imag / e2 - 1) ** 2)), rel=1e-9)
    assert 0.005 < r.storage_rms < 0.02 and 0.005 < r.loss_rms < 0.02  # about the 1 % noise
    assert r.frequency_band == (W[0], W[-1])
    assert set(r.as_dict()) >= {"storage_max", "storage_rms", "loss_max", "loss_rms"}
    assert Material.from_prony(E0=1e6, moduli=[1e6], times=[1.0]).fit_report is None
    assert fit == Material.from_prony(E0=fit.E0, moduli=fit.moduli, times=fit.relaxation_times)


def _roughness(fit):
    """Sum of squared second differences of log10 E_k over log10 tau_k."""
    return float(np.sum(np.diff(fit.moduli / fit.moduli.max(), 2) ** 2))


def test_smoothing_trades_roughness_for_residual():
    """A larger penalty gives a smoother spectrum (on the common times) and a larger residual;
    0.01 keeps the targets (measured E'' 0.88 %, seed 1)."""
    m = dma_truth()
    e1, e2 = noisy(m, 1)
    taus = np.logspace(-9, 5, 43)
    fits = [Material.fit_prony(W, e1, e2, times=taus, smoothing=s) for s in (0.0, 0.3, 3.0)]
    rms = [f.fit_report.storage_rms + f.fit_report.loss_rms for f in fits]
    assert rms[0] < rms[1] < rms[2]
    full = []
    for f in fits:
        x = np.zeros(taus.size)
        x[np.searchsorted(taus, f.relaxation_times[::-1])] = f.moduli[::-1]
        full.append(np.sum(np.diff(x, 2) ** 2))
    assert full[2] < full[1] < full[0]
    d1, d2 = errors(Material.fit_prony(W, e1, e2, smoothing=0.01), m)
    assert d1 < 0.03 and d2 < 0.05
    with pytest.raises(InputError, match="smoothing"):
        Material.fit_prony(W, e1, e2, smoothing=-1.0)


def test_from_prony_stores_terms_longest_time_first_and_keeps_pairs():
    m = Material.from_prony(E0=1e6, moduli=[3.0e6, 1.0e6, 2.0e6], times=[1e-2, 1.0, 1e-4])
    np.testing.assert_array_equal(m.relaxation_times, [1.0, 1e-2, 1e-4])
    np.testing.assert_array_equal(m.moduli, [1.0e6, 3.0e6, 2.0e6])
    assert np.all(np.diff(m.creep_times) < 0)


def test_optimised_times_match_a_spectrum_between_the_grid_times():
    """Noise-free data from 11 terms placed between the default grid's times (3 per decade):
    NNLS on the grid alone leaves measured 3.8 % in E' and 4.1 % in E''; moving the times
    too recovers the series to round-off (measured 4e-15, bound 1e-9)."""
    m = Material.from_prony(E0=2e6, moduli=np.full(11, 2e6 * 199 / 11), times=np.logspace(-6.85, 3.15, 11))
    e = m.complex_modulus(W)
    taus = default_times(W, 3.0)
    grid = fit_prony_series(W, e.real, e.imag, taus, refine=False)
    moved = fit_prony_series(W, e.real, e.imag, taus)
    d_grid = errors(Material.from_prony(E0=grid[0], moduli=grid[1], times=grid[2]), m)
    d_moved = errors(Material.from_prony(E0=moved[0], moduli=moved[1], times=moved[2]), m)
    assert max(d_grid) > 1e-2 and max(d_moved) < 1e-9
    assert moved[1].size == 11
    np.testing.assert_allclose(np.sort(moved[2]), np.sort(m.relaxation_times), rtol=1e-9)


def test_fit_report_compares_the_loss_with_the_measured_value():
    """Noise-free data whose E'' falls to 3e-7 |E*| in the glassy tail (below the fit's weight floor
    1e-4 |E*|). The report used to compare the fit with the floored value there and said 99.7 % for
    an exact fit; against the measured E'' it says what is true: measured 1.3e-15 (bound 1e-9)."""
    m = Material.from_prony(E0=1e6, moduli=[1e7, 2e7, 1e7], times=[1e-1, 1e-2, 1e-3])
    w = np.logspace(-2, 9, 56)
    e = m.complex_modulus(w)
    assert np.min(e.imag / np.abs(e)) < 1e-6
    fit = Material.fit_prony(w, e.real, e.imag)
    r = fit.fit_report
    true = np.max(np.abs(fit.complex_modulus(w).imag / e.imag - 1))
    assert r.loss_max < 1e-9 and r.loss_max == pytest.approx(true, rel=1e-6, abs=1e-15)


def test_fit_report_gives_the_worst_points():
    """One loss point 20 % off: it heads the worst E'' points, with its frequency and values."""
    m = dma_truth()
    e1, e2 = noisy(m, 1)
    e2[60] *= 1.2
    r = Material.fit_prony(W, e1, e2).fit_report
    worst = r.worst_loss[0]
    assert worst["frequency"] == W[60] and worst["measured"] == e2[60] and worst["error"] == r.loss_max
    assert abs(worst["fitted"] / e2[60] - 1) == pytest.approx(worst["error"], rel=1e-12)
    assert len(r.worst_storage) == 3 and r.worst_storage[0]["error"] == r.storage_max
    assert "temperature" not in worst  # a single sweep
    d = r.as_dict()
    assert d["worst_loss"][0]["frequency"] == W[60] and d["glassy_reached"]
    assert not d["relaxed_reached"]  # 1e-4 rad/s is 1 decade below the slowest rate: E' still falls 17 %


def test_relaxed_modulus_that_the_data_cannot_give_is_named():
    """Data that end where the material still relaxes steeply give E0 <= 0: the error names the
    lowest frequency and E' there."""
    m = dma_truth()
    w = np.logspace(-2, 8, 101)
    e = m.complex_modulus(w)
    rng = np.random.default_rng(1)
    with pytest.raises(InputError, match=r"E0 <= 0: at their lowest frequency \(0.01 rad/s, E' = "):
        Material.fit_prony(w, e.real * (1 + 0.01 * rng.standard_normal(w.size)), e.imag)
