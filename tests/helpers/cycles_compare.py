"""Rendering one bpy scene with Cycles and with Prism, and comparing the images by statistics.

Cycles is set up for comparisons as ``helpers/cycles.py`` does: CPU, box filter of 1 px, no adaptive
sampling, no denoising, no clamping, caustics on, single-scatter GGX wherever a node offers it (both
renderers then scatter once; Multiscatter GGX is compared on its own, ``test_multiscatter_cycles.py``),
bounce limits equal to Prism's. Images are compared normalised by their mean luminance
(the two renderers' absolute units may differ by a constant), per region (objects found by an ID render)
and by relative MSE.
"""

from __future__ import annotations

import bpy
import numpy as np

from .cycles import render_cycles_rgba, render_prism_rgba

LUMINANCE = np.array([0.2126729, 0.7151522, 0.0721750])


def single_scatter(scene=None) -> None:
    """Set every GGX-based node to single-scatter GGX (Cycles' default is multiscatter)."""
    for material in bpy.data.materials:
        if material.node_tree is None:
            continue
        for node in material.node_tree.nodes:
            if getattr(node, "distribution", None) == "MULTI_GGX":
                node.distribution = "GGX"


def render_cycles(scene, samples: int, max_bounces: int = 8, seed: int = 0) -> np.ndarray:
    """Scene-linear [H, W, 3] (row 0 on top) rendered by Cycles on the CPU, single-scatter GGX."""
    single_scatter(scene)
    return render_cycles_rgba(scene, samples, seed, max_bounces)[..., :3].astype(np.float64)


def render_prism(scene, samples: int, max_bounces: int = 8, seed: int = 0) -> np.ndarray:
    scene.prism.max_bounces = max_bounces
    return render_prism_rgba(scene, samples, seed)[..., :3].astype(np.float64)


def object_ids(scene, objects, samples: int = 16) -> np.ndarray:
    """int [H, W]: index into ``objects`` of the object each pixel sees entirely, or -1 (edges, others):
    a Cycles render with every object a distinct flat emission colour."""
    originals = {obj.name: [s.material for s in obj.material_slots] for obj in scene.objects if obj.type == "MESH"}
    black = _flat_emission("__id_black", (0.0, 0.0, 0.0))
    for obj in scene.objects:
        if obj.type == "MESH":
            for slot in obj.material_slots:
                slot.material = black
    for index, obj in enumerate(objects):
        code = ((index + 1) % 4 / 4.0, (index + 1) // 4 % 4 / 4.0, (index + 1) // 16 / 4.0)
        colour = _flat_emission(f"__id_{index}", code)
        for slot in obj.material_slots:
            slot.material = colour
    world = scene.world
    strength = None
    if world is not None and world.node_tree is not None and "Background" in world.node_tree.nodes:
        background = world.node_tree.nodes["Background"].inputs["Strength"]
        strength, background.default_value = background.default_value, 0.0
    hidden = [light for light in scene.objects if light.type == "LIGHT" and not light.hide_render]
    for light in hidden:
        light.hide_render = True
    image = render_cycles(scene, samples, max_bounces=1)
    for light in hidden:
        light.hide_render = False
    if strength is not None:
        world.node_tree.nodes["Background"].inputs["Strength"].default_value = strength
    for obj in scene.objects:
        if obj.name in originals:
            for slot, material in zip(obj.material_slots, originals[obj.name]):
                slot.material = material
    code = np.rint(image * 4.0)
    pure = np.all(np.abs(image * 4.0 - code) < 0.02, axis=-1)
    index = (code[..., 0] + 4 * code[..., 1] + 16 * code[..., 2]).astype(int) - 1
    return np.where(pure & (index >= 0) & (index < len(objects)), index, -1)


def _flat_emission(name, colour):
    material = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*colour, 1.0)
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(emission.outputs[0], output.inputs["Surface"])
    return material


def normalised(image):
    """The image divided by its mean luminance."""
    return image / float((image @ LUMINANCE).mean())


def relative_mse(a, b, eps=1e-2):
    """Mean of (a - b)² / (b² + eps) over pixels and channels."""
    return float(np.mean((a - b) ** 2 / (b * b + eps)))


def region_ratios(prism, cycles, ids, count, minimum_pixels=20):
    """{object index: mean luminance of ``prism`` / that of ``cycles`` over the object's pixels}."""
    lp, lc = prism @ LUMINANCE, cycles @ LUMINANCE
    ratios = {}
    for index in range(count):
        mask = ids == index
        if mask.sum() >= minimum_pixels:
            ratios[index] = float(lp[mask].mean() / lc[mask].mean())
    return ratios
