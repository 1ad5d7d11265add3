"""Errors a user can act on.

Every error raised because of user input (a scene, a lens file, a setting) is a
``PrismInputError``: its message names the offending object and the fix. The
Blender side shows the message as-is in a report; the batch script prints it
and exits non-zero.
"""


class PrismInputError(ValueError):
    """Bad user input; the message names the object and how to fix it."""


class UnknownGlassError(PrismInputError, KeyError):
    """A glass name that is not in the catalogue."""

    def __str__(self):  # KeyError would otherwise quote the message
        return self.args[0] if self.args else ""


class LensFileError(PrismInputError):
    """A malformed lens file; the message names the file, line and problem."""
