"""Blender's Light Path node in materials, as Cycles 4.5 renders it: the usual tricks (a lamp the camera does
not see, a card that casts no shadow) and the outputs read as colours (Ray Length, Ray Depth, Transparent
Depth), rendered by Cycles and by Prism from the same .blend and compared in absolute light and with the
closed forms."""

from __future__ import annotations

import math

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane, add_point_light, shader_material
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba

SAMPLES = 64


def _light_path_material(name):
    """(material, its nodes, its links, a Light Path node): a node material without its Principled BSDF."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    return material, nodes, links, nodes.new("ShaderNodeLightPath")


def _mix_material(name, output, first, second):
    """A material whose Mix Shader takes Light Path ▸ ``output`` as its factor: ``first`` where it is 0,
    ``second`` where it is 1 (each a (node type, {input: value}) pair)."""
    material, nodes, links, path = _light_path_material(name)
    mix = nodes.new("ShaderNodeMixShader")
    links.new(path.outputs[output], mix.inputs["Fac"])
    for slot, (kind, values) in ((1, first), (2, second)):
        shader = nodes.new(kind)
        for socket, value in values.items():
            shader.inputs[socket].default_value = value
        links.new(shader.outputs[0], mix.inputs[slot])
    links.new(mix.outputs[0], nodes["Material Output"].inputs["Surface"])
    return material


def _dark_world(scene):
    scene.world = bpy.data.worlds.new("Dark")
    scene.world.color = (0.0, 0.0, 0.0)


def _both(scene, bounces=4):
    cycles = render_cycles_rgba(scene, SAMPLES, max_bounces=bounces)
    scene.prism.max_bounces = bounces
    return render_prism_rgba(scene, SAMPLES), cycles


def test_is_camera_ray_hides_a_lamp_from_the_camera(prism_addon, fresh_scene):
    """An emissive panel over a grey floor, Emission for every ray but camera rays (Transparent for them):
    the camera sees the floor through the panel, lit by it as if the panel were a plain lamp."""
    _dark_world(fresh_scene)
    add_plane("Floor", 6.0, color=(0.5, 0.5, 0.5), specular=0.0)
    panel = add_plane("Panel", 1.0, location=(0.0, 0.0, 1.0))
    panel.rotation_euler = (math.pi, 0.0, 0.0)  # emitting downwards
    panel.data.materials[0] = _mix_material("Hidden lamp", "Is Camera Ray",
                                            ("ShaderNodeEmission", {"Strength": 10.0}), ("ShaderNodeBsdfTransparent", {}))
    add_camera((0.0, -2.5, 2.5), (0.8, 0.0, 0.0), resolution=(32, 24))
    prism, cycles = _both(fresh_scene)
    p, c = luminance(prism).mean(), luminance(cycles).mean()
    print(f"MEASURED hidden lamp: Prism {p:.4f}, Cycles {c:.4f}, ratio {p / c:.4f}")
    assert p == pytest.approx(c, rel=0.02)
    # Nothing in the image is brighter than the lit floor can be (ρ/π · L · π = 0.5 · 10 at most): the panel is
    # not seen; the floor under the lamp is lit.
    assert luminance(prism).max() < 5.0 and luminance(prism).max() > 0.5


def test_is_camera_ray_the_other_way_shows_a_lamp_that_lights_nothing(prism_addon, fresh_scene):
    """The same panel with the shaders swapped: the camera sees it glow (strength 10 towards the camera),
    and nothing else: every other ray, light sampling included, finds it transparent, so the floor is black."""
    _dark_world(fresh_scene)
    add_plane("Floor", 6.0, color=(0.5, 0.5, 0.5), specular=0.0)
    add_plane("Panel", 1.0, location=(0.0, 0.0, 1.0)).data.materials[0] = _mix_material(
        "Seen only", "Is Camera Ray", ("ShaderNodeBsdfTransparent", {}), ("ShaderNodeEmission", {"Strength": 10.0}))
    add_camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), resolution=(32, 24))
    prism, cycles = _both(fresh_scene)
    glow = luminance(prism)[10:14, 14:18]  # the panel's middle
    floor = luminance(prism)[:, :4]  # the floor beside it
    print(f"MEASURED seen-only lamp: glow {glow.mean():.4f} (Cycles {luminance(cycles)[10:14, 14:18].mean():.4f}), "
          f"floor max {floor.max():.6f}")
    assert glow.mean() == pytest.approx(10.0, rel=0.01)
    assert np.all(floor == 0.0)
    assert luminance(prism).mean() == pytest.approx(luminance(cycles).mean(), rel=0.02)


def test_is_shadow_ray_makes_a_card_cast_no_shadow(prism_addon, fresh_scene):
    """A red card over a grey floor lit by a point light, Transparent for shadow rays: the camera sees the
    card, and the floor under it is lit as the closed form ρ/π · I cos θ / r² says, with no shadow."""
    _dark_world(fresh_scene)
    albedo, power, height = 0.5, 200.0, 2.0
    add_plane("Floor", 6.0, color=(albedo,) * 3, specular=0.0)
    add_plane("Card", 0.8, location=(0.0, 0.0, 1.0)).data.materials[0] = _mix_material(
        "No shadow", "Is Shadow Ray", ("ShaderNodeBsdfDiffuse", {"Color": (0.8, 0.1, 0.1, 1.0)}),
        ("ShaderNodeBsdfTransparent", {}))
    add_point_light("Bulb", power, (0.0, 0.0, height))
    add_camera((0.0, -3.0, 3.0), (0.75, 0.0, 0.0), resolution=(32, 24))
    prism, cycles = _both(fresh_scene, bounces=1)
    p, c = luminance(prism).mean(), luminance(cycles).mean()
    card = prism[..., 0] > 2.0 * prism[..., 1]  # red pixels: the card seen
    print(f"MEASURED no-shadow card: Prism {p:.4f}, Cycles {c:.4f}, ratio {p / c:.4f}; card pixels {int(card.sum())}")
    assert card.sum() > 20
    assert p == pytest.approx(c, rel=0.02)
    # Straight under the light (floor point below the card): irradiance I / h², radiance ρ/π · that.
    direct = albedo / math.pi * power / (4.0 * math.pi) / height ** 2
    export_check = render_prism_rgba(_top_view(fresh_scene), SAMPLES)
    centre = luminance(export_check)[10:14, 14:18].mean()
    print(f"MEASURED under the card: {centre:.4f}, closed form {direct:.4f}")
    assert centre == pytest.approx(direct, rel=0.03)


def _top_view(scene):
    """The scene seen straight down from under the card (the camera between card and floor, 0.5 m up)."""
    camera = scene.camera
    camera.location, camera.rotation_euler = (0.0, 0.0, 0.5), (0.0, 0.0, 0.0)
    camera.data.lens = 200.0  # a narrow view: the floor within ±4.5 cm of the point under the light
    return scene


def _info_material(name, channels):
    """An Emission of strength 1 whose colour channels are sums of Light Path outputs: ``channels`` a list of
    three lists of (output, scale, offset)."""
    material, nodes, links, path = _light_path_material(name)
    combine = nodes.new("ShaderNodeCombineColor")
    for channel, terms in enumerate(channels):
        total = None
        for output, scale, offset in terms:
            term = nodes.new("ShaderNodeMath")
            term.operation = "MULTIPLY_ADD"
            links.new(path.outputs[output], term.inputs[0])
            term.inputs[1].default_value, term.inputs[2].default_value = scale, offset
            if total is not None:
                add = nodes.new("ShaderNodeMath")
                links.new(total, add.inputs[0])
                links.new(term.outputs[0], add.inputs[1])
                term = add
            total = term.outputs[0]
        links.new(total, combine.inputs[channel])
    emission = nodes.new("ShaderNodeEmission")
    links.new(combine.outputs[0], emission.inputs["Color"])
    links.new(emission.outputs[0], nodes["Material Output"].inputs["Surface"])
    return material


def _wall(name, y, facing_camera, material, size=12.0, x=0.0):
    wall = add_plane(name, size, location=(x, y, 0.0))
    wall.rotation_euler = (math.pi / 2 if facing_camera else -math.pi / 2, 0.0, 0.0)
    wall.data.materials[0] = material
    return wall


def test_ray_kinds_after_a_mirror_and_through_glass_read_as_cycles(prism_addon, fresh_scene):
    """Emitting walls ahead of and behind the camera show, as colour, what the ray that reached them was:
    R = 0.5 Is Transmission + 0.25 Is Reflection, G = 0.5 Is Glossy + 0.25 Is Singular + Is Diffuse + Is
    Camera, B = 0.5 Glossy Depth + 0.25 Transmission Depth + Diffuse Depth. The left half is seen through a
    smooth Refraction pane (IOR 1: straight through), the right half in a mirror facing the camera (the wall
    behind it): a transmitted singular glossy ray (0.5, 0.75, 0.25) and a reflected one (0.25, 0.75, 0.5)."""
    _dark_world(fresh_scene)
    info = _info_material("Ray kind", [
        [("Is Transmission Ray", 0.5, 0.0), ("Is Reflection Ray", 0.25, 0.0)],
        [("Is Glossy Ray", 0.5, 0.0), ("Is Singular Ray", 0.25, 0.0), ("Is Diffuse Ray", 1.0, 0.0),
         ("Is Camera Ray", 1.0, 0.0)],
        [("Glossy Depth", 0.5, 0.0), ("Transmission Depth", 0.25, 0.0), ("Diffuse Depth", 1.0, 0.0)]])
    _wall("Ahead", 4.0, True, info)
    _wall("Behind", -4.0, False, info)
    _wall("Pane", 2.0, True, shader_material("Pane", "ShaderNodeBsdfRefraction", IOR=1.0, Roughness=0.0),
          size=3.0, x=-1.5)
    _wall("Mirror", 2.0, True, shader_material("Mirror", "ShaderNodeBsdfGlossy", Roughness=0.0,
                                            Color=(1.0, 1.0, 1.0, 1.0)), size=3.0, x=1.5)
    add_camera((0.0, 0.0, 0.0), (math.pi / 2, 0.0, 0.0), resolution=(32, 16))
    prism, cycles = _both(fresh_scene)
    for name, columns, expected in (("through glass", slice(0, 15), (0.5, 0.75, 0.25)),
                                    ("in the mirror", slice(17, 32), (0.25, 0.75, 0.5))):
        p, c = prism[:, columns, :3].mean((0, 1)), cycles[:, columns, :3].mean((0, 1))
        print(f"MEASURED {name}: Prism {np.round(p, 4)}, Cycles {np.round(c, 4)}, expected {expected}")
        assert np.allclose(p, expected, rtol=0.01), name
        assert np.allclose(p, c, rtol=0.02), name


def test_ray_length_and_depths_read_as_cycles(prism_addon, fresh_scene):
    """An emitting wall 4 m ahead whose colour is (Ray Length / 8, (Ray Depth + 1) / 4, (Transparent Depth + 1)
    / 4), half of it seen through a cut-out card 2 m ahead: the direct half reads R = (4 m - clip start) / cos /
    8 (a camera ray starts at the clip start, as in Cycles), G = B = 1/4; through the card R is the same (a ray
    crossing a cut-out goes on: its length counts from where it started), B = 2/4; both as in Cycles."""
    _dark_world(fresh_scene)
    material = _info_material("Ray info", [[("Ray Length", 1 / 8, 0.0)], [("Ray Depth", 0.25, 0.25)],
                                            [("Transparent Depth", 0.25, 0.25)]])
    wall = add_plane("Wall", 12.0, location=(0.0, 4.0, 0.0))
    wall.rotation_euler = (math.pi / 2, 0.0, 0.0)  # facing -y, towards the camera
    wall.data.materials[0] = material
    card = add_plane("Card", 3.0, location=(-1.5, 2.0, 0.0))
    card.rotation_euler = (math.pi / 2, 0.0, 0.0)
    card.data.materials[0] = shader_material("Cut-out", "ShaderNodeBsdfTransparent")
    clip_m = add_camera((0.0, 0.0, 0.0), (math.pi / 2, 0.0, 0.0), resolution=(32, 16)).data.clip_start
    prism, cycles = _both(fresh_scene)
    half = 16
    width_m = 36.0 / 50.0  # tan of the half angle × 2 per metre of depth
    x = ((np.arange(32) + 0.5) / 32 - 0.5) * width_m
    y = ((np.arange(16) + 0.5) / 16 - 0.5) * width_m / 2
    secant = np.sqrt(1.0 + x[None, :] ** 2 + y[:, None] ** 2)
    for name, columns, depth_m, transparent in (("direct", slice(half + 1, 32), 4.0 - clip_m, 0),
                                                ("through", slice(0, half - 1), 4.0 - clip_m, 1)):
        p, c = prism[:, columns, :3], cycles[:, columns, :3]
        closed = np.stack([depth_m * secant[:, columns] / 8, np.full(p.shape[:2], 0.25),
                           np.full(p.shape[:2], (transparent + 1) / 4)], -1)
        print(f"MEASURED {name}: Prism {np.round(p.mean((0, 1)), 4)}, Cycles {np.round(c.mean((0, 1)), 4)}, closed "
              f"form {np.round(closed.mean((0, 1)), 4)}")
        assert np.allclose(p.mean((0, 1)), c.mean((0, 1)), rtol=0.02), name
        assert np.allclose(p.mean((0, 1)), closed.mean((0, 1)), rtol=0.01), name
        assert np.abs(p / closed - 1.0).max() < 0.05, name  # per pixel: wavelength noise of 64 samples
