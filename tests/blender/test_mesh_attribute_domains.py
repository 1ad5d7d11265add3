"""Colour and Geometry Nodes attributes on every domain Cycles renders (point, face, corner), as float
colours, byte colours (sRGB-encoded bytes, read scene-linear) and plain floats/vectors, reach node
materials: flat emissive cards whose Emission colour is the attribute render the attribute's value (closed
form: strength 1, camera-facing card, box filter), and Cycles renders the same mean luminance.

The point domain is what Add Color Attribute creates by default in Blender 4.x; it used to crash the
export (the per-corner gather kept an extra axis)."""

from __future__ import annotations

import bpy
import numpy as np

from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import black_world, emission_material, node, plane, socket

# (card name, attribute type, domain, node reading it, output socket, value set, expected linear RGB)
_CARDS = [
    ("point colour", "FLOAT_COLOR", "POINT", "ShaderNodeVertexColor", "Color", (0.8, 0.3, 0.1, 1.0),
     (0.8, 0.3, 0.1)),
    ("point bytes", "BYTE_COLOR", "POINT", "ShaderNodeAttribute", "Color", (0.5, 0.5, 0.5, 1.0),
     (0.2140, 0.2140, 0.2140)),  # sRGB 0.5 (byte 128 → 0.50196) decodes to 0.2159 linear
    ("face float", "FLOAT", "FACE", "ShaderNodeAttribute", "Fac", 0.6, (0.6, 0.6, 0.6)),
    ("corner vector", "FLOAT_VECTOR", "CORNER", "ShaderNodeAttribute", "Vector", (0.2, 0.5, 0.7),
     (0.2, 0.5, 0.7)),
]
_BYTE_LINEAR = ((0.50196 + 0.055) / 1.055) ** 2.4


def _card(index, name, data_type, domain, node_kind, output, value):
    def build(nodes, link):
        reader = node(nodes, node_kind)
        if node_kind == "ShaderNodeVertexColor":
            reader.layer_name = "paint"
        else:
            reader.attribute_name = "paint"
        return socket(reader, output, output=True)

    obj = plane(name, 1.0, location=(index * 1.2 - 1.8, 0.0, 0.0), mat=emission_material(name, build))
    mesh = obj.data
    if data_type in ("FLOAT_COLOR", "BYTE_COLOR"):
        attribute = mesh.color_attributes.new("paint", data_type, domain)
        mesh.color_attributes.active_color = attribute
        key = "color_srgb" if data_type == "BYTE_COLOR" else "color"
    else:
        attribute = mesh.attributes.new("paint", data_type, domain)
        key = "value" if data_type == "FLOAT" else "vector"
    flat = np.tile(np.atleast_1d(np.asarray(value, np.float32)), len(attribute.data))
    attribute.data.foreach_set(key, flat)
    return obj


def _scene(scene):
    black_world()
    for index, card in enumerate(_CARDS):
        _card(index, *card[:6])
    cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    cam.data.type, cam.data.ortho_scale = "ORTHO", 4.8
    cam.location = (0.0, 0.0, 5.0)
    scene.collection.objects.link(cam)
    scene.camera = cam
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 48, 10, 100
    scene.render.filter_size = 0.01  # no blur across card edges: each centre pixel sees one card


def _card_means(image):
    """Mean RGB of the 4 × 4 pixels at each card's centre ([4, 3])."""
    height, width = image.shape[:2]
    means = []
    for index in range(len(_CARDS)):
        x_m = index * 1.2 - 1.8
        column = int(round((x_m / 4.8 + 0.5) * width - 0.5))
        row = height // 2
        means.append(image[row - 2:row + 2, column - 2:column + 2, :3].reshape(-1, 3).mean(axis=0))
    return np.array(means)


def test_attributes_on_every_domain_render_their_value(prism_addon, fresh_scene):
    _scene(fresh_scene)
    prism = _card_means(render_prism_rgba(fresh_scene, samples=4))
    expected = np.array([card[6] for card in _CARDS])
    expected[1] = _BYTE_LINEAR
    # RGB → spectrum → CIE → Rec.709 round trip: a few per cent per channel at most.
    assert np.allclose(prism, expected, rtol=0.04, atol=0.004), (prism, expected)


def test_point_colour_attribute_matches_cycles_in_absolute_luminance(prism_addon, fresh_scene):
    _scene(fresh_scene)
    prism = luminance(_card_means(render_prism_rgba(fresh_scene, samples=4)))
    cycles = luminance(_card_means(render_cycles_rgba(fresh_scene, samples=4)))
    ratios = prism / cycles
    print("prism / cycles mean luminance per card:", dict(zip([c[0] for c in _CARDS], ratios.round(4))))
    assert np.all(np.abs(ratios - 1.0) < 0.02), ratios
