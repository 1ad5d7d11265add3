"""World fog scenes built in bpy: a black world whose Volume is one node, and the grey floor in white fog lit by
a point light above and behind the camera that Prism and Cycles render alike. Shared by
tests/blender/test_world_fog.py and the benchmark experiment media_vs_cycles."""

from __future__ import annotations

import bpy

from helpers.bpy_scenes import add_camera, add_plane, add_point_light

FLOOR_RESOLUTION = (32, 24)


def fog_world(kind, **inputs):
    """A black world whose Volume is one ``kind`` node with ``inputs`` (names with spaces as given)."""
    world = bpy.data.worlds.new("Fog")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    nodes["Background"].inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    volume = nodes.new(kind)
    for name, value in inputs.items():
        volume.inputs[name].default_value = value
    links.new(volume.outputs[0], nodes["World Output"].inputs["Volume"])
    bpy.context.scene.world = world
    return world


def lit_floor(light, resolution=FLOOR_RESOLUTION):
    """An 8 m grey floor (albedo 0.5, no specular), ``light()`` adding its light, a camera 4 m back looking down."""
    add_plane("Floor", 8.0, color=(0.5, 0.5, 0.5), specular=0.0)
    light()
    add_camera((0.0, -4.0, 2.0), (1.2, 0.0, 0.0), resolution=resolution)


def point_light_in_fog(resolution=FLOOR_RESOLUTION):
    """The floor in white scattering fog (Volume Scatter, density 0.15 /m) lit by a 400 W point light above and
    behind the camera (out of the view); the scene."""
    fog_world("ShaderNodeVolumeScatter", Density=0.15, Color=(1.0, 1.0, 1.0, 1.0))
    lit_floor(lambda: add_point_light("Bulb", 400.0, (0.0, -5.0, 3.5)), resolution)
    return bpy.context.scene
