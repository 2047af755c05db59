"""Exceptions raised by dem_contact.

``InputError`` (a ``ValueError``) is raised for any invalid input and names the parameter and its valid
range. ``NumericalError`` is raised when a simulation fails numerically (NaN, blow-up, a contact that
never ends); it is never hidden behind a returned number.
"""


class InputError(ValueError):
    """An input parameter is outside its valid range."""


class NumericalError(ArithmeticError):
    """A simulation failed numerically (NaN, blow-up, contact that does not end)."""


def kernel_failed(err: BaseException, what: str) -> NumericalError:
    """The NumericalError for an exception raised inside compiled code (``what``: which kernels, where). numba
    reports a failure inside a kernel as whatever exception it can (ZeroDivisionError, IndexError, or a
    SystemError from a parallel region); its results are then never used."""
    return NumericalError(f"{what} failed ({type(err).__name__}: {err})")
