"""A material with only its Volume linked (no Surface) is a null surface around a medium, as Cycles renders
a volume's missing surface; a density driven by what a point inside a volume does not have (the Normal) is
rendered at the socket's own value and warned, naming the material, node and input (a Noise Texture's is baked:
``test_textured_volume.py``)."""

from __future__ import annotations

import importlib

import bpy
import pytest

from helpers.batch_outcome import batch_warning
from helpers.bpy_scenes import add_camera, add_plane, add_point_light, shader_material
from helpers.error_scenes import base_scene
from helpers.node_scenes import black_world


def _volume_only(obj, density=1.0):
    """Replace ``obj``'s material by one whose Material Output has a Principled Volume of ``density`` and no
    Surface."""
    material = shader_material("Fog", "ShaderNodeVolumePrincipled", output="Volume", Density=density)
    obj.data.materials[0] = material
    return material


EXPECTED_WARNING = ("Material 'Fog': the 'Principled Volume' node (Principled Volume) has its Density driven by "
                    "nodes that read Normal, which a point inside a volume does not have (no surface there, and the "
                    "ray's direction changes); Prism uses the Density set on the socket, 1, throughout the volume.")


def test_a_volume_only_material_compiles_to_a_null_surface_around_a_medium(prism_addon, fresh_scene, bad_input,
                                                                           capsys, tmp_path):
    base_scene()
    material = _volume_only(bpy.data.objects["Floor"])
    nodes = importlib.import_module(f"{prism_addon.__name__}.engine.export.nodes")
    closure = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.bsdf.closure")
    compiled = nodes.compile_material(material, load_pixels=False)
    assert [spec.kind for spec in compiled.shader.closures] == [closure.TRANSPARENT]
    assert tuple(compiled.shader.closures[0].tint.rgb) == (1.0, 1.0, 1.0)
    assert compiled.warnings == []
    assert compiled.medium.scatter == [(1.0, (0.5, 0.5, 0.5))]  # Principled Volume's defaults
    volume = material.node_tree.nodes["Principled Volume"]
    geometry = material.node_tree.nodes.new("ShaderNodeNewGeometry")
    material.node_tree.links.new(geometry.outputs["Normal"], volume.inputs["Density"])
    compiled = nodes.compile_material(material, load_pixels=False)
    assert compiled.warnings == [EXPECTED_WARNING]
    bad_input("material whose Principled Volume Density is driven by the Normal",
              *batch_warning(capsys, tmp_path, EXPECTED_WARNING))


def test_a_volume_only_card_lets_the_floor_show_through_as_in_cycles(prism_addon, fresh_scene):
    """A lit grey floor, half covered (as the camera sees it) by a volume-only card: Cycles and Prism show the
    floor through the card; before, Prism drew an opaque black card. The volume's density is 0: an open card
    has no inside, so Cycles' fog would fill everything behind it (media fill closed meshes only)."""
    from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba

    black_world()
    add_plane("Floor", 4.0, specular=0.0)
    card = add_plane("Card", 1.0, location=(0.5, 0.0, 1.0))
    _volume_only(card, density=0.0)
    add_point_light("Bulb", 200.0, (0.0, 0.0, 3.0))
    add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), lens_mm=50.0, resolution=(16, 8))
    cycles = luminance(render_cycles_rgba(fresh_scene, 16))
    prism = luminance(render_prism_rgba(fresh_scene, 16))
    right = (slice(2, 6), slice(10, 14))  # behind the card
    print(f"MEASURED behind the volume-only card: Prism {prism[right].mean():.4f}, Cycles {cycles[right].mean():.4f}")
    assert cycles[right].mean() > 0.05
    assert prism[right].mean() / cycles[right].mean() == pytest.approx(1.0, abs=0.05)
