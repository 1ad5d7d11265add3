"""While Prism is the scene's render engine the Shader Editor is offered and shows the material's node tree,
as with Cycles: Blender's ShaderNodeTree poll accepts an engine only when it declares
``bl_use_shading_nodes_custom = False`` (Cycles is named in the poll itself; a Python engine defaults to
True, "uses its own nodes", and the Shader Editor disappears from the editor-type menu)."""

from __future__ import annotations

import bpy


def _editor_types(scene, engine):
    """The editor types Blender offers an area (Area.ui_type's items, polled in context) with ``engine``."""
    scene.render.engine = engine
    area = bpy.context.screen.areas[0]
    with bpy.context.temp_override(area=area, space_data=area.spaces.active):
        try:
            area.ui_type = "no such editor"
        except TypeError as error:  # the message lists the valid items, as polled now
            return str(error)
    raise AssertionError("an unknown editor type was accepted")


def test_engine_declares_blender_shader_nodes(prism_addon):
    engine = prism_addon.engine.render.render_engine.PrismRenderEngine
    assert engine.bl_use_shading_nodes_custom is False
    assert engine.bl_use_eevee_viewport is True  # Material Preview stays EEVEE's, as Cycles declares


def test_shader_editor_is_offered_with_prism_as_with_cycles(prism_addon):
    bpy.ops.wm.read_homefile(use_factory_startup=True)  # a screen with areas, unlike the empty home file
    scene = bpy.context.scene
    assert "'ShaderNodeTree'" in _editor_types(scene, "CYCLES")
    assert "'ShaderNodeTree'" in _editor_types(scene, "PRISM")
