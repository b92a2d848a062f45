"""The error family (``equimesh/errors.py``)."""

from equimesh import EquimeshError, InvalidLengthError, InvalidPolygonError


def test_errors_are_value_errors():
    """The error family: both input errors are EquimeshError and ValueError."""
    for error in (InvalidPolygonError, InvalidLengthError):
        assert issubclass(error, EquimeshError) and issubclass(error, ValueError)
