"""Prism's ``RenderEngine``: thin, it hands every render to a ``RenderSession``."""

import bpy

from .passes import COMBINED, enabled_passes


class PrismRenderEngine(bpy.types.RenderEngine):
    """Spectral path tracer: dispersive glass, real lenses, blackbody lights."""

    bl_idname = "PRISM"
    bl_label = "Prism"
    # Material/light previews are drawn by EEVEE: a spectral preview would cost seconds per icon.
    bl_use_preview = False
    bl_use_eevee_viewport = True

    def render(self, depsgraph):
        from .render_request import handed_over
        from .session import RenderSession

        RenderSession(self, depsgraph, *handed_over()).run()

    def update_render_passes(self, scene=None, renderlayer=None):
        name, ids, kind = COMBINED
        self.register_pass(scene, renderlayer, name, len(ids), ids, kind)
        for name, channels, ids, kind in enabled_passes(scene, renderlayer):
            self.register_pass(scene, renderlayer, name, channels, ids, kind)


def register():
    bpy.utils.register_class(PrismRenderEngine)


def unregister():
    bpy.utils.unregister_class(PrismRenderEngine)
