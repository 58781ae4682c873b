"""Small validators used at the public boundary. Each names the parameter it checks."""
import math

import numpy as np

from .errors import InputError


def check_positive(name, value, *, allow_zero=False):
    """Return ``float(value)`` if it is finite and > 0 (>= 0 with ``allow_zero``)."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a real number, got {value!r}") from None
    bound = "a finite number >= 0" if allow_zero else "a finite number > 0"
    if not math.isfinite(x) or x < 0 or (x == 0 and not allow_zero):
        raise InputError(f"{name} must be {bound}, got {value!r}")
    return x


def check_range(name, value, low, high):
    """Return ``float(value)`` if ``low <= value <= high``."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a real number in [{low}, {high}], got {value!r}") from None
    if not (low <= x <= high):
        raise InputError(f"{name} must be in [{low}, {high}], got {value!r}")
    return x


def check_int(name, value, low, high=None):
    """Return ``int(value)`` if it is an integer with ``low <= value (<= high)``."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise InputError(f"{name} must be an integer >= {low}, got {value!r}")
    if value < low or (high is not None and value > high):
        rng = f"[{low}, {high}]" if high is not None else f">= {low}"
        raise InputError(f"{name} must be an integer in {rng}, got {value!r}")
    return int(value)


def check_array(name, value, *, ndim=None, positive=False, min_size=1):
    """Return ``value`` as a finite float array (a copy), optionally all > 0."""
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be an array of real numbers, got {type(value).__name__}") from None
    if ndim is not None and a.ndim not in np.atleast_1d(ndim):
        raise InputError(f"{name} must have {ndim} dimension(s), got shape {a.shape}")
    if a.size < min_size:
        raise InputError(f"{name} must have at least {min_size} entries, got {a.size}")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name} must be finite (no NaN or inf); {np.count_nonzero(~np.isfinite(a))} bad entries")
    if positive and np.any(a <= 0):
        raise InputError(f"{name} must be > 0 everywhere, got min {a.min()!r}")
    return a
