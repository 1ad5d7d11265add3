"""Prism: a spectral render engine for Blender.

Registration only, in a fixed order (settings before the engine that reads them,
panels last); ``unregister`` undoes it in reverse. Nothing heavy is imported here:
colour-science, scipy and embreex load only when a render starts (or in the separate
process that compiles the kernels in the background: ``engine.warmup``).
"""

from . import operators, ui
from .engine import properties
from .engine.render import render_engine
from .engine.warmup import triggers as kernel_warmup

# The warm-up's triggers after the engine (a scene can only use a registered engine).
_REGISTRATION_ORDER = (properties, render_engine, kernel_warmup, operators, ui)


def register():
    for part in _REGISTRATION_ORDER:
        part.register()


def unregister():
    for part in reversed(_REGISTRATION_ORDER):
        part.unregister()
