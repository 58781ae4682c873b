"""Line preconditioner for strongly non-symmetric 2-D steady-sliding operators.

The periodic symbol factors as ``a_q = green(|q|) J(-q_x v)``: a symmetric elastic operator
``G`` times the creep operator ``C``, a convolution along x alone (the memory of the
material, causal in the sliding direction). With ``R`` the restriction to the contact set,
the preconditioner is

    M = (R C R^T)^-1 R G^-1 R^T,

``G`` inverted in full space (one FFT pair) and ``C`` inverted *exactly on the contact set*,
one x-line at a time (each x-line of the set is a small dense system with the line kernel
``c[i - j]``). The restricted creep inverse is what removes the non-normality: ``R A^-1 R^T``
does not, since the memory of a contact spot reaches the gaps behind it.

Cost: ``sum m^3`` flops per Newton point to invert (``m`` contact points on a line; lines
whose contact has not changed keep their inverse through ``cache``), ``sum m^2`` per
application. The inverses are stored in ``dtype`` (float32 by default): the line systems are
well conditioned, so the preconditioner changes by ~1e-7 relative, far below the inner
solves' tolerance, while its memory traffic halves. Lines are formed in batches of ``chunk``
(sorted by length, padded with the identity), inverted and applied on the FFT's cores.
"""

import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from ..parallel import get_threads

__all__ = ["CHUNK", "line_preconditioner"]

CHUNK = 32
"""x-lines per batched dense inverse: large enough for BLAS to pay, small enough to pad little
(lines are sorted by length). Ablation row "line batches" (one line per call instead): the same
products, 1.19x the wall time over the case set, 1.7x to 2.4x on the cases that use the line
preconditioner (the 128² rubber curve 0.87 s against 0.36 s); the value itself is not tuned."""
_POOL = None  # ((pid, workers), executor): see _run


def _run(func, items):
    """``func(item)`` for every item, on :func:`bem.parallel.get_threads` threads (1 runs them
    here): numpy releases the GIL in the batched inverses and products, and BLAS itself stays
    single-threaded."""
    global _POOL
    workers = get_threads()
    if workers == 1 or len(items) < 2:
        for item in items:
            func(item)
        return
    key = (os.getpid(), workers)  # a forked child does not inherit the threads
    if _POOL is None or _POOL[0] != key:
        _POOL = (key, ThreadPoolExecutor(max_workers=workers))
    for _ in _POOL[1].map(func, items):
        pass


def _chunks(order, chunk):
    """``order`` (line numbers sorted by size) cut into batches of ``chunk``."""
    order = list(order)
    return [np.array(order[i : i + chunk]) for i in range(0, len(order), chunk)]


def _line_matrices(kernel, x, valid):
    """Dense creep matrices ``c[x_i - x_j]`` of a batch of lines (``x``: positions along x,
    padded; ``valid``: the real entries), with the identity on the padding."""
    n0 = (kernel.size + 1) // 2
    x = x.astype(np.int32)
    mats = kernel[(x + (n0 - 1))[:, :, None] - x[:, None, :]]
    weight = valid.astype(kernel.dtype)
    mats *= weight[:, :, None]
    mats *= weight[:, None, :]
    rows, cols = np.nonzero(~valid)
    mats[rows, cols, cols] = 1.0
    return mats


def _batches(idx, n1, cache, chunk, dtype):
    """The contact set's lines in batches: ``blocks`` (gather positions, valid mask,
    destinations, inverse matrices) and the ``jobs`` of lines whose inverse is not cached."""
    xs, ys = np.divmod(idx, n1)
    order = np.lexsort((xs, ys))  # by line (y), then along it (x)
    lines, starts, counts = np.unique(ys[order], return_index=True, return_counts=True)
    positions = [order[a : a + c] for a, c in zip(starts, counts)]  # in idx, along x
    keys = [xs[pos].tobytes() for pos in positions]
    xs_padded = np.append(xs, 0)  # read through ``pos``, whose padding is idx.size
    kept, blocks, jobs = {}, [], []
    for batch in _chunks(np.argsort(counts, kind="stable"), chunk):
        m = int(counts[batch].max())
        pos = np.full((len(batch), m), idx.size)  # idx.size: padding, reads a zero
        for row, k in enumerate(batch):
            pos[row, : counts[k]] = positions[k]
        valid = pos < idx.size
        mats = np.zeros((len(batch), m, m), dtype=dtype)
        missing = []
        for row, k in enumerate(batch):
            hit = cache.get(lines[k])
            if hit is not None and hit[0] == keys[k]:
                mats[row, : counts[k], : counts[k]] = hit[1]
            else:
                missing.append(row)
        if missing:
            jobs.append((mats, missing, xs_padded[pos[missing]], valid[missing]))
        for row, k in enumerate(batch):  # views: the cache keeps these blocks alive
            kept[lines[k]] = (keys[k], mats[row, : counts[k], : counts[k]])
        blocks.append((pos, valid, pos[valid], mats))
    return blocks, jobs, kept


def line_preconditioner(op, contact, cache=None, *, budget, chunk=CHUNK, dtype=np.float32):
    """Approximate inverse of ``op`` restricted to ``contact`` (boolean, grid shaped), as a
    map on the contact values; ``None`` where it does not apply (``op.factors_along_x`` false)
    or where the dense line inverses and their cache would exceed ``budget`` bytes.

    ``op`` is a :class:`bem.halfspace.periodic.PeriodicHalfSpace` (its precision ``op.dtype`` is the
    FFT pair's); ``cache`` (a dict kept by the caller across Newton points) keeps the
    inverses of lines whose contact has not changed. The inverses are stored in ``dtype``: float32
    by default, not a tuning but the precision the use allows, since the line systems are well
    conditioned and a preconditioner only has to be near the inverse: float32 changes it by ~1e-7
    relative, far below the inner tolerance, and halves its memory traffic.
    """
    if not op.factors_along_x:
        return None
    n1 = op.shape[1]
    kernel = op.creep_line_kernel(dtype)
    idx = np.flatnonzero(contact)
    counts = np.bincount(idx % n1, minlength=n1)
    if 2 * np.dtype(dtype).itemsize * float(np.sum(counts.astype(float) ** 2)) > budget:
        return None
    cache = {} if cache is None else cache
    blocks, jobs, kept = _batches(idx, n1, cache, chunk, dtype)

    def invert(job):
        mats, rows, x, valid = job
        mats[rows] = np.linalg.inv(_line_matrices(kernel, x, valid))

    _run(invert, jobs)
    cache.clear()
    cache.update(kept)
    full = np.zeros(op.shape, dtype=op.dtype)
    flat = full.reshape(-1)

    def apply(r):
        flat[idx] = r
        w = np.append(np.take(op.elastic_inverse(full).reshape(-1), idx), 0.0)
        w = w.astype(dtype)
        z = np.empty_like(r)

        def solve(block):
            pos, valid, dest, inv = block
            z[dest] = np.matmul(inv, w[pos][:, :, None])[:, :, 0][valid]

        _run(solve, blocks)
        return z

    return apply
