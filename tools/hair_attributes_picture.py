"""Hair Curves coloured by their own attributes, rendered by Prism and by Cycles from the same scene, side by
side: docs/images/hair_attributes.png.

    .venv/bin/python tools/hair_attributes_picture.py [--samples 64]

Two grooms of 300 curved, tapering strands ("3D Curves", Diffuse BSDF) under a sun and a grey world. Left: a
random colour per strand (a curve-domain colour attribute) times a brightness rising from root to tip (a
point-domain float, interpolated along each segment). Right: a Checker Texture on the strands' UV map, the
"surface_uv_coordinate" each root records (here the root's place on the disc), which Cycles takes as the default
UV map. Prints each image's mean luminance and their ratio (absolute light, no normalisation).
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "hair_attributes.png"


def _checkered(obj, positions, sizes):
    from helpers.node_scenes import material, node

    roots = positions.reshape(len(sizes), sizes[0], 3)[:, 0, :2]
    uv = (roots + 0.5).clip(0.0, 1.0)  # the root's place on the 1 m disc
    obj.data.attributes.new("surface_uv_coordinate", "FLOAT2", "CURVE").data.foreach_set("vector", uv.ravel())
    mat, nodes, link = material("Checker on UV")
    coordinates = nodes.new("ShaderNodeTexCoord")
    checker = node(nodes, "ShaderNodeTexChecker", Color1=(0.85, 0.55, 0.15), Color2=(0.15, 0.3, 0.7), Scale=4.0)
    link(coordinates.outputs["UV"], checker.inputs["Vector"])
    bsdf = node(nodes, "ShaderNodeBsdfDiffuse")
    link(checker.outputs["Color"], bsdf.inputs["Color"])
    link(bsdf.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def _scene(bpy):
    import numpy as np

    from helpers.hair_scenes import groom, hair_object, lit, tint_and_fade
    from helpers.node_scenes import camera

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    lit(scene)
    rng = np.random.default_rng(5)
    for x, kind in ((-0.65, "tint"), (0.65, "checker")):
        sizes, positions, radii = groom(count=600)
        obj = hair_object(f"Groom {kind}", sizes, positions, radii=radii)
        obj.location.x = x
        obj.data.materials.append(tint_and_fade(obj, sizes, rng, tint_range=(0.15, 0.9), root_fade=0.25)
                                  if kind == "tint" else _checkered(obj, positions, sizes))
    camera((0.0, -3.4, 1.6), (0.0, 0.0, 0.45), resolution=(240, 120))
    return scene


if __name__ == "__main__":
    from side_by_side import picture_main

    picture_main(__doc__.splitlines()[0], _scene, OUTPUT, samples=64, bounces=8)
