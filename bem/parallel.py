"""One thread setting for the whole of :mod:`bem`.

Every FFT (scipy's ``workers``) and every thread pool of :mod:`bem` (the line
preconditioner's batched dense products) uses :func:`get_threads` threads, at the moment it
runs. By default that is every core this process may run on; :func:`set_threads` changes it
for the process and :func:`use_threads` for a ``with`` block. A pool of worker processes
sharing the cores (a sweep over speeds) sets 1 in each worker, so that ``workers x threads``
does not exceed the cores.

BLAS thread pools are not touched here: numpy's dense products in :mod:`bem` are small, and
:mod:`threadpoolctl` limits them where it matters.

Examples
--------
>>> import bem
>>> with bem.use_threads(1):
...     bem.get_threads()
1
"""

import os
from contextlib import contextmanager

from .errors import InputError

__all__ = ["get_threads", "set_threads", "use_threads", "available_cores"]

_threads = None  # None: every available core


def available_cores():
    """Cores this process may run on (its CPU affinity where the platform tells it)."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def get_threads():
    """Threads every FFT and pool of :mod:`bem` uses now (an int >= 1)."""
    return available_cores() if _threads is None else _threads


def _checked(n):
    if n is None:
        return None
    if isinstance(n, bool) or not isinstance(n, int) and not hasattr(n, "__index__"):
        raise InputError(f"threads must be an integer >= 1 or None (every core), got {n!r}")
    if int(n) < 1:
        raise InputError(f"threads must be an integer >= 1 or None (every core), got {int(n)}")
    return int(n)


def set_threads(n):
    """Use ``n`` threads (an integer >= 1; ``None``: every available core) in every FFT and
    pool of :mod:`bem` from now on; returns the previous setting (``None`` or an int)."""
    global _threads
    previous, _threads = _threads, _checked(n)
    return previous


@contextmanager
def use_threads(n):
    """``with use_threads(n):`` runs its block with :func:`set_threads` ``(n)`` and restores
    the previous setting afterwards, also when the block raises."""
    previous = set_threads(n)
    try:
        yield get_threads()
    finally:
        set_threads(previous)
