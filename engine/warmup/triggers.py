"""When Blender starts the background kernel warm-up: a scene becomes Prism's.

- The scene's engine set to Prism: a ``bpy.msgbus`` subscription to ``RenderSettings.engine``. Blender
  drops every subscription when a file loads, so ``load_post`` subscribes again.
- A file whose scene already uses Prism: the ``load_post`` handler (it also runs for the start-up file).
- Registering the add-on while the current scene uses Prism: checked at once where the context has a
  scene (the bpy module), else by a one-shot timer (add-ons register under a restricted context).

Each asks ``launch.start``, which compiles only when the cache is cold for this tracer source and no
warm-up runs. Nothing here imports numba, colour-science or embreex: the decision reads the kernel
folder's stamp and lock files (a few milliseconds, hashing the tracer's sources once).

Only with a user interface by default: in ``blender -b`` (and the bpy module) a render follows at once
in the same process, which compiles what it needs itself. ``PRISM_KERNEL_WARMUP=1`` starts warm-ups in
background mode too (the tests), ``PRISM_KERNEL_WARMUP=0`` never. In the bpy module msgbus notifications
and timers never run (there is no event loop): there ``engine_changed`` is what Blender would call.
"""

from __future__ import annotations

import os
import traceback

import bpy
from bpy.app.handlers import persistent

ENVIRONMENT_VARIABLE = "PRISM_KERNEL_WARMUP"
ENGINE = "PRISM"
START_DELAY_S = 2.0  # after registration: Blender finishes starting up first

_OWNER = object()  # owns this add-on's msgbus subscriptions


def enabled() -> bool:
    """Whether warm-ups start in this Blender (see the module docstring)."""
    setting = os.environ.get(ENVIRONMENT_VARIABLE, "").strip()
    if setting in {"0", "1"}:
        return setting == "1"
    return not bpy.app.background


def warm_up_for(scene) -> bool:
    """Start the warm-up if ``scene`` renders with Prism and it is enabled; True if a process started."""
    if scene is None or not enabled() or scene.render.engine != ENGINE:
        return False
    from . import launch

    try:
        return launch.start() is not None
    except Exception:  # noqa: BLE001 - a warm-up is an optimisation: never break Blender over it
        traceback.print_exc()
        return False


def engine_changed(*_) -> None:
    """msgbus: some scene's render engine changed (Blender says not which: the context's scene)."""
    warm_up_for(getattr(bpy.context, "scene", None))


def _subscribe() -> None:
    bpy.msgbus.clear_by_owner(_OWNER)
    bpy.msgbus.subscribe_rna(key=(bpy.types.RenderSettings, "engine"), owner=_OWNER, args=(),
                             notify=engine_changed)


@persistent
def file_loaded(*_) -> None:
    """load_post: subscribe again (loading dropped it) and warm up if the loaded scene uses Prism."""
    _subscribe()
    warm_up_for(bpy.context.scene)


def _check_after_start():
    warm_up_for(getattr(bpy.context, "scene", None))
    return None  # once


def register():
    _subscribe()
    bpy.app.handlers.load_post.append(file_loaded)
    scene = getattr(bpy.context, "scene", None)  # None under the restricted registration context
    if scene is not None:
        warm_up_for(scene)
    elif enabled() and not bpy.app.timers.is_registered(_check_after_start):
        bpy.app.timers.register(_check_after_start, first_interval=START_DELAY_S)


def unregister():
    if bpy.app.timers.is_registered(_check_after_start):
        bpy.app.timers.unregister(_check_after_start)
    if file_loaded in bpy.app.handlers.load_post:
        bpy.app.handlers.load_post.remove(file_loaded)
    bpy.msgbus.clear_by_owner(_OWNER)
