"""Small validators used at the public boundary. Each names the parameter it checks, the range
it expects and the value it received, written as a plain number (``0.5``, never
``np.float64(0.5)``).

Examples
--------
>>> from bem.checks import check_positive
>>> check_positive("speed", 0.01)
0.01
>>> check_positive("speed", "0.01")
Traceback (most recent call last):
...
bem.errors.InputError: speed must be a real number (not a string), got '0.01'
"""

import difflib
import math

import numpy as np

from .errors import InputError

__all__ = ["show", "check_positive", "check_range", "check_int", "check_array", "check_keywords"]


def show(value):
    """``repr`` of ``value`` with numpy scalars written as plain Python numbers."""
    if isinstance(value, np.generic) or (isinstance(value, np.ndarray) and value.ndim == 0):
        value = value.item()
    return repr(value)


def _real(name, value, expected):
    """``float(value)`` for a real number (not a string, a bool or a complex number)."""
    if isinstance(value, (str, bytes)):
        raise InputError(f"{name} must be {expected} (not a string), got {show(value)}")
    if isinstance(value, (bool, np.bool_)):
        raise InputError(f"{name} must be {expected}, got {show(value)}")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be {expected}, got {show(value)}") from None


def check_positive(name, value, *, allow_zero=False):
    """Return ``float(value)`` if it is a finite real number > 0 (>= 0 with ``allow_zero``)."""
    x = _real(name, value, "a real number")
    bound = "a finite number >= 0" if allow_zero else "a finite number > 0"
    if not math.isfinite(x) or x < 0 or (x == 0 and not allow_zero):
        raise InputError(f"{name} must be {bound}, got {show(value)}")
    return x


def check_range(name, value, low, high):
    """Return ``float(value)`` if it is a real number with ``low <= value <= high``."""
    x = _real(name, value, f"a real number in [{show(low)}, {show(high)}]")
    if not (low <= x <= high):
        raise InputError(f"{name} must be in [{show(low)}, {show(high)}], got {show(value)}")
    return x


def check_int(name, value, low, high=None):
    """Return ``int(value)`` if it is an integer with ``low <= value (<= high)``."""
    expected = f"an integer >= {low}" if high is None else f"an integer in [{low}, {high}]"
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise InputError(f"{name} must be {expected}, got {show(value)}")
    if value < low or (high is not None and value > high):
        raise InputError(f"{name} must be {expected}, got {show(value)}")
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
        raise InputError(f"{name} must be > 0 everywhere, got min {show(a.min())}")
    return a


def check_keywords(function, given, valid):
    """Refuse keyword arguments of ``function`` outside ``valid``, naming each one and the
    closest valid name (``lod`` -> did you mean ``load``?)."""
    unknown = [k for k in given if k not in valid]
    if not unknown:
        return
    parts = []
    for key in unknown:
        close = difflib.get_close_matches(key, sorted(valid), n=1, cutoff=0.6)
        parts.append(f"{key!r}" + (f" (did you mean {close[0]!r}?)" if close else ""))
    raise InputError(
        f"{function}() got unknown keyword argument{'s' if len(parts) > 1 else ''} "
        f"{', '.join(parts)}; valid: {', '.join(sorted(valid))}"
    )
