"""Which emitters light a shadow catcher's pass (Cycles' SHADER_EXCLUDE_SHADOW_CATCHER).

The copy of a camera path that shades a shadow catcher for its pass (``state.CATCHER_PASS``,
``stages.shadow_catcher``) sees the scene without its other objects: a Blender light whose object is not
a shadow catcher (Object ▸ Visibility ▸ Shadow Catcher of the light; on by default) and every emissive
triangle of an object that is not one neither light it nor are seen by it; the world and its sun discs
do (Cycles makes the world a catcher). ``LightArrays.catcher_excluded`` holds the answer per emitter.
"""

from __future__ import annotations

from .jit import inlined
from .state import CATCHER_PASS


@inlined
def excluded_from_catcher(state, i, settings, lights, emitter):
    """Whether ``emitter`` (a light row, or rows + a render primitive) brings path ``i`` no light because the
    path is a shadow catcher pass copy and the emitter is not part of the catcher's world."""
    return settings.shadow_catcher and state.flags[i] & CATCHER_PASS != 0 and lights.catcher_excluded[emitter] != 0
