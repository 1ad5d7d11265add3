"""The Wavelength node against Cycles in absolute values: squares of emission coloured by the node at fixed
wavelengths (inside the visible range, in Cycles' extrapolated 375-380 nm interval, beyond 780 nm) and one
square whose wavelength varies across it (400-700 nm from its UV), rendered by both engines from the same
scene. Before, Prism read the node's colour as 0 (black) with a warning."""

from __future__ import annotations

import bpy
import numpy as np
import pytest

from helpers.cycles import render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import black_world, emission_material, node, plane

FIXED_NM = (450.0, 520.0, 589.0, 650.0, 377.0, 800.0)
SQUARE_PX = 24
MARGIN = 3


def _fixed(nm):
    def build(nodes, link):
        return node(nodes, "ShaderNodeWavelength", Wavelength=nm).outputs["Color"]
    return build


def _varying(nodes, link):
    """Wavelength 400 + 300 u across the square."""
    coordinates = node(nodes, "ShaderNodeTexCoord")
    separate = node(nodes, "ShaderNodeSeparateXYZ")
    scale = node(nodes, "ShaderNodeMath")
    scale.operation = "MULTIPLY_ADD"
    scale.inputs[1].default_value, scale.inputs[2].default_value = 300.0, 400.0
    wavelength = node(nodes, "ShaderNodeWavelength")
    link(coordinates.outputs["UV"], separate.inputs["Vector"])
    link(separate.outputs["X"], scale.inputs[0])
    link(scale.outputs[0], wavelength.inputs["Wavelength"])
    return wavelength.outputs["Color"]


def _squares(builds):
    scene = bpy.context.scene
    black_world()
    for k, build in enumerate(builds):
        plane(f"Square {k}", 1.0, location=(k * 1.0 + 0.5, 0.0, 0.0), mat=emission_material(f"Colour {k}", build))
    data = bpy.data.cameras.new("Front")
    data.type, data.ortho_scale = "ORTHO", float(len(builds))
    camera = bpy.data.objects.new("Front", data)
    camera.location = (len(builds) / 2.0, 0.0, 5.0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    scene.render.resolution_x, scene.render.resolution_y = SQUARE_PX * len(builds), SQUARE_PX
    scene.render.resolution_percentage = 100


def _square(rgba, k):
    return rgba[MARGIN:SQUARE_PX - MARGIN, k * SQUARE_PX + MARGIN:(k + 1) * SQUARE_PX - MARGIN, :3]


def test_wavelength_node_colours_match_cycles(prism_addon, fresh_scene):
    _squares([_fixed(nm) for nm in FIXED_NM] + [_varying])
    cycles = render_cycles_rgba(fresh_scene, 16)
    prism = render_prism_rgba(fresh_scene, 16)
    for k, nm in enumerate(FIXED_NM):
        c, p = _square(cycles, k).reshape(-1, 3).mean(axis=0), _square(prism, k).reshape(-1, 3).mean(axis=0)
        print(f"{nm} nm: cycles {np.round(c, 4)} prism {np.round(p, 4)}")
        assert p == pytest.approx(c, rel=0.03, abs=0.006), nm
    assert _square(cycles, 5).max() == 0.0 and np.abs(_square(prism, 5)).max() < 1e-6, "black beyond 780 nm"
    # the varying square in bands of two pixel columns (25 nm each; a pixel's colour varies steeply within it)
    varying = len(FIXED_NM)
    c, p = (_square(image, varying).mean(axis=0).reshape(-1, 2, 3).mean(axis=1) for image in (cycles, prism))
    print("varying square, largest difference per channel:", np.round(np.abs(p - c).max(axis=0), 4))
    assert np.abs(p - c).max() < 0.01 and np.abs(p.sum(axis=0) - c.sum(axis=0)).max() < 0.02 * c.sum()
