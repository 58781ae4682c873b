"""Exceptions raised by viscobem.

All input validation errors are :class:`InputError`, a :class:`ValueError` whose message
names the offending parameter, the valid range and the value received. A solve that does
not reach its tolerance raises :class:`ConvergenceError`; it never returns numbers that
look valid.
"""


class ViscobemError(Exception):
    """Base class of every error raised on purpose by viscobem."""


class InputError(ViscobemError, ValueError):
    """A parameter is outside its valid range; the message names it."""


class ConvergenceError(ViscobemError, RuntimeError):
    """An iterative solve stopped before reaching its tolerance.

    Attributes
    ----------
    result : object or None
        The unconverged result (``success=False``) for inspection, if available.
    """

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result
