"""The thread settings of :mod:`bem`: FFT and pool threads, and BLAS threads.

Every FFT (scipy's ``workers``) and every thread pool of :mod:`bem` (the line
preconditioner's batched dense products) uses :func:`get_threads` threads, at the moment it
runs. By default that is every core this process may run on; :func:`set_threads` changes it
for the process and :func:`use_threads` for a ``with`` block. A pool of worker processes
sharing the cores (a sweep over speeds) sets 1 in each worker, so that ``workers x threads``
does not exceed the cores.

BLAS (numpy's dense products and solves) runs on :func:`get_blas_threads` threads inside the
parts of :mod:`bem` that call it in loops (:func:`blas_limit`: the contact solver, the Prony
fit). The default is 1: those calls are small (GMRES's Hessenberg systems, the line
preconditioner's batches, which already run on the FFT's threads, a Prony fit's SVDs), and a
BLAS thread pool spinning beside the FFT threads is slower on every measured size, up to
1000x when the other core is busy (SPEC §7). :func:`set_blas_threads` (or ``use_threads(...,
blas=)``) changes it; ``None`` leaves BLAS to its own setting (``OPENBLAS_NUM_THREADS`` & co.).

Examples
--------
>>> import bem
>>> with bem.use_threads(1, blas=2):
...     bem.get_threads(), bem.get_blas_threads()
(1, 2)
"""

import os
from contextlib import contextmanager, nullcontext

from .errors import InputError

__all__ = [
    "available_cores",
    "blas_limit",
    "get_blas_threads",
    "get_threads",
    "set_blas_threads",
    "set_threads",
    "use_threads",
]

_threads = None  # None: every available core
_blas = 1  # None: BLAS's own setting
_UNSET = object()


def available_cores():
    """Cores this process may run on (its CPU affinity where the platform tells it)."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def get_threads():
    """Threads every FFT and pool of :mod:`bem` uses now (an int >= 1)."""
    return available_cores() if _threads is None else _threads


def get_blas_threads():
    """BLAS threads inside :mod:`bem`'s dense loops (an int >= 1, or ``None``: BLAS's own)."""
    return _blas


def _checked(n, name):
    if n is None:
        return None
    if isinstance(n, bool) or not isinstance(n, int) and not hasattr(n, "__index__"):
        raise InputError(f"{name} must be an integer >= 1 or None, got {n!r}")
    if int(n) < 1:
        raise InputError(f"{name} must be an integer >= 1 or None, got {int(n)}")
    return int(n)


def set_threads(n):
    """Use ``n`` threads (an integer >= 1; ``None``: every available core) in every FFT and
    pool of :mod:`bem` from now on; returns the previous setting (``None`` or an int)."""
    global _threads
    previous, _threads = _threads, _checked(n, "threads")
    return previous


def set_blas_threads(n):
    """Use ``n`` BLAS threads (an integer >= 1; ``None``: leave BLAS's own setting) in
    :mod:`bem`'s dense loops from now on; returns the previous setting."""
    global _blas
    previous, _blas = _blas, _checked(n, "blas threads")
    return previous


@contextmanager
def use_threads(n, *, blas=_UNSET):
    """``with use_threads(n):`` runs its block with :func:`set_threads` ``(n)`` (and, given
    ``blas``, :func:`set_blas_threads` ``(blas)``) and restores the previous settings
    afterwards, also when the block raises."""
    previous = set_threads(n)
    previous_blas = _blas if blas is _UNSET else set_blas_threads(blas)
    try:
        yield get_threads()
    finally:
        set_threads(previous)
        set_blas_threads(previous_blas)


def blas_limit():
    """A context that holds BLAS to :func:`get_blas_threads` threads (nothing if ``None``)."""
    if _blas is None:
        return nullcontext()
    from threadpoolctl import threadpool_limits

    return threadpool_limits(limits=_blas, user_api="blas")
