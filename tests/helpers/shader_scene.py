"""A lit scene of spheres, each with one shader set-up (the BSDF nodes and how they combine), on a grey
floor under an area light and a dim world: what the closures do, for Prism against Cycles."""

from __future__ import annotations

import bpy
import numpy as np

from .node_scenes import camera, node, plane, socket, surface_material, uv_sphere


def _principled(**inputs):
    def build(nodes, link):
        bsdf = node(nodes, "ShaderNodeBsdfPrincipled", **inputs)
        bsdf.distribution = "GGX"
        return bsdf.outputs[0]
    return build


def _textured_principled(nodes, link):
    bsdf = node(nodes, "ShaderNodeBsdfPrincipled", Roughness=0.4)
    bsdf.distribution = "GGX"
    checker = node(nodes, "ShaderNodeTexChecker", Scale=6.0, Color1=(0.8, 0.15, 0.1), Color2=(0.1, 0.5, 0.8))
    link(checker.outputs["Color"], bsdf.inputs["Base Color"])
    return bsdf.outputs[0]


def _glossy(nodes, link):
    glossy = node(nodes, "ShaderNodeBsdfAnisotropic", Color=(0.9, 0.6, 0.3), Roughness=0.3)
    glossy.distribution = "GGX"
    return glossy.outputs[0]


def _mix_fresnel(nodes, link):
    diffuse = node(nodes, "ShaderNodeBsdfDiffuse", Color=(0.7, 0.1, 0.1))
    glossy = node(nodes, "ShaderNodeBsdfAnisotropic", Color=(1.0, 1.0, 1.0), Roughness=0.2)
    glossy.distribution = "GGX"
    weight = node(nodes, "ShaderNodeLayerWeight", Blend=0.3)
    mix = nodes.new("ShaderNodeMixShader")
    link(weight.outputs["Fresnel"], mix.inputs["Fac"])
    link(diffuse.outputs[0], mix.inputs[1])
    link(glossy.outputs[0], mix.inputs[2])
    return mix.outputs[0]


def _add_noise(nodes, link):
    diffuse = node(nodes, "ShaderNodeBsdfDiffuse")
    noise = node(nodes, "ShaderNodeTexNoise", Scale=5.0, Detail=2.0)
    link(noise.outputs["Color"], diffuse.inputs["Color"])
    glossy = node(nodes, "ShaderNodeBsdfAnisotropic", Color=(0.2, 0.2, 0.2), Roughness=0.15)
    glossy.distribution = "GGX"
    add = nodes.new("ShaderNodeAddShader")
    link(diffuse.outputs[0], add.inputs[0])
    link(glossy.outputs[0], add.inputs[1])
    return add.outputs[0]


def _bumped(nodes, link):
    bsdf = node(nodes, "ShaderNodeBsdfPrincipled", Base_Color=(0.6, 0.6, 0.55), Roughness=0.3)
    bsdf.distribution = "GGX"
    noise = node(nodes, "ShaderNodeTexNoise", Scale=8.0, Detail=1.0)
    bump = node(nodes, "ShaderNodeBump", Strength=1.0, Distance=0.05)
    link(noise.outputs["Fac"], bump.inputs["Height"])
    link(bump.outputs["Normal"], bsdf.inputs["Normal"])
    return bsdf.outputs[0]


def _single_scatter(kind, **inputs):
    """A builder of one GGX node of ``kind`` (Glass, Refraction, …) set to single scattering."""

    def build(nodes, link):
        bsdf = node(nodes, kind, **inputs)
        bsdf.distribution = "GGX"
        return bsdf.outputs[0]
    return build


def _diffuse_mixed_with(kind, colour, other_colour, fac):
    """A builder of a Mix Shader: Diffuse of ``colour`` (first) and a ``kind`` node of ``other_colour``."""

    def build(nodes, link):
        other = node(nodes, kind, Color=other_colour)
        diffuse = node(nodes, "ShaderNodeBsdfDiffuse", Color=colour)
        mix = node(nodes, "ShaderNodeMixShader", Fac=fac)
        link(diffuse.outputs[0], mix.inputs[1])
        link(other.outputs[0], mix.inputs[2])
        return mix.outputs[0]
    return build


# Pale: light crossing a sphere meets the colour twice, and the product of two smooth spectra is less
# saturated than the product of two RGB triples (Prism is spectral, Cycles RGB).
_translucent_mix = _diffuse_mixed_with("ShaderNodeBsdfTranslucent", (0.6, 0.8, 0.6), (0.6, 0.8, 0.6), 0.5)
_transparent_mix = _diffuse_mixed_with("ShaderNodeBsdfTransparent", (0.5, 0.6, 0.8), (0.9, 0.9, 0.9), 0.4)


def _group(nodes, link):
    """A node group (Diffuse tinted by a colour ramp of its input) behind a reroute."""
    tree = bpy.data.node_groups.get("Tinted diffuse") or bpy.data.node_groups.new("Tinted diffuse", "ShaderNodeTree")
    if not tree.nodes:
        tree.interface.new_socket("Fac", in_out="INPUT", socket_type="NodeSocketFloat")
        tree.interface.new_socket("Shader", in_out="OUTPUT", socket_type="NodeSocketShader")
        inside_in = tree.nodes.new("NodeGroupInput")
        inside_out = tree.nodes.new("NodeGroupOutput")
        ramp = tree.nodes.new("ShaderNodeValToRGB")
        ramp.color_ramp.elements[0].color = (0.9, 0.7, 0.1, 1.0)
        ramp.color_ramp.elements[1].color = (0.1, 0.2, 0.9, 1.0)
        diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
        tree.links.new(inside_in.outputs[0], ramp.inputs["Fac"])
        tree.links.new(ramp.outputs["Color"], diffuse.inputs["Color"])
        tree.links.new(diffuse.outputs[0], inside_out.inputs[0])
    group = nodes.new("ShaderNodeGroup")
    group.node_tree = tree
    gradient = nodes.new("ShaderNodeTexGradient")
    reroute = nodes.new("NodeReroute")
    link(gradient.outputs["Fac"], reroute.inputs[0])
    link(reroute.outputs[0], group.inputs[0])
    return group.outputs[0]


def _ripple_normal_map(size=64, ripples=6, slope=0.6):
    """A tangent-space normal map (Non-Color, 8-bit) of ripples along U: n ∝ (-dh/du, 0, 1)."""
    u = (np.arange(size) + 0.5) / size
    dh = slope * np.cos(2.0 * np.pi * ripples * u)
    n = np.stack([-dh, np.zeros_like(dh), np.ones_like(dh)], -1) / np.sqrt(1.0 + dh * dh)[:, None]
    pixels = np.ones((size, size, 4), np.float32)
    pixels[..., :3] = 0.5 * n[None, :, :] + 0.5
    image = bpy.data.images.get("ripples") or bpy.data.images.new("ripples", size, size)
    image.colorspace_settings.name = "Non-Color"
    image.pixels.foreach_set(pixels.ravel())
    return image


def _normal_mapped(nodes, link):
    bsdf = node(nodes, "ShaderNodeBsdfPrincipled", Base_Color=(0.7, 0.5, 0.3), Roughness=0.35)
    bsdf.distribution = "GGX"
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = _ripple_normal_map()
    normal_map = node(nodes, "ShaderNodeNormalMap", Strength=1.0)
    normal_map.uv_map = "UVMap"
    link(texture.outputs["Color"], normal_map.inputs["Color"])
    link(normal_map.outputs["Normal"], bsdf.inputs["Normal"])
    return bsdf.outputs[0]


def _emission_by_fresnel(nodes, link):
    """Emission where the view is head-on, a glossy coat at grazing angles (Fresnel node as the factor)."""
    emission = node(nodes, "ShaderNodeEmission", Color=(1.0, 0.6, 0.3), Strength=1.5)
    glossy = node(nodes, "ShaderNodeBsdfAnisotropic", Color=(0.8, 0.8, 0.8), Roughness=0.25)
    glossy.distribution = "GGX"
    fresnel = node(nodes, "ShaderNodeFresnel", IOR=1.8)
    mix = nodes.new("ShaderNodeMixShader")
    link(fresnel.outputs["Fac"], mix.inputs["Fac"])
    link(emission.outputs[0], mix.inputs[1])
    link(glossy.outputs[0], mix.inputs[2])
    return mix.outputs[0]


#: (name, material builder) of the spheres, left to right, back row to front row.
SHADERS = [
    ("principled plastic", _principled(Base_Color=(0.2, 0.4, 0.8), Roughness=0.3)),
    ("principled textured", _textured_principled),
    ("principled metal", _principled(Base_Color=(0.95, 0.7, 0.3), Metallic=1.0, Roughness=0.35)),
    ("principled coat", _principled(Base_Color=(0.6, 0.05, 0.05), Roughness=0.6, Coat_Weight=1.0,
                                    Coat_Roughness=0.05, Coat_Tint=(0.9, 0.9, 0.6))),
    ("glossy", _glossy),
    ("mix by layer weight", _mix_fresnel),
    ("add diffuse + glossy on noise", _add_noise),
    ("bump from noise", _bumped),
    ("rough glass", _single_scatter("ShaderNodeBsdfGlass", Color=(0.9, 0.95, 1.0), Roughness=0.45, IOR=1.45)),
    ("translucent + diffuse", _translucent_mix),
    ("group and reroute", _group),
    ("principled specular tint", _principled(Base_Color=(0.3, 0.3, 0.3), Roughness=0.25, Specular_IOR_Level=0.8,
                                             Specular_Tint=(1.0, 0.5, 0.2))),
    ("normal map (tangent space)", _normal_mapped),
    ("rough refraction", _single_scatter("ShaderNodeBsdfRefraction", Color=(0.95, 0.9, 0.8), Roughness=0.4,
                                         IOR=1.45)),
    ("transparent + diffuse", _transparent_mix),
    ("emission by Fresnel + glossy", _emission_by_fresnel),
]


def build_shader_scene(resolution=(128, 96)):
    """Sixteen spheres in four rows of four seen from above; returns (names, sphere objects)."""
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.6, 0.7, 0.9, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.15
    bpy.context.scene.world = world
    floor_material = surface_material("floor", lambda nodes, link: node(
        nodes, "ShaderNodeBsdfDiffuse", Color=(0.5, 0.5, 0.5)).outputs[0])
    plane("floor", 14.0, mat=floor_material)
    light = bpy.data.lights.new("Panel", "AREA")
    light.shape, light.size, light.energy = "SQUARE", 3.0, 1500.0
    lamp = bpy.data.objects.new("Panel", light)
    lamp.location, lamp.rotation_euler = (1.0, -2.0, 5.0), (0.35, 0.0, 0.0)
    bpy.context.scene.collection.objects.link(lamp)
    names, spheres = [], []
    for index, (name, build) in enumerate(SHADERS):
        row, column = divmod(index, 4)
        sphere = uv_sphere(f"sphere {index}", 0.45, ((column - 1.5) * 1.0, 1.5 - row * 1.0, 0.45),
                           mat=surface_material(name, build))
        sphere.data.uv_layers.active.name = "UVMap"
        names.append(name)
        spheres.append(sphere)
    camera((0.0, -4.6, 4.4), (0.0, 0.0, 0.2), lens_mm=40.0, resolution=resolution)
    return names, spheres
