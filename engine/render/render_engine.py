"""Prism's ``RenderEngine``: thin, it hands every render to a ``RenderSession``, every bake to a
``BakeSession`` and the rendered viewport to a ``ViewportSession``."""

import sys

import bpy

from .result_passes import COMBINED, enabled_passes


class PrismRenderEngine(bpy.types.RenderEngine):
    """Spectral path tracer: dispersive glass, real lenses, blackbody lights."""

    bl_idname = "PRISM"
    bl_label = "Prism"
    bl_use_preview = True  # material and light previews render with Prism (fast settings)
    bl_use_eevee_viewport = True  # Material Preview shading stays EEVEE's; Rendered is Prism's
    # Prism renders Blender's own shader node trees: False makes ShaderNodeTree's poll accept the scene
    # (Blender's default for a Python engine, True, hides the Shader Editor as for an engine with its own
    # node system). Cycles needs no flag: Blender names it in that poll.
    bl_use_shading_nodes_custom = False

    def render(self, depsgraph):
        from .request import handed_over
        from .session import RenderSession

        RenderSession(self, depsgraph, *handed_over()).run()

    def bake(self, depsgraph, object, pass_type, pass_filter, width, height):  # noqa: A002 - Blender's name
        from .bake_session import BakeSession

        BakeSession(self, depsgraph, object, pass_type, pass_filter, width, height).run()

    def view_update(self, context, depsgraph):
        from ..viewport.session import session_of

        session_of(self).view_update(context, depsgraph)

    def view_draw(self, context, depsgraph):
        from ..viewport.session import session_of

        session_of(self).view_draw(self, context, depsgraph)

    def update_render_passes(self, scene=None, renderlayer=None):
        name, ids, kind = COMBINED
        self.register_pass(scene, renderlayer, name, len(ids), ids, kind)
        for name, channels, ids, kind in enabled_passes(scene, renderlayer):
            self.register_pass(scene, renderlayer, name, channels, ids, kind)


def register():
    bpy.utils.register_class(PrismRenderEngine)


def unregister():
    viewport = sys.modules.get(f"{__package__.rsplit('.', 1)[0]}.viewport.session")  # <add-on>.engine.viewport
    if viewport is not None:  # never imported when no viewport rendered
        viewport.stop_all()
    bpy.utils.unregister_class(PrismRenderEngine)
