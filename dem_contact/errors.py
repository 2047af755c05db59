"""Exceptions raised by dem_contact.

``InputError`` (a ``ValueError``) is raised for any invalid input and names the parameter and its valid
range. ``NumericalError`` is raised when a simulation fails numerically (NaN, blow-up, a contact that
never ends); it is never hidden behind a returned number.
"""


class InputError(ValueError):
    """An input parameter is outside its valid range."""


class NumericalError(ArithmeticError):
    """A simulation failed numerically (NaN, blow-up, contact that does not end)."""
