"""User actions (operators) that Prism adds to Blender.

Each module listed in ``_MODULE_NAMES`` has ``register()`` and ``unregister()``;
they run in this order and are undone in reverse.
"""

import importlib

_MODULE_NAMES: tuple[str, ...] = ("lens_overlay", "autofocus")


def _modules():
    return [importlib.import_module(f".{name}", __name__) for name in _MODULE_NAMES]


def register():
    for module in _modules():
        module.register()


def unregister():
    for module in reversed(_modules()):
        module.unregister()
