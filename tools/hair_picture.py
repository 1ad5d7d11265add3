"""Principled Hair rendered by Prism and by Cycles from the same scene, side by side: docs/images/hair.png.

    .venv/bin/python tools/hair_picture.py [--samples 64]

Three grooms of 300 curved, tapering strands ("3D Curves") under a sun and a grey world: Principled Hair
(Chiang) with Melanin 0.8 (Redness 0.3), Melanin 0.3 (Redness 0.7) and Direct Coloring (0.6, 0.35, 0.2). Prints
each image's mean luminance and their ratio (absolute light, no normalisation); the picture shows both with the
same view transform.
"""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "hair.png"
GROOMS = ((-1.3, dict(parametrization="MELANIN", Melanin=0.8, Melanin_Redness=0.3)),
          (0.0, dict(parametrization="MELANIN", Melanin=0.3, Melanin_Redness=0.7)),
          (1.3, dict(parametrization="COLOR", Color=(0.6, 0.35, 0.2))))


def _scene(bpy):
    from helpers.hair_scenes import groom, hair_object, lit
    from helpers.node_scenes import camera, material, node

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    lit(scene)
    for x, settings in GROOMS:
        settings = dict(settings)
        mat, nodes, link = material(f"Hair {x}")
        parametrization = settings.pop("parametrization")
        hair = node(nodes, "ShaderNodeBsdfHairPrincipled", **settings)
        hair.parametrization = parametrization
        link(hair.outputs[0], nodes["Output"].inputs["Surface"])
        sizes, positions, radii = groom()
        obj = hair_object(f"Groom {x}", sizes, positions, radii=radii)
        obj.location.x = x
        obj.data.materials.append(mat)
    camera((0.0, -4.2, 1.3), (0.0, 0.0, 0.5), resolution=(240, 120))
    return scene


if __name__ == "__main__":
    from side_by_side import picture_main

    picture_main(__doc__.splitlines()[0], _scene, OUTPUT, samples=64, bounces=8)
