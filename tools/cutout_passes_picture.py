"""Render passes through cut-outs, Prism beside Cycles: docs/images/cutout_passes.png.

    .venv/bin/python tools/cutout_passes_picture.py [--samples 64]

A card tilted 40° over a grey floor, its Principled Alpha a checker (0 and 1) so that half of it is holes, under a
point light; View Layer ▸ Alpha Threshold at Blender's 0.5. Two rows (Prism, Cycles 4.5) of four panels: Combined,
Depth (1 / depth, scaled alike in both rows), Normal (x, y, z as R, G, B, from 0.5 ± 0.5) and Diffuse Color. In
the holes both engines write the floor's depth, normal and colour. Prints each panel's mean, absolute.
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "docs" / "images" / "cutout_passes.png"
WIDTH, HEIGHT = 160, 112


def _card_with_holes():
    """The card of ``build_lit_card_scene``, tilted, red where it is opaque, its alpha a 4 x 4 checker."""
    import bpy

    card = bpy.data.objects["Card"]
    card.rotation_euler = (math.radians(40.0), 0.0, 0.0)
    tree = card.active_material.node_tree
    checker = tree.nodes.new("ShaderNodeTexChecker")
    checker.inputs["Scale"].default_value = 4.0
    checker.inputs["Color1"].default_value = (1.0, 1.0, 1.0, 1.0)
    checker.inputs["Color2"].default_value = (0.0, 0.0, 0.0, 1.0)
    tree.links.new(checker.outputs["Fac"], tree.nodes["Principled BSDF"].inputs["Alpha"])


def _panels(layers):
    """Display-ready linear RGB of Combined, Depth, Normal and Diffuse Color."""
    depth = layers["Depth"][..., 0]
    inverse = np.where(depth < 1e9, 1.0 / np.maximum(depth, 1e-6), 0.0) * 2.0
    return (layers["Combined"][..., :3], np.repeat(inverse[..., None], 3, -1) ** 2.2,
            (layers["Normal"] * 0.5 + 0.5) ** 2.2, layers["DiffCol"])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=64)
    arguments = parser.parse_args()
    sys.path[:0] = [str(ROOT), str(ROOT / "tests"), str(ROOT / "tools")]
    import bpy
    from PIL import Image, ImageDraw

    from blender.test_passes import _render_layers, _switch_on
    from helpers.bpy_scenes import build_lit_card_scene
    from helpers.cycles import configure_cycles
    from render import load_addon_package
    from side_by_side import _display

    addon = load_addon_package()
    addon.register()
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    build_lit_card_scene(resolution=(WIDTH, HEIGHT))
    _card_with_holes()
    scene = bpy.context.scene
    scene.render.use_compositing = False
    scene.prism.samples = scene.prism.samples_per_pass = arguments.samples
    _switch_on(scene, ("z", "normal", "diffuse_color"))
    rows = []
    with tempfile.TemporaryDirectory() as directory:
        for label, engine in (("Prism", "PRISM"), ("Cycles 4.5", "CYCLES")):
            if engine == "CYCLES":
                configure_cycles(scene, arguments.samples)
            layers = _render_layers(addon, scene, Path(directory) / f"{engine}.exr", engine=engine)
            panels = _panels(layers)
            means = [float(np.mean(layers[name][..., :3])) for name in ("Combined", "Depth", "Normal", "DiffCol")]
            print(f"MEASURED {label}: means of Combined, Depth, Normal, DiffCol", np.round(means, 4), flush=True)
            rows.append((label, panels))
    captions = ("Combined", "Depth (1 / m)", "Normal", "Diffuse Color")
    canvas = Image.new("RGB", (4 * (WIDTH + 6) + 70, 2 * (HEIGHT + 6) + 18), (255, 255, 255))
    draw = ImageDraw.Draw(canvas)
    for column, caption in enumerate(captions):
        draw.text((70 + column * (WIDTH + 6) + 4, 3), caption, fill=(0, 0, 0))
    for row, (label, panels) in enumerate(rows):
        top = 18 + row * (HEIGHT + 6)
        draw.text((4, top + HEIGHT // 2), label, fill=(0, 0, 0))
        for column, rgb in enumerate(panels):
            canvas.paste(Image.fromarray(_display(np.asarray(rgb, np.float64))), (70 + column * (WIDTH + 6), top))
    OUTPUT.parent.mkdir(parents=True, exist_ok=True)
    canvas.save(OUTPUT)
    print(f"wrote {OUTPUT}", flush=True)


if __name__ == "__main__":
    main()
