"""An independent periodic sliding operator, for checking the solver's answers.

Built from :mod:`numpy.fft` (full complex spectrum) and the material's *relaxation* series
``1 / E(w)`` — not from :mod:`bem.fft`, :mod:`bem.periodic` or the creep series the solver
uses — so agreement checks the FFT layout, the Nyquist handling and the Prony/creep
interconversion as well as the contact solution. Conventions as SPEC §2.2: axis 0 is x, the
surface slides in ``+x`` at ``speed`` and ``u_q = 2 (1 - nu**2) / |q| / E(w = -q_x v) p_q``.
The symbol is made Hermitian, ``a_q -> (a_q + conj(a_-q)) / 2`` with ``-q`` taken on the
grid: this changes only the x-Nyquist modes, whose symbol becomes its real part (SPEC §7),
and makes ``1 / a_q`` the exact inverse of the real operator.
"""
import numpy as np


def wavevectors(shape, length):
    """Full-spectrum wavevector components (rad/m), broadcastable, axis 0 = x."""
    freqs = [2 * np.pi * np.fft.fftfreq(n, length / n) for n in shape]
    return np.meshgrid(*freqs, indexing="ij", sparse=True)


def symbol(shape, length, material, speed):
    """``a_q`` (m/Pa) on the full spectrum; zero at ``q = 0``."""
    q = wavevectors(shape, length)
    qn = np.sqrt(sum(c**2 for c in q))
    with np.errstate(divide="ignore"):
        green = np.where(qn > 0, 2 * (1 - material.nu**2) / np.where(qn > 0, qn, 1.0), 0.0)
    a = green / material.complex_modulus(-q[0] * speed)
    mirror = a[tuple(np.ix_(*[(-np.arange(n)) % n for n in shape]))]  # a at -q on the grid
    return 0.5 * (a + np.conj(mirror))


def displacement(pressure, a):
    """Zero-mean displacement (m) of ``pressure`` (Pa) through the full-spectrum symbol ``a``."""
    return np.real(np.fft.ifftn(np.fft.fftn(pressure) * a))


def full_contact_pressure(heights, a):
    """Zero-mean pressure (Pa) making the gap vanish everywhere; add the mean load to it.

    Full contact is the one case where the contact problem is solved exactly in Fourier
    space; ``a`` must be Hermitian (as :func:`symbol` returns it).
    """
    inv = np.where(a != 0, 1.0 / np.where(a != 0, a, 1.0), 0.0)
    return np.real(np.fft.ifftn(np.fft.fftn(heights) * inv))


def x_derivative(field, length):
    """Spectral derivative along x (axis 0) of a periodic field (SPEC §7: never differences)."""
    qx = wavevectors(field.shape, length)[0]
    if field.shape[0] % 2 == 0:  # the Nyquist mode has no defined derivative sign
        qx = np.where(np.abs(qx) == np.pi * field.shape[0] / length, 0.0, qx)
    return np.real(np.fft.ifftn(1j * qx * np.fft.fftn(field)))
