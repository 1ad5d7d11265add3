"""Prism's ``RenderEngine``: thin, it hands every render to a ``RenderSession``."""

import bpy


class PrismRenderEngine(bpy.types.RenderEngine):
    """Spectral path tracer: dispersive glass, real lenses, blackbody lights."""

    bl_idname = "PRISM"
    bl_label = "Prism"
    bl_use_preview = False
    bl_use_eevee_viewport = True

    def render(self, depsgraph):
        from .session import RenderSession

        RenderSession(self, depsgraph).run()


def register():
    bpy.utils.register_class(PrismRenderEngine)


def unregister():
    bpy.utils.unregister_class(PrismRenderEngine)
