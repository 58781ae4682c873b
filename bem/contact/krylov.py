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

RESTART_MAX = 200
"""Most GMRES basis vectors: orthogonalisation (~4 j n flops at step j) outgrows the products.
A loose inner solve is one restart cycle (:mod:`bem.contact.inner`), so this is also how far a
Newton point that moves the set gets. Ablation row "long GMRES restarts" (30 instead): 0.88x the
products on the quick set, all of it the sinusoid near full contact (2023 against 9832), against
2.03x on the 1-D SLS 1e4 case (10,585 against 5202); and the 128² cell at E_inf/E0 = 1e4 of
``tests/bem/test_robustness.py`` (slow) no longer converges: its attempt ends at ``maxiter``
(residual 0.71 after 400 steps of about 30 products), where 200 take 176 steps."""


def restart_length(n, *, budget):
    """GMRES restart length for systems of ``n`` unknowns: ``budget / n`` basis vectors (the
    basis holds ``budget`` doubles at most and is only touched as far as the solve gets),
    at least one and at most :data:`RESTART_MAX`. Restarts are what make strongly non-symmetric
    systems slow, so the basis is as long as memory allows; below that the memory budget
    (``ContactOptions.restart_budget``) is the user's to trade."""
    return int(min(RESTART_MAX, max(1, budget // max(n, 1))))


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


def _orthogonalise(V, w, h_column, reorthogonalise):
    """Classical Gram–Schmidt of ``w`` against the rows of ``V`` (in place), repeated once if it
    cancelled (Kahan–Parlett "twice is enough"); the coefficients are added to ``h_column``.
    Returns the norm of what is left."""
    norm_w = np.linalg.norm(w)
    for _ in range(2):
        h = V @ w
        w -= h @ V
        h_column += h
        norm_new = np.linalg.norm(w)
        if norm_new > reorthogonalise * norm_w:
            break
        norm_w = norm_new
    return norm_new


def _rotate(column, cs, sn, j):
    """Apply the previous Givens rotations to the Hessenberg ``column`` ``j`` and make the one
    that zeroes its subdiagonal (stored in ``cs[j], sn[j]``)."""
    for i in range(j):
        t = cs[i] * column[i] + sn[i] * column[i + 1]
        column[i + 1] = -sn[i] * column[i] + cs[i] * column[i + 1]
        column[i] = t
    den = np.hypot(column[j], column[j + 1])
    cs[j], sn[j] = (1.0, 0.0) if den == 0 else (column[j] / den, column[j + 1] / den)
    column[j] = den
    column[j + 1] = 0.0


def gmres(matvec, b, *, atol, maxiter, restart, M=None, reorthogonalise=0.5**0.5):
    """Restarted GMRES(``restart``) from ``x = 0``; see module docstring.

    A second Gram–Schmidt pass is made only when the first kept less than ``reorthogonalise``
    of the vector's norm (cancellation). The default 1/sqrt(2) is Kahan–Parlett's "twice is
    enough" criterion, a theorem rather than a tuning: above it one pass is orthogonal to working
    accuracy, and two passes always are. Ablation row "reorthogonalisation" (one pass): no product
    on the case set, but on nearly dependent Krylov vectors one pass stops at a true residual of
    ~3e-4 (``tests/bem/contact/test_krylov.py``).
    """
    n = b.size
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
            H[j + 1, j] = _orthogonalise(V[: j + 1], w, H[: j + 1, j], reorthogonalise)
            Hbar[: j + 2, j] = H[: j + 2, j]
            if H[j + 1, j] > 0:
                V[j + 1] = w / H[j + 1, j]
            else:  # lucky breakdown: the solution lies in the current space
                V[j + 1] = 0.0
            _rotate(H[:, j], cs, sn, j)
            g[j + 1] = -sn[j] * g[j]
            g[j] = cs[j] * g[j]
            j_done = j + 1
            if abs(g[j + 1]) <= atol or k >= maxiter or H[j, j] == 0:
                break
        # breakdown on a singular system: the last product added no direction of A's range, so the
        # least-squares solution lies in the earlier ones (its column would make the solve singular)
        singular = bool(j_done) and H[j_done - 1, j_done - 1] == 0
        j_done -= singular
        y = np.linalg.solve(np.triu(H[:j_done, :j_done]), g[:j_done]) if j_done else np.zeros(0)
        x += y @ V[:j_done] if M is None else M(y @ V[:j_done])
        # Arnoldi: b - A x_new = r - V_{j+1} Hbar y, without another product
        coef = -(Hbar[: j_done + 1, :j_done] @ y)
        coef[0] += beta
        r = coef @ V[: j_done + 1]
        beta = float(np.linalg.norm(r))
        if singular:
            break
    return x, beta, k
