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
