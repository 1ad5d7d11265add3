"""Time and memory of exporting many instances (the geometry export's per-instance cost).

    .venv/bin/python tools/measure_instance_export.py [--instances 100000]

Builds a vertex-instancing grid of about ``--instances`` copies of a cube (12
triangles, 8 vertices... 24 corners) in the bpy module, then exports the evaluated
depsgraph's geometry three times and prints the best wall time, the time per
instance, the bytes per instance of the exported arrays, and the peak memory the
export allocated per instance (a fourth run under tracemalloc: numpy reports its
buffers to it).
"""

from __future__ import annotations

import argparse
import importlib
import math
import sys
import time
import tracemalloc
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def build_scene(instances: int):
    import bpy

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    bpy.ops.mesh.primitive_cube_add(size=0.05, location=(0.0, 0.0, -5.0))
    cube = bpy.context.object
    side = max(1, round(math.sqrt(instances)) - 1)
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=side, y_subdivisions=side, size=100.0)
    grid = bpy.context.object
    grid.instance_type = "VERTS"
    grid.show_instancer_for_viewport = grid.show_instancer_for_render = False  # time the instances only
    cube.parent = grid
    return len(grid.data.vertices)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--instances", type=int, default=100_000)
    arguments = parser.parse_args()
    import bpy

    from render import exit_now, load_addon_package

    addon = load_addon_package()
    addon.register()
    meshes = importlib.import_module(f"{addon.__name__}.engine.export.meshes")
    count = build_scene(arguments.instances)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    times = []
    for _ in range(3):
        started = time.perf_counter()
        geometry = meshes.export_meshes(depsgraph, [])
        times.append(time.perf_counter() - started)
    del geometry
    tracemalloc.start()  # a separate run: tracing every allocation slows it several times
    geometry = meshes.export_meshes(depsgraph, [])
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    kept = sum(a.nbytes for a in (geometry.vertices, geometry.triangles, geometry.triangle_material,
                                  geometry.triangle_object, geometry.corner_normals))
    best = min(times)
    print(f"instances: {count} (+1 original), triangles: {len(geometry.triangles)}")
    print(f"export_meshes: {best:.3f} s best of {len(times)} ({best / count * 1e6:.1f} µs per instance)")
    print(f"arrays kept: {kept / count:.0f} bytes per instance; peak during export: {peak / count:.0f} bytes per instance")
    exit_now(0)


if __name__ == "__main__":
    main()
