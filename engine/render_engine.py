"""Prism's ``RenderEngine``: thin, it hands every render to a ``RenderSession`` and the rendered
viewport to a ``ViewportSession``."""

import sys

import bpy

NOISE_PASS = ("Noise", 3, "RGB", "COLOR")
SAMPLE_COUNT_PASS = ("Sample Count", 1, "X", "VALUE")


def enabled_passes(scene) -> list[tuple[str, int, str, str]]:
    """The optional passes (name, channels, channel ids, type) the scene asks for."""
    prism = getattr(scene, "prism", None)
    passes = []
    if prism is not None and prism.use_pass_variance:
        passes.append(NOISE_PASS)
    if prism is not None and prism.use_pass_sample_count:
        passes.append(SAMPLE_COUNT_PASS)
    return passes


class PrismRenderEngine(bpy.types.RenderEngine):
    """Spectral path tracer: dispersive glass, real lenses, blackbody lights."""

    bl_idname = "PRISM"
    bl_label = "Prism"
    bl_use_preview = True  # material and light previews render with Prism (fast settings)
    bl_use_eevee_viewport = True  # Material Preview shading stays EEVEE's; Rendered is Prism's

    def render(self, depsgraph):
        from .render_request import handed_over
        from .session import RenderSession

        RenderSession(self, depsgraph, *handed_over()).run()

    def view_update(self, context, depsgraph):
        from .viewport.session import session_of

        session_of(self).view_update(context, depsgraph)

    def view_draw(self, context, depsgraph):
        from .viewport.session import session_of

        session_of(self).view_draw(self, context, depsgraph)

    def update_render_passes(self, scene=None, renderlayer=None):
        self.register_pass(scene, renderlayer, "Combined", 4, "RGBA", "COLOR")
        for name, channels, ids, kind in enabled_passes(scene):
            self.register_pass(scene, renderlayer, name, channels, ids, kind)


def register():
    bpy.utils.register_class(PrismRenderEngine)


def unregister():
    viewport = sys.modules.get(f"{__package__}.viewport.session")
    if viewport is not None:  # never imported when no viewport rendered
        viewport.stop_all()
    bpy.utils.unregister_class(PrismRenderEngine)
