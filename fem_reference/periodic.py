"""Periodic cells: the displacement on a block's right side is the one on its left side.

A strip ``[x_lo, x_hi] x [-H, 0]`` stands for one period of a solid whose surface and loads repeat
with period ``x_hi - x_lo``. Its right side's degrees of freedom are not unknowns: each equals the
one at the same height on the left side (:func:`periodic_constraint`), composed with the hanging
nodes' constraint (:func:`fem_reference.quadtree.constraint_matrix`) in
:func:`fem_reference.kinematics.quadrature_operators`. The material's memory wraps the same way: an
element at the upstream end takes its inflow from the downstream end of its row
(:func:`fem_reference.memory.mesh_flow`), so the viscous strains are the steady periodic solution,
not a solution that starts relaxed.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["periodic_constraint"]


def periodic_constraint(basis):
    """``(T, right)``: ``u = T u`` sets the right side's DOFs of a vector ``basis`` (boundaries ``left``
    and ``right``) from the left side's at the same height; ``right`` are those DOFs."""
    N = basis.N
    rows, cols = [], []
    for comp in ("u^1", "u^2"):
        left = basis.get_dofs("left").all(comp)
        right = basis.get_dofs("right").all(comp)
        yl, yr = basis.doflocs[1, left], basis.doflocs[1, right]
        left, right = left[np.argsort(yl)], right[np.argsort(yr)]
        span = float(np.ptp(basis.doflocs[1])) or 1.0
        if left.size != right.size or not np.allclose(np.sort(yl), np.sort(yr), rtol=0, atol=1e-9 * span):
            raise ValueError("the left and right sides of a periodic cell must carry nodes at the same heights")
        rows.append(right)
        cols.append(left)
    rows, cols = np.concatenate(rows), np.concatenate(cols)
    keep = np.setdiff1d(np.arange(N), rows)
    T = sp.csr_matrix(
        (np.ones(rows.size + keep.size), (np.concatenate([rows, keep]), np.concatenate([cols, keep]))), shape=(N, N)
    )
    return T, np.sort(rows)
