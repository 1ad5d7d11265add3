"""One benchmark scene's pass against the embreex ceiling, and where its time goes, stage by stage.

    .venv/bin/python tools/profile_pass.py cornell_glass [--size 64] [--spp 16] [--threads 2]
        [--passes 5] [--seed 0] [--no-ceiling] [--no-stages]
    .venv/bin/python tools/profile_pass.py --blend renders/demo.blend [--spp 4] ...   (bpy module)

The first form renders a benchmark scene (``benchmarks/scenes.py``); ``--blend`` exports a .blend
file's scene and render settings through the add-on, as ``render.py`` does (``--size`` is then the
file's resolution).

Prints the best of ``--passes`` timed passes after a warm-up pass (wall and process CPU time, paths/s,
rays/s), the time bare embreex needs for exactly the rays of one pass (recorded on another, untimed
pass with ``benchmarks.ceiling`` and replayed on the renderer's triangles with the same thread count),
their ratio (the project's "fraction of the ceiling", in wall and in CPU time), and the pass split by
stage kernel and Embree query in CPU time (``benchmarks.stage_split``, on passes of its own). On a
shared machine the CPU-time figures are the stable ones; wall-clock ratios need a quiet moment.
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def _timed_pass(renderer):
    wall, cpu = time.perf_counter(), time.process_time()
    rays = renderer.stats["rays_cast"]
    renderer.render_pass()
    return time.perf_counter() - wall, time.process_time() - cpu, renderer.stats["rays_cast"] - rays


def _blend(path, args):
    """(scene, settings) of a .blend file, exported by the add-on as ``render.py`` does."""
    import bpy
    from dataclasses import replace

    from render import load_addon_package

    package = load_addon_package()
    package.register()
    bpy.ops.wm.open_mainfile(filepath=str(Path(path).resolve()))
    export = importlib.import_module(package.__name__ + ".engine.export")
    export_settings = importlib.import_module(package.__name__ + ".engine.export.settings").export_settings
    scene = export.export_scene(bpy.context.evaluated_depsgraph_get(), [])
    settings = export_settings(bpy.context.scene, samples=10**6, seed=args.seed, threads=args.threads, preview=False,
                               border=None)
    return scene, replace(settings, samples_per_pass=args.spp)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scene", nargs="?", default="cornell_glass")
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--spp", type=int, default=16)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--passes", type=int, default=5)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--no-ceiling", action="store_true")
    parser.add_argument("--no-stages", action="store_true")
    parser.add_argument("--blend", help="a .blend file to export and profile instead of a benchmark scene")
    parser.add_argument("--json", help="also write the figures to this file (JSON)")
    args = parser.parse_args(argv)
    report = dict(scene=args.scene, threads=args.threads, spp=args.spp)

    from dataclasses import replace

    from benchmarks import ceiling, prism_runs, scenes, stage_split

    if args.blend:
        scene, settings = _blend(args.blend, args)
        args.scene = Path(args.blend).name
    else:
        scene = scenes.build(args.scene, (args.size, args.size))
        settings = replace(prism_runs.settings_for({}, samples=10**6, seed=args.seed, threads=args.threads),
                           samples_per_pass=args.spp)
    Renderer = importlib.import_module(stage_split._tracer(scene) + ".renderer").Renderer
    width, height = (int(r) for r in scene.camera.resolution)
    paths = width * height * args.spp
    with Renderer(scene, settings) as renderer:
        renderer.render_pass()  # warm-up: kernels loaded, buffers allocated
        runs = [_timed_pass(renderer) for _ in range(args.passes)]
        wall, cpu, rays = min(runs)  # the least disturbed pass on a shared machine
        print(f"scene {args.scene} {width}x{height}, {args.spp} spp/pass ({paths:,} paths), "
              f"{args.threads} thread(s); best of {args.passes} passes")
        print(f"  pass wall {wall:.4f} s, cpu {cpu:.4f} s, {rays:,} rays ({rays / paths:.2f} per path)")
        print(f"  paths/s {paths / wall:,.0f}   rays/s {rays / wall:,.0f}   rays per CPU-s {rays / cpu:,.0f}")
        report.update(scene=args.scene, width=width, height=height, paths=paths, pass_seconds=wall, pass_cpu=cpu,
                      rays=rays, triangles=int(len(renderer.tables.geometry.triangles)))
        if not args.no_ceiling:
            recorder = ceiling.record_pass(renderer)
            replayer = ceiling.Replayer(renderer.tables.geometry, recorder.batches, args.threads)
            embree = min(replayer.seconds() for _ in range(args.passes))
            embree_cpu = min(replayer.cpu_seconds() for _ in range(args.passes))
            replayer.close()
            n = recorder.ray_count
            print(f"  embreex ceiling: {n:,} rays ({recorder.count(ceiling.CLOSEST):,} closest, "
                  f"{recorder.count(ceiling.OCCLUDED):,} shadow, {recorder.count(ceiling.BEFORE):,} through films) "
                  f"in {embree:.4f} s = {n / embree:,.0f} rays/s, cpu {embree_cpu:.4f} s")
            # the recorded pass and the timed passes cast about as many rays: scale to the timed pass's
            print(f"  fraction of the ceiling: {embree * rays / n / wall:.1%} (wall), "
                  f"{embree_cpu * rays / n / cpu:.1%} (CPU time)")
            report.update(fraction=embree * rays / n / wall, cpu_fraction=embree_cpu * rays / n / cpu)
    if not args.no_stages:
        split = stage_split.stage_split(scene, {}, args.threads, passes=args.passes, seed=args.seed, settings=settings)
        print(f"  stages, CPU ms per pass of {split['paths']:,} paths (mean of {args.passes} wrapped passes; "
              f"pass wall {1000 * split['pass_seconds']:.1f} ms, chunks' CPU {1000 * split['chunk_cpu']:.1f} ms):")
        for row in split["rows"]:
            share = "" if row["share"] != row["share"] else f"{100 * row['share']:5.1f} %"
            print(f"    {row['stage']:48s} {1000 * row['cpu']:8.2f}  {share:>7s}  {row['calls']:6.0f} calls")
        print(f"    {'threads x wall - chunks CPU (idle, waits)':48s} {1000 * split['unexplained']:8.2f}")
        report["stages"] = split
    if args.json:
        Path(args.json).write_text(json.dumps(report, indent=1))
    if args.blend:  # the bpy module can hang at exit after a render (engine/batch/process_exit.py)
        from render import exit_now

        exit_now(0)
    return 0


if __name__ == "__main__":
    sys.exit(main())
