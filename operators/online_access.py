"""Blender's Allow Online Access preference (``bpy.app.online_access``, Blender 4.2+): an extension that
declares the ``network`` permission must still make no connection while the user has it off. The Farm
panel and ``prism.farm_submit`` ask here before any HTTP to the Flamenco Manager."""

from __future__ import annotations

import bpy

OFFLINE_MESSAGE = (
    "Farm: online access is off, so Prism does not contact the Flamenco Manager: turn on Preferences ▸ System ▸ "
    "Network ▸ Allow Online Access (or start Blender with --online-mode)."
)


def online_access_allowed() -> bool:
    """True when Blender allows extensions to connect (always on Blender before 4.2, which lacks the
    setting). Read at call time: the user may change it while Blender runs."""
    return bool(getattr(bpy.app, "online_access", True))
