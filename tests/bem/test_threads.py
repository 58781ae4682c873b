"""One thread setting (bem.set_threads / bem.use_threads) that every FFT and pool honours:
bem.fft, the isolated operator, the contact-map periodogram of bem.analysis.anisotropy, the line
preconditioner's thread pool (tests/bem/contact/test_line_preconditioner.py) and the sweep's process pool."""

import multiprocessing as mp
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest
import scipy.fft

import bem
from bem import fft, parallel
from bem.analysis import anisotropy
from bem.errors import InputError
from bem.halfspace.isolated import IsolatedHalfSpace
from bem.halfspace.periodic import PeriodicHalfSpace
from bem.materials.prony_fit import fit_prony_series

ELASTIC = bem.Material.elastic(1e7)


@pytest.fixture
def fft_workers(monkeypatch):
    """The ``workers`` argument of every scipy.fft call made through bem."""
    seen = []
    for name in ("rfftn", "irfftn", "ifft", "irfft", "fftn"):
        original = getattr(scipy.fft, name)

        def spy(*args, _original=original, **kwargs):
            seen.append(kwargs.get("workers"))
            return _original(*args, **kwargs)

        monkeypatch.setattr(scipy.fft, name, spy)
    return seen


def test_default_is_every_available_core():
    assert parallel.get_threads() == parallel.available_cores() >= 1


@pytest.mark.parametrize("n", [1, 2, 3])
def test_fft_periodic_and_isolated_operators_use_the_setting(fft_workers, n):
    x = np.random.default_rng(0).standard_normal((16, 16))
    with bem.use_threads(n):
        fft.inverse(fft.forward(x), x.shape)
        PeriodicHalfSpace((16, 16), 1e-3, ELASTIC, 0.0).displacement(x)
        IsolatedHalfSpace((16, 16), 1e-3, ELASTIC, 0.0).displacement(x)
        anisotropy.periodogram_full(x > 0, 1e-3)
    assert len(fft_workers) >= 7 and set(fft_workers) == {n}


def test_use_threads_restores_the_previous_setting_also_on_error():
    before = bem.get_threads()
    bem.set_threads(2)
    try:
        with pytest.raises(RuntimeError), bem.use_threads(1):
            assert bem.get_threads() == 1
            raise RuntimeError("inside")
        assert bem.get_threads() == 2
    finally:
        bem.set_threads(None)
    assert bem.get_threads() == before


@pytest.mark.parametrize("bad", [0, -1, 1.5, "2", True])
def test_bad_thread_counts_are_refused(bad):
    with pytest.raises(InputError, match="threads must be an integer >= 1"):
        bem.set_threads(bad)
    assert bem.get_threads() == parallel.available_cores()


def test_the_sweeps_process_pool_runs_bem_on_one_thread_per_worker():
    """The sweep's worker processes share the cores: each uses 1 thread for FFTs and pools."""
    from viscobem_cli.run import points

    with ProcessPoolExecutor(1, mp_context=mp.get_context("spawn"), initializer=points._pool_init) as pool:
        assert pool.submit(bem.get_threads).result(timeout=120) == 1


@pytest.fixture
def blas_limits(monkeypatch):
    """The ``limits`` of every threadpoolctl BLAS limit that bem sets."""
    import threadpoolctl

    seen = []
    original = threadpoolctl.threadpool_limits

    def spy(*args, **kwargs):
        seen.append(kwargs.get("limits", args[0] if args else None))
        return original(*args, **kwargs)

    monkeypatch.setattr(threadpoolctl, "threadpool_limits", spy)
    return seen


def _solve_and_fit():
    """A contact solve and a Prony fit: the two parts of bem that hold BLAS to the setting."""
    s = bem.surfaces.self_affine(16, 1e-3, hurst=0.8, scales=4, rms_slope=0.1, seed=0)
    bem.solve(s, bem.Material.standard_linear_solid(E0=1e6, E_inf=3e6, creep_time=0.01), speed=0.01, load=1e-3)
    m = bem.Material.standard_linear_solid(E0=1e6, E_inf=3e6, creep_time=0.01)
    w = np.logspace(0, 4, 20)
    e = m.complex_modulus(w)
    fit_prony_series(w, e.real, e.imag, np.logspace(-4, 0, 5))


def test_blas_threads_are_one_setting_the_user_can_change(blas_limits):
    """BLAS inside bem runs on get_blas_threads() threads (1 by default), set like the FFT
    threads: set_blas_threads, or use_threads(n, blas=...), restored afterwards; None leaves BLAS
    to its own setting (no limit is set)."""
    assert bem.get_blas_threads() == 1
    _solve_and_fit()
    assert blas_limits and set(blas_limits) == {1}
    blas_limits.clear()
    with bem.use_threads(1, blas=2):
        _solve_and_fit()
    assert blas_limits and set(blas_limits) == {2}
    assert bem.get_blas_threads() == 1
    blas_limits.clear()
    previous = bem.set_blas_threads(None)
    try:
        _solve_and_fit()
        assert blas_limits == []
    finally:
        bem.set_blas_threads(previous)
    with pytest.raises(InputError, match="blas threads must be an integer >= 1"):
        bem.set_blas_threads(0)
