"""Krylov solvers for the linear systems on the contact set (inner loop of the contact solver).

Both take a matrix-free ``matvec``, a right-hand side ``b``, an optional preconditioner
``M`` (a callable approximating ``A^-1``; CG applies it on the left and needs it symmetric
positive definite, GMRES on the right, so that both stop on the true residual) and stop when
``||b - A x||_2 <= atol`` or after ``maxiter`` products; they return
``(x, residual_norm, matvecs)`` (products with ``A``; the caller counts its own ``M``). They start from ``x = 0``: the contact solver passes
corrections, so a warm start is already in its right-hand side.

- :func:`cg` for the symmetric positive definite case (elastic or zero speed).
- :func:`gmres` (restarted, Householder-free: classical Gram–Schmidt with a second pass
  whenever the first shrank the vector below 1/sqrt(2) of its norm, which is as stable as
  modified Gram–Schmidt and uses matrix–vector BLAS calls) for the non-symmetric but positive-real steady-sliding operator: its symmetric part has the
  symbol ``Re a_q > 0``, so the field of values excludes 0 and GMRES converges.
"""

import numpy as np

TWICE_IS_ENOUGH = 1 / np.sqrt(2)  # default share for a second Gram–Schmidt pass (Kahan–Parlett)


def restart_length(n, *, budget=2**26, low=30, high=200):
    """GMRES restart length for systems of ``n`` unknowns: ``budget / n`` basis vectors (the
    basis holds ``budget`` doubles at most and is only touched as far as the solve gets),
    clipped to ``[low, high]``. Restarts are what make strongly non-symmetric systems slow,
    so the basis is as long as memory allows; orthogonalisation (~4 j n flops at step j)
    caps it."""
    return int(min(high, max(low, budget // max(n, 1))))


def cg(matvec, b, *, atol, maxiter, M=None):
    """(Preconditioned) conjugate gradients for SPD ``matvec``; see module docstring."""
    x = np.zeros_like(b)
    r = b.copy()
    if np.linalg.norm(r) <= atol:
        return x, float(np.linalg.norm(r)), 0
    z = r if M is None else M(r)
    rz = float(r @ z)
    d = z.copy()
    k = 0
    res = float(np.linalg.norm(r))
    while k < maxiter:
        ad = matvec(d)
        k += 1
        dad = float(d @ ad)
        if dad <= 0 or rz <= 0:  # loss of positivity: stop with what we have
            break
        alpha = rz / dad
        x += alpha * d
        r -= alpha * ad
        res = float(np.linalg.norm(r))
        if res <= atol:
            break
        z = r if M is None else M(r)
        rz_new = float(r @ z)
        d *= rz_new / rz
        d += z
        rz = rz_new
    return x, res, k


def gmres(matvec, b, *, atol, maxiter, restart=None, M=None, reorthogonalise=TWICE_IS_ENOUGH):
    """Restarted GMRES(``restart``) from ``x = 0``; see module docstring.

    ``restart`` defaults to :func:`restart_length` of the system. A second Gram–Schmidt pass
    is made only when the first kept less than ``reorthogonalise`` of the vector's norm
    (cancellation); otherwise one pass is orthogonal to working accuracy.
    """
    n = b.size
    if restart is None:
        restart = restart_length(n)
    x = np.zeros_like(b)
    r = b.copy()
    beta = float(np.linalg.norm(r))
    k = 0
    m = max(1, min(restart, maxiter, n))
    V = np.empty((m + 1, n))
    while beta > atol and k < maxiter:
        H = np.zeros((m + 1, m))
        Hbar = np.zeros((m + 1, m))  # unrotated Hessenberg matrix, for the residual
        V[0] = r / beta
        cs, sn = np.zeros(m), np.zeros(m)
        g = np.zeros(m + 1)
        g[0] = beta
        j_done = 0
        for j in range(m):
            w = matvec(V[j] if M is None else M(V[j]))
            k += 1
            norm_w = np.linalg.norm(w)
            for _ in range(2):  # CGS, repeated once if it cancelled (Kahan–Parlett "twice is enough")
                h = V[: j + 1] @ w
                w -= h @ V[: j + 1]
                H[: j + 1, j] += h
                norm_new = np.linalg.norm(w)
                if norm_new > reorthogonalise * norm_w:
                    break
                norm_w = norm_new
            H[j + 1, j] = norm_new
            Hbar[: j + 2, j] = H[: j + 2, j]
            if H[j + 1, j] > 0:
                V[j + 1] = w / H[j + 1, j]
            else:  # lucky breakdown: the solution lies in the current space
                V[j + 1] = 0.0
            for i in range(j):  # apply previous Givens rotations
                t = cs[i] * H[i, j] + sn[i] * H[i + 1, j]
                H[i + 1, j] = -sn[i] * H[i, j] + cs[i] * H[i + 1, j]
                H[i, j] = t
            den = np.hypot(H[j, j], H[j + 1, j])
            cs[j], sn[j] = (1.0, 0.0) if den == 0 else (H[j, j] / den, H[j + 1, j] / den)
            H[j, j] = den
            H[j + 1, j] = 0.0
            g[j + 1] = -sn[j] * g[j]
            g[j] = cs[j] * g[j]
            j_done = j + 1
            if abs(g[j + 1]) <= atol or k >= maxiter or H[j, j] == 0:
                break
        y = np.linalg.solve(np.triu(H[:j_done, :j_done]), g[:j_done]) if j_done else np.zeros(0)
        x += y @ V[:j_done] if M is None else M(y @ V[:j_done])
        # Arnoldi: b - A x_new = r - V_{j+1} Hbar y, without another product
        coef = -(Hbar[: j_done + 1, :j_done] @ y)
        coef[0] += beta
        r = coef @ V[: j_done + 1]
        beta = float(np.linalg.norm(r))
        if j_done and H[j_done - 1, j_done - 1] == 0:
            break
    return x, beta, k
