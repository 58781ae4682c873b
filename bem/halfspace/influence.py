"""Influence coefficients of uniformly loaded elements on a half-space: elastic and steady sliding.

Units: coefficients are normal surface displacements (m) per unit pressure (1 Pa) on one
element, for a half-space of unit reduced modulus ``E* = E / (1 - nu**2) = 1 Pa``; the
caller multiplies by ``(1 - nu**2)`` times a compliance (1/Pa). Displacement is positive
into the solid.

- Strips (1-D profiles, plane strain), width ``w``: ``u(x) = -(2/pi) ∫ p(s) ln|x - s| ds``.
  In plane strain ``u`` is defined only up to a constant; lengths in the logarithm are
  measured in units of a reference length ``ell`` (the domain side), so the elastic
  coefficient vanishes, up to ``O(w**2 / ell**2)``, at distance ``ell``.
- Squares (2-D surfaces, 3-D half-space), side ``w``: ``u(x, y) = (1/pi) ∫∫ p / r dA``,
  Love's closed form (A.E.H. Love, Phil. Trans. R. Soc. A 228 (1929) 377,
  doi:10.1098/rsta.1929.0009) written with the signed corner function
  ``f(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|)``, valid in all four quadrants (docs/theory.md §12).

Steady sliding (docs/theory.md §3): a creep term of time ``lambda`` at speed ``v`` contributes
``C ∫_0^inf exp(-z) G(x + L z) dz`` with ``L = v lambda`` (the displacement at ``x`` is
the memory of the elastic field that the material point saw ahead of ``x``). For strips this
has a closed form with exponential integrals, written relative to ``ln(L) - gamma_Euler``
(the dropped part is a constant, absorbed by the rigid approach) and with power series
near the origin, so nothing cancels at large ``L`` (docs/theory.md §12). For squares it is a
quadrature along ``x`` at the shifted (off-grid) points, see :func:`square_creep`.
"""

import numpy as np
from scipy import special
from scipy.linalg import eigh_tridiagonal

__all__ = [
    "strip_elastic",
    "strip_creep",
    "square_elastic",
    "square_creep",
    "square_creep_sum",
    "love_corner",
    "log_antiderivative",
]

_GL_X, _GL_W = np.polynomial.legendre.leggauss(10)
_GLAG_X, _GLAG_W = np.polynomial.laguerre.laggauss(10)  # nodes <= 30: inside 40 shift
_FAR = 64.0  # beyond this many element sides the square uses its multipole expansion
_CUT = 40.0  # exp(-40) ~ 4e-18: exponential weight beyond it is dropped


# ----------------------------------------------------------------------------- strips
def log_antiderivative(t):
    """``t ln|t| - t`` (0 at t = 0): antiderivative of ``ln|t|``."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(t != 0, t * np.log(np.abs(np.where(t != 0, t, 1.0))), 0.0) - t


def strip_elastic(x, width, ell):
    """Elastic strip coefficient (m/Pa at ``E* = 1``) at offsets ``x`` (m) from its centre."""
    x = np.asarray(x, dtype=float)
    return (
        -(2.0 / np.pi) * ell * (log_antiderivative((x + width / 2) / ell) - log_antiderivative((x - width / 2) / ell))
    )


def _series_coefficients(terms=40):
    """Taylor coefficients of ``alpha + exp(alpha) S(alpha)``, ``S = sum_k (-alpha)^k / (k k!)``."""
    k = np.arange(terms)
    s = np.zeros(terms)
    s[1:] = (-1.0) ** k[1:] / (k[1:] * special.factorial(k[1:]))
    e = 1.0 / special.factorial(k)
    t = np.array([np.dot(s[: m + 1], e[m::-1]) for m in range(terms)])
    t[1] += 1.0  # exactly zero: the O(alpha) terms cancel
    return t


_T = _series_coefficients()
_E2 = np.where(np.arange(40) >= 2, 1.0 / special.factorial(np.arange(40)), 0.0)


def _capital_phi(a):
    """``Phi(a) = ∫_0^a (Psi(s) + gamma) ds`` with ``Psi(s) = ∫_0^inf exp(-z) ln|s + z| dz``.

    ``Psi(s) = ln|s| - exp(s) Ei(-s)`` (``-gamma`` at 0) and
    ``Phi(a) = Psi(a) + gamma + a (ln|a| - 1 + gamma)``; for ``|a| < 2`` the power series
    ``Phi = -(e^a - 1 - a)(ln|a| + gamma) - (a + e^a S(a))`` (no cancellation, O(a^2 ln a));
    for ``|a| > 40`` the asymptotic series of ``exp(a) Ei(-a)`` (30 terms, < 1e-17).
    """
    a = np.asarray(a, dtype=float)
    out = np.zeros(a.shape)
    g = np.euler_gamma
    small = np.abs(a) < 2
    if np.any(small):
        s = a[small]
        powers = s[:, None] ** np.arange(_T.size)
        with np.errstate(divide="ignore", invalid="ignore"):
            lg = np.where(s != 0, np.log(np.abs(np.where(s != 0, s, 1.0))), 0.0) + g
        out[small] = -(powers @ _E2) * lg - powers @ _T
    mid = ~small & (np.abs(a) <= _CUT)
    big = np.abs(a) > _CUT
    psi = np.empty(a.shape)
    if np.any(mid):
        s = a[mid]
        psi[mid] = np.log(np.abs(s)) - np.exp(s) * special.expi(-s)
    if np.any(big):
        s = a[big]
        k = np.arange(30)
        psi[big] = np.log(np.abs(s)) + np.sum(
            (-1.0) ** k * special.factorial(k) * (1.0 / s[:, None]) ** (k + 1), axis=1
        )
    large = ~small
    s = a[large]
    out[large] = psi[large] + g + s * (np.log(np.abs(s)) - 1.0 + g)
    return out


def strip_creep(x, width, shift):
    """Creep-term strip coefficient ``∫_0^inf exp(-z) G_strip(x + shift z) dz`` (m/Pa, ``E* = 1``).

    Relative to ``ln(shift) - gamma``: the constant ``-(2/pi) width (ln(shift/ell) - gamma)``
    is dropped (see the module docstring). ``shift = v lambda > 0`` (m).
    """
    x = np.asarray(x, dtype=float)
    return -(2.0 / np.pi) * shift * (_capital_phi((x + width / 2) / shift) - _capital_phi((x - width / 2) / shift))


# ----------------------------------------------------------------------------- squares
def love_corner(X, Y):
    """Signed corner function ``X asinh(Y/|X|) + Y asinh(X/|Y|)`` (0 on the axes' limits): the
    integral of ``1/r`` over the rectangle from the origin to ``(X, Y)``, valid in every quadrant."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ax, ay = np.abs(X), np.abs(Y)
        t1 = np.where(ax > 0, X * np.arcsinh(Y / np.where(ax > 0, ax, 1.0)), 0.0)
        t2 = np.where(ay > 0, Y * np.arcsinh(X / np.where(ay > 0, ay, 1.0)), 0.0)
    return t1 + t2


def square_elastic(x, y, width):
    """Elastic square coefficient (m/Pa at ``E* = 1``) at offsets ``(x, y)`` (m) from its centre.

    Love's formula ``(1/pi) sum_corners ± f``; beyond ``64 width`` (where the four corner terms
    would cancel to ~1e-11) the multipole expansion ``(A/r)(1 + w^2 / (24 r^2))/pi``, whose
    next term is ``O((w/r)^4) < 1e-8`` relative.
    """
    x, y = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
    h = width / 2
    r = np.hypot(x, y)
    far = r > _FAR * width
    out = np.empty(x.shape)
    if np.any(far):
        rf = r[far]
        out[far] = width**2 / rf * (1.0 + width**2 / (24.0 * rf**2)) / np.pi
    near = ~far
    xn, yn = x[near], y[near]
    out[near] = (
        love_corner(xn + h, yn + h)
        - love_corner(xn + h, yn - h)
        - love_corner(xn - h, yn + h)
        + love_corner(xn - h, yn - h)
    ) / np.pi
    return out


def _pieces(length, shift, grade_left=False, grade_right=False):
    """Sub-interval edges of ``[0, min(length, 40 shift)]`` for the weight ``exp(-t/shift)``:
    graded in steps of ``shift`` (1, 2, 4, 8, 16) when ``shift < length`` and, optionally,
    geometrically toward an end where the integrand has a ``t ln t`` kink."""
    top = min(length, _CUT * shift)
    edges = [0.0, top] + [shift * c for c in (1, 2, 4, 8, 16)]
    g = length * 0.15 ** np.arange(1, 14)
    if grade_left:
        edges += list(g)
    if grade_right:
        edges += list(length - g)
    e = np.unique(np.asarray(edges))
    return e[e <= top]


def _nodes(edges, shift):
    """Gauss–Legendre nodes ``t`` and weights ``exp(-t/shift)/shift * dt`` on the pieces."""
    lo, hi = edges[:-1, None], edges[1:, None]
    t = (0.5 * (hi - lo) * (_GL_X + 1) + lo).ravel()
    w = (0.5 * (hi - lo) * _GL_W).ravel()
    return t, w * np.exp(-t / shift) / shift


def square_creep(n, width, shift):
    """Creep-term square coefficients ``∫_0^inf exp(-z) G_sq(x + shift z, y) dz`` (m/Pa, ``E* = 1``).

    Parameters
    ----------
    n : int
        Elements per side; offsets ``x = m width / 2`` for ``m = -(2n-1) .. 2n-1`` (element
        centres at even ``m``, element edges at odd ``m``) and ``y = j width``, ``j = 0..n-1``.
    width : float
        Element side (m).
    shift : float
        ``L = v lambda`` (m), > 0.

    Returns
    -------
    ndarray, shape ``(4n - 1, n)``

    Notes
    -----
    Written as ``I(s) = (1/L) ∫_s^inf exp(-(t - s)/L) G(t, y) dt``, the integral is split at the
    half-element points ``m w / 2`` (where the kinks of ``G`` lie), each half element is
    integrated by Gauss–Legendre at the shifted off-grid points (graded toward the kinks on
    the row ``y = 0``, where ``G`` has a ``t ln t`` term, and in steps of ``L`` when
    ``L < w / 2``, condensed to a 10-point Gauss rule of that weight; by Gauss–Laguerre when
    ``40 L < w / 2``), and the pieces are summed backward,
    ``I(s_m) = exp(-w/(2L)) I(s_{m+1}) + ∫_{s_m}^{s_{m+1}}``. Beyond the last point the
    tail is integrated over pieces growing geometrically to ``40 L``.
    """
    return square_creep_sum(n, width, [shift], [1.0])


def _gauss_rule(t, w, k=10):
    """``k``-point Gauss rule of the discrete measure ``(t, w)`` (Lanczos / discretized
    Stieltjes, then Golub–Welsch): exact for polynomials of degree ``< 2k`` under that measure."""
    scale = t.max()
    x = t / scale
    alpha, beta = np.zeros(k), np.zeros(k)
    q_prev = np.zeros_like(x)
    q = np.full_like(x, 1.0 / np.sqrt(w.sum()))
    for i in range(k):
        z = x * q
        alpha[i] = np.dot(w, z * q)
        z = z - alpha[i] * q - (beta[i - 1] * q_prev if i else 0.0)
        if i + 1 < k:
            beta[i] = np.sqrt(np.dot(w, z * z))
            q_prev, q = q, z / beta[i]
    nodes, vecs = eigh_tridiagonal(alpha, beta[:-1])
    return nodes * scale, w.sum() * vecs[0] ** 2


def _half_element_nodes(h, shift):
    """Nodes and weights of one half element ``[0, h]`` for the weight ``exp(-t/L)/L``."""
    if _CUT * shift <= h:  # weight concentrated at the left end, G smooth there: Gauss–Laguerre
        return shift * _GLAG_X, _GLAG_W
    # a 10-point Gauss rule of the truncated exponential weight, from its graded discretisation
    return _gauss_rule(*_nodes(_pieces(h, shift), shift))


def _sweep(seg, s, yy, width, shift, first_row):
    """Kink correction (row y = 0), tail and backward recurrence for one block of rows."""
    h = width / 2
    if first_row:  # the half elements touching the kinks at x = ±w/2 get graded quadrature
        for kink in (-1, 1):
            i = int(np.flatnonzero(np.isclose(s, kink * h, rtol=0, atol=1e-9 * h))[0])
            for cell, left in ((i - 1, False), (i, True)):
                tg, wg = _nodes(_pieces(h, shift, grade_left=left, grade_right=not left), shift)
                seg[cell, 0] = np.dot(square_elastic(s[cell] + tg, 0.0, width), wg)
    # tail beyond the last point: pieces doubling in width up to 40 L
    top = max(_CUT * shift, h)
    grow = h * 2.0 ** np.arange(int(np.ceil(np.log2(top / h))) + 1)
    edges = np.unique(np.concatenate([[0.0, top], grow[grow < top], _pieces(h, shift)]))
    tt, wtt = _nodes(edges, shift)
    tail = square_elastic(s[-1] + tt[:, None], yy[None, :], width).T @ wtt
    # backward recurrence I_m = r I_{m+1} + seg_m as a first-order filter on the reversed rows
    r = np.exp(-h / shift)
    out = np.empty((s.size, yy.size))
    out[-1] = tail
    from scipy.signal import lfilter  # imported here: scipy.signal is slow to import

    out[-2::-1] = lfilter([1.0], [1.0, -r], seg[::-1], axis=0, zi=(r * tail)[None, :])[0]
    return out


def square_creep_sum(n, width, shifts, weights):
    """``sum_k weights[k] * square_creep(n, width, shifts[k])``, sharing the work of all terms
    with ``shift >= width / 2`` (their Gauss–Legendre nodes coincide; only the weights differ).

    Same offsets and shape as :func:`square_creep`; ``weights`` in any unit (e.g. the creep
    compliances ``C_k``, 1/Pa). ``weights`` of shape ``(sets, terms)`` gives ``sets`` such sums
    from one quadrature, shape ``(sets, 4n - 1, n)``.
    """
    h = width / 2
    s = np.arange(-(2 * n - 1), 2 * n) * h
    y = width * np.arange(n)
    shifts = np.asarray(shifts, dtype=float)
    weights = np.asarray(weights, dtype=float)
    single = weights.ndim == 1
    weights = np.atleast_2d(weights).T[:, :, None, None]  # (terms, sets, 1, 1)
    shared = shifts >= h
    t_sh = _nodes(np.array([0.0, h]), h)[0]
    w_sh = [_nodes(np.array([0.0, h]), L)[1] for L in shifts[shared]]
    own = [(L, c, *_half_element_nodes(h, L)) for L, c in zip(shifts[~shared], weights[~shared])]
    out = np.zeros((weights.shape[1], s.size, n))
    most = max([t_sh.size] + [o[2].size for o in own])
    chunk = max(1, 2**21 // (s.size * most))  # rows per block: bounded memory
    for j0 in range(0, n, chunk):
        yy = y[j0 : j0 + chunk]
        rows = slice(j0, j0 + yy.size)
        if w_sh:
            vals = square_elastic(s[:-1, None, None] + t_sh[None, :, None], yy[None, None, :], width)
            for L, c, wt in zip(shifts[shared], weights[shared], w_sh):
                out[:, :, rows] += c * _sweep(np.einsum("mtj,t->mj", vals, wt), s, yy, width, L, j0 == 0)
        for L, c, t, wt in own:
            vals = square_elastic(s[:-1, None, None] + t[None, :, None], yy[None, None, :], width)
            out[:, :, rows] += c * _sweep(np.einsum("mtj,t->mj", vals, wt), s, yy, width, L, j0 == 0)
    return out[0] if single else out
