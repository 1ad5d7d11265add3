"""World node trees for the Blender tests: an equirectangular image, a Nishita sky, with Mapping."""

from __future__ import annotations

import bpy
import numpy as np


def hot_spot_hdri(width=64, height=32, sun_texel=(9, 40), sun_value=(2400.0, 2200.0, 1900.0)):
    """float32 [H, W, 3], row 0 at the zenith: a blue-to-white sky, a darker brown ground and a 2 x 2 texel
    hot region (a small sun) at texel row/column ``sun_texel``."""
    rows = (np.arange(height) + 0.5) / height  # 0 = zenith
    sky = np.stack([0.25 + 0.35 * rows, 0.35 + 0.35 * rows, 0.6 + 0.2 * rows], axis=-1)
    ground = np.array([0.12, 0.09, 0.06])
    column = np.where((rows < 0.5)[:, None], sky, ground)
    image = np.repeat(column[:, None, :], width, axis=1).astype(np.float32)
    r, c = sun_texel
    image[r:r + 2, c:c + 2] = sun_value
    return image


def blender_image(name: str, rgb: np.ndarray):
    """A packed float image of ``rgb`` [H, W, 3] (row 0 on top), scene-linear."""
    height, width, _ = rgb.shape
    image = bpy.data.images.new(name, width, height, alpha=True, float_buffer=True)
    rgba = np.ones((height, width, 4), np.float32)
    rgba[..., :3] = rgb
    image.pixels.foreach_set(rgba[::-1].ravel())
    image.pack()
    return image


def environment_world(image, strength=1.0, rotation=None, scale=None, interpolation="Linear"):
    """A world whose Background shows ``image`` through an Environment Texture (and a Mapping node when
    ``rotation`` / ``scale`` are given)."""
    world = bpy.data.worlds.new("HDRI")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    background = nodes["Background"]
    background.inputs["Strength"].default_value = strength
    texture = nodes.new("ShaderNodeTexEnvironment")
    texture.image = image
    texture.interpolation = interpolation
    links.new(texture.outputs["Color"], background.inputs["Color"])
    if rotation is not None or scale is not None:
        coordinates = nodes.new("ShaderNodeTexCoord")
        mapping = nodes.new("ShaderNodeMapping")
        mapping.inputs["Rotation"].default_value = rotation or (0.0, 0.0, 0.0)
        mapping.inputs["Scale"].default_value = scale or (1.0, 1.0, 1.0)
        links.new(coordinates.outputs["Generated"], mapping.inputs["Vector"])
        links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    bpy.context.scene.world = world
    return world


def sky_world(strength=1.0, **settings):
    """A world whose Background shows a Nishita Sky Texture with ``settings`` (node property names)."""
    world = bpy.data.worlds.new("Sky")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    background = nodes["Background"]
    background.inputs["Strength"].default_value = strength
    sky = nodes.new("ShaderNodeTexSky")
    sky.sky_type = "NISHITA"
    for name, value in settings.items():
        setattr(sky, name, value)
    links.new(sky.outputs["Color"], background.inputs["Color"])
    bpy.context.scene.world = world
    return world
