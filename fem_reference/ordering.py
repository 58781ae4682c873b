"""Fill-reducing ordering of the FEM's mixed systems for SuperLU.

The systems couple displacements, pressures (a zero diagonal block at ``nu = 0.5``) and the
viscous terms' transported values. SuperLU's own column orderings (COLAMD on ``A^T A``) see
none of the mesh's two-dimensional structure, and their factors grew to four times those of a
nested dissection of the same graph. Nested dissection (METIS, through ``pymetis``) of the
symmetrised pattern orders the unknowns symmetrically, so that the diagonal stays the natural
pivot; each unknown with a zero diagonal is tied to the neighbour it couples to most strongly
and follows it, so that eliminating that neighbour has made its pivot nonzero when its turn
comes. SuperLU then pivots off the diagonal only where a pivot is smaller than
:data:`PIVOT_THRESHOLD` of its column (threshold partial pivoting), which keeps the order in
all but a few columns.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["equilibrate", "nested_dissection", "PIVOT_THRESHOLD"]

# SuperLU takes the diagonal pivot unless it is below this share of its column's largest entry.
# On the 8-term rubber's carried system at its friction peak (120,458 unknowns) with this order:
# factor entries 3.4e7 at 1e-4, 4.9e7 at 1e-3, 1.0e8 at 1e-2, about 1.4e8 at 0.1, and a singular
# factor at 0 (no pivoting at all); COLAMD at SuperLU's default of 1 took 1.48e8. The residual after
# three refinement steps was the same (about 7e-6 for a random right-hand side) at every threshold
PIVOT_THRESHOLD = 1e-4


def equilibrate(A):
    """``(r, c, diag(r) A diag(c))``: one sweep of Ruiz's scaling, every row and then every column
    divided by the square root of its largest entry, which brings entries that span many orders
    (moduli against the unit couplings of the transported values) within a few of one."""
    A = sp.csr_matrix(A)
    r = 1.0 / np.sqrt(_peaks(A, axis=1))
    scaled = sp.csr_matrix(sp.diags(r) @ A)
    c = 1.0 / np.sqrt(_peaks(scaled, axis=0))
    return r, c, sp.csr_matrix(scaled @ sp.diags(c))


def _peaks(A, axis):
    peak = np.asarray(abs(A).max(axis=axis).todense()).ravel()
    # an empty row or column (a singular system) is left to the factorisation to report
    return np.where(peak > 0, peak, 1.0)


def nested_dissection(A):
    """A symmetric permutation ``order`` of the unknowns of the square sparse ``A``, so that
    ``A[order][:, order]`` factors with little fill in its natural order."""
    A = sp.csr_matrix(A)
    n = A.shape[0]
    S = abs(A) + abs(A.T)
    S = sp.csr_matrix(S)
    diag = S.diagonal()
    S.setdiag(0)
    S.eliminate_zeros()
    scale = np.asarray(S.max(axis=1).todense()).ravel()
    zero = diag <= 1e-14 * np.maximum(scale, np.finfo(float).tiny)
    # each zero-diagonal unknown joins its strongest neighbour with a nonzero diagonal
    rep = np.arange(n)
    for i in np.flatnonzero(zero):
        cols = S.indices[S.indptr[i] : S.indptr[i + 1]]
        vals = S.data[S.indptr[i] : S.indptr[i + 1]]
        ok = ~zero[cols]
        if ok.any():
            rep[i] = cols[ok][np.argmax(vals[ok])]
    heads = np.flatnonzero(rep == np.arange(n))
    label = np.full(n, -1)
    label[heads] = np.arange(heads.size)
    label = label[rep]
    P = sp.csr_matrix((np.ones(n), (label, np.arange(n))), shape=(heads.size, n))
    G = sp.csr_matrix(P @ S @ P.T)
    G.setdiag(0)
    G.eliminate_zeros()
    G.sort_indices()
    if G.nnz == 0:
        perm = np.arange(heads.size)
    else:
        perm = np.asarray(_metis_nd(G), dtype=np.int64)
    # expand each group: its head first, then the unknowns tied to it
    rank = np.empty(heads.size, dtype=np.int64)
    rank[perm] = np.arange(heads.size)
    key = rank[label] * 2 + (rep != np.arange(n))
    return np.argsort(key, kind="stable")


def _metis_nd(G):
    import pymetis

    perm, _ = pymetis.nested_dissection(pymetis.CSRAdjacency(G.indptr, G.indices))
    return perm
