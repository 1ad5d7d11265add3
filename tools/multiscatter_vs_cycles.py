"""Prism / Cycles absolute luminance of GGX-based shaders, before (single scattering) and after
(Multiscatter GGX), per roughness: the table in docs/materials.md ("Multiscatter GGX").

    .venv/bin/python tools/multiscatter_vs_cycles.py [--samples 64] [--roughness 0.25 0.5 0.6 0.75 1]

Needs the bpy module (Cycles is the oracle). Six spheres in a row under a uniform white world
(``tests/helpers/furnace_zoo.py``); each ratio is the mean luminance of a sphere's inner disc. "Before" is
Prism with every node set to GGX, what Prism rendered for Multiscatter GGX until it compensated energy.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _patches(one_node, principled, r):
    return [
        ("Principled metal 0.95", principled(Base_Color=(0.95,) * 3, Metallic=1.0, Roughness=r)),
        ("Principled dielectric white", principled(Base_Color=(1.0,) * 3, Roughness=r)),
        ("Glossy white", one_node("ShaderNodeBsdfAnisotropic", Color=(1.0,) * 3, Roughness=r)),
        ("Glossy (0.9, 0.6, 0.3)", one_node("ShaderNodeBsdfAnisotropic", Color=(0.9, 0.6, 0.3), Roughness=r)),
        ("Metallic F82 (0.9, 0.6, 0.3)", one_node("ShaderNodeBsdfMetallic", Base_Color=(0.9, 0.6, 0.3), Roughness=r)),
        ("Glass white IOR 1.5", one_node("ShaderNodeBsdfGlass", Color=(1.0,) * 3, Roughness=r, IOR=1.5)),
    ]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=64)
    parser.add_argument("--roughness", type=float, nargs="+", default=[0.25, 0.5, 0.6, 0.75, 1.0])
    args = parser.parse_args()
    sys.path[:0] = [str(ROOT), str(ROOT / "tests")]
    import bpy
    import numpy as np

    from helpers.cycles import render_cycles_rgba, render_prism_rgba
    from helpers.cycles_compare import LUMINANCE
    from helpers.furnace_zoo import build_furnace_zoo, one_node, principled
    from render import load_addon_package

    load_addon_package().register()

    def luminances(image, masks):
        luminance = image[..., :3] @ LUMINANCE
        return np.array([luminance[mask].mean() for mask in masks])

    table = {}
    for r in args.roughness:
        bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
        scene = bpy.context.scene
        patches = _patches(one_node, principled, r)
        masks = build_furnace_zoo(patches)
        cycles = luminances(render_cycles_rgba(scene, args.samples, 0, 16), masks)
        scene.prism.max_bounces = 16
        after = luminances(render_prism_rgba(scene, args.samples, 0), masks)
        for material in bpy.data.materials:
            for node in material.node_tree.nodes if material.node_tree else ():
                if getattr(node, "distribution", None) == "MULTI_GGX":
                    node.distribution = "GGX"
        before = luminances(render_prism_rgba(scene, args.samples, 0), masks)
        for (name, _), c, b, a in zip(patches, cycles, before, after):
            table.setdefault(name, []).append(f"{b / c:.3f} → {a / c:.3f}")
    print("| BSDF (Multiscatter GGX) | " + " | ".join(f"r = {r:g}" for r in args.roughness) + " |")
    print("|---|" + "---|" * len(args.roughness))
    for name, cells in table.items():
        print(f"| {name} | " + " | ".join(cells) + " |")
    sys.stdout.flush()
    os._exit(0)  # the bpy module can hang in a destructor at exit (engine/batch/process_exit.py)


if __name__ == "__main__":
    main()
