"""The one exception Embree's failures become."""

from __future__ import annotations


class EmbreeError(RuntimeError):
    """Embree could not be loaded, or one of its calls failed (the message says which and why)."""
