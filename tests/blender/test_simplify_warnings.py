"""Cycles settings Cycles applies at sync and Prism does not (Render ▸ Simplify ▸ Texture Limit and Culling, Light
Paths ▸ Fast GI Approximation): each named in a warning, with what Prism renders instead, only when it would change
Cycles' image of the scene."""

from __future__ import annotations

import importlib

import bpy
import numpy as np

from helpers.node_scenes import camera, material, node, plane


def _textured_plane(size_px):
    """A plane whose Principled Base Color reads an image of ``size_px`` × ``size_px // 2``, a camera and a grey
    world."""
    image = bpy.data.images.new("Bricks", size_px, size_px // 2)
    image.pixels.foreach_set(np.full(size_px * size_px // 2 * 4, 0.5, np.float32))
    mat, nodes, link = material("Bricks")
    texture = node(nodes, "ShaderNodeTexImage")
    texture.image = image
    principled = node(nodes, "ShaderNodeBsdfPrincipled")
    link(texture.outputs["Color"], principled.inputs["Base Color"])
    link(principled.outputs[0], nodes["Output"].inputs["Surface"])
    floor = plane("Floor", 2.0, mat=mat)
    camera((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), resolution=(8, 8))
    bpy.context.scene.world = bpy.data.worlds.new("Grey")
    bpy.context.scene.world.color = (0.5, 0.5, 0.5)
    return floor


def _warnings(prism_addon):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    warnings = []
    export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    return warnings


def _about(warnings, text):
    return [w for w in warnings if text in w]


def test_a_texture_limit_that_would_shrink_an_image_is_named(prism_addon, fresh_scene):
    """Texture Limit 256 with a 512 px image in use: named, with Cycles' halving; 1024, or Simplify off: silent."""
    _textured_plane(512)
    cycles = fresh_scene.cycles
    cycles.texture_limit_render = "256"
    assert not _about(_warnings(prism_addon), "Texture Limit")  # Simplify is off: Cycles ignores the limit too
    fresh_scene.render.use_simplify = True
    found = _about(_warnings(prism_addon), "Texture Limit")
    assert len(found) == 1 and "Texture Limit 256 px is not applied" in found[0] and "'Bricks'" in found[0], found
    cycles.texture_limit_render = "1024"
    assert not _about(_warnings(prism_addon), "Texture Limit")


def test_culling_of_an_object_that_allows_it_is_named(prism_addon, fresh_scene):
    """Camera Culling on in Simplify and on the object: the object is named; the object's own switch off: silent."""
    floor = _textured_plane(64)
    fresh_scene.render.use_simplify = True
    fresh_scene.cycles.use_camera_cull = True
    assert not _about(_warnings(prism_addon), "Culling")
    floor.cycles.use_camera_cull = True
    found = _about(_warnings(prism_addon), "Culling")
    assert len(found) == 1 and "Camera Culling (margin 0.1)" in found[0] and "'Floor'" in found[0], found
    fresh_scene.render.use_simplify = False
    assert not _about(_warnings(prism_addon), "Culling")


def test_fast_gi_is_named_with_its_bounces(prism_addon, fresh_scene):
    """Fast GI Approximation on (AO Bounces 1 by default): named; AO Bounces 0, which disables it: silent."""
    _textured_plane(64)
    cycles = fresh_scene.cycles
    assert not _about(_warnings(prism_addon), "Fast GI")
    cycles.use_fast_gi = True
    found = _about(_warnings(prism_addon), "Fast GI")
    assert len(found) == 1 and "after 1 bounce with the World's ambient occlusion" in found[0], found
    cycles.ao_bounces_render = 0
    assert not _about(_warnings(prism_addon), "Fast GI")
