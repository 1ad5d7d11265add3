"""The bpy side of the equal-time experiments against Cycles (``media_vs_cycles``, ``real_sizes_vs_cycles``): one
scene rendered by Prism and by Cycles at each sample count with two seeds, every render timed, in a process of
its own (the harness never imports bpy).

    python -m benchmarks.experiments._bpy_renders --scene fog --resolution 96 72 --spp 16 32 64 \\
        --bounces 8 --out renders.npz

Scenes: ``fog`` and ``subsurface`` come from the tests' builders (``tests/helpers``), so the benchmark renders
what the tests compare with Cycles: ``fog_scenes.point_light_in_fog``, ``subsurface_scenes.skin_spheres_in_sun``.
``demo`` is the README's demo room (``demo/build_demo_scene.py``: gold monkey, dispersive glass prism, blackbody
lights), ``mesh_1m`` the benchmark's Cornell box with a 1M-triangle sphere (``benchmarks.scenes``), rebuilt in
Blender as the Cycles peer does (``benchmarks.peers.cycles``). Both renderers render through
``bpy.ops.render.render`` (export or scene sync, sampling, the EXR written and read back: what an F12 costs),
each after one untimed warm-up render (kernels loaded, caches filled), taking turns (Prism, Cycles, Prism,
Cycles) so that a load on the shared machine falls on both. Writes ``--out`` (npz): ``images`` [renderer, spp,
seed, H, W, 3] scene-linear RGB and ``seconds`` [renderer, spp, seed].
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
RENDERERS = ("prism", "cycles")
SEEDS = (0, 1)
THREADS = 2  # Cycles' too: helpers.cycles.configure_cycles fixes 2 threads


def _arguments(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", choices=("fog", "subsurface", "demo", "mesh_1m"), required=True)
    parser.add_argument("--resolution", type=int, nargs=2, required=True, metavar=("WIDTH", "HEIGHT"))
    parser.add_argument("--spp", type=int, nargs="+", required=True)
    parser.add_argument("--bounces", type=int, default=8)
    parser.add_argument("--out", required=True)
    return parser.parse_args(argv)


def _build(name, resolution):
    import bpy

    if name == "demo":
        import tempfile

        from demo.build_demo_scene import build

        with tempfile.TemporaryDirectory() as folder:
            build(Path(folder) / "demo.blend")  # the scene stays open
        scene = bpy.context.scene
        scene.render.resolution_x, scene.render.resolution_y = resolution
        scene.render.resolution_percentage = 100
        return scene
    if name == "mesh_1m":
        from benchmarks import scenes
        from benchmarks.peers.cycles import build_blender_scene

        return build_blender_scene(scenes.build(name, tuple(resolution)))
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    if name == "fog":
        from helpers.fog_scenes import point_light_in_fog

        return point_light_in_fog(tuple(resolution))
    from helpers.subsurface_scenes import skin_spheres_in_sun

    return skin_spheres_in_sun(tuple(resolution))


def main(argv=None) -> int:
    args = _arguments(argv)
    sys.modules.setdefault("matplotlib", None)  # colour-science skips it when absent (as in Blender): ~1 s less
    sys.path[:0] = [str(ROOT), str(ROOT / "tests")]
    import bpy  # noqa: F401  (before the add-on, as Blender would)

    from helpers.cycles import render_cycles_rgba, render_prism_rgba
    from render import load_addon_package

    load_addon_package().register()
    scene = _build(args.scene, args.resolution)
    scene.prism.max_bounces = args.bounces
    scene.prism.threads = THREADS

    def render(renderer, spp, seed):
        started = time.perf_counter()
        if renderer == "prism":
            image = render_prism_rgba(scene, spp, seed)
        else:  # CPU, box filter, no adaptive sampling, denoising or clamping
            image = render_cycles_rgba(scene, spp, seed, max_bounces=args.bounces)
        return image[..., :3], time.perf_counter() - started

    for renderer in RENDERERS:
        render(renderer, args.spp[0], 99)  # warm-up, untimed
    width, height = args.resolution
    images = np.zeros((len(RENDERERS), len(args.spp), len(SEEDS), height, width, 3), np.float32)
    seconds = np.zeros(images.shape[:3])
    for s, spp in enumerate(args.spp):
        for k, seed in enumerate(SEEDS):
            for r, renderer in enumerate(RENDERERS):
                images[r, s, k], seconds[r, s, k] = render(renderer, spp, seed)
    np.savez(args.out, images=images, seconds=seconds, spp=np.array(args.spp), renderers=np.array(RENDERERS),
             blender=np.array(bpy.app.version_string))
    return 0


if __name__ == "__main__":
    status = main()
    from render import exit_now  # bpy's exit can hang after a render (docs: ENVIRONMENT.md)

    exit_now(status)
