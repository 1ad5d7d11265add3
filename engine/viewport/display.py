"""The viewport's latest image drawn in ``view_draw``: the only gpu calls of the rendered viewport.

The image stays scene-linear. ``RenderEngine.bind_display_space_shader`` binds the shader Blender
wants an engine's pixels drawn with (since Blender 2.91 its builtin IMAGE shader), and Blender then
passes the region's float buffer through the scene's display device, view transform (AgX, Filmic,
Standard), look, exposure and gamma when it shows the viewport, as it does for Cycles. Each frame is
uploaded once as a half-float texture (values above 1 survive for the view transform) and drawn over
the whole region, stretched when it is a coarse one (the texture filter smooths it), with
premultiplied alpha: outside the render border, alpha 0, nothing is drawn.
"""

from __future__ import annotations

_UNIT_SQUARE = ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0))


class FrameDisplay:
    """Keeps the texture of the frame last drawn (GPU resources live in the draw callback's context)."""

    def __init__(self):
        self._frame = None
        self._texture = None
        self._batch = None

    def draw(self, engine, scene, frame, width: int, height: int) -> bool:
        """Draw ``frame`` (a ``progressive.Frame``) over a ``width`` x ``height`` pixel region with the
        current (region pixel space) matrices; returns whether something was drawn."""
        import gpu
        from gpu_extras.batch import batch_for_shader

        if frame is None:
            return False
        if frame is not self._frame:
            pixels = gpu.types.Buffer("FLOAT", frame.rgba.size, frame.rgba.reshape(-1))
            self._texture = gpu.types.GPUTexture((frame.width, frame.height), format="RGBA16F", data=pixels)
            self._frame = frame
        shader = gpu.shader.from_builtin("IMAGE")
        if self._batch is None:
            self._batch = batch_for_shader(shader, "TRI_STRIP", {"pos": _UNIT_SQUARE, "texCoord": _UNIT_SQUARE})
        gpu.state.blend_set("ALPHA_PREMULT")
        engine.bind_display_space_shader(scene)
        try:
            shader.uniform_sampler("image", self._texture)
            with gpu.matrix.push_pop():
                gpu.matrix.scale((float(width), float(height)))
                self._batch.draw(shader)
        finally:
            engine.unbind_display_space_shader()
            gpu.state.blend_set("NONE")
        return True

    def free(self) -> None:
        self._frame = self._texture = self._batch = None
