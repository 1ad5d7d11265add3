"""Prism: a spectral render engine for Blender.

Registration only, in a fixed order (settings before the engine that reads them,
panels last); ``unregister`` undoes it in reverse. Nothing heavy is imported here:
colour-science, scipy and embreex load only when a render starts.
"""

from . import operators, ui
from .engine import properties, render_engine

_REGISTRATION_ORDER = (properties, render_engine, operators, ui)


def register():
    for part in _REGISTRATION_ORDER:
        part.register()


def unregister():
    for part in reversed(_REGISTRATION_ORDER):
        part.unregister()
